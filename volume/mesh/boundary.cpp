#include "volume/mesh/boundary.h"

#include <algorithm>
#include <cassert>
#include <limits>

#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume
{

namespace
{

bool tet_ids_in_range(const TetVertices& tet, int num_vertices)
{
    for (int v : tet)
        if (v < 0 || v >= num_vertices) return false;
    return true;
}

/// Live tets whose four ids are valid vertices: the only ones the topology helpers look at.
bool usable_tet(const TetMesh& mesh, int t)
{
    return !mesh.is_dead(t) && tet_ids_in_range(mesh.tets[t], mesh.num_vertices());
}

/// A face filed under its smallest vertex (the bucket) by its two other vertices.
struct FaceKey
{
    int mid, high;
    TetFace face;
};

}  // namespace

Triangle face_vertices(const TetMesh& mesh, const TetFace& face)
{
    const auto& fv = tet::kFaceVertices[face.local_face];
    const auto& t = mesh.tets[face.tet];
    return {t[fv[0]], t[fv[1]], t[fv[2]]};
}

FaceGroups group_tet_faces(const TetMesh& mesh)
{
    const int nv = mesh.num_vertices();
    const int nt = mesh.num_tet_slots();

    // counting sort of the faces by their smallest vertex: O(n), buckets stay tiny
    std::vector<int> bucket_start(nv + 1, 0);
    for (int t = 0; t < nt; ++t)
    {
        if (!usable_tet(mesh, t)) continue;
        for (int f = 0; f < 4; ++f)
        {
            const Triangle s = sorted_triple(face_vertices(mesh, {t, f}));
            ++bucket_start[s[0] + 1];
        }
    }
    for (int v = 0; v < nv; ++v) bucket_start[v + 1] += bucket_start[v];
    std::vector<FaceKey> keys(bucket_start[nv]);
    std::vector<int> fill(bucket_start.begin(), bucket_start.end() - 1);
    for (int t = 0; t < nt; ++t)
    {
        if (!usable_tet(mesh, t)) continue;
        for (int f = 0; f < 4; ++f)
        {
            const Triangle s = sorted_triple(face_vertices(mesh, {t, f}));
            keys[fill[s[0]]++] = {s[1], s[2], {t, f}};
        }
    }

    FaceGroups groups;
    groups.uses.reserve(keys.size());
    groups.start.reserve(keys.size() / 2 + 2);
    for (int v = 0; v < nv; ++v)
    {
        auto first = keys.begin() + bucket_start[v];
        auto last = keys.begin() + bucket_start[v + 1];
        std::sort(first, last, [](const FaceKey& a, const FaceKey& b) {
            if (a.mid != b.mid) return a.mid < b.mid;
            if (a.high != b.high) return a.high < b.high;
            return a.face.tet < b.face.tet;  // deterministic order of the uses
        });
        for (auto it = first; it != last; ++it)
        {
            if (it == first || it->mid != (it - 1)->mid || it->high != (it - 1)->high)
                groups.start.push_back(static_cast<int>(groups.uses.size()));
            groups.uses.push_back(it->face);
        }
    }
    groups.start.push_back(static_cast<int>(groups.uses.size()));
    return groups;
}

std::vector<Triangle> tet_boundary_faces(const TetMesh& mesh)
{
    const FaceGroups groups = group_tet_faces(mesh);
    std::vector<Triangle> boundary;
    for (int k = 0; k < groups.num_faces(); ++k)
        if (groups.start[k + 1] - groups.start[k] == 1)
            boundary.push_back(face_vertices(mesh, groups.uses[groups.start[k]]));
    return boundary;
}

std::vector<Triangle> tet_surface_faces(const TetMesh& mesh)
{
    const FaceGroups groups = group_tet_faces(mesh);
    std::vector<Triangle> faces;
    for (int k = 0; k < groups.num_faces(); ++k)
    {
        const int first = groups.start[k], count = groups.start[k + 1] - first;
        if (count == 1)
        {
            faces.push_back(face_vertices(mesh, groups.uses[first]));
            continue;
        }
        if (count != 2) continue;  // a non-conforming face (check_mesh reports it)
        const TetFace& a = groups.uses[first];
        const TetFace& b = groups.uses[first + 1];
        const int ra = mesh.tet_refs[a.tet], rb = mesh.tet_refs[b.tet];
        if (ra != rb) faces.push_back(face_vertices(mesh, ra < rb ? a : b));
    }
    return faces;
}

std::vector<Triangle> tet_surface_faces_by_adjacency(const TetMesh& mesh)
{
    // (sorted triple, face): the grouping's order is that of the sorted triples
    std::vector<std::pair<Triangle, Triangle>> found;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (!usable_tet(mesh, t)) continue;
        for (int f = 0; f < 4; ++f)
        {
            const int n = mesh.neighbors[t][f];
            // a boundary face, or an interface face seen from the smaller ref
            if (n != kNoTet && mesh.tet_refs[t] >= mesh.tet_refs[n]) continue;
            const Triangle face = face_vertices(mesh, {t, f});
            found.push_back({sorted_triple(face), face});
        }
    }
    std::sort(found.begin(), found.end());
    std::vector<Triangle> faces;
    faces.reserve(found.size());
    for (const auto& entry : found) faces.push_back(entry.second);
    assert(faces == tet_surface_faces(mesh) && "tet_surface_faces_by_adjacency: stale adjacency");
    return faces;
}

