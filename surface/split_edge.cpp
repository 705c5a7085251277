#include <algorithm>

#include "surface/detail/local_ops_geometry.h"
#include "surface/local_ops.h"
#include "surface/surface_quality.h"

namespace hdimesh::surface
{
namespace
{
// A split that turns its triangles past the limit (across a dropped crease) keeps no angle under
// OperatorLimits::min_angle_across_crease_deg, and its triangles may not fold against the model
// (its normal is one side's of the crease).
constexpr double kMaxTurnAcrossCreaseDeg = 85.0;
}  // namespace

OpResult try_split(OperatorContext& ctx, EdgeHandle e, const Vec3d* at)
{
    if (!ctx.limits.insert) return refused(OpStatus::Disabled);
    using namespace detail;
    SurfaceMesh& mesh = ctx.mesh;
    OpResult result;
    const HalfedgeHandle h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
    const VertexHandle a = mesh.from_vertex_handle(h0), b = mesh.to_vertex_handle(h0);
    const Vec3d pa = mesh.point(a), pb = mesh.point(b);
    const double length = (pb - pa).norm();

    // Class layer: the new vertex lies on the edge's curve, if any.
    const int curve = ctx.edge_curve(e);
    VertexClass cls = VertexClass::Smooth;
    if (mesh.is_boundary(e))
        cls = VertexClass::Boundary;
    else if (curve != kNoCurve)
        cls = VertexClass::Ridge;

    // Geometry layer: the projected midpoint must not jump away (a projection onto the wrong
    // sheet or curve) and the new triangles must not turn.
    const Vec3d mid = 0.5 * (pa + pb);
    Vec3d p = mid;
    int model_face = ctx.model_face(a);
    ProjectedPoint projected = ctx.model.project_near(at && cls == VertexClass::Smooth ? *at : mid,
                                                      cls, curve, model_face);
    if (at && cls == VertexClass::Smooth)
        p = *at;
    else if (projected.ok)
        p = projected.point;
    if (projected.ok && projected.face >= 0) model_face = projected.face;  // the hint near p
    if ((p - mid).norm() > 0.5 * length)
    {
        result.status = OpStatus::Geometry;
        return result;
    }
    const double max_turn_cos = cos_deg(std::max(ctx.limits.max_normal_turn_deg, 60.0));
    const double across_crease_cos = cos_deg(kMaxTurnAcrossCreaseDeg);
    for (const HalfedgeHandle h : {h0, h1})
    {
        const FaceHandle f = mesh.face_handle(h);
        if (!f.is_valid()) continue;
        const Vec3d from = mesh.point(mesh.from_vertex_handle(h)),
                    to = mesh.point(mesh.to_vertex_handle(h));
        const Vec3d opposite = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
        const Vec3d old_normal = triangle_normal(from, to, opposite);
        const bool turn_from_old =
            turn_ok_cos(old_normal, triangle_normal(from, p, opposite), max_turn_cos) &&
            turn_ok_cos(old_normal, triangle_normal(p, to, opposite), max_turn_cos);
        // An edge across a crease the features dropped (a chord far from the model): its new
        // vertex, on the model, turns the triangles a lot; that is the point of the split. Then
        // the new triangles must not fold against the model under the new vertex, and stay well
        // shaped.
        const bool follows_model =
            !turn_from_old && projected.ok && cls == VertexClass::Smooth &&
            turn_ok_cos(projected.normal, triangle_normal(from, p, opposite), across_crease_cos) &&
            turn_ok_cos(projected.normal, triangle_normal(p, to, opposite), across_crease_cos) &&
            triangle_min_angle_deg(from, p, opposite) >= ctx.limits.min_angle_across_crease_deg &&
            triangle_min_angle_deg(p, to, opposite) >= ctx.limits.min_angle_across_crease_deg;
        if (!turn_from_old && !follows_model)
        {
            result.status = OpStatus::Geometry;
            return result;
        }
    }
    if (ctx.hooks.allow_split && !ctx.hooks.allow_split(mesh, e, p))
    {
        result.status = OpStatus::Hook;
        return result;
    }

    // Commit. Each new face takes the ref of the face it was cut from (found by its opposite
    // vertex).
    VertexHandle opposite[2];
    int ref[2] = {0, 0};
    int side = 0;
    for (const HalfedgeHandle h : {h0, h1})
    {
        const FaceHandle f = mesh.face_handle(h);
        if (f.is_valid())
        {
            opposite[side] = mesh.to_vertex_handle(mesh.next_halfedge_handle(h));
            ref[side] = mesh.property(ctx.props.face_ref, f);
        }
        ++side;
    }
    const VertexHandle v = mesh.add_vertex(p);
    mesh.property(ctx.props.vertex_class, v) = cls;
    mesh.property(ctx.props.vertex_curve, v) = cls == VertexClass::Smooth ? kNoCurve : curve;
    mesh.property(ctx.props.vertex_model_face, v) = model_face;
    mesh.property(ctx.props.vertex_size, v) =
        0.5 * (mesh.property(ctx.props.vertex_size, a) + mesh.property(ctx.props.vertex_size, b));
    mesh.split(e, v);
    for (auto h : mesh.voh_range(v))
    {
        const VertexHandle w = mesh.to_vertex_handle(h);
        mesh.property(ctx.props.edge_curve, mesh.edge_handle(h)) =
            (w == a || w == b) ? curve : kNoCurve;
    }
    for (auto f : mesh.vf_range(v))
    {
        const auto fv = face_vertices(mesh, f);
        for (int s = 0; s < 2; ++s)
            if (opposite[s].is_valid() && std::find(fv.begin(), fv.end(), opposite[s]) != fv.end())
                mesh.property(ctx.props.face_ref, f) = ref[s];
    }
    if (ctx.hooks.on_split) ctx.hooks.on_split(mesh, a, b, v);
    result.status = OpStatus::Done;
    result.vertex = v;
    return result;
}

}  // namespace hdimesh::surface
