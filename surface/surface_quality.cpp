#include "surface/surface_quality.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "surface/detail/closest_point_tree.h"

namespace hdimesh::surface
{
namespace
{

std::array<Vec3d, 3> face_points(const SurfaceMesh& mesh, FaceHandle f)
{
    auto fv = mesh.cfv_iter(f);
    const Vec3d a = mesh.point(*fv);
    const Vec3d b = mesh.point(*++fv);
    const Vec3d c = mesh.point(*++fv);
    return {a, b, c};
}

double edge_size(const SurfaceMesh& mesh, EdgeHandle e, const OpenMesh::VPropHandleT<double>* sizes,
                 double uniform_size)
{
    if (sizes)
    {
        const auto h = mesh.halfedge_handle(e, 0);
        const double s0 = mesh.property(*sizes, mesh.from_vertex_handle(h));
        const double s1 = mesh.property(*sizes, mesh.to_vertex_handle(h));
        if (s0 > 0.0 && s1 > 0.0) return 0.5 * (s0 + s1);
    }
    return uniform_size;
}

std::vector<Vec3d> samples(const SurfaceMesh& mesh)
{
    std::vector<Vec3d> out;
    out.reserve(mesh.n_vertices() + mesh.n_edges() + mesh.n_faces());
    for (auto v : mesh.vertices())
        if (!mesh.is_isolated(v)) out.push_back(mesh.point(v));
    for (auto e : mesh.edges())
    {
        const auto h = mesh.halfedge_handle(e, 0);
        out.push_back(
            0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h))));
    }
    for (auto f : mesh.faces())
    {
        const auto p = face_points(mesh, f);
        out.push_back((p[0] + p[1] + p[2]) / 3.0);
    }
    return out;
}

ClosestPointTree triangle_tree(const SurfaceMesh& mesh)
{
    std::vector<std::array<Vec3d, 3>> tris;
    tris.reserve(mesh.n_faces());
    for (auto f : mesh.faces()) tris.push_back(face_points(mesh, f));
    return ClosestPointTree::from_triangles(std::move(tris));
}

double max_distance(const std::vector<Vec3d>& points, const ClosestPointTree& tree)
{
    double worst = 0.0;
    for (const Vec3d& p : points) worst = std::max(worst, tree.closest(p).distance);
    return worst;
}

}  // namespace

std::array<double, 3> triangle_angles_deg(const Vec3d& a, const Vec3d& b, const Vec3d& c)
{
    auto angle = [](const Vec3d& apex, const Vec3d& p, const Vec3d& q) {
        const Vec3d u = p - apex, v = q - apex;
        const double s = OpenMesh::cross(u, v).norm(), co = OpenMesh::dot(u, v);
        return std::atan2(s, co) * 180.0 / M_PI;
    };
    return {angle(a, b, c), angle(b, c, a), angle(c, a, b)};
}

double triangle_min_angle_deg(const Vec3d& a, const Vec3d& b, const Vec3d& c)
{
    const auto angles = triangle_angles_deg(a, b, c);
    return std::min({angles[0], angles[1], angles[2]});
}

double face_qe(const SurfaceMesh& mesh, FaceHandle f)
{
    const auto p = face_points(mesh, f);
    return triangle_qe(p[0], p[1], p[2]);
}

double bounding_box_diagonal(const SurfaceMesh& mesh)
{
    Vec3d lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    bool any = false;
    for (auto v : mesh.vertices())
    {
        lo.minimize(mesh.point(v));
        hi.maximize(mesh.point(v));
        any = true;
    }
    return any ? (hi - lo).norm() : 0.0;
}

QualityReport measure_quality(const SurfaceMesh& mesh, double uniform_size)
{
    QualityReport r;
    r.vertices = mesh.n_vertices();
    r.faces = mesh.n_faces();
    r.edges = mesh.n_edges();
    r.diagonal = bounding_box_diagonal(mesh);
    if (mesh.n_faces() == 0) return r;
    r.qe_min = std::numeric_limits<double>::max();
    r.min_angle_deg = 180.0;
    std::size_t good_qe = 0, good_angles = 0;
    double qe_sum = 0.0;
    for (auto f : mesh.faces())
    {
        const auto p = face_points(mesh, f);
        const double q = triangle_qe(p[0], p[1], p[2]);
        const auto angles = triangle_angles_deg(p[0], p[1], p[2]);
        r.qe_min = std::min(r.qe_min, q);
        qe_sum += q;
        r.qe_histogram[std::min(9, static_cast<int>(q * 10.0))] += 1;
        if (q >= 0.7) ++good_qe;
        const double lo = std::min({angles[0], angles[1], angles[2]});
        const double hi = std::max({angles[0], angles[1], angles[2]});
        r.min_angle_deg = std::min(r.min_angle_deg, lo);
        r.max_angle_deg = std::max(r.max_angle_deg, hi);
        if (lo >= 25.0) ++good_angles;
    }
    const double nf = static_cast<double>(mesh.n_faces());
    r.qe_mean = qe_sum / nf;
    r.percent_qe_ge_07 = 100.0 * good_qe / nf;
    r.percent_all_angles_ge_25 = 100.0 * good_angles / nf;

    OpenMesh::VPropHandleT<double> sizes;
    const bool has_sizes = mesh.get_property_handle(sizes, property_names::vertex_size);
    std::size_t good_qt = 0, too_long = 0, too_short = 0, measured = 0;
    for (auto e : mesh.edges())
    {
        const double h = uniform_size > 0.0 ? uniform_size
                                            : edge_size(mesh, e, has_sizes ? &sizes : nullptr, 0.0);
        if (!(h > 0.0)) continue;
        ++measured;
        const double len = mesh.calc_edge_length(e);
        const double qt = size_quality(len, h);
        if (qt >= kSizeQualityThreshold)
            ++good_qt;
        else if (len > h)
            ++too_long;
        else
            ++too_short;
    }
    if (measured > 0)
    {
        r.percent_qt_ge_066 = 100.0 * good_qt / measured;
        r.percent_too_long = 100.0 * too_long / measured;
        r.percent_too_short = 100.0 * too_short / measured;
    }
    return r;
}

