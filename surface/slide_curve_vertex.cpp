// A curve vertex slid along its curve to where the worst angle of its ball is largest.
//
// Where two curves meet at a corner with a narrow sector between them, the triangle filling the
// sector has at most the sector's angle at the corner, and the chords from the corner set that
// angle. A curved ridge opens up away from the corner (fandisk: 19.4° between the first input
// segments, 21.6° between points two segments out), so moving the curve vertex next to the
// corner farther along its curve raises the worst angle there. Nodal shifting cannot find this:
// it balances the two curve edges, which is what made the narrow triangle.

#include <algorithm>
#include <array>
#include <vector>

#include "surface/local_ops.h"
#include "surface/local_ops_geometry.h"

namespace hdimesh::surface
{
namespace
{

// The faces around v (points in face order, index of v, normal before the move) and the other
// ends of its edges, collected once: trial positions only move v.
struct SlideBall
{
    std::vector<detail::StarFace> faces;
    std::vector<Vec3d> neighbours;
    Vec3d centre;  // v before the move

    SlideBall(const SurfaceMesh& mesh, VertexHandle v) : centre(mesh.point(v))
    {
        detail::collect_star(mesh, v, faces);
        for (auto w : mesh.vv_range(v)) neighbours.push_back(mesh.point(w));
    }

    // Worst angle (degrees) of the ball with v at p; -1 when a face turns too much or an edge
    // leaves the allowed band.
    double worst_angle(const Vec3d& p, const SlideOptions& options, double max_turn_deg) const
    {
        // An edge may not leave the band, nor get farther out of it than it is.
        for (const Vec3d& w : neighbours)
        {
            const double length = (w - p).norm(), now = (w - centre).norm();
            if (length > options.max_edge_length && length > now) return -1.0;
            if (length < options.min_edge_length && length < now) return -1.0;
        }
        double worst = 180.0;
        for (const detail::StarFace& face : faces)
        {
            const std::array<Vec3d, 3> after = face.with_moved_at(p);
            if (!detail::turn_ok(face.normal, detail::normal(after), max_turn_deg)) return -1.0;
            worst = std::min(worst, triangle_min_angle_deg(after[0], after[1], after[2]));
        }
        return worst;
    }
};

}  // namespace

OpResult slide_curve_vertex(OperatorContext& ctx, VertexHandle v, const SlideOptions& options)
{
    SurfaceMesh& mesh = ctx.mesh;
    OpResult result;
    // Topology: an interior curve vertex with exactly two curve edges (a corner never moves).
    const VertexClass cls = ctx.vertex_class(v);
    if (cls != VertexClass::Ridge && cls != VertexClass::Boundary)
    {
        result.status = OpStatus::Class;
        return result;
    }
    std::vector<Vec3d> curve_ends;
    for (auto h : mesh.voh_range(v))
        if (ctx.edge_curve(mesh.edge_handle(h)) == ctx.vertex_curve(v))
            curve_ends.push_back(mesh.point(mesh.to_vertex_handle(h)));
    if (curve_ends.size() != 2)
    {
        result.status = OpStatus::Class;
        return result;
    }

    // Geometry and quality: trial points along the chords toward either curve neighbour,
    // projected onto the curve; the best worst angle wins if it beats the present one.
    const Vec3d p = mesh.point(v);
    const SlideBall ball(mesh, v);
    const double before = ball.worst_angle(p, SlideOptions{1e300, 0.0, options.samples}, ctx.limits.max_normal_turn_deg);
    double best = before;
    ProjectedPoint best_point;
    for (const Vec3d& end : curve_ends)
        for (int i = 1; i <= options.samples; ++i)
        {
            // Up to 0.8 of the way: the neighbour's other edges are not looked at here.
            const double t = 0.8 * static_cast<double>(i) / static_cast<double>(options.samples);
            const ProjectedPoint q =
                ctx.model.project_near(p + t * (end - p), cls, ctx.vertex_curve(v), ctx.model_face(v));
            if (!q.ok) continue;
            const double angle = ball.worst_angle(q.point, options, ctx.limits.max_normal_turn_deg);
            if (angle > best + options.min_gain_deg)
            {
                best = angle;
                best_point = q;
            }
        }
    if (!best_point.ok)
    {
        result.status = OpStatus::Quality;
        return result;
    }
    // The chords of the moved faces stay near the model (the vertex itself is on its curve).
    if (ctx.limits.max_model_distance > 0.0)
        for (const auto& face : ball.faces)
        {
            const std::array<Vec3d, 3> after = face.with_moved_at(best_point.point);
            if (!ctx.near_model((after[0] + after[1] + after[2]) / 3.0, v, ctx.limits.max_model_distance))
            {
                result.status = OpStatus::Geometry;
                return result;
            }
        }
    if (ctx.hooks.allow_move && !ctx.hooks.allow_move(mesh, v, best_point.point))
    {
        result.status = OpStatus::Hook;
        return result;
    }
    mesh.set_point(v, best_point.point);
    if (best_point.face >= 0) mesh.property(ctx.props.vertex_model_face, v) = best_point.face;
    if (ctx.hooks.on_move) ctx.hooks.on_move(mesh, v, p);
    result.status = OpStatus::Done;
    result.vertex = v;
    return result;
}

}  // namespace hdimesh::surface
