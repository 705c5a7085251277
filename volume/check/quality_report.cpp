#include "volume/check/quality_report.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <vector>

#include "common/atomic_file.h"
#include "common/errors.h"
#include "volume/mesh/boundary.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume
{

namespace
{

constexpr double kPi = 3.14159265358979323846;

double percent(long part, long whole)
{
    return whole > 0 ? 100.0 * double(part) / double(whole) : 0.0;
}

/// Outward unit normals of the four faces (zero for a degenerate face).
std::array<Vec3, 4> face_normals(const std::array<const Vec3*, 4>& p)
{
    std::array<Vec3, 4> normals;
    for (int f = 0; f < 4; ++f)
    {
        const auto& fv = tet::kFaceVertices[f];
        const Vec3 n = (*p[fv[1]] - *p[fv[0]]).cross(*p[fv[2]] - *p[fv[0]]);
        const double length = n.norm();
        normals[f] = length > 0.0 ? Vec3(n / length) : Vec3::Zero();
    }
    return normals;
}

std::string json_number(double x)
{
    if (!std::isfinite(x)) return "null";  // JSON has no inf/NaN
    std::ostringstream out;
    out << std::setprecision(17) << x;
    return out.str();
}

std::string fixed(double x, int digits)
{
    std::ostringstream out;
    out << std::fixed << std::setprecision(digits) << x;
    return out.str();
}

std::string xml_escape(const std::string& text)
{
    std::string out;
    for (char c : text)
    {
        if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else if (c == '&')
            out += "&amp;";
        else
            out += c;
    }
    return out;
}

/// One bar chart of the SVG: bars with their count above, a label under each.
void draw_histogram(std::ostringstream& svg, double x0, double y0, double width, double height,
                    const std::string& title, const std::vector<long>& counts,
                    const std::vector<std::string>& labels, const std::vector<std::string>& colors)
{
    svg << "<text x='" << x0 + width / 2 << "' y='" << y0 - 12
        << "' text-anchor='middle' font-size='15' font-weight='bold'>" << xml_escape(title)
        << "</text>\n";
    svg << "<rect x='" << x0 << "' y='" << y0 << "' width='" << width << "' height='" << height
        << "' fill='none' stroke='#999'/>\n";
    const long largest = std::max<long>(1, *std::max_element(counts.begin(), counts.end()));
    const double slot = width / counts.size();
    for (std::size_t i = 0; i < counts.size(); ++i)
    {
        const double bar = (height - 20) * double(counts[i]) / double(largest);
        const double x = x0 + i * slot + 0.1 * slot;
        svg << "<rect x='" << x << "' y='" << y0 + height - bar << "' width='" << 0.8 * slot
            << "' height='" << bar << "' fill='" << colors[i] << "'/>\n";
        svg << "<text x='" << x + 0.4 * slot << "' y='" << y0 + height - bar - 4
            << "' text-anchor='middle' font-size='11'>" << counts[i] << "</text>\n";
        svg << "<text x='" << x + 0.4 * slot << "' y='" << y0 + height + 16
            << "' text-anchor='middle' font-size='11'>" << xml_escape(labels[i]) << "</text>\n";
    }
}

}  // namespace

int qe_histogram_bin(double qe)
{
    if (!(qe > 0.0)) return 0;
    if (qe >= 1.0) return 9;
    // numpy.histogram's edges are k*0.1 (0.30000000000000004, ...): correct floor(10 q) against
    // them
    int bin = std::min(9, static_cast<int>(qe * 10.0));
    if (qe < bin * 0.1)
        --bin;
    else if (bin < 9 && qe >= (bin + 1) * 0.1)
        ++bin;
    return bin;
}

int length_ratio_histogram_bin(double ratio)
{
    const auto it =
        std::upper_bound(kLengthRatioBinEdges.begin(), kLengthRatioBinEdges.end(), ratio);
    const int bin = static_cast<int>(it - kLengthRatioBinEdges.begin()) - 1;
    return std::clamp(bin, 0, 7);
}

namespace
{

/// The cosines of the six dihedral angles, at edges e0..e5; 1 (an angle of 0) at an edge of a
/// degenerate face.
std::array<double, 6> dihedral_cosines(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
    const auto normals = face_normals({&a, &b, &c, &d});
    std::array<double, 6> cosines;
    for (int e = 0; e < 6; ++e)
    {
        const auto& faces = tet::kEdgeFaces[e];
        const Vec3 &n = normals[faces[0]], &m = normals[faces[1]];
        // the interior angle between two faces is pi minus the angle of their outward normals
        cosines[e] = n.isZero() || m.isZero() ? 1.0 : std::clamp(-n.dot(m), -1.0, 1.0);
    }
    return cosines;
}

}  // namespace

std::array<double, 6> dihedral_angles_deg(const Vec3& a, const Vec3& b, const Vec3& c,
                                          const Vec3& d)
{
    std::array<double, 6> angles = dihedral_cosines(a, b, c, d);
    for (double& angle : angles) angle = dihedral_cosine_to_deg(angle);
    return angles;
}

double dihedral_cosine_to_deg(double cosine) { return std::acos(cosine) * 180.0 / kPi; }

double smallest_dihedral_cosine(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
    const std::array<double, 6> cosines = dihedral_cosines(a, b, c, d);
    return *std::max_element(cosines.begin(), cosines.end());
}

namespace
{

/// The solid angle of tet abcd at a (Van Oosterom and Strackee).
double solid_angle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
    const Vec3 x = b - a, y = c - a, z = d - a;
    const double lx = x.norm(), ly = y.norm(), lz = z.norm();
    const double numerator = std::abs(x.dot(y.cross(z)));
    const double denominator = lx * ly * lz + x.dot(y) * lz + x.dot(z) * ly + y.dot(z) * lx;
    return 2.0 * std::atan2(numerator, denominator);
}

/// How many of `below` (tets under the floor) are forced: an edge whose tets' dihedral angles
/// sum below the sharp ridge angle (a boundary edge of a sharp ridge), a vertex whose tets'
/// solid angles sum below the sharp corner's, or a face on a poor kept boundary triangle.
int count_forced(const TetMesh& mesh, const std::vector<int>& below,
                 const std::vector<Triangle>& boundary, const QualityReportOptions& options)
{
    const int nv = mesh.num_vertices();
    std::vector<char> on_boundary(nv, 0);
    for (const auto& tri : boundary)
        for (int v : tri) on_boundary[v] = 1;
    // candidates: the boundary vertices and boundary-to-boundary edges of the tets below
    std::vector<int> vertex_slot(nv, -1);
    std::vector<double> vertex_angle;
    std::vector<std::vector<std::pair<int, double>>> edge_angle;  // per first vertex slot
    for (int t : below)
        for (int v : mesh.tets[t])
            if (on_boundary[v] && vertex_slot[v] < 0)
            {
                vertex_slot[v] = static_cast<int>(vertex_angle.size());
                vertex_angle.push_back(0.0);
                edge_angle.emplace_back();
            }
    auto edge_entry = [&](int a, int b, bool add) -> double* {
        if (vertex_slot[a] < 0 || vertex_slot[b] < 0) return nullptr;
        auto& list = edge_angle[vertex_slot[std::min(a, b)]];
        for (auto& [other, angle] : list)
            if (other == std::max(a, b)) return &angle;
        if (!add) return nullptr;
        list.push_back({std::max(a, b), 0.0});
        return &list.back().second;
    };
    for (int t : below)
        for (const auto& e : tet::kEdgeVertices)
            edge_entry(mesh.tets[t][e[0]], mesh.tets[t][e[1]], true);
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t)) continue;
        const auto& tv = mesh.tets[t];
        if (!(vertex_slot[tv[0]] >= 0 || vertex_slot[tv[1]] >= 0 || vertex_slot[tv[2]] >= 0 ||
              vertex_slot[tv[3]] >= 0))
            continue;
        const Vec3 &a = mesh.points[tv[0]], &b = mesh.points[tv[1]], &c = mesh.points[tv[2]],
                   &d = mesh.points[tv[3]];
        if (vertex_slot[tv[0]] >= 0) vertex_angle[vertex_slot[tv[0]]] += solid_angle(a, b, c, d);
        if (vertex_slot[tv[1]] >= 0) vertex_angle[vertex_slot[tv[1]]] += solid_angle(b, a, c, d);
        if (vertex_slot[tv[2]] >= 0) vertex_angle[vertex_slot[tv[2]]] += solid_angle(c, a, b, d);
        if (vertex_slot[tv[3]] >= 0) vertex_angle[vertex_slot[tv[3]]] += solid_angle(d, a, b, c);
        const auto angles = dihedral_angles_deg(a, b, c, d);
        for (int e = 0; e < 6; ++e)
            if (double* sum =
                    edge_entry(tv[tet::kEdgeVertices[e][0]], tv[tet::kEdgeVertices[e][1]], false))
                *sum += angles[e];
    }
    std::vector<Triangle> poor;
    if (options.kept_surface)
        for (const auto& tri : boundary)
            if (triangle_quality(mesh.points[tri[0]], mesh.points[tri[1]], mesh.points[tri[2]]) <
                options.floor)
            {
                Triangle key = tri;
                std::sort(key.begin(), key.end());
                poor.push_back(key);
            }
    std::sort(poor.begin(), poor.end());
    int forced = 0;
    for (int t : below)
    {
        const auto& tv = mesh.tets[t];
        bool is_forced = false;
        for (int v : tv)
            is_forced = is_forced || (vertex_slot[v] >= 0 && vertex_angle[vertex_slot[v]] <
                                                                 options.sharp_corner_steradians);
        for (const auto& e : tet::kEdgeVertices)
            if (const double* sum = edge_entry(tv[e[0]], tv[e[1]], false))
                is_forced = is_forced || *sum < options.sharp_ridge_deg;
        for (int f = 0; f < 4 && !poor.empty(); ++f)
        {
            Triangle key;
            for (int k = 0; k < 3; ++k) key[k] = tv[tet::kFaceVertices[f][k]];
            std::sort(key.begin(), key.end());
            is_forced = is_forced || std::binary_search(poor.begin(), poor.end(), key);
        }
        forced += is_forced;
    }
    return forced;
}

}  // namespace

