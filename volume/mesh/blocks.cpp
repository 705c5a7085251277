#include "volume/mesh/blocks.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <unordered_map>
#include <utility>

#include "common/morton.h"
#include "volume/mesh/tet_topology.h"

namespace hdimesh::volume
{

namespace
{

/// Not a power of two, so a shifted round's cuts never line up with the last one's.
constexpr double kRoundShift = 0.381966;

/// Sorted (key, index) pairs of the mesh's triangles or edges, and which vertices they touch:
/// most faces and edges of a block have a vertex on none and skip the search.
template <class Key>
struct EntityIndex
{
    std::vector<std::pair<Key, int>> keys;
    std::vector<char> touches;  ///< per vertex

    int find(const Key& key) const
    {
        for (int v : key)
            if (static_cast<std::size_t>(v) >= touches.size() || !touches[v]) return -1;
        auto it = std::lower_bound(keys.begin(), keys.end(), std::make_pair(key, -1));
        return it != keys.end() && it->first == key ? it->second : -1;
    }
};

Edge sorted_pair(const Edge& e) { return {std::min(e[0], e[1]), std::max(e[0], e[1])}; }

Triangle face_key(const TetVertices& tv, int f)
{
    const auto& fv = tet::kFaceVertices[f];
    return sorted_triple({tv[fv[0]], tv[fv[1]], tv[fv[2]]});
}

template <class Key, class Entities, class Sort>
EntityIndex<Key> index_entities(const Entities& entities, int num_vertices, Sort sort_key)
{
    EntityIndex<Key> index;
    index.touches.assign(num_vertices, 0);
    index.keys.reserve(entities.size());
    for (std::size_t i = 0; i < entities.size(); ++i)
    {
        index.keys.push_back({sort_key(entities[i]), static_cast<int>(i)});
        for (int v : entities[i]) index.touches[v] = 1;
    }
    std::sort(index.keys.begin(), index.keys.end());
    return index;
}

struct PointHash
{
    std::size_t operator()(const Vec3& p) const
    {
        std::uint64_t h = 1469598103934665603ull, bits;
        for (int k = 0; k < 3; ++k)
        {
            const double x = p[k] + 0.0;  // -0.0 and 0.0 compare equal: they must hash alike
            std::memcpy(&bits, &x, sizeof bits);
            h = (h ^ bits) * 1099511628211ull;
        }
        return static_cast<std::size_t>(h ^ (h >> 29));
    }
};
struct PointEqual
{
    bool operator()(const Vec3& a, const Vec3& b) const
    {
        return a.x() == b.x() && a.y() == b.y() && a.z() == b.z();
    }
};

/// What every block reads of the whole mesh, built once.
struct SharedView
{
    const TetMesh& mesh;
    const std::vector<int>& block_of_tet;
    EntityIndex<Triangle> triangles;
    EntityIndex<Edge> edges;
    std::vector<char> required_triangle, required_edge, ridge;  ///< per entity
    std::vector<char> required_tet;                             ///< per tet slot
    std::vector<char> pinned_vertex;                            ///< corner or required: never moved
    std::vector<int> index_in_block;  ///< per tet slot: its place in its block's list
};

/// One block: its mesh, and after the work, the whole mesh's id of each of its vertices
/// (-1: new).
struct Block
{
    TetMesh mesh;
    std::vector<int> copied_triangles, copied_edges;  ///< the whole mesh's, by index
    std::vector<int> cut_vertices;  ///< the whole mesh's, on faces shared with another block
    std::unordered_map<Vec3, int, PointHash, PointEqual> kept;  ///< fixed vertex -> global id
    std::vector<int> global_vertex;
};

Block extract_block(const SharedView& view, const std::vector<int>& tets, int b)
{
    const TetMesh& mesh = view.mesh;
    Block block;
    TetMesh& out = block.mesh;
    std::vector<int> vertices;
    vertices.reserve(4 * tets.size());
    for (int t : tets)
        for (int v : mesh.tets[t]) vertices.push_back(v);
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    auto local = [&](int v) {
        return static_cast<int>(std::lower_bound(vertices.begin(), vertices.end(), v) -
                                vertices.begin());
    };
    for (int v : vertices)
        out.add_vertex(mesh.points[v], mesh.vertex_refs[v], mesh.vertex_classes[v]);
    for (int t : tets)
    {
        const auto& tv = mesh.tets[t];
        const int lt =
            out.add_tet({local(tv[0]), local(tv[1]), local(tv[2]), local(tv[3])}, mesh.tet_refs[t]);
        if (view.required_tet[t]) out.required_tets.push_back(lt);
    }
    // the adjacency inside the block is the mesh's: no search
    out.neighbors.resize(tets.size());
    for (std::size_t i = 0; i < tets.size(); ++i)
        for (int f = 0; f < 4; ++f)
        {
            const int n = mesh.neighbors[tets[i]][f];
            out.neighbors[i][f] =
                n != kNoTet && view.block_of_tet[n] == b ? view.index_in_block[n] : kNoTet;
        }
    // faces: the mesh's triangles with a tet here (once), and the frozen faces
    std::vector<char> frozen(vertices.size(), 0), cut(vertices.size(), 0);
    for (std::size_t i = 0; i < tets.size(); ++i)
    {
        const int t = tets[i];
        const auto& tv = mesh.tets[t];
        for (int f = 0; f < 4; ++f)
        {
            const int n = mesh.neighbors[t][f];
            const bool inside = n != kNoTet && view.block_of_tet[n] == b;
            if (inside && n < t) continue;  // seen from n
            const auto& fv = tet::kFaceVertices[f];
            const Triangle face = {tv[fv[0]], tv[fv[1]], tv[fv[2]]};
            const int found = view.triangles.find(sorted_triple(face));
            const bool locked = n != kNoTet && !inside;
            if (found < 0 && !locked) continue;
            const Triangle& tri = found >= 0 ? mesh.triangles[found] : face;
            const int lt =
                out.add_triangle({local(tri[0]), local(tri[1]), local(tri[2])},
                                 found >= 0 ? mesh.triangle_refs[found] : kFrozenFaceRef);
            if (found >= 0) block.copied_triangles.push_back(found);
            if (locked || (found >= 0 && view.required_triangle[found]))
                out.required_triangles.push_back(lt);
            if (locked)
                for (int k = 0; k < 3; ++k) frozen[out.triangles[lt][k]] = 1;
            if (locked && view.block_of_tet[n] >= 0)
                for (int k = 0; k < 3; ++k) cut[out.triangles[lt][k]] = 1;
        }
    }
    // feature edges of the block's tets
    if (!mesh.edges.empty())
    {
        for (int t : tets)
        {
            const auto& tv = mesh.tets[t];
            for (const auto& e : tet::kEdgeVertices)
            {
                const int found = view.edges.find(sorted_pair({tv[e[0]], tv[e[1]]}));
                if (found >= 0) block.copied_edges.push_back(found);
            }
        }
        std::sort(block.copied_edges.begin(), block.copied_edges.end());
        block.copied_edges.erase(std::unique(block.copied_edges.begin(), block.copied_edges.end()),
                                 block.copied_edges.end());
        for (int i : block.copied_edges)
        {
            const int le = static_cast<int>(out.edges.size());
            out.edges.push_back({local(mesh.edges[i][0]), local(mesh.edges[i][1])});
            out.edge_refs.push_back(mesh.edge_refs[i]);
            if (view.ridge[i]) out.ridges.push_back(le);
            if (view.required_edge[i]) out.required_edges.push_back(le);
        }
    }
    for (int v : mesh.corners)
        if (std::binary_search(vertices.begin(), vertices.end(), v))
            out.corners.push_back(local(v));
    for (std::size_t i = 0; i < vertices.size(); ++i)
        if (frozen[i] || view.pinned_vertex[vertices[i]])
            out.required_vertices.push_back(static_cast<int>(i));
    for (std::size_t i = 0; i < vertices.size(); ++i)
        if (cut[i]) block.cut_vertices.push_back(vertices[i]);
    // the vertices the work may not move or remove (the operators' own rule), found again by
    // their positions
    const MeshConstraints constraints(out);
    for (std::size_t i = 0; i < vertices.size(); ++i)
        if (!constraints.is_free_vertex(static_cast<int>(i)))
            block.kept.emplace(out.points[i], vertices[i]);
    return block;
}

/// After the work: the whole mesh's id of each block vertex a tet, triangle or edge uses
/// (-1: new).
void map_block_vertices(Block& block)
{
    TetMesh& m = block.mesh;
    std::vector<char> used(m.num_vertices(), 0);
    m.for_each_vertex_id([&](int& v) { used[v] = 1; });
    block.global_vertex.assign(m.num_vertices(), -2);  // -2: unused
    for (int v = 0; v < m.num_vertices(); ++v)
    {
        if (!used[v]) continue;
        auto it = block.kept.find(m.points[v]);
        block.global_vertex[v] = it != block.kept.end() ? it->second : -1;
    }
    block.kept.clear();
}

/// Keeps the first of each key in `keys` (sorted key, position): returns positions to keep.
template <class Key>
std::vector<char> first_of_each(std::vector<std::pair<Key, int>> keys)
{
    std::vector<char> keep(keys.size(), 0);
    std::sort(keys.begin(), keys.end());
    for (std::size_t i = 0; i < keys.size(); ++i)
        if (i == 0 || keys[i].first != keys[i - 1].first) keep[keys[i].second] = 1;
    return keep;
}

std::vector<char> merge_blocks(TetMesh& mesh, const BlockPartition& partition,
                               std::vector<Block>& blocks, const SharedView& view)
{
    std::vector<char> frozen(mesh.num_vertices(), 0);
    for (const Block& block : blocks)
        for (int v : block.cut_vertices) frozen[v] = 1;
    // the block-free parts of the mesh keep their entities; the blocks bring theirs
    std::vector<char> triangle_copied(mesh.triangles.size(), 0), edge_copied(mesh.edges.size(), 0);
    for (const Block& block : blocks)
    {
        for (int i : block.copied_triangles) triangle_copied[i] = 1;
        for (int i : block.copied_edges) edge_copied[i] = 1;
    }
    std::vector<Triangle> triangles;
    std::vector<int> triangle_refs;
    std::vector<char> triangle_required;
    std::vector<Edge> edges;
    std::vector<int> edge_refs;
    std::vector<char> edge_ridge, edge_required;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
        if (!triangle_copied[i])
        {
            triangles.push_back(mesh.triangles[i]);
            triangle_refs.push_back(mesh.triangle_refs[i]);
            triangle_required.push_back(view.required_triangle[i]);
        }
    for (std::size_t i = 0; i < mesh.edges.size(); ++i)
        if (!edge_copied[i])
        {
            edges.push_back(mesh.edges[i]);
            edge_refs.push_back(mesh.edge_refs[i]);
            edge_ridge.push_back(view.ridge[i]);
            edge_required.push_back(view.required_edge[i]);
        }
    // tets: the block-free ones in order, then each block's; the adjacency is kept from both
    // sides and the faces on a cut matched by their vertices
    const int nt = mesh.num_tet_slots();
    std::vector<char> required_tet(nt, 0);
    for (int t : mesh.required_tets) required_tet[t] = 1;
    std::vector<TetVertices> tets, neighbors;
    std::vector<int> tet_refs;
    std::vector<char> tet_required;
    struct OpenFace
    {
        Triangle key;
        int tet, face;
        bool operator<(const OpenFace& o) const
        {
            return key != o.key ? key < o.key : (tet != o.tet ? tet < o.tet : face < o.face);
        }
    };
    std::vector<OpenFace> open;
    std::vector<int> kept_index(nt, -1);
    for (int t = 0; t < nt; ++t)
        if (!mesh.is_dead(t) && partition.block_of_tet[t] < 0)
            kept_index[t] = static_cast<int>(tets.size()), tets.push_back(mesh.tets[t]);
    for (int t = 0; t < nt; ++t)
    {
        const int i = kept_index[t];
        if (i < 0) continue;
        tet_refs.push_back(mesh.tet_refs[t]);
        tet_required.push_back(required_tet[t]);
        TetVertices row;
        for (int f = 0; f < 4; ++f)
        {
            const int n = mesh.neighbors[t][f];
            row[f] = n == kNoTet ? kNoTet : kept_index[n];
            if (n != kNoTet && kept_index[n] < 0) open.push_back({face_key(tets[i], f), i, f});
        }
        neighbors.push_back(row);
    }

    for (Block& block : blocks)
    {
        TetMesh& m = block.mesh;
        std::vector<int>& to_global = block.global_vertex;
        for (int v = 0; v < m.num_vertices(); ++v)
            if (to_global[v] == -1)
                to_global[v] = mesh.add_vertex(m.points[v], m.vertex_refs[v], m.vertex_classes[v]);
        std::vector<char> required(m.num_tet_slots(), 0);
        for (int t : m.required_tets) required[t] = 1;
        const int offset = static_cast<int>(tets.size());
        for (int t = 0; t < m.num_tet_slots(); ++t)
        {
            const auto& tv = m.tets[t];
            tets.push_back(
                {to_global[tv[0]], to_global[tv[1]], to_global[tv[2]], to_global[tv[3]]});
            tet_refs.push_back(m.tet_refs[t]);
            tet_required.push_back(required[t]);
            TetVertices row;
            for (int f = 0; f < 4; ++f)
            {
                const int n = m.neighbors[t][f];
                row[f] = n == kNoTet ? kNoTet : offset + n;
                if (n == kNoTet) open.push_back({face_key(tets.back(), f), offset + t, f});
            }
            neighbors.push_back(row);
        }
        std::vector<char> required_triangle(m.triangles.size(), 0), ridge(m.edges.size(), 0),
            required_edge(m.edges.size(), 0);
        for (int i : m.required_triangles) required_triangle[i] = 1;
        for (int i : m.ridges) ridge[i] = 1;
        for (int i : m.required_edges) required_edge[i] = 1;
        for (std::size_t i = 0; i < m.triangles.size(); ++i)
        {
            if (m.triangle_refs[i] == kFrozenFaceRef) continue;
            const Triangle& tri = m.triangles[i];
            triangles.push_back({to_global[tri[0]], to_global[tri[1]], to_global[tri[2]]});
            triangle_refs.push_back(m.triangle_refs[i]);
            // (a face frozen here is required in the block only; one required in the input
            // never splits, so its key is the input's)
            triangle_required.push_back(required_triangle[i]);
        }
        for (std::size_t i = 0; i < m.edges.size(); ++i)
        {
            edges.push_back({to_global[m.edges[i][0]], to_global[m.edges[i][1]]});
            edge_refs.push_back(m.edge_refs[i]);
            edge_ridge.push_back(ridge[i]);
            edge_required.push_back(required_edge[i]);
        }
        block = Block();
    }

    // a frozen face or edge between blocks came back from each: keep the first
    std::vector<std::pair<Triangle, int>> triangle_keys(triangles.size());
    for (std::size_t i = 0; i < triangles.size(); ++i)
        triangle_keys[i] = {sorted_triple(triangles[i]), static_cast<int>(i)};
    const std::vector<char> keep_triangle = first_of_each(std::move(triangle_keys));
    auto is_input_required = [&](const Triangle& tri) {
        const int found = view.triangles.find(sorted_triple(tri));
        return found >= 0 && view.required_triangle[found];
    };
    mesh.triangles.clear();
    mesh.triangle_refs.clear();
    mesh.required_triangles.clear();
    for (std::size_t i = 0; i < triangles.size(); ++i)
    {
        if (!keep_triangle[i]) continue;
        if (triangle_required[i] && is_input_required(triangles[i]))
            mesh.required_triangles.push_back(static_cast<int>(mesh.triangles.size()));
        mesh.triangles.push_back(triangles[i]);
        mesh.triangle_refs.push_back(triangle_refs[i]);
    }
    std::vector<std::pair<Edge, int>> edge_keys(edges.size());
    for (std::size_t i = 0; i < edges.size(); ++i)
        edge_keys[i] = {sorted_pair(edges[i]), static_cast<int>(i)};
    const std::vector<char> keep_edge = first_of_each(std::move(edge_keys));
    mesh.edges.clear();
    mesh.edge_refs.clear();
    mesh.ridges.clear();
    mesh.required_edges.clear();
    for (std::size_t i = 0; i < edges.size(); ++i)
    {
        if (!keep_edge[i]) continue;
        const int e = static_cast<int>(mesh.edges.size());
        if (edge_ridge[i]) mesh.ridges.push_back(e);
        if (edge_required[i]) mesh.required_edges.push_back(e);
        mesh.edges.push_back(edges[i]);
        mesh.edge_refs.push_back(edge_refs[i]);
    }
    // a face open on both sides is a cut: its two tets are neighbours; once, the boundary
    std::sort(open.begin(), open.end());
    for (std::size_t i = 0; i + 1 < open.size(); ++i)
        if (open[i].key == open[i + 1].key)
        {
            neighbors[open[i].tet][open[i].face] = open[i + 1].tet;
            neighbors[open[i + 1].tet][open[i + 1].face] = open[i].tet;
            ++i;
        }
    mesh.tets = std::move(tets);
    mesh.tet_refs = std::move(tet_refs);
    mesh.neighbors = std::move(neighbors);
    mesh.required_tets.clear();
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (tet_required[t]) mesh.required_tets.push_back(t);
    const CompactionMaps maps = mesh.compact();  // drops the vertices the blocks removed
    std::vector<char> kept(mesh.num_vertices(), 0);
    for (std::size_t v = 0; v < frozen.size(); ++v)
        if (frozen[v] && maps.old2new_verts[v] >= 0) kept[maps.old2new_verts[v]] = 1;
    return kept;
}

}  // namespace

int block_count(long long live_tets, int tets_per_block)
{
    if (tets_per_block < 1) return 1;
    return static_cast<int>(
        std::max<long long>(1, (live_tets + tets_per_block / 2) / tets_per_block));
}

BlockPartition contiguous_blocks(const TetMesh& mesh, int num_blocks)
{
    BlockPartition partition;
    partition.num_blocks = std::max(num_blocks, 1);
    partition.block_of_tet.assign(mesh.num_tet_slots(), -1);
    const long long n = mesh.num_live_tets();
    long long i = 0;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_dead(t))
            partition.block_of_tet[t] = static_cast<int>(i++ * partition.num_blocks / n);
    return partition;
}

