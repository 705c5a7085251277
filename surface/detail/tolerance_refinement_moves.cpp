// The refinement's changes of the output: splits toward a far model point or beside a chord
// the triangles refuse, and snaps of a vertex onto a far model point.

#include <algorithm>
#include <vector>

#include "surface/detail/local_ops_geometry.h"
#include "surface/detail/tolerance_refinement.h"
#include "surface/surface_quality.h"

namespace hdimesh::surface::detail
{
namespace
{

// A refinement snap moves a vertex at most this fraction of the size (farther: a split's job).
constexpr double kMaxSnapDistance = 0.6;
// A split refused onto its far model point is tried these fractions of the way from the edge's
// midpoint (the snap's steps, try_snap_vertex).
constexpr double kSplitTowardSteps[] = {0.75, 0.5, 0.35};

}  // namespace

// A split of e with its new vertex onto model point `target` (far from the output near e).
// Refused there (at a rim sharper than the size the new triangles turn past the split's 60°),
// part of the way from the edge's midpoint, projected onto the model, keeping the
// angles as a snap does: the midpoint split alone leaves the point almost as far and still
// spends the budget. Only after the polish, as the snaps: earlier the polish moves the vertex
// anyway (docs/tuning.md).
OpResult ToleranceRefinement::split_toward(EdgeHandle e, const Vec3d& target, bool part_of_the_way)
{
    // (The floor judged where the vertex lands: the target projected onto the model.)
    const ProjectedPoint landing = ctx_.model.project_near(
        target, VertexClass::Smooth, kNoCurve,
        ctx_.model_face(mesh_.from_vertex_handle(mesh_.halfedge_handle(e, 0))));
    OpResult r = clear_of_floor(e, landing.ok ? landing.point : target)
                     ? try_split(ctx_, e, &target)
                     : refused(OpStatus::Geometry);
    // (A curve edge's split stays on its curve: the target is not its to reach.)
    if (r.done() || !part_of_the_way || ctx_.is_feature(e)) return r;
    const auto h = mesh_.halfedge_handle(e, 0);
    const VertexHandle a = mesh_.from_vertex_handle(h);
    const Vec3d pa = mesh_.point(a), pb = mesh_.point(mesh_.to_vertex_handle(h));
    const Vec3d mid = 0.5 * (pa + pb);
    // The new triangles keep no angle under the snap's bound or under the worst of the two
    // triangles before (else the worst angle falls, docs/tuning.md).
    std::vector<Vec3d> opposite;
    double old_min_angle = 180.0;
    for (const auto side : {h, mesh_.opposite_halfedge_handle(h)})
    {
        if (mesh_.is_boundary(side)) continue;
        const Vec3d c = mesh_.point(mesh_.to_vertex_handle(mesh_.next_halfedge_handle(side)));
        opposite.push_back(c);
        old_min_angle = std::min(old_min_angle, triangle_min_angle_deg(pa, pb, c));
    }
    const double min_angle = std::min(tolerance_.snap_min_angle_deg, old_min_angle);
    for (const double step : kSplitTowardSteps)
    {
        const ProjectedPoint on_model = ctx_.model.project_near(
            mid + step * (target - mid), VertexClass::Smooth, kNoCurve, ctx_.model_face(a));
        if (!on_model.ok) continue;
        const Vec3d& p = on_model.point;
        if (std::any_of(opposite.begin(), opposite.end(), [&](const Vec3d& c) {
                return triangle_min_angle_deg(pa, p, c) < min_angle ||
                       triangle_min_angle_deg(p, pb, c) < min_angle;
            }))
            continue;
        if (!clear_of_floor(e, p)) continue;
        const OpResult partial = try_split(ctx_, e, &p);
        if (partial.done()) return partial;
    }
    return r;
}

// Whether a vertex at p splitting e makes no edge shorter than the refinement's floor (to e's
// ends and the vertices opposite it).
bool ToleranceRefinement::clear_of_floor(EdgeHandle e, const Vec3d& p) const
{
    const double floor = tolerance_.min_split_length;
    if (!(floor > 0.0)) return true;
    for (int side = 0; side < 2; ++side)
    {
        const auto h = mesh_.halfedge_handle(e, side);
        if ((mesh_.point(mesh_.to_vertex_handle(h)) - p).norm() < floor) return false;
        if (!mesh_.is_boundary(h) &&
            (mesh_.point(mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h))) - p).norm() < floor)
            return false;
    }
    return true;
}