namespace
{

/// The tets' shapes in the metric: Qe at the centroid's metric, and Mmg's quality.
void add_metric_quality(const TetMesh& mesh, const SizeField& field, QualityReport& report)
{
    std::vector<Metric> at_vertex(mesh.num_vertices(), Metric::Zero());
    std::vector<char> known(mesh.num_vertices(), 0);
    double qe_sum = 0.0, mmg_sum = 0.0;
    double qe_min = std::numeric_limits<double>::infinity(), mmg_min = qe_min;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t)) continue;
        const auto& tv = mesh.tets[t];
        Metric mean = Metric::Zero();
        for (int v : tv)
        {
            if (!known[v]) at_vertex[v] = field.metric(mesh.points[v]), known[v] = 1;
            mean += 0.25 * at_vertex[v];
        }
        const Vec3 &a = mesh.points[tv[0]], &b = mesh.points[tv[1]], &c = mesh.points[tv[2]],
                   &d = mesh.points[tv[3]];
        const double qe = metric_tet_quality(field.metric(0.25 * (a + b + c + d)), a, b, c, d);
        const double mmg = mmg_tet_quality(mean, a, b, c, d);
        qe_sum += qe;
        mmg_sum += mmg;
        qe_min = std::min(qe_min, qe);
        mmg_min = std::min(mmg_min, mmg);
    }
    report.anisotropic = true;
    if (report.tets == 0) return;
    report.min_metric_qe = qe_min;
    report.mean_metric_qe = qe_sum / report.tets;
    report.min_mmg_quality = mmg_min;
    report.mean_mmg_quality = mmg_sum / report.tets;
}

}  // namespace