BlockPartition morton_blocks(const TetMesh& mesh, int num_blocks, int round,
                             const std::vector<char>* active)
{
    BlockPartition partition;
    partition.num_blocks = std::max(num_blocks, 1);
    const int nt = mesh.num_tet_slots();
    partition.block_of_tet.assign(nt, -1);
    std::vector<std::pair<std::uint64_t, int>> keyed;
    keyed.reserve(nt);
    std::vector<Vec3> centroids;
    centroids.reserve(nt);
    Vec3 low = Vec3::Constant(std::numeric_limits<double>::max()), high = -low;
    for (int t = 0; t < nt; ++t)
    {
        if (mesh.is_dead(t) || (active && !(*active)[t])) continue;
        const auto& tv = mesh.tets[t];
        const Vec3 c = 0.25 * (mesh.points[tv[0]] + mesh.points[tv[1]] + mesh.points[tv[2]] +
                               mesh.points[tv[3]]);
        low = low.cwiseMin(c);
        high = high.cwiseMax(c);
        centroids.push_back(c);
        keyed.push_back({0, t});
    }
    if (keyed.empty()) return partition;
    const double extent = std::max((high - low).maxCoeff(), 1e-300);
    // a block spans about extent / cbrt(blocks); the shift moves the cuts by a part of that
    const double shift =
        round * kRoundShift * extent / std::cbrt(static_cast<double>(partition.num_blocks));
    const double scale = static_cast<double>(kMortonCellMax) / (extent + shift);
    for (std::size_t i = 0; i < keyed.size(); ++i)
    {
        const Vec3 cell = (centroids[i] - low + Vec3::Constant(shift)) * scale;
        keyed[i].first =
            morton_key(static_cast<std::uint64_t>(cell.x()), static_cast<std::uint64_t>(cell.y()),
                       static_cast<std::uint64_t>(cell.z()));
    }
    std::sort(keyed.begin(), keyed.end());
    const long long n = static_cast<long long>(keyed.size());
    for (long long i = 0; i < n; ++i)
        partition.block_of_tet[keyed[i].second] = static_cast<int>(i * partition.num_blocks / n);
    return partition;
}