std::vector<ListedTriangle> listed_triangles(const TetMesh& mesh)
{
    std::vector<ListedTriangle> listed;
    listed.reserve(mesh.triangles.size());
    const int nv = mesh.num_vertices();
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    {
        const Triangle& tri = mesh.triangles[i];
        if (std::all_of(tri.begin(), tri.end(), [nv](int v) { return v >= 0 && v < nv; }))
            listed.push_back({sorted_triple(tri), static_cast<int>(i)});
    }
    std::sort(listed.begin(), listed.end());
    return listed;
}

std::pair<std::vector<ListedTriangle>::const_iterator, std::vector<ListedTriangle>::const_iterator>
listings(const std::vector<ListedTriangle>& listed, const Triangle& key)
{
    return std::equal_range(
        listed.begin(), listed.end(), ListedTriangle{key, -1},
        [](const ListedTriangle& a, const ListedTriangle& b) { return a.key < b.key; });
}

double enclosed_volume(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles)
{
    if (triangles.empty()) return 0.0;
    Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 high = -low;
    for (const auto& tri : triangles)
        for (int v : tri)
        {
            low = low.cwiseMin(points[v]);
            high = high.cwiseMax(points[v]);
        }
    const Vec3 centre = 0.5 * (low + high);
    double six_volume = 0.0;
    for (const auto& tri : triangles)
        six_volume += signed_volume6(centre, points[tri[0]], points[tri[1]], points[tri[2]]);
    return six_volume / 6.0;
}

std::vector<Edge> unique_tet_edges(const TetMesh& mesh)
{
    const int nv = mesh.num_vertices();
    const int nt = mesh.num_tet_slots();

    // every tet edge filed under its lower vertex; duplicates removed inside each bucket
    std::vector<int> bucket_start(nv + 1, 0);
    for (int t = 0; t < nt; ++t)
    {
        if (!usable_tet(mesh, t)) continue;
        for (const auto& ev : tet::kEdgeVertices)
            ++bucket_start[std::min(mesh.tets[t][ev[0]], mesh.tets[t][ev[1]]) + 1];
    }
    for (int v = 0; v < nv; ++v) bucket_start[v + 1] += bucket_start[v];
    std::vector<int> higher(bucket_start[nv]);
    std::vector<int> fill(bucket_start.begin(), bucket_start.end() - 1);
    for (int t = 0; t < nt; ++t)
    {
        if (!usable_tet(mesh, t)) continue;
        for (const auto& ev : tet::kEdgeVertices)
        {
            const int a = mesh.tets[t][ev[0]], b = mesh.tets[t][ev[1]];
            higher[fill[std::min(a, b)]++] = std::max(a, b);
        }
    }

    std::vector<Edge> edges;
    edges.reserve(higher.size() / 5 + 1);  // about 7 tet-edge uses per edge in a volume mesh
    for (int v = 0; v < nv; ++v)
    {
        auto first = higher.begin() + bucket_start[v];
        auto last = higher.begin() + bucket_start[v + 1];
        std::sort(first, last);
        for (auto it = first; it != last; ++it)
            if (it == first || *it != *(it - 1)) edges.push_back({v, *it});
    }
    return edges;
}

VertexGraph vertex_graph(const TetMesh& mesh)
{
    const int nv = mesh.num_vertices();
    const std::vector<Edge> edges = unique_tet_edges(mesh);
    VertexGraph graph;
    graph.start.assign(nv + 1, 0);
    for (const auto& e : edges)
    {
        ++graph.start[e[0] + 1];
        ++graph.start[e[1] + 1];
    }
    for (int v = 0; v < nv; ++v) graph.start[v + 1] += graph.start[v];
    graph.neighbors.resize(graph.start[nv]);
    std::vector<int> fill(graph.start.begin(), graph.start.end() - 1);
    for (const auto& e : edges)
    {
        graph.neighbors[fill[e[0]]++] = e[1];
        graph.neighbors[fill[e[1]]++] = e[0];
    }
    for (int v = 0; v < nv; ++v)
        std::sort(graph.neighbors.begin() + graph.start[v],
                  graph.neighbors.begin() + graph.start[v + 1]);
    return graph;
}

}  // namespace hdimesh::volume