QualityReport compute_quality_report(const TetMesh& mesh, const SizeField* field,
                                     const QualityReportOptions& options)
{
    QualityReport report;
    report.qe_floor = options.floor;
    std::vector<int> below;
    const int nv = mesh.num_vertices();
    auto in_range = [nv](const TetVertices& tv) {
        return std::all_of(tv.begin(), tv.end(), [nv](int v) { return v >= 0 && v < nv; });
    };

    // tets: volume, Qe, dihedral angles (tracked as cosines: acos only twice at the end)
    std::vector<char> used(nv, 0);
    double qe_sum = 0.0, min_qe = std::numeric_limits<double>::infinity();
    double min_cos = 1.0, max_cos = -1.0;
    long qe_ge_05 = 0, qe_lt_02 = 0;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t) || !in_range(mesh.tets[t])) continue;
        const auto& tv = mesh.tets[t];
        const Vec3 &a = mesh.points[tv[0]], &b = mesh.points[tv[1]], &c = mesh.points[tv[2]],
                   &d = mesh.points[tv[3]];
        for (int v : tv) used[v] = 1;
        ++report.tets;
        report.volume += signed_volume(a, b, c, d);
        const double qe = tet_quality(a, b, c, d);
        qe_sum += qe;
        min_qe = std::min(min_qe, qe);
        qe_ge_05 += qe >= 0.5;
        qe_lt_02 += qe < 0.2;
        if (qe < options.floor) below.push_back(t);
        ++report.qe_histogram[qe_histogram_bin(qe)];
        const auto normals = face_normals({&a, &b, &c, &d});
        for (const auto& faces : tet::kEdgeFaces)
        {
            const Vec3 &n = normals[faces[0]], &m = normals[faces[1]];
            if (n.isZero() || m.isZero()) continue;
            const double cosine = -n.dot(m);
            min_cos = std::min(min_cos, cosine);
            max_cos = std::max(max_cos, cosine);
        }
    }
    report.vertices = static_cast<int>(std::count(used.begin(), used.end(), 1));
    if (report.tets > 0)
    {
        report.min_qe = min_qe;
        report.mean_qe = qe_sum / report.tets;
        report.percent_qe_ge_05 = percent(qe_ge_05, report.tets);
        report.percent_qe_lt_02 = percent(qe_lt_02, report.tets);
        if (min_cos <= max_cos)
        {
            report.min_dihedral_deg = dihedral_cosine_to_deg(std::clamp(max_cos, -1.0, 1.0));
            report.max_dihedral_deg = dihedral_cosine_to_deg(std::clamp(min_cos, -1.0, 1.0));
        }
    }

    // boundary: the tets' own boundary faces, not mesh.triangles (which the checker compares)
    const std::vector<Triangle> boundary = tet_boundary_faces(mesh);
    report.boundary_triangles = static_cast<int>(boundary.size());
    report.declared_triangles = static_cast<int>(mesh.triangles.size());
    report.enclosed_volume = enclosed_volume(mesh.points, boundary);
    report.below_floor = static_cast<int>(below.size());
    if (!below.empty()) report.forced_below_floor = count_forced(mesh, below, boundary, options);
    if (!boundary.empty())
    {
        double sum = 0.0, lowest = std::numeric_limits<double>::infinity();
        for (const auto& tri : boundary)
        {
            const double q =
                triangle_quality(mesh.points[tri[0]], mesh.points[tri[1]], mesh.points[tri[2]]);
            sum += q;
            lowest = std::min(lowest, q);
        }
        report.min_boundary_triangle_qe = lowest;
        report.mean_boundary_triangle_qe = sum / boundary.size();
    }

    // edges: lengths, and against the field at their midpoints
    const std::vector<Edge> edges = unique_tet_edges(mesh);
    report.edges = static_cast<long>(edges.size());
    if (edges.empty()) return report;
    report.has_size = field != nullptr;
    double min_length = std::numeric_limits<double>::infinity(), max_length = 0.0;
    double qt_sum = 0.0, ratio_sum = 0.0;
    double min_qt = std::numeric_limits<double>::infinity();
    double min_ratio = std::numeric_limits<double>::infinity(), max_ratio = 0.0;
    long qt_ok = 0, too_long = 0, too_short = 0, unit = 0;
    for (const auto& e : edges)
    {
        const Vec3 &a = mesh.points[e[0]], &b = mesh.points[e[1]];
        const double length = (b - a).norm();
        min_length = std::min(min_length, length);
        max_length = std::max(max_length, length);
        if (!field) continue;
        const EdgeInField edge{length, edge_target_size(*field, a, b)};
        const double qt = edge.quality();
        const double ratio = edge.in_field();
        qt_sum += qt;
        ratio_sum += ratio;
        min_qt = std::min(min_qt, qt);
        min_ratio = std::min(min_ratio, ratio);
        max_ratio = std::max(max_ratio, ratio);
        qt_ok += qt >= kSizeQualityThreshold;
        too_long += edge.too_long();
        too_short += edge.too_short();
        ++report.length_ratio_histogram[length_ratio_histogram_bin(ratio)];
        unit += ratio >= std::sqrt(0.5) && ratio <= std::sqrt(2.0);
    }
    report.min_edge_length = min_length;
    report.max_edge_length = max_length;
    if (field)
    {
        report.percent_qt_ge_066 = percent(qt_ok, report.edges);
        report.percent_too_long = percent(too_long, report.edges);
        report.percent_too_short = percent(too_short, report.edges);
        report.min_qt = min_qt;
        report.mean_qt = qt_sum / report.edges;
        report.min_length_ratio = min_ratio;
        report.max_length_ratio = max_ratio;
        report.mean_length_ratio = ratio_sum / report.edges;
        report.percent_unit_length = percent(unit, report.edges);
        if (field->anisotropic()) add_metric_quality(mesh, *field, report);
    }
    return report;
}

