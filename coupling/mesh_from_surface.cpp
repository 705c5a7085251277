// A tet mesh from a closed surface: validate, find the regions, remesh, fill each region,
// optimize. See the header for the stages.
#include "coupling/mesh_from_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>
#include <sstream>
#include <unordered_set>

#include "common/errors.h"
#include "common/size_quality.h"
#include "common/stage_timer.h"
#include "coupling/detail/surface_sizes.h"
#include "coupling/detail/thin_parts.h"
#include "hdi/knn.h"
#include "surface/features.h"
#include "surface/sizing.h"
#include "surface/soup_repair.h"
#include "surface/surface_model.h"
#include "volume/check/check.h"
#include "volume/check/surface_regions.h"
#include "volume/size/size_fields.h"

namespace hdimesh::coupling
{

using detail::ClosestSurfaceSize;
using detail::KeptSurfaceSize;
using surface::SurfaceMesh;
using surface::TriangleSoup;
using surface::Vec3d;
using volume::TetMesh;
using volume::Triangle;
using volume::Vec3;

namespace
{

/// The validated surface, compact: only the points the triangles use, renumbered in order.
struct Boundary
{
    std::vector<Vec3> points;
    std::vector<int> new2old_point;  ///< into the caller's points
    std::vector<Triangle> triangles;
    std::vector<int> refs;
    std::vector<volume::Edge> ridges;  ///< feature edges of the remeshed surface
    std::vector<int> corners;
};

Boundary compact_boundary(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                          const std::vector<int>& refs)
{
    Boundary b;
    std::vector<int> old2new(points.size(), -1);
    b.triangles = triangles;
    for (auto& t : b.triangles)
        for (int& v : t)
        {
            if (old2new[v] < 0)
            {
                old2new[v] = static_cast<int>(b.points.size());
                b.points.push_back(points[v]);
                b.new2old_point.push_back(v);
            }
            v = old2new[v];
        }
    b.refs = refs;
    return b;
}

/// An OpenMesh surface over the boundary (valid: the checks passed), every vertex smooth.
SurfaceMesh to_surface_mesh(const Boundary& b)
{
    SurfaceMesh mesh;
    surface::SurfaceProperties props(mesh);
    std::vector<surface::VertexHandle> handles;
    handles.reserve(b.points.size());
    for (const auto& p : b.points) handles.push_back(mesh.add_vertex(Vec3d(p[0], p[1], p[2])));
    for (std::size_t f = 0; f < b.triangles.size(); ++f)
    {
        const auto& t = b.triangles[f];
        const auto face = mesh.add_face(handles[t[0]], handles[t[1]], handles[t[2]]);
        if (!face.is_valid())
            throw TopologyError("triangle " + std::to_string(f + 1) +
                                " cannot be added to the surface mesh");
        mesh.property(props.face_ref, face) = b.refs[f];
    }
    for (auto v : mesh.vertices())
    {
        mesh.property(props.vertex_class, v) = surface::VertexClass::Smooth;
        mesh.property(props.vertex_curve, v) = surface::kNoCurve;
        mesh.property(props.vertex_size, v) = 0.0;
    }
    for (auto e : mesh.edges()) mesh.property(props.edge_curve, e) = surface::kNoCurve;
    return mesh;
}

/// The remeshed surface back into arrays, with its ridges and corners.
Boundary from_surface_mesh(SurfaceMesh& mesh)
{
    Boundary b;
    const surface::SurfaceProperties props(mesh);
    std::vector<int> old2new(mesh.n_vertices(), -1);
    for (auto v : mesh.vertices())
    {
        if (mesh.status(v).deleted()) continue;
        old2new[v.idx()] = static_cast<int>(b.points.size());
        const Vec3d& p = mesh.point(v);
        b.points.emplace_back(p[0], p[1], p[2]);
        b.new2old_point.push_back(v.idx());
        if (mesh.property(props.vertex_class, v) == surface::VertexClass::Corner)
            b.corners.push_back(old2new[v.idx()]);
    }
    for (auto f : mesh.faces())
    {
        if (mesh.status(f).deleted()) continue;
        Triangle t;
        int k = 0;
        for (auto v : mesh.fv_range(f)) t[k++] = old2new[v.idx()];
        b.triangles.push_back(t);
        b.refs.push_back(mesh.property(props.face_ref, f));
    }
    for (auto e : mesh.edges())
    {
        if (mesh.status(e).deleted() || mesh.property(props.edge_curve, e) == surface::kNoCurve)
            continue;
        const auto h = mesh.halfedge_handle(e, 0);
        b.ridges.push_back(
            {old2new[mesh.from_vertex_handle(h).idx()], old2new[mesh.to_vertex_handle(h).idx()]});
    }
    return b;
}

constexpr int kFoldRounds = 4;       // remeshes after the first, each halving at the folds
constexpr double kFoldRadius = 3.0;  // ... the sizes within this many local sizes of a crossing

/// The centroids of the remeshed triangles that cross another (none when the check finds no
/// crossing).
std::vector<Vec3> fold_centres(const Boundary& b, const volume::SurfaceCheckOptions& check)
{
    std::vector<Vec3> centres;
    if (!check.check_self_intersections) return centres;
    for (const auto& defect : volume::check_closed_surface(b.points, b.triangles, check))
        if (defect.kind == volume::SurfaceDefectKind::SelfIntersection)
            for (int f : defect.faces)
            {
                const Triangle& t = b.triangles[f];
                centres.push_back((b.points[t[0]] + b.points[t[1]] + b.points[t[2]]) / 3.0);
            }
    return centres;
}

/// Per input vertex, the size the remesher aimed at there (its target on the remeshed
/// surface, interpolated), halved within kFoldRadius sizes of a fold centre.
std::vector<double> sizes_halved_near(const SurfaceMesh& input, SurfaceMesh& remeshed,
                                      const std::vector<Vec3>& folds)
{
    const surface::SurfaceProperties props(remeshed);
    std::vector<double> targets(remeshed.n_vertices(), 0.0);
    for (auto v : remeshed.vertices()) targets[v.idx()] = remeshed.property(props.vertex_size, v);
    const surface::SurfaceModel model(remeshed);
    const hdi::KnnIndex index(folds);
    std::vector<double> sizes(input.n_vertices(), 0.0);
    for (auto v : input.vertices())
    {
        const Vec3d& p = input.point(v);
        double size = model.interpolate(p, targets);
        int nearest = -1;
        double squared = 0;
        index.nearest(Vec3(p[0], p[1], p[2]), 1, &nearest, &squared);
        if (nearest >= 0 && squared < kFoldRadius * kFoldRadius * size * size) size *= 0.5;
        sizes[v.idx()] = size;
    }
    return sizes;
}

void check_sizing(const SurfaceSizing& s, std::size_t num_points, const std::string& source)
{
    const int given = int(s.hsiz != 0) + int(s.hausd != 0) + int(!s.vertex_sizes.empty()) +
                      int(s.field != nullptr);
    if (given > 1)
        throw InputError(
            "give at most one of a uniform size, hausd, sizes at the "
            "vertices and a size field");
    auto positive_or_unset = [](double x) { return x == 0 || (std::isfinite(x) && x > 0); };
    if (!positive_or_unset(s.hsiz)) throw InputError("the uniform size must be positive");
    if (!positive_or_unset(s.hausd)) throw InputError("hausd must be positive");
    if (!positive_or_unset(s.hmin) || !positive_or_unset(s.hmax))
        throw InputError("hmin and hmax must be positive");
    if (s.hmin > 0 && s.hmax > 0 && s.hmin > s.hmax) throw InputError("hmin is larger than hmax");
    if (!s.vertex_sizes.empty())
    {
        if (s.vertex_sizes.size() != num_points)
            throw InputError(source + ": " + std::to_string(s.vertex_sizes.size()) + " sizes for " +
                             std::to_string(num_points) + " points");
        for (std::size_t v = 0; v < num_points; ++v)
            if (!(std::isfinite(s.vertex_sizes[v]) && s.vertex_sizes[v] > 0))
                throw InputError(source + ": the size at vertex " + std::to_string(v + 1) +
                                 " is not positive");
    }
}

surface::SizingOptions surface_sizing(const SurfaceSizing& s)
{
    surface::SizingOptions o;
    o.hsiz = s.hsiz;
    o.hausd = s.hausd;
    o.hmin = s.hmin;
    o.hmax = s.hmax;
    o.hgrad = s.hgrad != 0 ? s.hgrad : 1.3;
    return o;
}

/// Mean length of the surface edges at each vertex.
std::vector<double> mean_incident_edge_length(const SurfaceMesh& mesh)
{
    std::vector<double> sizes(mesh.n_vertices(), 0.0);
    for (auto v : mesh.vertices())
    {
        double sum = 0;
        int n = 0;
        for (auto w : mesh.vv_range(v))
        {
            sum += (mesh.point(w) - mesh.point(v)).norm();
            ++n;
        }
        sizes[v.idx()] = n ? sum / n : 0.0;
    }
    return sizes;
}

std::shared_ptr<const SizeField> clamped(std::shared_ptr<const SizeField> field,
                                         const SurfaceSizing& s)
{
    if (!(s.hmin > 0) && !(s.hmax > 0)) return field;
    return std::make_shared<volume::ClampedSize>(
        std::move(field), s.hmin, s.hmax > 0 ? s.hmax : std::numeric_limits<double>::infinity());
}

/// The thin parts of the input against the size wanted at its vertices (uniform or given per
/// vertex; none when the remesher chooses, from the curvature).
detail::ThinParts thin_parts(const SurfaceMesh& input, const surface::SurfaceRemeshSettings& s,
                             double grade, const detail::ThinPartOptions& options)
{
    std::vector<double> wanted = s.input_sizes;
    if (wanted.empty() && s.sizing.hsiz > 0) wanted.assign(input.n_vertices(), s.sizing.hsiz);
    if (wanted.empty()) return {};
    return detail::find_thin_parts(input, wanted, grade, options);
}

/// The surface to fill and its sizes: the input kept, or remeshed to the sizing.
Boundary prepare_boundary(const Boundary& input, const VolumeFromSurfaceOptions& options,
                          VolumeFromSurfaceReport& report)
{
    const SurfaceSizing& sizing = options.sizing;
    SurfaceMesh mesh = to_surface_mesh(input);
    std::vector<double> input_sizes;  // per input point of `mesh`
    if (!sizing.vertex_sizes.empty())
        for (int old : input.new2old_point) input_sizes.push_back(sizing.vertex_sizes[old]);
    else if (sizing.field)
        for (const auto& p : input.points) input_sizes.push_back(sizing.field->size(p));

    if (options.keep_surface)
    {
        if (sizing.hsiz > 0)
            report.field = std::make_shared<volume::ConstantSize>(sizing.hsiz);
        else if (sizing.field)
            report.field = sizing.field;
        else
        {
            const surface::SizingOptions o = surface_sizing(sizing);
            std::vector<double> sizes;
            if (!input_sizes.empty())
            {
                sizes = input_sizes;
                surface::bound_and_grade(mesh, sizes, o);
            }
            else if (sizing.hausd > 0)
            {
                surface::detect_features(mesh, options.remesh.features);
                const surface::SurfaceModel model(mesh);
                sizes = surface::curvature_sizes(mesh, model, o);
            }
            else
            {
                sizes = mean_incident_edge_length(mesh);
                surface::bound_and_grade(mesh, sizes, o);
            }
            report.field = std::make_shared<ClosestSurfaceSize>(mesh, std::move(sizes));
        }
        report.field = clamped(report.field, sizing);
        return input;
    }

    surface::SurfaceRemeshSettings settings = options.remesh;
    settings.sizing = surface_sizing(sizing);
    settings.input_sizes.clear();
    if (!input_sizes.empty())
    {
        // a field the same at every input point is a uniform size (the remesher's uniform path)
        const auto [lo, hi] = std::minmax_element(input_sizes.begin(), input_sizes.end());
        if (sizing.field && *lo == *hi)
            settings.sizing.hsiz = *lo;
        else
            settings.input_sizes = input_sizes;
    }
    if (!(settings.sizing.hsiz > 0) && settings.input_sizes.empty() && !(sizing.hausd > 0) &&
        !(sizing.hmax > 0))
        settings.sizing.hmax = 2.0 * surface::mean_edge_length(mesh);
    // Thin parts (ears, fins) get sizes their thickness allows, on the surface and in the volume.
    const double grade = settings.sizing.hgrad > 1 ? settings.sizing.hgrad - 1 : 0.3;
    detail::ThinPartOptions thin_options;
    thin_options.workers = options.adapt.workers;
    const detail::ThinParts thin = thin_parts(mesh, settings, grade, thin_options);
    settings.input_size_bounds = thin.bounds;
    const SurfaceMesh input_mesh = mesh;  // remesh_surface works in place
    report.remesh = surface::remesh_surface(mesh, settings);
    Boundary remeshed = from_surface_mesh(mesh);
    // A part thinner than the size (a finger, a tip) can fold the remeshed surface onto itself:
    // remesh again from the input with the sizes halved around each crossing, a few rounds.
    std::size_t last_folds = std::numeric_limits<std::size_t>::max();
    for (int round = 0; round < kFoldRounds; ++round)
    {
        const std::vector<Vec3> folds = fold_centres(remeshed, options.check);
        if (folds.empty()) break;
        // a round that did not reduce the crossings will not: stop (the check then refuses)
        if (folds.size() >= last_folds) break;
        last_folds = folds.size();
        settings.input_sizes = sizes_halved_near(input_mesh, mesh, folds);
        mesh = input_mesh;
        report.remesh = surface::remesh_surface(mesh, settings);
        remeshed = from_surface_mesh(mesh);
        ++report.fold_rounds;
    }

    if (sizing.hsiz > 0)
        report.field = std::make_shared<volume::ConstantSize>(sizing.hsiz);
    else if (sizing.field)
        report.field = sizing.field;
    else
    {
        const surface::SurfaceProperties props(mesh);
        std::vector<double> sizes(mesh.n_vertices(), 0.0);
        for (auto v : mesh.vertices()) sizes[v.idx()] = mesh.property(props.vertex_size, v);
        report.field = std::make_shared<ClosestSurfaceSize>(mesh, std::move(sizes));
    }
    if (!thin.points.empty() && (sizing.hsiz > 0 || sizing.field))
    {
        // the volume's bounds from the remeshed surface: dense where the input's triangles
        // may not be
        std::vector<double> wanted(mesh.n_vertices(), sizing.hsiz);
        if (!(sizing.hsiz > 0))
            for (auto v : mesh.vertices())
                wanted[v.idx()] = sizing.field->size(surface::to_point(mesh.point(v)));
        const detail::ThinParts remeshed_thin =
            detail::find_thin_parts(mesh, wanted, grade, thin_options);
        if (!remeshed_thin.points.empty())
            report.field = std::make_shared<detail::ThinPartSize>(report.field, remeshed_thin,
                                                                  grade, options.adapt.workers);
    }
    report.field = clamped(report.field, sizing);
    return remeshed;
}

double worst_quality(const TetMesh& mesh)
{
    double worst = std::numeric_limits<double>::infinity();
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_dead(t)) worst = std::min(worst, mesh.quality(t));
    return mesh.num_live_tets() ? worst : 0.0;
}

constexpr double kLocalCrossing = 4.0;  // local sizes a fold of crossing faces may span

std::string format_point(const Vec3& p)
{
    char text[96];
    std::snprintf(text, sizeof text, "(%.6g, %.6g, %.6g)", p[0], p[1], p[2]);
    return text;
}

std::string format_number(double x)
{
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return text;
}

/// The local size a hole's loop is measured in: the sizing's, or where it is only known after
/// the remesh (hausd, the default), its upper bound (hmax, else twice the mean edge).
std::function<double(const Vec3d&)> hole_size(const SurfaceSizing& s, const TriangleSoup& soup)
{
    const double hmin = s.hmin > 0 ? s.hmin : 0.0;
    const double hmax = s.hmax > 0 ? s.hmax : std::numeric_limits<double>::infinity();
    auto clamp = [hmin, hmax](double h) { return std::min(std::max(h, hmin), hmax); };
    if (s.hsiz > 0) return [h = clamp(s.hsiz)](const Vec3d&) { return h; };
    if (s.field)
        return [field = s.field, clamp](const Vec3d& p) {
            return clamp(field->size(surface::to_point(p)));
        };
    if (!s.vertex_sizes.empty())
    {
        std::vector<Vec3> points;
        for (const auto& p : soup.points) points.push_back(surface::to_point(p));
        auto index = std::make_shared<const hdi::KnnIndex>(points);
        return [index, sizes = s.vertex_sizes, clamp](const Vec3d& p) {
            int nearest = 0;
            double squared = 0;
            index->nearest(surface::to_point(p), 1, &nearest, &squared);
            return clamp(sizes[nearest]);
        };
    }
    if (s.hmax > 0) return [h = s.hmax](const Vec3d&) { return h; };
    double sum = 0;
    long count = 0;
    for (const auto& t : soup.triangles)
        for (int k = 0; k < 3; ++k)
        {
            const int a = t[k], b = t[(k + 1) % 3];
            if (a < 0 || b < 0 || a >= static_cast<int>(soup.points.size()) ||
                b >= static_cast<int>(soup.points.size()))
                continue;
            sum += (soup.points[a] - soup.points[b]).norm();
            ++count;
        }
    const double h = clamp(count ? 2.0 * sum / count : 0.0);
    return [h](const Vec3d&) { return h; };
}

/// The input's crossing pairs: where each cluster of crossing faces spans at most
/// kLocalCrossing local sizes, a fold the remesh clears (noted; the remeshed surface is
/// checked before the fill); a wider crossing (two parts through each other) is refused.
int note_crossings(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                   const std::string& source, const std::function<double(const Vec3d&)>& size,
                   std::optional<std::vector<volume::SurfaceDefect>> known, Workers* workers,
                   std::vector<std::string>& notes)
{
    std::vector<volume::SurfaceDefect> crossings;
    if (known)
        crossings = std::move(*known);
    else
    {
        volume::SurfaceCheckOptions check;
        check.workers = workers;
        for (auto& defect : volume::check_closed_surface(points, triangles, check))
            if (defect.kind == volume::SurfaceDefectKind::SelfIntersection)
                crossings.push_back(std::move(defect));
    }
    if (crossings.empty()) return 0;
    // clusters: faces of one pair, and faces sharing a point, belong together
    std::vector<int> faces;
    for (const auto& c : crossings) faces.insert(faces.end(), c.faces.begin(), c.faces.end());
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    auto slot = [&](int f) {
        return static_cast<int>(std::lower_bound(faces.begin(), faces.end(), f) - faces.begin());
    };
    std::vector<int> parent(faces.size());
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    auto unite = [&](int i, int j) {
        i = find(i);
        j = find(j);
        if (i != j) parent[std::max(i, j)] = std::min(i, j);
    };
    for (const auto& c : crossings)
        for (std::size_t k = 1; k < c.faces.size(); ++k) unite(slot(c.faces[0]), slot(c.faces[k]));
    std::vector<std::pair<int, int>> at_point;  // (point, slot)
    for (std::size_t i = 0; i < faces.size(); ++i)
        for (int v : triangles[faces[i]]) at_point.push_back({v, static_cast<int>(i)});
    std::sort(at_point.begin(), at_point.end());
    for (std::size_t k = 1; k < at_point.size(); ++k)
        if (at_point[k].first == at_point[k - 1].first)
            unite(at_point[k].second, at_point[k - 1].second);
    std::vector<Vec3> lo(faces.size(), Vec3::Constant(std::numeric_limits<double>::infinity()));
    std::vector<Vec3> hi(faces.size(), Vec3::Constant(-std::numeric_limits<double>::infinity()));
    for (std::size_t i = 0; i < faces.size(); ++i)
        for (int v : triangles[faces[i]])
        {
            const int r = find(static_cast<int>(i));
            lo[r] = lo[r].cwiseMin(points[v]);
            hi[r] = hi[r].cwiseMax(points[v]);
        }
    int clusters = 0;
    for (std::size_t i = 0; i < faces.size(); ++i)
    {
        if (find(static_cast<int>(i)) != static_cast<int>(i)) continue;
        ++clusters;
        const Vec3 centre = 0.5 * (lo[i] + hi[i]);
        const double h = size(surface::to_vec3d(centre));
        if ((hi[i] - lo[i]).norm() > kLocalCrossing * h)
            throw InputError(volume::format_surface_defects(crossings, source) +
                             "\n(a crossing spanning more than " + format_number(kLocalCrossing) +
                             " local sizes, near " + format_point(centre) +
                             ", is two parts through each other, not a fold the remesh clears)");
    }
    const Triangle& t = triangles[crossings[0].faces[0]];
    notes.push_back(source + ": " + std::to_string(crossings.size()) +
                    " pair(s) of triangles cross in " + std::to_string(clusters) +
                    " small fold(s) (the first near " +
                    format_point((points[t[0]] + points[t[1]] + points[t[2]]) / 3.0) +
                    "); the remeshed surface is checked instead");
    return static_cast<int>(crossings.size());
}

constexpr int kCutRounds = 3;  // rounds of cutting crossing folds out

/// The soup as the checker's arrays.
void soup_arrays(const TriangleSoup& soup, std::vector<Vec3>& points,
                 std::vector<Triangle>& triangles)
{
    points.clear();
    for (const auto& p : soup.points) points.emplace_back(p[0], p[1], p[2]);
    triangles.assign(soup.triangles.begin(), soup.triangles.end());
}

/// Crossing folds of the repaired input cut out with the ring of triangles around them, and the
/// holes closed again (a local repair in bounded rounds, as MeshFix's): a round is kept only
/// when its holes close and the surface stays closed and manifold. What still crosses is left
/// to note_crossings.
std::optional<std::vector<volume::SurfaceDefect>> cut_out_crossings(
    TriangleSoup& soup, std::vector<int>& source_point, const surface::SoupRepairOptions& repair,
    const std::string& source, Workers* workers, std::vector<std::string>& notes)
{
    std::vector<Vec3> points;
    std::vector<Triangle> triangles;
    volume::SurfaceCheckOptions topology;
    topology.check_self_intersections = false;
    volume::SurfaceCheckOptions crossings;
    crossings.workers = workers;
    for (int round = 0; round < kCutRounds; ++round)
    {
        soup_arrays(soup, points, triangles);
        std::vector<char> crossing(triangles.size(), 0);
        std::vector<volume::SurfaceDefect> found;
        for (auto& defect : volume::check_closed_surface(points, triangles, crossings))
            if (defect.kind == volume::SurfaceDefectKind::SelfIntersection)
            {
                for (int f : defect.faces) crossing[f] = 1;
                found.push_back(std::move(defect));
            }
        const int pairs = static_cast<int>(found.size());
        if (!pairs) return found;
        std::vector<char> near(points.size(), 0);
        for (std::size_t f = 0; f < triangles.size(); ++f)
            if (crossing[f])
                for (int v : triangles[f]) near[v] = 1;
        TriangleSoup trial;
        trial.points = soup.points;
        Vec3 first = Vec3::Zero();
        int cut = 0;
        for (std::size_t f = 0; f < triangles.size(); ++f)
        {
            const Triangle& t = triangles[f];
            if (near[t[0]] || near[t[1]] || near[t[2]])
            {
                if (cut++ == 0) first = (points[t[0]] + points[t[1]] + points[t[2]]) / 3.0;
                continue;
            }
            trial.triangles.push_back(soup.triangles[f]);
            trial.refs.push_back(soup.refs[f]);
        }
        surface::SoupRepairReport closed;
        try
        {
            surface::repair_soup(trial, source, repair, &closed);
        }
        catch (const InputError&)
        {
            return found;  // the soup kept: its crossings are these
        }
        soup_arrays(trial, points, triangles);
        if (!volume::check_closed_surface(points, triangles, topology).empty()) return found;
        for (int& p : closed.source_point) p = source_point[p];
        source_point = std::move(closed.source_point);
        soup = std::move(trial);
        notes.push_back(source + ": repaired: cut out " + std::to_string(cut) +
                        " triangles around " + std::to_string(pairs) +
                        " crossing pair(s) (the first near " + format_point(first) +
                        ") and closed " + std::to_string(closed.closed_holes) + " hole(s)");
    }
    return std::nullopt;  // the last round's soup is not checked yet
}

}  // namespace

