#include <algorithm>
#include <cassert>
#include <cstdlib>

#include "surface/detail/local_ops_geometry.h"
#include "surface/local_ops.h"

namespace hdimesh::surface
{
namespace
{

int target_valence(const SurfaceMesh& mesh, VertexHandle v) { return mesh.is_boundary(v) ? 4 : 6; }

// A distance flip must bring the pair at least this much nearer (not a swap of rounding noise).
constexpr double kDistanceFlipGain = 0.75;

}  // namespace

// Debian's libOpenMeshCore is built with its assertions on: each status or connectivity
// look-up inside the library checks the handle and builds, compares and frees a type-name
// string, so is_flip_ok and valence, being out-of-line library calls, cost several times these
// inline versions. The same answer: a debug build checks each against OpenMesh's.
bool flip_topology_ok(const SurfaceMesh& mesh, EdgeHandle e)
{
    const bool ok = [&] {
        const HalfedgeHandle h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
        if (mesh.is_boundary(h0) || mesh.is_boundary(h1)) return false;
        const VertexHandle c = mesh.to_vertex_handle(mesh.next_halfedge_handle(h0));
        const VertexHandle d = mesh.to_vertex_handle(mesh.next_halfedge_handle(h1));
        if (c == d) return false;
        for (const VertexHandle w : mesh.vv_range(c))
            if (w == d) return false;  // (c and d joined already)
        return true;
    }();
    assert(ok == mesh.is_flip_ok(e));
    return ok;
}

int ring_valence(const SurfaceMesh& mesh, VertexHandle v)
{
    int count = 0;
    for (auto h : mesh.voh_range(v))
    {
        (void)h;
        ++count;
    }
    assert(count == static_cast<int>(mesh.valence(v)));
    return count;
}

namespace
{

// Whether flipping ab to cd brings the four ring valences nearer their targets.
bool valence_improves(const SurfaceMesh& mesh, VertexHandle a, VertexHandle b, VertexHandle c,
                      VertexHandle d)
{
    const int va = ring_valence(mesh, a), vb = ring_valence(mesh, b);
    const int vc = ring_valence(mesh, c), vd = ring_valence(mesh, d);
    const int ta = target_valence(mesh, a), tb = target_valence(mesh, b);
    const int tc = target_valence(mesh, c), td = target_valence(mesh, d);
    const int before =
        std::abs(va - ta) + std::abs(vb - tb) + std::abs(vc - tc) + std::abs(vd - td);
    const int after = std::abs(va - 1 - ta) + std::abs(vb - 1 - tb) + std::abs(vc + 1 - tc) +
                      std::abs(vd + 1 - td);
    return after < before;
}

// Whether new triangle t (normal n) follows the model under its centroid within the turn limit.
bool follows_model(OperatorContext& ctx, const std::array<Vec3d, 3>& t, const Vec3d& n,
                   VertexHandle near, double min_cos)
{
    const ProjectedPoint foot = ctx.model.project_near(
        (t[0] + t[1] + t[2]) / 3.0, VertexClass::Smooth, kNoCurve, ctx.model_face(near));
    // (A degenerate input face has no normal: turn_ok_cos would take any turn.)
    return foot.ok && foot.normal.sqrnorm() > 0.5 && detail::turn_ok_cos(foot.normal, n, min_cos);
}

// Geometry: neither new triangle turns much, and the pair does not fold more than it was
// (or than a gently curved surface would).
bool flip_geometry_ok(OperatorContext& ctx, FlipGoal goal, const std::array<Vec3d, 3>& old0,
                      const std::array<Vec3d, 3>& old1, const std::array<Vec3d, 3>& new0,
                      const std::array<Vec3d, 3>& new1, VertexHandle c)
{
    using namespace detail;
    const Vec3d n_old0 = normal(old0), n_old1 = normal(old1), n_new0 = normal(new0),
                n_new1 = normal(new1);
    Vec3d n_mean = n_old0 + n_old1;
    if (n_mean.norm() > 0.0) n_mean.normalize();
    static const double gentle_fold_cos = cos_deg(20.0);
    const double min_cos = cos_deg(ctx.limits.max_normal_turn_deg);
    const bool turns_little =
        turn_ok_cos(n_mean, n_new0, min_cos) && turn_ok_cos(n_mean, n_new1, min_cos);
    // A chord across a crease the features dropped folds its pair over the crease; the distance
    // flip that lays the two triangles onto the crease's two sides turns them a lot, which is the
    // point of it (the mean of a folded pair's normals is no reference). Then each new triangle
    // must follow the model under its centroid within the turn limit.
    const bool across_crease = !turns_little && goal == FlipGoal::Distance &&
                               follows_model(ctx, new0, n_new0, c, min_cos) &&
                               follows_model(ctx, new1, n_new1, c, min_cos);
    return !((!turns_little && !across_crease) ||
             OpenMesh::dot(n_new0, n_new1) <
                 std::min(OpenMesh::dot(n_old0, n_old1), gentle_fold_cos) - 1e-12);
}

// The farthest from the model of an edge's midpoint and its two triangles' centroids.
double farthest_sample(OperatorContext& ctx, const Vec3d& mid, VertexHandle near,
                       const std::array<Vec3d, 3>& t0, const std::array<Vec3d, 3>& t1)
{
    return std::max({ctx.distance_to_model(mid, near),
                     ctx.distance_to_model((t0[0] + t0[1] + t0[2]) / 3.0, near),
                     ctx.distance_to_model((t1[0] + t1[1] + t1[2]) / 3.0, near)});
}

}  // namespace

OpResult try_flip(OperatorContext& ctx, EdgeHandle e, FlipGoal goal)
{
    if (!ctx.limits.swap) return refused(OpStatus::Disabled);
    using namespace detail;
    SurfaceMesh& mesh = ctx.mesh;
    OpResult result;
    if (ctx.is_feature(e))
    {
        result.status = OpStatus::Class;
        return result;
    }
    //        c                 c
    //       / \               /|\      .
    //      a---b     ->      a | b
    //       \ /               \|/
    //        d                 d
    // faces (a, b, c) and (b, a, d) become (a, d, c) and (d, b, c).
    const HalfedgeHandle h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
    const FaceHandle f0 = mesh.face_handle(h0), f1 = mesh.face_handle(h1);
    if (mesh.property(ctx.props.face_ref, f0) != mesh.property(ctx.props.face_ref, f1))
    {
        result.status = OpStatus::Class;
        return result;
    }
    const VertexHandle a = mesh.from_vertex_handle(h0), b = mesh.to_vertex_handle(h0);
    const VertexHandle c = mesh.to_vertex_handle(mesh.next_halfedge_handle(h0));
    const VertexHandle d = mesh.to_vertex_handle(mesh.next_halfedge_handle(h1));
    const Vec3d pa = mesh.point(a), pb = mesh.point(b), pc = mesh.point(c), pd = mesh.point(d);

    // The layers from the cheapest rejection up (all must pass: the order only decides the time
    // and the reported layer). Valence: four ring counts refuse most edges of a settled mesh;
    // the topology test looks for the flipped edge in a ring. (c and d exist: a boundary
    // edge is a feature.)
    if (goal == FlipGoal::Valence && !valence_improves(mesh, a, b, c, d))
    {
        result.status = OpStatus::Quality;
        return result;
    }
    if (!flip_topology_ok(mesh, e))
    {
        result.status = OpStatus::Topology;
        return result;
    }
    const std::array<Vec3d, 3> old0{pa, pb, pc}, old1{pb, pa, pd}, new0{pa, pd, pc},
        new1{pd, pb, pc};
    const double old_min = std::min(qe(old0), qe(old1)), new_min = std::min(qe(new0), qe(new1));
    const bool keeps_enough =
        goal == FlipGoal::Quality ? new_min > old_min + 1e-6 : !(new_min < 0.5 * old_min);
    if (new_min < ctx.limits.min_new_quality || !keeps_enough)
    {
        result.status = OpStatus::Quality;
        return result;
    }
    if (!flip_geometry_ok(ctx, goal, old0, old1, new0, new1, c))
    {
        result.status = OpStatus::Geometry;
        return result;
    }
    // Distance to the model last: it is the expensive test.
    if (goal == FlipGoal::Distance)
    {
        if (!(farthest_sample(ctx, 0.5 * (pc + pd), c, new0, new1) <
              kDistanceFlipGain * farthest_sample(ctx, 0.5 * (pa + pb), a, old0, old1)))
        {
            result.status = OpStatus::Quality;
            return result;
        }
    }
    if (ctx.limits.max_model_distance > 0.0)
    {
        const Vec3d mid = 0.5 * (pc + pd);
        if (!ctx.near_model(mid, c, ctx.limits.max_model_distance))
        {
            result.status = OpStatus::Geometry;
            return result;
        }
    }
    if (ctx.hooks.allow_flip && !ctx.hooks.allow_flip(mesh, e))
    {
        result.status = OpStatus::Hook;
        return result;
    }
    mesh.flip(e);
    if (ctx.hooks.on_flip) ctx.hooks.on_flip(mesh, a, b, c, d);
    result.status = OpStatus::Done;
    return result;
}

}  // namespace hdimesh::surface