std::string format_quality_table(const QualityReport& r)
{
    std::vector<std::pair<std::string, std::string>> rows;
    rows.push_back({"vertices", std::to_string(r.vertices)});
    rows.push_back({"tets", std::to_string(r.tets)});
    rows.push_back({"edges", std::to_string(r.edges)});
    rows.push_back({"boundary triangles", std::to_string(r.boundary_triangles) +
                                              "  (stored triangles " +
                                              std::to_string(r.declared_triangles) + ")"});
    rows.push_back(
        {"volume", fixed(r.volume, 9) + "  (enclosed " + fixed(r.enclosed_volume, 9) + ")"});
    rows.push_back({"Qe min / mean", fixed(r.min_qe, 6) + " / " + fixed(r.mean_qe, 6)});
    rows.push_back({"Qe >= 0.5", fixed(r.percent_qe_ge_05, 2) + " %"});
    rows.push_back({"Qe < 0.2", fixed(r.percent_qe_lt_02, 2) + " %"});
    rows.push_back({"Qe < " + fixed(r.qe_floor, 1),
                    std::to_string(r.below_floor) + " tets (" +
                        std::to_string(r.forced_below_floor) +
                        " forced by sharp input ridges or corners, or kept triangles)"});
    {
        std::string bins;
        for (int k = 0; k < 10; ++k) bins += (k ? " " : "") + std::to_string(r.qe_histogram[k]);
        rows.push_back({"Qe histogram (tenths)", bins});
    }
    rows.push_back({"dihedral min / max",
                    fixed(r.min_dihedral_deg, 2) + " / " + fixed(r.max_dihedral_deg, 2) + " deg"});
    rows.push_back(
        {"boundary triangle Qe min / mean",
         fixed(r.min_boundary_triangle_qe, 6) + " / " + fixed(r.mean_boundary_triangle_qe, 6)});
    rows.push_back({"edge length min / max",
                    fixed(r.min_edge_length, 6) + " / " + fixed(r.max_edge_length, 6)});
    if (r.has_size)
    {
        rows.push_back({"Qt >= 0.66", fixed(r.percent_qt_ge_066, 2) + " %"});
        rows.push_back({"too long (L > 1.515 hth)", fixed(r.percent_too_long, 2) + " %"});
        rows.push_back({"too short (L < 0.66 hth)", fixed(r.percent_too_short, 2) + " %"});
        rows.push_back({"Qt min / mean", fixed(r.min_qt, 6) + " / " + fixed(r.mean_qt, 6)});
        rows.push_back({"L/hth min / mean / max", fixed(r.min_length_ratio, 4) + " / " +
                                                      fixed(r.mean_length_ratio, 4) + " / " +
                                                      fixed(r.max_length_ratio, 4)});
        std::string bins;
        for (int k = 0; k < 8; ++k)
            bins += (k ? " " : "") + std::to_string(r.length_ratio_histogram[k]);
        rows.push_back({"L/hth histogram", bins});
        rows.push_back({"  (bins)", "<0.5 0.5-0.66 0.66-0.8 0.8-1 1-1.25 1.25-1.515 1.515-2 >2"});
        rows.push_back({"L/hth in [0.707, 1.414]", fixed(r.percent_unit_length, 2) + " %"});
        if (r.anisotropic)
        {
            rows.push_back({"metric Qe min / mean",
                            fixed(r.min_metric_qe, 6) + " / " + fixed(r.mean_metric_qe, 6)});
            rows.push_back({"metric quality (Mmg) min / mean",
                            fixed(r.min_mmg_quality, 6) + " / " + fixed(r.mean_mmg_quality, 6)});
        }
    }
    else
    {
        rows.push_back({"size", "no size field given"});
    }
    std::size_t width = 0;
    for (const auto& row : rows) width = std::max(width, row.first.size());
    std::ostringstream out;
    for (const auto& [name, value] : rows)
        out << name << std::string(width + 2 - name.size(), ' ') << value << "\n";
    return out.str();
}