TetMesh mesh_volume_from_surface(const TriangleSoup& soup, const VolumeFromSurfaceOptions& options,
                                 VolumeFromSurfaceReport* report_out)
{
    VolumeFromSurfaceReport report;
    const Stopwatch total;
    const std::string source = options.source.empty() ? "the surface" : options.source;
    report.input_points = static_cast<int>(soup.points.size());
    report.input_triangles = static_cast<int>(soup.triangles.size());
    if (soup.triangles.empty()) throw InputError(source + ": no triangles");
    check_sizing(options.sizing, soup.points.size(), source);

    Boundary boundary;
    VolumeFromSurfaceOptions repaired_options;  // sizes at the vertices follow the repair
    const VolumeFromSurfaceOptions* used = &options;
    {
        const StageTimer timer(report.seconds_check, report.cpu_seconds_check);
        std::vector<Vec3> points;
        std::vector<Triangle> triangles;
        std::vector<int> refs;
        if (options.repair.strict)
        {
            points.reserve(soup.points.size());
            for (const auto& p : soup.points) points.emplace_back(p[0], p[1], p[2]);
            triangles.assign(soup.triangles.begin(), soup.triangles.end());
            report.merged_points = volume::merge_coincident_points(points, triangles);
            volume::require_closed_surface(points, triangles, source, options.check);
            refs = soup.refs;
        }
        else
        {
            TriangleSoup repaired = soup;
            surface::SoupRepairReport repair;
            surface::SoupRepairOptions repair_options = options.repair;
            repair_options.close_holes = true;
            repair_options.local_size = hole_size(options.sizing, soup);
            surface::repair_soup(repaired, source, repair_options, &repair);
            report.merged_points = static_cast<int>(repair.merged_vertices);
            report.repairs = repair.notes;
            soup_arrays(repaired, points, triangles);
            // crossings are the remeshed surface's to clear (checked after it); with the input
            // kept they are refused
            volume::SurfaceCheckOptions topology = options.check;
            topology.check_self_intersections = options.keep_surface;
            if (const auto defects = volume::check_closed_surface(points, triangles, topology);
                !defects.empty())
                throw InputError(volume::format_surface_defects(defects, source) +
                                 "\n(holes up to " +
                                 format_number(repair_options.hole_size_factor) +
                                 " local sizes across are closed; larger ones are refused)");
            std::optional<std::vector<volume::SurfaceDefect>> crossings;
            if (!options.keep_surface && options.check.check_self_intersections)
            {
                crossings = cut_out_crossings(repaired, repair.source_point, repair_options, source,
                                              options.adapt.workers, report.repairs);
                soup_arrays(repaired, points, triangles);
            }
            if (!options.sizing.vertex_sizes.empty())
            {
                repaired_options = options;
                auto& sizes = repaired_options.sizing.vertex_sizes;
                sizes.clear();
                for (int old : repair.source_point)
                    sizes.push_back(options.sizing.vertex_sizes[old]);
                used = &repaired_options;
            }
            refs = repaired.refs;
            if (!options.keep_surface && options.check.check_self_intersections)
                report.input_crossings =
                    note_crossings(points, triangles, source, repair_options.local_size,
                                   std::move(crossings), options.adapt.workers, report.repairs);
        }
        const volume::SurfaceRegions regions = volume::find_surface_regions(points, triangles);
        report.turned_shells = regions.turned_shells;
        refs.resize(triangles.size(), 0);
        boundary = compact_boundary(points, regions.triangles, refs);
    }
    {
        const StageTimer timer(report.seconds_remesh, report.cpu_seconds_remesh);
        boundary = prepare_boundary(boundary, *used, report);
        for (const std::string& line : report.remesh.report.notes)
            report.repairs.push_back(source + ": " + line);  // a stage stopped at its bound
    }

    volume::SurfaceRegions regions;
    {
        const StageTimer timer(report.seconds_check, report.cpu_seconds_check);
        if (!options.keep_surface)
        {
            const auto defects =
                volume::check_closed_surface(boundary.points, boundary.triangles, options.check);
            if (!defects.empty())
                throw InputError(
                    volume::format_surface_defects(defects, source + " remeshed") +
                    "\n(the surface remeshed to this size cannot bound a volume: try a smaller "
                    "size, or keep the input surface with --keep-surface)");
        }
        regions = volume::find_surface_regions(boundary.points, boundary.triangles);
    }

    TetMesh mesh;
    {
        const StageTimer timer(report.seconds_fill, report.cpu_seconds_fill);
        report.shells = static_cast<int>(regions.shells.size());
        report.regions = static_cast<int>(regions.regions.size());
        report.voids = report.shells - report.regions;
        report.surface_points = static_cast<int>(boundary.points.size());
        report.surface_triangles = static_cast<int>(boundary.triangles.size());

        for (const auto& p : boundary.points) mesh.add_vertex(p, 0, volume::VertexClass::Surface);
        for (std::size_t r = 0; r < regions.regions.size(); ++r)
        {
            const int ref = regions.regions[r].ref;
            const std::vector<Triangle> faces = regions.region_faces(static_cast<int>(r));
            volume::CavityFill fill =
                volume::fill_cavity(mesh, faces, report.field.get(), options.fill);
            // a front stalled in a part thinner than its sizes closes with fewer points; the
            // refinement then brings the sizes back
            for (double scale = 2.0; !fill.filled && scale <= 8.0; scale *= 2.0)
            {
                const volume::ScaledSize coarser(*report.field, scale);
                fill = volume::fill_cavity(mesh, faces, &coarser, options.fill);
                if (fill.filled)
                    report.repairs.push_back(source + ": region " + std::to_string(ref) +
                                             ": the fill closed at " +
                                             std::to_string(static_cast<int>(scale)) +
                                             " x the sizes (it stalled at them); refined after");
            }
            if (!fill.filled)
                throw TopologyError(source + ": region " + std::to_string(ref) + " (" +
                                    std::to_string(faces.size()) +
                                    " triangles): the tet filler gave up: " + fill.failure);
            fill.ref = ref;
            report.fills.add(fill);
            report.fill_points += static_cast<int>(fill.new_points.size());
            volume::commit_cavity(mesh, fill);
        }
        for (std::size_t f = 0; f < regions.triangles.size(); ++f)
            mesh.add_triangle(regions.triangles[f], boundary.refs[f]);
        for (const auto& e : boundary.ridges)
        {
            mesh.ridges.push_back(static_cast<int>(mesh.edges.size()));
            mesh.edges.push_back(e);
            mesh.edge_refs.push_back(0);
        }
        mesh.corners = boundary.corners;
        mesh.build_adjacency();
        mesh.classify_vertices();
        report.fill_tets = mesh.num_live_tets();
        report.fill_min_quality = worst_quality(mesh);
        if (const auto violations = volume::check_mesh(mesh); !violations.empty())
            throw Error(source + ": the fill made an invalid mesh:\n" +
                        volume::format_violations(violations));
    }

    {
        const StageTimer timer(report.seconds_optimize, report.cpu_seconds_optimize);
        if (options.refine || options.optimize)
        {
            AdaptOptions adapt_options = options.adapt;
            adapt_options.refine = options.refine;
            adapt_options.optimize = options.optimize;
            adapt_options.surface = false;  // the surface was remeshed (or kept) already
            std::shared_ptr<const SizeField> field = report.field;
            if (options.keep_surface)
            {
                adapt_options.project = false;
                field = std::make_shared<KeptSurfaceSize>(field, mesh);
            }
            report.adapt = adapt(mesh, *field, adapt_options);
        }
        if (!mesh.has_adjacency()) mesh.build_adjacency();
    }
    report.tets = mesh.num_live_tets();
    report.vertices = mesh.num_vertices();
    report.min_quality = worst_quality(mesh);
    report.seconds_total = total.wall_seconds();
    report.cpu_seconds_total = total.cpu_seconds();
    if (report_out) *report_out = std::move(report);
    return mesh;
}

