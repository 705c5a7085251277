#include <algorithm>
#include <array>
#include <cassert>
#include <utility>
#include <vector>

#include "surface/detail/local_ops_geometry.h"
#include "surface/local_ops.h"

namespace hdimesh::surface
{
namespace
{

// Class layer: a corner never goes; a curve vertex goes only along its own curve; a smooth
// vertex may go anywhere (but an unclassified mesh's boundary vertex is treated as a curve).
bool class_allows_collapse(const OperatorContext& ctx, HalfedgeHandle h)
{
    const SurfaceMesh& mesh = ctx.mesh;
    const VertexHandle v0 = mesh.from_vertex_handle(h);
    const EdgeHandle e = mesh.edge_handle(h);
    switch (ctx.vertex_class(v0))
    {
        case VertexClass::Corner: return false;
        case VertexClass::Ridge:
        case VertexClass::Boundary:
            return ctx.edge_curve(e) != kNoCurve && ctx.edge_curve(e) == ctx.vertex_curve(v0);
        case VertexClass::Smooth: return !mesh.is_boundary(v0);
    }
    return false;
}

// OpenMesh's topology test of a triangle mesh's collapse (TriConnectivity::is_collapse_ok: the
// edge and its ends alive, neither side's two other edges both on the boundary, the two
// opposite vertices distinct, no common neighbour of the ends but those two, no inner edge
// between two boundary vertices), with the same answer, read through the mesh's inline
// accessors. Debian's libOpenMeshCore is built with its assertions on: each status look-up
// inside the library builds, compares and frees a type-name string, a large part of
// is_collapse_ok's time. A debug build checks each answer against OpenMesh's.
bool collapse_topology_ok(
    SurfaceMesh& mesh,
    HalfedgeHandle v0v1)  // (not const: OpenMesh's test for a large ring tags vertices)
{
    if (mesh.status(mesh.edge_handle(v0v1)).deleted()) return false;
    const HalfedgeHandle v1v0 = mesh.opposite_halfedge_handle(v0v1);
    const VertexHandle v0 = mesh.to_vertex_handle(v1v0), v1 = mesh.to_vertex_handle(v0v1);
    if (mesh.status(v0).deleted() || mesh.status(v1).deleted()) return false;
    // The vertex opposite the edge on a side with a face (invalid: none), refused when that
    // face's other two edges are both on the boundary.
    auto opposite_vertex = [&](HalfedgeHandle side, bool& refused) {
        if (mesh.is_boundary(side)) return VertexHandle();
        const HalfedgeHandle h1 = mesh.next_halfedge_handle(side),
                             h2 = mesh.next_halfedge_handle(h1);
        refused = mesh.is_boundary(mesh.opposite_halfedge_handle(h1)) &&
                  mesh.is_boundary(mesh.opposite_halfedge_handle(h2));
        return mesh.to_vertex_handle(h1);
    };
    bool refused = false;
    const VertexHandle vl = opposite_vertex(v0v1, refused);
    if (refused) return false;
    const VertexHandle vr = opposite_vertex(v1v0, refused);
    if (refused || vl == vr) return false;
    if (mesh.is_boundary(v0) && mesh.is_boundary(v1) && !mesh.is_boundary(v0v1) &&
        !mesh.is_boundary(v1v0))
        return false;
    // No common neighbour but vl and vr: v1's ring gathered once, v0's looked up in it. A ring
    // larger than the buffer (a CAD fan of hundreds of spokes, where that lookup would cost the
    // product of the two valences) is left to OpenMesh's tagging test, linear in them.
    std::array<VertexHandle, 32> ring_of_v1;
    std::size_t ring_size = 0;
    for (const VertexHandle u : mesh.vv_range(v1))
    {
        if (ring_size == ring_of_v1.size()) return mesh.is_collapse_ok(v0v1);
        ring_of_v1[ring_size++] = u;
    }
    const auto ring_end = ring_of_v1.begin() + static_cast<std::ptrdiff_t>(ring_size);
    for (const VertexHandle w : mesh.vv_range(v0))
        if (w != vl && w != vr && std::find(ring_of_v1.begin(), ring_end, w) != ring_end)
            return false;
    return true;
}

// Whether a face of the collapsing vertex survives a collapse onto v1 (a face of v1 too is
// removed).
bool survives_collapse(const SurfaceMesh& mesh, FaceHandle f, VertexHandle v1)
{
    const auto fv = detail::face_vertices(mesh, f);
    return std::find(fv.begin(), fv.end(), v1) == fv.end();
}

}  // namespace

OpStatus collapse_shape_status(const OperatorContext& ctx, HalfedgeHandle h, double max_new_length,
                               bool require_quality_gain, double min_new_angle_deg)
{
    using namespace detail;
    SurfaceMesh& mesh = ctx.mesh;  // (OpenMesh's topology test is not const; it changes nothing)
    const VertexHandle v0 = mesh.from_vertex_handle(h), v1 = mesh.to_vertex_handle(h);
    // The layers from the cheapest rejection up (every layer must pass, so the order only decides
    // the time and the reported layer): the class and the length bound are a few lookups and
    // refuse most attempts of the remesh loop (a collapse that would make a neighbour too long);
    // OpenMesh's topology test walks both rings.
    if (!class_allows_collapse(ctx, h)) return OpStatus::Class;
    const Vec3d p1 = mesh.point(v1);
    if (max_new_length > 0.0)
    {
        for (auto w : mesh.vv_range(v0))
            if (w != v1 && (mesh.point(w) - p1).norm() > max_new_length) return OpStatus::Quality;
    }
    const bool topology_ok = collapse_topology_ok(mesh, h);
    assert(topology_ok ==
           mesh.is_collapse_ok(h));  // (which sets vertex tags: nothing here reads them)
    if (!topology_ok) return OpStatus::Topology;

    // Geometry and quality layers: the faces of v0 that survive, with v0 moved onto v1.
    auto survives = [&](FaceHandle f) { return survives_collapse(mesh, f, v1); };
    double new_min = 1.0;
    const double min_cos = cos_deg(ctx.limits.max_normal_turn_deg);
    for (auto f : mesh.vf_range(v0))
    {
        if (!survives(f)) continue;
        const auto before = face_points(mesh, f);
        const auto after = face_points_with(mesh, f, v0, p1);
        if (!turn_ok_cos(normal(before), normal(after), min_cos)) return OpStatus::Geometry;
        const double q = qe(after);
        if (q < ctx.limits.min_new_quality ||
            (min_new_angle_deg > 0.0 &&
             triangle_min_angle_deg(after[0], after[1], after[2]) < min_new_angle_deg))
            return OpStatus::Quality;
        new_min = std::min(new_min, q);
    }
    if (require_quality_gain)
    {
        double old_min = 1.0;
        for (const VertexHandle v : {v0, v1})
            for (auto f : mesh.vf_range(v)) old_min = std::min(old_min, qe(face_points(mesh, f)));
        if (!(new_min > old_min + 1e-9)) return OpStatus::Quality;
    }
    return OpStatus::Done;
}

OpStatus collapse_status(const OperatorContext& ctx, HalfedgeHandle h, double max_new_length,
                         bool require_quality_gain, double min_new_angle_deg)
{
    using namespace detail;
    const OpStatus shape =
        collapse_shape_status(ctx, h, max_new_length, require_quality_gain, min_new_angle_deg);
    if (shape != OpStatus::Done) return shape;
    const SurfaceMesh& mesh = ctx.mesh;
    const VertexHandle v0 = mesh.from_vertex_handle(h), v1 = mesh.to_vertex_handle(h);
    const Vec3d p1 = mesh.point(v1);
    // The centroids of the changed faces against the model, last: the expensive test.
    if (ctx.limits.max_model_distance > 0.0)
        for (auto f : mesh.vf_range(v0))
        {
            if (!survives_collapse(mesh, f, v1)) continue;
            const auto after = face_points_with(mesh, f, v0, p1);
            if (!ctx.near_model((after[0] + after[1] + after[2]) / 3.0, v1,
                                ctx.limits.max_model_distance))
                return OpStatus::Geometry;
        }
    if (ctx.hooks.allow_collapse && !ctx.hooks.allow_collapse(mesh, h)) return OpStatus::Hook;
    return OpStatus::Done;
}

OpResult try_collapse(OperatorContext& ctx, HalfedgeHandle h, double max_new_length,
                      bool require_quality_gain, double min_new_angle_deg)
{
    if (!ctx.limits.insert) return refused(OpStatus::Disabled);
    SurfaceMesh& mesh = ctx.mesh;
    OpResult result;
    const VertexHandle v0 = mesh.from_vertex_handle(h), v1 = mesh.to_vertex_handle(h);
    result.status =
        collapse_status(ctx, h, max_new_length, require_quality_gain, min_new_angle_deg);
    if (result.status != OpStatus::Done) return result;

    // Commit. OpenMesh merges the edges (v0, x) and (v1, x) of the two removed faces and may keep
    // either one, so the curve ids are recorded by end vertex and written back afterwards (only
    // the curve edges: most collapses have none, and then no list is allocated).
    std::vector<std::pair<VertexHandle, int>> curve_by_end;
    for (const auto& [from, to] : {std::pair{v0, v1}, std::pair{v1, v0}})
        for (auto oh : mesh.voh_range(from))
        {
            const int curve = ctx.edge_curve(mesh.edge_handle(oh));
            if (mesh.to_vertex_handle(oh) != to && curve != kNoCurve)
                curve_by_end.emplace_back(mesh.to_vertex_handle(oh), curve);
        }
    mesh.collapse(h);
    for (auto oh : mesh.voh_range(v1))
    {
        const VertexHandle w = mesh.to_vertex_handle(oh);
        int curve = kNoCurve;
        for (const auto& [end, c] : curve_by_end)
            if (end == w) curve = c;
        mesh.property(ctx.props.edge_curve, mesh.edge_handle(oh)) = curve;
    }
    if (ctx.hooks.on_collapse) ctx.hooks.on_collapse(mesh, v0, v1);
    result.status = OpStatus::Done;
    result.vertex = v1;
    return result;
}

}  // namespace hdimesh::surface