std::string quality_report_json(const QualityReport& r)
{
    std::ostringstream out;
    auto array = [](const auto& values) {
        std::string text = "[";
        for (std::size_t i = 0; i < values.size(); ++i)
            text += (i ? ", " : "") + std::to_string(values[i]);
        return text + "]";
    };
    out << "{\n";
    out << "  \"vertices\": " << r.vertices << ",\n";
    out << "  \"tets\": " << r.tets << ",\n";
    out << "  \"boundary_triangles\": " << r.boundary_triangles << ",\n";
    out << "  \"declared_triangles\": " << r.declared_triangles << ",\n";
    out << "  \"edges\": " << r.edges << ",\n";
    out << "  \"volume\": " << json_number(r.volume) << ",\n";
    out << "  \"enclosed_volume\": " << json_number(r.enclosed_volume) << ",\n";
    out << "  \"min_qe\": " << json_number(r.min_qe) << ",\n";
    out << "  \"mean_qe\": " << json_number(r.mean_qe) << ",\n";
    out << "  \"qe_histogram\": " << array(r.qe_histogram) << ",\n";
    out << "  \"percent_qe_ge_05\": " << json_number(r.percent_qe_ge_05) << ",\n";
    out << "  \"percent_qe_lt_02\": " << json_number(r.percent_qe_lt_02) << ",\n";
    out << "  \"qe_floor\": " << json_number(r.qe_floor) << ",\n";
    out << "  \"below_floor\": " << r.below_floor << ",\n";
    out << "  \"forced_below_floor\": " << r.forced_below_floor << ",\n";
    out << "  \"min_dihedral_deg\": " << json_number(r.min_dihedral_deg) << ",\n";
    out << "  \"max_dihedral_deg\": " << json_number(r.max_dihedral_deg) << ",\n";
    out << "  \"min_boundary_triangle_qe\": " << json_number(r.min_boundary_triangle_qe) << ",\n";
    out << "  \"mean_boundary_triangle_qe\": " << json_number(r.mean_boundary_triangle_qe) << ",\n";
    out << "  \"min_edge_length\": " << json_number(r.min_edge_length) << ",\n";
    out << "  \"max_edge_length\": " << json_number(r.max_edge_length) << ",\n";
    out << "  \"has_size\": " << (r.has_size ? "true" : "false");
    if (r.has_size)
    {
        out << ",\n";
        out << "  \"percent_qt_ge_066\": " << json_number(r.percent_qt_ge_066) << ",\n";
        out << "  \"percent_too_long\": " << json_number(r.percent_too_long) << ",\n";
        out << "  \"percent_too_short\": " << json_number(r.percent_too_short) << ",\n";
        out << "  \"min_qt\": " << json_number(r.min_qt) << ",\n";
        out << "  \"mean_qt\": " << json_number(r.mean_qt) << ",\n";
        out << "  \"min_length_ratio\": " << json_number(r.min_length_ratio) << ",\n";
        out << "  \"mean_length_ratio\": " << json_number(r.mean_length_ratio) << ",\n";
        out << "  \"max_length_ratio\": " << json_number(r.max_length_ratio) << ",\n";
        out << "  \"length_ratio_histogram\": " << array(r.length_ratio_histogram) << ",\n";
        out << "  \"length_ratio_bin_edges\": [0, 0.5, 0.66, 0.8, 1, 1.25, 1.515, 2, null],\n";
        out << "  \"percent_unit_length\": " << json_number(r.percent_unit_length) << ",\n";
        out << "  \"anisotropic\": " << (r.anisotropic ? "true" : "false");
        if (r.anisotropic)
        {
            out << ",\n  \"min_metric_qe\": " << json_number(r.min_metric_qe) << ",\n";
            out << "  \"mean_metric_qe\": " << json_number(r.mean_metric_qe) << ",\n";
            out << "  \"min_mmg_quality\": " << json_number(r.min_mmg_quality) << ",\n";
            out << "  \"mean_mmg_quality\": " << json_number(r.mean_mmg_quality);
        }
    }
    out << "\n}\n";
    return out.str();
}