std::vector<char> run_in_blocks(TetMesh& mesh, const BlockPartition& partition, Workers* workers,
                                const std::function<void(TetMesh& block, int index)>& work)
{
    assert(mesh.has_adjacency());
    const int nv = mesh.num_vertices();
    SharedView view{mesh, partition.block_of_tet, {}, {}, {}, {}, {}, {}, {}, {}};
    view.triangles = index_entities<Triangle>(mesh.triangles, nv, sorted_triple);
    view.edges = index_entities<Edge>(mesh.edges, nv, sorted_pair);
    view.required_triangle.assign(mesh.triangles.size(), 0);
    for (int i : mesh.required_triangles) view.required_triangle[i] = 1;
    view.required_edge.assign(mesh.edges.size(), 0);
    for (int i : mesh.required_edges) view.required_edge[i] = 1;
    view.ridge.assign(mesh.edges.size(), 0);
    for (int i : mesh.ridges) view.ridge[i] = 1;
    view.required_tet.assign(mesh.num_tet_slots(), 0);
    for (int t : mesh.required_tets) view.required_tet[t] = 1;
    view.pinned_vertex.assign(nv, 0);
    for (int v : mesh.corners) view.pinned_vertex[v] = 1;
    for (int v : mesh.required_vertices) view.pinned_vertex[v] = 1;

    // each block's tets in mesh order (a counting sort)
    const int nb = partition.num_blocks;
    std::vector<std::vector<int>> tets(nb);
    view.index_in_block.assign(mesh.num_tet_slots(), -1);
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        const int b = partition.block_of_tet[t];
        if (b < 0) continue;
        view.index_in_block[t] = static_cast<int>(tets[b].size());
        tets[b].push_back(t);
    }

    std::vector<Block> blocks(nb);
    const auto task = [&](std::size_t b) {
        blocks[b] = extract_block(view, tets[b], static_cast<int>(b));
        std::vector<int>().swap(tets[b]);
        TetMesh& block = blocks[b].mesh;
        work(block, static_cast<int>(b));
        // the merge takes each block's adjacency as it is
        if (block.num_live_tets() != block.num_tet_slots()) block.compact();
        if (!block.has_adjacency()) block.build_adjacency();
        map_block_vertices(blocks[b]);
    };
    if (workers && workers->threads() > 1 && nb > 1)
        workers->run(nb, task);
    else
        for (int b = 0; b < nb; ++b) task(b);
    return merge_blocks(mesh, partition, blocks, view);
}

std::vector<char> tets_near(const TetMesh& mesh, std::vector<char> vertices, int rings)
{
    std::vector<char> near(mesh.num_tet_slots(), 0);
    for (int ring = 0; ring < rings; ++ring)
    {
        for (int t = 0; t < mesh.num_tet_slots(); ++t)
        {
            if (mesh.is_dead(t) || near[t]) continue;
            for (int v : mesh.tets[t])
                if (vertices[v]) near[t] = 1;
        }
        if (ring + 1 < rings)
            for (int t = 0; t < mesh.num_tet_slots(); ++t)
                if (near[t])
                    for (int v : mesh.tets[t]) vertices[v] = 1;
    }
    return near;
}

}  // namespace hdimesh::volume
