#include <algorithm>
#include <vector>

#include "surface/detail/local_ops_geometry.h"
#include "surface/local_ops.h"

namespace hdimesh::surface
{
namespace
{

// Best triangulation of the hole polygon ring[0..m-1] (Klincsek's dynamic program): maximize the
// worst Qe, with every triangle turned at most max_turn from the vertex normal and no chord that
// already exists as an edge elsewhere in the mesh.
struct HoleTriangulation
{
    double worst = -1.0;  // < 0: none is legal
    std::vector<std::array<int, 3>> triangles;
};

HoleTriangulation triangulate_hole(const SurfaceMesh& mesh, const std::vector<VertexHandle>& ring,
                                   const Vec3d& vertex_normal, double max_turn_deg)
{
    using namespace detail;
    const double max_turn_cos = cos_deg(max_turn_deg);
    const int m = static_cast<int>(ring.size());
    std::vector<std::vector<double>> best(m, std::vector<double>(m, -1.0));
    std::vector<std::vector<int>> split(m, std::vector<int>(m, -1));
    auto chord_ok = [&](int i, int j) {
        if (j == i + 1 || (i == 0 && j == m - 1)) return true;  // a side of the polygon
        return !mesh.find_halfedge(ring[i], ring[j]).is_valid();
    };
    for (int i = 0; i + 1 < m; ++i) best[i][i + 1] = 1.0;  // a side: nothing to triangulate
    for (int span = 2; span < m; ++span)
        for (int i = 0; i + span < m; ++i)
        {
            const int j = i + span;
            if (!chord_ok(i, j)) continue;
            for (int k = i + 1; k < j; ++k)
            {
                if (best[i][k] < 0.0 || best[k][j] < 0.0) continue;
                const std::array<Vec3d, 3> t{mesh.point(ring[i]), mesh.point(ring[k]),
                                             mesh.point(ring[j])};
                if (!turn_ok_cos(vertex_normal, normal(t), max_turn_cos)) continue;
                const double q = std::min({best[i][k], best[k][j], qe(t)});
                if (q > best[i][j])
                {
                    best[i][j] = q;
                    split[i][j] = k;
                }
            }
        }
    HoleTriangulation out;
    out.worst = best[0][m - 1];
    if (out.worst < 0.0) return out;
    std::vector<std::array<int, 2>> todo{{0, m - 1}};
    while (!todo.empty())
    {
        const auto [i, j] = todo.back();
        todo.pop_back();
        if (j - i < 2) continue;
        const int k = split[i][j];
        out.triangles.push_back({i, k, j});
        todo.push_back({i, k});
        todo.push_back({k, j});
    }
    return out;
}

}  // namespace

OpResult try_remove_vertex(OperatorContext& ctx, VertexHandle v)
{
    if (!ctx.limits.insert) return refused(OpStatus::Disabled);
    using namespace detail;
    SurfaceMesh& mesh = ctx.mesh;
    OpResult result;
    if (ctx.vertex_class(v) != VertexClass::Smooth)
    {
        result.status = OpStatus::Class;
        return result;
    }
    if (mesh.is_boundary(v)) return result;
    // The ring in the orientation of the faces: face (v, ring[i], ring[i+1]).
    std::vector<VertexHandle> ring;
    const HalfedgeHandle start = mesh.halfedge_handle(v);
    HalfedgeHandle h = start;
    do
    {
        ring.push_back(mesh.to_vertex_handle(h));
        h = mesh.opposite_halfedge_handle(mesh.prev_halfedge_handle(h));
    } while (h != start && ring.size() <= 9);
    const int m = static_cast<int>(ring.size());
    if (m < 3 || m > 8) return result;
    for (int i = 0; i < m; ++i)
    {
        if (mesh.is_boundary(ring[i])) return result;  // add_face could meet a complex vertex
        for (int j = i + 1; j < m; ++j)
            if (ring[i] == ring[j]) return result;
    }
    int ref = 0;
    bool first = true;
    Vec3d vertex_normal(0, 0, 0);
    double old_min = 1.0;
    for (auto f : mesh.vf_range(v))
    {
        const int r = mesh.property(ctx.props.face_ref, f);
        if (!first && r != ref)
        {
            result.status = OpStatus::Class;
            return result;
        }
        ref = r;
        first = false;
        const auto p = face_points(mesh, f);
        vertex_normal += OpenMesh::cross(p[1] - p[0], p[2] - p[0]);
        old_min = std::min(old_min, qe(p));
    }
    if (!(vertex_normal.norm() > 0.0))
    {
        result.status = OpStatus::Geometry;
        return result;
    }
    vertex_normal.normalize();

    const HoleTriangulation hole =
        triangulate_hole(mesh, ring, vertex_normal, ctx.limits.max_normal_turn_deg);
    if (hole.worst < 0.0)
    {
        result.status = OpStatus::Geometry;
        return result;
    }
    if (!(hole.worst > old_min + 1e-9) || hole.worst < ctx.limits.min_new_quality)
    {
        result.status = OpStatus::Quality;
        return result;
    }
    if (ctx.limits.max_model_distance > 0.0)
        for (const auto& t : hole.triangles)
        {
            const Vec3d centroid =
                (mesh.point(ring[t[0]]) + mesh.point(ring[t[1]]) + mesh.point(ring[t[2]])) / 3.0;
            if (!ctx.near_model(centroid, ring[t[0]], ctx.limits.max_model_distance))
            {
                result.status = OpStatus::Geometry;
                return result;
            }
        }
    if (ctx.hooks.allow_remove_vertex)
    {
        std::vector<std::array<VertexHandle, 3>> planned;
        planned.reserve(hole.triangles.size());
        for (const auto& t : hole.triangles)
            planned.push_back({ring[t[0]], ring[t[1]], ring[t[2]]});
        if (!ctx.hooks.allow_remove_vertex(mesh, v, planned))
        {
            result.status = OpStatus::Hook;
            return result;
        }
    }

    // Commit: the ring vertices are interior and the chords are new, so every add_face succeeds.
    mesh.delete_vertex(v, false);
    std::vector<FaceHandle> new_faces;
    for (const auto& t : hole.triangles)
    {
        const FaceHandle f = mesh.add_face(ring[t[0]], ring[t[1]], ring[t[2]]);
        if (!f.is_valid()) continue;  // cannot happen after the checks above
        mesh.property(ctx.props.face_ref, f) = ref;
        new_faces.push_back(f);
    }
    // Chords are new edges (default property values): they belong to no curve.
    for (const auto& t : hole.triangles)
        for (int s = 0; s < 3; ++s)
        {
            const int i = std::min(t[s], t[(s + 1) % 3]), j = std::max(t[s], t[(s + 1) % 3]);
            if (j == i + 1 || (i == 0 && j == m - 1)) continue;
            const HalfedgeHandle chord = mesh.find_halfedge(ring[i], ring[j]);
            if (chord.is_valid())
                mesh.property(ctx.props.edge_curve, mesh.edge_handle(chord)) = kNoCurve;
        }
    if (ctx.hooks.on_remove_vertex) ctx.hooks.on_remove_vertex(mesh, v, new_faces);
    result.status = OpStatus::Done;
    return result;
}

}  // namespace hdimesh::surface