std::array<double, 2> hausdorff_distance(const SurfaceMesh& a, const SurfaceMesh& b)
{
    const ClosestPointTree tree_a = triangle_tree(a), tree_b = triangle_tree(b);
    return {max_distance(samples(a), tree_b), max_distance(samples(b), tree_a)};
}

std::vector<DistanceSample> farthest_samples(const SurfaceMesh& a, const SurfaceMesh& b,
                                             std::size_t count)
{
    const ClosestPointTree tree_b = triangle_tree(b);
    std::vector<DistanceSample> all;
    for (const Vec3d& p : samples(a))
    {
        const auto hit = tree_b.closest(p);
        all.push_back({p, hit.point, hit.distance});
    }
    count = std::min(count, all.size());
    std::partial_sort(
        all.begin(), all.begin() + static_cast<std::ptrdiff_t>(count), all.end(),
        [](const DistanceSample& x, const DistanceSample& y) { return x.distance > y.distance; });
    all.resize(count);
    return all;
}

std::string format_quality_table(const QualityReport& before, const QualityReport& after)
{
    std::string out;
    char line[256];
    auto row = [&](const char* name, const std::string& x, const std::string& y) {
        std::snprintf(line, sizeof line, "  %-26s %14s %14s\n", name, x.c_str(), y.c_str());
        out += line;
    };
    auto num = [](double v, const char* fmt) {
        char buf[64];
        std::snprintf(buf, sizeof buf, fmt, v);
        return std::string(buf);
    };
    row("", "before", "after");
    row("vertices", num(static_cast<double>(before.vertices), "%.0f"),
        num(static_cast<double>(after.vertices), "%.0f"));
    row("triangles", num(static_cast<double>(before.faces), "%.0f"),
        num(static_cast<double>(after.faces), "%.0f"));
    row("Qe min", num(before.qe_min, "%.4f"), num(after.qe_min, "%.4f"));
    row("Qe mean", num(before.qe_mean, "%.4f"), num(after.qe_mean, "%.4f"));
    row("% Qe >= 0.7", num(before.percent_qe_ge_07, "%.2f"), num(after.percent_qe_ge_07, "%.2f"));
    row("min angle (deg)", num(before.min_angle_deg, "%.2f"), num(after.min_angle_deg, "%.2f"));
    row("max angle (deg)", num(before.max_angle_deg, "%.2f"), num(after.max_angle_deg, "%.2f"));
    row("% all angles >= 25", num(before.percent_all_angles_ge_25, "%.3f"),
        num(after.percent_all_angles_ge_25, "%.3f"));
    row("% edges Qt >= 0.66", num(before.percent_qt_ge_066, "%.2f"),
        num(after.percent_qt_ge_066, "%.2f"));
    row("% too long", num(before.percent_too_long, "%.2f"), num(after.percent_too_long, "%.2f"));
    row("% too short", num(before.percent_too_short, "%.2f"), num(after.percent_too_short, "%.2f"));
    if (after.hausdorff_to_model >= 0.0)
    {
        const double d = after.diagonal > 0.0 ? after.diagonal : 1.0;
        row("Hausdorff out->in / diag", "", num(after.hausdorff_to_model / d, "%.3e"));
        row("Hausdorff in->out / diag", "", num(after.hausdorff_from_model / d, "%.3e"));
    }
    out += "  Qe histogram (tenths):\n   ";
    for (int i = 0; i < 10; ++i)
    {
        std::snprintf(line, sizeof line, " %7zu", after.qe_histogram[i]);
        out += line;
    }
    out += "\n";
    return out;
}

SurfaceTopology measure_topology(const SurfaceMesh& mesh)
{
    SurfaceTopology t;
    t.vertices = static_cast<long>(mesh.n_vertices());
    t.edges = static_cast<long>(mesh.n_edges());
    t.faces = static_cast<long>(mesh.n_faces());
    // components: union-find over the edges, path halving
    std::vector<int> parent(mesh.n_vertices());
    for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
    auto find = [&](int x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    for (auto e : mesh.edges())
    {
        const auto h = mesh.halfedge_handle(e, 0);
        parent[find(mesh.from_vertex_handle(h).idx())] = find(mesh.to_vertex_handle(h).idx());
    }
    for (std::size_t i = 0; i < parent.size(); ++i)
        if (find(static_cast<int>(i)) == static_cast<int>(i)) ++t.components;
    // boundary loops: walk each unvisited boundary halfedge's cycle once
    std::vector<char> walked(mesh.n_halfedges(), 0);
    for (auto h : mesh.halfedges())
    {
        if (!mesh.is_boundary(h) || walked[h.idx()]) continue;
        ++t.boundary_loops;
        for (auto g = h; !walked[g.idx()]; g = mesh.next_halfedge_handle(g)) walked[g.idx()] = 1;
    }
    return t;
}

}  // namespace hdimesh::surface