TetMesh mesh_volume_from_surface(const SurfaceMesh& surface,
                                 const VolumeFromSurfaceOptions& options,
                                 VolumeFromSurfaceReport* report)
{
    TriangleSoup soup;
    OpenMesh::FPropHandleT<int> face_ref;
    const bool has_refs = surface.get_property_handle(face_ref, surface::property_names::face_ref);
    for (auto v : surface.vertices()) soup.points.push_back(surface.point(v));
    for (auto f : surface.faces())
    {
        std::array<int, 3> t;
        int k = 0;
        for (auto v : surface.fv_range(f)) t[k++] = v.idx();
        soup.triangles.push_back(t);
        soup.refs.push_back(has_refs ? surface.property(face_ref, f) : 0);
    }
    return mesh_volume_from_surface(soup, options, report);
}

TriangleSoup triangle_soup(const TetMesh& mesh)
{
    TriangleSoup soup;
    for (const auto& p : mesh.points) soup.points.emplace_back(p[0], p[1], p[2]);
    soup.triangles.assign(mesh.triangles.begin(), mesh.triangles.end());
    soup.refs = mesh.triangle_refs;
    soup.refs.resize(soup.triangles.size(), 0);
    return soup;
}

std::string format_volume_from_surface_report(const VolumeFromSurfaceReport& r)
{
    std::ostringstream out;
    char line[256];
    std::snprintf(line, sizeof line,
                  "surface: %d points, %d triangles (%d repeated points merged); %d shell%s, %d "
                  "region%s, %d void%s (%d shell%s turned)\n",
                  r.input_points, r.input_triangles, r.merged_points, r.shells,
                  r.shells == 1 ? "" : "s", r.regions, r.regions == 1 ? "" : "s", r.voids,
                  r.voids == 1 ? "" : "s", r.turned_shells, r.turned_shells == 1 ? "" : "s");
    out << line;
    const std::string refolded = r.fold_rounds == 0
                                     ? ""
                                     : " (remeshed " + std::to_string(r.fold_rounds) +
                                           " more time(s), finer where it crossed itself)";
    std::snprintf(line, sizeof line, "boundary: %d points, %d triangles%s\n", r.surface_points,
                  r.surface_triangles, refolded.c_str());
    out << line;
    std::snprintf(line, sizeof line, "fill: %d tets, %d interior points, min Qe %.4f (%s)\n",
                  r.fill_tets, r.fill_points, r.fill_min_quality, r.fills.format().c_str());
    out << line;
    std::snprintf(line, sizeof line, "result: %d tets, %d vertices, min Qe %.4f\n", r.tets,
                  r.vertices, r.min_quality);
    out << line;
    std::snprintf(line, sizeof line,
                  "time (cpu s): check %.3f, remesh %.3f, fill %.3f, optimize %.3f, total %.3f "
                  "(wall %.3f)\n",
                  r.cpu_seconds_check, r.cpu_seconds_remesh, r.cpu_seconds_fill,
                  r.cpu_seconds_optimize, r.cpu_seconds_total, r.seconds_total);
    out << line;
    return out.str();
}

}  // namespace hdimesh::coupling