void write_quality_json(const QualityReport& report, const std::string& path)
{
    const std::string json = quality_report_json(report);
    write_file_atomically(path, [&](std::ostream& out) { out << json; });
}

void write_quality_svg(const QualityReport& r, const std::string& path)
{
    const double panel_width = 420, panel_height = 260, margin = 40, top = 70;
    const double width = 2 * panel_width + 3 * margin, height = top + panel_height + 60;
    std::ostringstream svg;
    svg << "<?xml version='1.0' encoding='UTF-8'?>\n"
        << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='" << height
        << "' font-family='sans-serif'>\n"
        << "<rect width='100%' height='100%' fill='white'/>\n";
    svg << "<text x='" << margin << "' y='24' font-size='14'>" << r.tets << " tets, " << r.vertices
        << " vertices, " << r.edges << " edges; Qe min " << fixed(r.min_qe, 4) << ", mean "
        << fixed(r.mean_qe, 4) << "; dihedral " << fixed(r.min_dihedral_deg, 1) << "-"
        << fixed(r.max_dihedral_deg, 1) << " deg</text>\n";

    std::vector<long> qe_counts(r.qe_histogram.begin(), r.qe_histogram.end());
    std::vector<std::string> qe_labels, qe_colors;
    for (int k = 0; k < 10; ++k)
    {
        qe_labels.push_back(fixed(k / 10.0, 1));
        qe_colors.push_back(k < 2 ? "#d62728" : k < 5 ? "#ff9f1c" : "#2ca02c");
    }
    draw_histogram(svg, margin, top, panel_width, panel_height,
                   "Qe (shape), " + fixed(r.percent_qe_ge_05, 1) + " % >= 0.5", qe_counts,
                   qe_labels, qe_colors);

    const double x1 = 2 * margin + panel_width;
    if (r.has_size)
    {
        std::vector<long> counts(r.length_ratio_histogram.begin(), r.length_ratio_histogram.end());
        const std::vector<std::string> labels = {"<0.5", "0.5",  "0.66",  "0.8",
                                                 "1",    "1.25", "1.515", ">2"};
        const std::vector<std::string> colors = {"#d62728", "#ff9f1c", "#2ca02c", "#2ca02c",
                                                 "#2ca02c", "#2ca02c", "#ff9f1c", "#d62728"};
        draw_histogram(svg, x1, top, panel_width, panel_height,
                       "L/hth (size), " + fixed(r.percent_qt_ge_066, 1) + " % with Qt >= 0.66",
                       counts, labels, colors);
    }
    else
    {
        svg << "<text x='" << x1 + panel_width / 2 << "' y='" << top + panel_height / 2
            << "' text-anchor='middle' font-size='15'>no size field: L/hth not measured</text>\n";
    }
    svg << "</svg>\n";
    const std::string text = svg.str();
    write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace hdimesh::volume
