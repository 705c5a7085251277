// A curve vertex slid along its curve to where the worst angle of its ball is largest.
//
// Where two curves meet at a corner with a narrow sector between them, the triangle filling the
// sector has at most the sector's angle at the corner, and the chords from the corner set that
// angle. A curved ridge opens up away from the corner (its chords two segments out make a wider
// angle than the first ones), so moving the curve vertex next to the
// corner farther along its curve raises the worst angle there. Nodal shifting cannot find this:
// it balances the two curve edges, which is what made the narrow triangle.

#include <algorithm>
#include <array>
#include <vector>

#include "surface/detail/local_ops_geometry.h"
#include "surface/local_ops.h"

namespace hdimesh::surface
{
namespace
{

// The star of v with the slide's measures.
struct SlideStar : detail::TrialStar
{
    using TrialStar::TrialStar;

    // Worst angle (degrees) with v at p, no legality test: the present state.
    double worst_angle(const Vec3d& p) const
    {
        double worst = 180.0;
        for (const detail::StarFace& face : faces)
        {
            const std::array<Vec3d, 3> after = face.with_moved_at(p);
            worst = std::min(worst, triangle_min_angle_deg(after[0], after[1], after[2]));
        }
        return worst;
    }

    // Layer 2 (after the band, TrialStar::lengths_ok), the turn of every face.
    bool turns_ok(const Vec3d& p, double min_cos) const
    {
        for (const detail::StarFace& face : faces)
            if (!detail::turn_ok_cos(face.normal, detail::normal(face.with_moved_at(p)), min_cos))
                return false;
        return true;
    }

    // The farthest of the faces' centroids and edge midpoints from the model with v at p.
    double worst_distance(const OperatorContext& ctx, VertexHandle v, const Vec3d& p) const
    {
        double worst = 0.0;
        for (const detail::StarFace& face : faces)
        {
            const std::array<Vec3d, 3> t = face.with_moved_at(p);
            const Vec3d samples[4] = {(t[0] + t[1] + t[2]) / 3.0, 0.5 * (t[0] + t[1]),
                                      0.5 * (t[1] + t[2]), 0.5 * (t[2] + t[0])};
            for (const Vec3d& x : samples) worst = std::max(worst, ctx.distance_to_model(x, v));
        }
        return worst;
    }
};

}  // namespace

OpResult slide_curve_vertex(OperatorContext& ctx, VertexHandle v, const SlideOptions& options)
{
    SurfaceMesh& mesh = ctx.mesh;
    // Topology and class: a ridge or boundary vertex with exactly two curve edges (a corner
    // never moves).
    const VertexClass cls = ctx.vertex_class(v);
    if (cls != VertexClass::Ridge && cls != VertexClass::Boundary) return refused(OpStatus::Class);
    const std::vector<Vec3d> curve_ends = detail::curve_neighbour_points(ctx, v);
    if (curve_ends.size() != 2) return refused(OpStatus::Class);

    const Vec3d p = mesh.point(v);
    const SlideStar star(mesh, v);
    const double before = star.worst_angle(p);
    const double min_cos = detail::cos_deg(ctx.limits.max_normal_turn_deg);
    // The distance bound: the tolerance (or the operators' limit), never tighter than now.
    double max_distance =
        options.tolerance > 0.0 ? options.tolerance : ctx.limits.max_model_distance;
    if (max_distance > 0.0) max_distance = std::max(max_distance, star.worst_distance(ctx, v, p));

    // Every trial through the layers (band, turn, distance: the costliest last), then the best
    // worst angle among the legal ones.
    double best = -1.0;
    ProjectedPoint best_point;
    OpStatus refusal = OpStatus::Quality;
    for (const Vec3d& end : curve_ends)
        for (int i = 1; i <= options.samples; ++i)
        {
            // Up to 0.8 of the way: the neighbour's other edges are not looked at here.
            const double t = 0.8 * static_cast<double>(i) / static_cast<double>(options.samples);
            const ProjectedPoint q = ctx.model.project_near(p + t * (end - p), cls,
                                                            ctx.vertex_curve(v), ctx.model_face(v));
            if (!q.ok) continue;
            const double angle = star.worst_angle(q.point);
            if (!(angle > best) || !(angle > before + options.min_gain_deg)) continue;
            if (!star.lengths_ok(q.point, options.min_length, options.max_length) ||
                !star.turns_ok(q.point, min_cos))
            {
                refusal = OpStatus::Geometry;
                continue;
            }
            if (max_distance > 0.0 && star.worst_distance(ctx, v, q.point) > max_distance)
            {
                refusal = OpStatus::Geometry;
                continue;
            }
            best = angle;
            best_point = q;
        }
    if (!best_point.ok) return refused(refusal);
    return commit_move(ctx, v, best_point.point, best_point.face);
}

}  // namespace hdimesh::surface