// The curve edge (boundary or ridge) of f nearest to model point `point` (invalid: none).
EdgeHandle ToleranceRefinement::nearest_curve_edge(FaceHandle f, std::size_t point) const
{
    const Vec3d& q = tolerance_.model_points[point];
    EdgeHandle nearest;
    double best = 1e300;
    for (auto e : mesh_.fe_range(f))
    {
        if (!ctx_.is_feature(e)) continue;
        const auto h = mesh_.halfedge_handle(e, 0);
        const double d = (closest_point_on_segment(q, mesh_.point(mesh_.from_vertex_handle(h)),
                                                   mesh_.point(mesh_.to_vertex_handle(h))) -
                          q)
                             .sqrnorm();
        if (d < best) best = d, nearest = e;
    }
    return nearest;
}

// A vertex of `face` (the output triangle closest to model point `point`, far from it) moved
// onto the point: the nearest vertex that may go there (a smooth one onto a smooth point, a
// curve vertex onto a point of its curve) and whose move keeps the star's shape and sizes
// and brings no other model point around it out of the tolerance. Invalid handle: none.
VertexHandle ToleranceRefinement::snap_toward(std::size_t point, FaceHandle face, bool smooth_point)
{
    const Vec3d& target = tolerance_.model_points[point];
    std::vector<VertexHandle> vertices;
    for (auto v : mesh_.fv_range(face)) vertices.push_back(v);
    return snap_one_of(vertices, target, smooth_point);
}

// An end of chord e (far from the model) moved toward `target`, the model point under its midpoint.
VertexHandle ToleranceRefinement::snap_vertex_of_edge(EdgeHandle e, const Vec3d& target)
{
    const auto h = mesh_.halfedge_handle(e, 0);
    return snap_one_of({mesh_.from_vertex_handle(h), mesh_.to_vertex_handle(h)}, target, true);
}

// The first of `vertices`, nearest first, that try_snap_vertex moves toward `target`, with
// the star's edges kept in the Qt band of the reference size and the model points around
// the star and the target as witnesses.
VertexHandle ToleranceRefinement::snap_one_of(std::vector<VertexHandle> vertices,
                                              const Vec3d& target, bool smooth_point)
{
    std::sort(vertices.begin(), vertices.end(), [&](VertexHandle a, VertexHandle b) {
        const double da = (mesh_.point(a) - target).sqrnorm(),
                     db = (mesh_.point(b) - target).sqrnorm();
        return da != db ? da < db : a.idx() < b.idx();  // ties by index: deterministic
    });
    for (const VertexHandle v : vertices)
    {
        const VertexClass cls = ctx_.vertex_class(v);
        if (cls == VertexClass::Corner || (cls == VertexClass::Smooth) != smooth_point) continue;
        const double size = tolerance_.reference_size > 0.0
                                ? tolerance_.reference_size
                                : mesh_.property(ctx_.props.vertex_size, v);
        const Vec3d p = mesh_.point(v);
        if ((p - target).norm() > kMaxSnapDistance * size) continue;
        if (keeper_.try_snap(v, target, false))
        {
            run_.set_size(v);
            return v;
        }
    }
    return VertexHandle();
}

// A split beside a chord whose own split the triangles refuse: the longest other edge of
// either face at it, when not too short to split.
OpResult ToleranceRefinement::split_beside(EdgeHandle e)
{
    OpResult result = refused(OpStatus::Geometry);
    for (int side = 0; side < 2 && !result.done(); ++side)
    {
        const FaceHandle f = mesh_.face_handle(mesh_.halfedge_handle(e, side));
        if (!f.is_valid()) continue;
        EdgeHandle longest;
        double best = 0.0;
        for (auto other : mesh_.fe_range(f))
            if (other != e && mesh_.calc_edge_length(other) > best)
                best = mesh_.calc_edge_length(other), longest = other;
        if (longest.is_valid() &&
            best >= 2.0 * tolerance_.min_length_ratio * run_.edge_size(longest) &&
            best >= 2.0 * tolerance_.min_split_length)
            result = try_split(ctx_, longest);
    }
    return result;
}

}  // namespace hdimesh::surface::detail
