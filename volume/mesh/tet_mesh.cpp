#include "volume/mesh/tet_mesh.h"

#include <algorithm>
#include <cassert>

#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume
{

const char* to_string(VertexClass c)
{
    switch (c)
    {
        case VertexClass::Interior: return "interior";
        case VertexClass::Surface: return "surface";
        case VertexClass::Ridge: return "ridge";
        case VertexClass::Corner: return "corner";
    }
    return "?";
}

Classification to_classification(VertexClass c, int id)
{
    switch (c)
    {
        case VertexClass::Interior: return {Dimension::Volume, id, false};
        case VertexClass::Surface: return {Dimension::Surface, id, false};
        case VertexClass::Ridge: return {Dimension::Curve, id, false};
        case VertexClass::Corner: return {Dimension::Corner, id, false};
    }
    return {};
}

VertexClass to_vertex_class(const Classification& c)
{
    switch (c.dimension)
    {
        case Dimension::Volume: return VertexClass::Interior;
        case Dimension::Surface: return VertexClass::Surface;
        case Dimension::Curve: return VertexClass::Ridge;
        case Dimension::Corner: return VertexClass::Corner;
    }
    return VertexClass::Interior;
}

int TetMesh::add_vertex(const Vec3& p, int ref, VertexClass cls)
{
    points.push_back(p);
    vertex_refs.push_back(ref);
    vertex_classes.push_back(cls);
    return num_vertices() - 1;
}

int TetMesh::add_tet(const TetVertices& v, int ref)
{
    tets.push_back(v);
    tet_refs.push_back(ref);
    if (!neighbors.empty()) neighbors.push_back({kNoTet, kNoTet, kNoTet, kNoTet});
    return num_tet_slots() - 1;
}

int TetMesh::add_triangle(const Triangle& v, int ref)
{
    triangles.push_back(v);
    triangle_refs.push_back(ref);
    return static_cast<int>(triangles.size()) - 1;
}

void TetMesh::kill_tet(int t)
{
    assert(!is_dead(t));
    tets[t][0] = kDeadTet;
}

int TetMesh::num_live_tets() const
{
    int n = 0;
    for (const auto& t : tets) n += (t[0] != kDeadTet);
    return n;
}

double TetMesh::volume(int t) const
{
    assert(!is_dead(t));
    const auto& v = tets[t];
    return signed_volume(points[v[0]], points[v[1]], points[v[2]], points[v[3]]);
}

double TetMesh::quality(int t) const
{
    assert(!is_dead(t));
    const auto& v = tets[t];
    return tet_quality(points[v[0]], points[v[1]], points[v[2]], points[v[3]]);
}

double TetMesh::total_volume() const
{
    double sum = 0.0;
    for (int t = 0; t < num_tet_slots(); ++t)
        if (!is_dead(t)) sum += volume(t);
    return sum;
}

std::size_t TetMesh::memory_bytes() const
{
    auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
    return bytes(points) + bytes(vertex_refs) + bytes(vertex_classes) + bytes(tets) +
           bytes(tet_refs) + bytes(neighbors) + bytes(triangles) + bytes(triangle_refs) +
           bytes(edges) + bytes(edge_refs) + bytes(ridges) + bytes(corners) +
           bytes(required_vertices) + bytes(required_edges) + bytes(required_triangles) +
           bytes(required_tets);
}

namespace
{

/// A tet face filed under its smallest vertex: the other two (sorted) and where it came from.
struct FaceEntry
{
    int mid, high;
    int tet_face;  // 4 * tet + local face
    bool operator<(const FaceEntry& o) const { return mid != o.mid ? mid < o.mid : high < o.high; }
};

}  // namespace

int TetMesh::build_adjacency()
{
    const int nv = num_vertices();
    const int nt = num_tet_slots();
    neighbors.assign(nt, {kNoTet, kNoTet, kNoTet, kNoTet});

    // bucket every face by its smallest vertex (counting sort: O(n))
    std::vector<int> bucket_start(nv + 1, 0);
    for (int t = 0; t < nt; ++t)
    {
        if (is_dead(t)) continue;
        for (int f = 0; f < 4; ++f)
        {
            const auto& fv = tet::kFaceVertices[f];
            const int low = std::min({tets[t][fv[0]], tets[t][fv[1]], tets[t][fv[2]]});
            ++bucket_start[low + 1];
        }
    }
    for (int v = 0; v < nv; ++v) bucket_start[v + 1] += bucket_start[v];
    std::vector<FaceEntry> entries(bucket_start[nv]);
    std::vector<int> fill(bucket_start.begin(), bucket_start.end() - 1);
    for (int t = 0; t < nt; ++t)
    {
        if (is_dead(t)) continue;
        for (int f = 0; f < 4; ++f)
        {
            const auto& fv = tet::kFaceVertices[f];
            std::array<int, 3> s = {tets[t][fv[0]], tets[t][fv[1]], tets[t][fv[2]]};
            std::sort(s.begin(), s.end());
            entries[fill[s[0]]++] = {s[1], s[2], 4 * t + f};
        }
    }

    // match equal faces inside each (small) bucket
    int overshared = 0;
    for (int v = 0; v < nv; ++v)
    {
        auto first = entries.begin() + bucket_start[v];
        auto last = entries.begin() + bucket_start[v + 1];
        std::sort(first, last);
        for (auto it = first; it != last;)
        {
            auto run_end = it + 1;
            while (run_end != last && run_end->mid == it->mid && run_end->high == it->high)
                ++run_end;
            const auto count = run_end - it;
            if (count == 2)
            {
                const int a = it->tet_face, b = (it + 1)->tet_face;
                neighbors[a / 4][a % 4] = b / 4;
                neighbors[b / 4][b % 4] = a / 4;
            }
            else if (count > 2)
            {
                ++overshared;
            }
            it = run_end;
        }
    }
    return overshared;
}

void TetMesh::classify_vertices()
{
    vertex_classes.assign(points.size(), VertexClass::Interior);
    for (const auto& tri : triangles)
        for (int v : tri) vertex_classes[v] = VertexClass::Surface;
    for (int e : ridges)
        for (int v : edges[e]) vertex_classes[v] = VertexClass::Ridge;
    for (int v : corners) vertex_classes[v] = VertexClass::Corner;
}

CompactionMaps TetMesh::compact()
{
    CompactionMaps maps;
    const int nv = num_vertices();
    const int nt = num_tet_slots();

    // tets: keep the live ones in order
    maps.old2new_tets.assign(nt, -1);
    int live = 0;
    for (int t = 0; t < nt; ++t)
        if (!is_dead(t)) maps.old2new_tets[t] = live++;

    // vertices: keep those referenced by anything
    std::vector<char> used(nv, 0);
    for_each_vertex_id([&](int& v) { used[v] = 1; });
    maps.old2new_verts.assign(nv, -1);
    int kept = 0;
    for (int v = 0; v < nv; ++v)
        if (used[v]) maps.old2new_verts[v] = kept++;

    const auto& v2v = maps.old2new_verts;
    const auto& t2t = maps.old2new_tets;
    // In place: an entity only ever moves to a smaller or equal index.
    for_each_vertex_array([&](auto& values) {
        for (int v = 0; v < nv; ++v)
            if (v2v[v] >= 0) values[v2v[v]] = values[v];
        values.resize(kept);
    });
    for_each_vertex_id([&](int& v) { v = v2v[v]; });

    const bool adjacency = has_adjacency();
    auto keep_live_tets = [&](auto& values) {
        for (int t = 0; t < nt; ++t)
            if (t2t[t] >= 0) values[t2t[t]] = values[t];
        values.resize(live);
    };
    for_each_tet_array(keep_live_tets);
    if (adjacency)
    {
        keep_live_tets(neighbors);
        for (auto& row : neighbors)
            for (int& n : row)
                if (n != kNoTet) n = t2t[n];
    }
    else
        neighbors.clear();

    std::vector<int> kept_required_tets;
    for (int t : required_tets)
        if (t2t[t] >= 0) kept_required_tets.push_back(t2t[t]);
    required_tets = std::move(kept_required_tets);
    return maps;
}

}  // namespace hdimesh::volume
