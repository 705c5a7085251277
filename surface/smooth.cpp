#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "surface/local_ops.h"
#include "surface/local_ops_geometry.h"

namespace hdimesh::surface
{
namespace
{

// A curve vertex moves toward the point of its curve that balances its two curve edges.
bool optimal_point_curve(const OperatorContext& ctx, VertexHandle v, Vec3d& optimal)
{
    const SurfaceMesh& mesh = ctx.mesh;
    std::vector<Vec3d> ends;
    for (auto h : mesh.voh_range(v))
        if (ctx.edge_curve(mesh.edge_handle(h)) == ctx.vertex_curve(v)) ends.push_back(mesh.point(mesh.to_vertex_handle(h)));
    if (ends.size() != 2) return false;
    optimal = 0.5 * (ends[0] + ends[1]);
    return true;
}

// The ball of v collected once per shift (the trial positions only move v): each face's
// points in face order, where v is among them, and its normal before the move.
struct Ball
{
    using Face = detail::StarFace;
    std::vector<Face> faces;
    // quality() at v's own position: every normal is unchanged, so it only asks for one that
    // is not degenerate (measured: the recomputed normals were 4 % of the remesher's time).
    double quality_before = 1.0;

    Ball(const SurfaceMesh& mesh, VertexHandle v)
    {
        faces.swap(storage());
        detail::collect_star(mesh, v, faces);
        for (const Face& face : faces)
        {
            if (quality_before < 0.0) break;
            quality_before = face.normal.sqrnorm() > 0.5 ? std::min(quality_before, detail::qe(face.points)) : -1.0;
        }
    }
    ~Ball() { faces.swap(storage()); }
    Ball(const Ball&) = delete;
    Ball& operator=(const Ball&) = delete;

    // One shift per vertex and iteration: the faces' capacity is kept from one ball to the next
    // (measured: malloc and free were 2 % of the remesher's time).
    static std::vector<Face>& storage()
    {
        static thread_local std::vector<Face> kept;
        return kept;
    }

    // Worst Qe with v at p; -1 if a triangle turns more than the angle of cosine min_cos or degenerates.
    // Stops early, returning a value below `refused_below`, once the worst is under it: the
    // caller refuses any such move whatever the exact value (a smart shift's refused trials
    // were most of the polish's shifting).
    double quality(const Vec3d& p, double min_cos, double refused_below) const
    {
        double worst = 1.0;
        for (const Face& face : faces)
        {
            const std::array<Vec3d, 3> after = face.with_moved_at(p);
            if (!detail::turn_ok_cos(face.normal, detail::normal(after), min_cos)) return -1.0;
            worst = std::min(worst, detail::qe(after));
            if (worst < refused_below) return worst;
        }
        return worst;
    }
};

// George's optimal point for a smooth vertex: for each outer edge (a, b) of the ball, the apex
// of the equilateral triangle on (a, b) in the tangent plane, on the vertex's side; weights
// 1/Qe² so the worst triangles pull hardest. From the ball's faces (a, b: the points after v in
// face order), in the order of the circulation around v that collected them.
bool optimal_point_smooth(const Ball& ball, const Vec3d& n, Vec3d& optimal)
{
    using namespace detail;
    Vec3d sum(0, 0, 0);
    double weight_sum = 0.0;
    for (const Ball::Face& face : ball.faces)
    {
        const Vec3d& pv = face.points[face.moved];
        const Vec3d& pa = face.points[(face.moved + 1) % 3];
        const Vec3d& pb = face.points[(face.moved + 2) % 3];
        Vec3d side = OpenMesh::cross(n, pb - pa);  // (a, b, v) is counter-clockwise about n
        const double len = side.norm();
        if (!(len > 0.0)) return false;
        side /= len;
        const Vec3d ideal = 0.5 * (pa + pb) + (std::sqrt(3.0) / 2.0) * (pb - pa).norm() * side;
        const double q = std::max(qe({pv, pa, pb}), 0.05);
        const double w = 1.0 / (q * q);
        sum += w * ideal;
        weight_sum += w;
    }
    if (!(weight_sum > 0.0)) return false;
    optimal = sum / weight_sum;
    return true;
}

}  // namespace

OpResult shift_vertex(OperatorContext& ctx, VertexHandle v, const ShiftOptions& options)
{
    SurfaceMesh& mesh = ctx.mesh;
    OpResult result;
    const VertexClass cls = ctx.vertex_class(v);
    if (cls == VertexClass::Corner || mesh.is_isolated(v))
    {
        result.status = OpStatus::Class;
        return result;
    }
    if (cls == VertexClass::Smooth && mesh.is_boundary(v))
    {
        result.status = OpStatus::Class;  // an unclassified boundary vertex: leave it alone
        return result;
    }
    const Vec3d p = mesh.point(v);
    const Ball ball(mesh, v);
    Vec3d optimal;
    Vec3d n(0, 0, 0);
    if (cls == VertexClass::Smooth)
    {
        // The tangent plane of the ball (its area-weighted normal): the vertex is on the model
        // already, so this is the plane of the local fit without another projection.
        for (const Ball::Face& face : ball.faces)
        {
            const auto& q = face.points;
            n += OpenMesh::cross(q[1] - q[0], q[2] - q[0]);
        }
        if (!(n.norm() > 0.0)) return result;
        n.normalize();
        if (!optimal_point_smooth(ball, n, optimal))
        {
            result.status = OpStatus::Geometry;
            return result;
        }
    }
    else if (!optimal_point_curve(ctx, v, optimal))
    {
        result.status = OpStatus::Class;
        return result;
    }

    const double min_cos = detail::cos_deg(ctx.limits.max_normal_turn_deg);
    const double old_quality = ball.quality_before;
    // Below this a trial is refused by one of the tests after ball.quality() below.
    const double refused_below =
        options.smart ? old_quality - 1e-12 : std::min(ctx.limits.min_new_quality, old_quality);
    for (double step = options.step; step > options.step / 5.0; step *= 0.5)
    {
        Vec3d target = p + step * (optimal - p);
        if (cls == VertexClass::Smooth) target -= OpenMesh::dot(target - p, n) * n;  // stay in the plane
        const ProjectedPoint projected = ctx.model.project_near(target, cls, ctx.vertex_curve(v), ctx.model_face(v));
        if (!projected.ok) continue;
        const Vec3d q = projected.point;
        const double new_quality = ball.quality(q, min_cos, refused_below);
        if (new_quality < ctx.limits.min_new_quality && new_quality < old_quality) continue;
        if (new_quality < 0.0) continue;
        if (options.smart && new_quality < old_quality - 1e-12) continue;
        if (options.accept && !options.accept(q))
        {
            result.status = OpStatus::Geometry;
            return result;
        }
        return commit_move(ctx, v, q, projected.face);
    }
    result.status = OpStatus::Quality;
    return result;
}

}  // namespace hdimesh::surface
