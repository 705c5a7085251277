#include "volume/mesh/reorder.h"

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <utility>
#include <vector>

#include "common/morton.h"

namespace hdimesh::volume
{

CompactionMaps renumber_spatially(TetMesh& mesh)
{
    assert(mesh.num_live_tets() == mesh.num_tet_slots() &&
           "renumber_spatially needs a compact mesh");
    CompactionMaps maps;
    const int nv = mesh.num_vertices();
    const int nt = mesh.num_tet_slots();
    if (nv == 0 || nt == 0) return maps;
    Vec3 low = mesh.points[0], high = mesh.points[0];
    for (const Vec3& p : mesh.points)
    {
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
    }
    const double extent = std::max((high - low).maxCoeff(), 1e-300);
    const double scale = static_cast<double>((1 << 21) - 1) / extent;
    std::vector<std::pair<std::uint64_t, int>> keyed(nv);
    for (int v = 0; v < nv; ++v)
    {
        const Vec3 cell = (mesh.points[v] - low) * scale;
        const std::uint64_t code =
            morton_key(static_cast<std::uint64_t>(cell.x()), static_cast<std::uint64_t>(cell.y()),
                       static_cast<std::uint64_t>(cell.z()));
        keyed[v] = {code, v};
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<int>& old2new_verts = maps.old2new_verts;
    old2new_verts.resize(nv);
    for (int k = 0; k < nv; ++k) old2new_verts[keyed[k].second] = k;

    auto permute_vertices = [&](auto& values) {
        auto copy = values;
        for (int v = 0; v < nv; ++v) values[old2new_verts[v]] = copy[v];
    };
    mesh.for_each_vertex_array(permute_vertices);
    mesh.for_each_vertex_id([&](int& v) { v = old2new_verts[v]; });

    // tets by smallest (new) vertex id, a counting sort: stable, linear
    std::vector<int> start(nv + 1, 0);
    auto smallest = [&](int t) {
        const auto& tv = mesh.tets[t];
        return std::min(std::min(tv[0], tv[1]), std::min(tv[2], tv[3]));
    };
    for (int t = 0; t < nt; ++t) ++start[smallest(t) + 1];
    for (int v = 0; v < nv; ++v) start[v + 1] += start[v];
    std::vector<int>& old2new_tets = maps.old2new_tets;
    old2new_tets.resize(nt);
    for (int t = 0; t < nt; ++t) old2new_tets[t] = start[smallest(t)]++;

    auto permute_tets = [&](auto& values) {
        auto copy = values;
        for (int t = 0; t < nt; ++t) values[old2new_tets[t]] = copy[t];
    };
    mesh.for_each_tet_array(permute_tets);
    if (mesh.has_adjacency())
    {
        permute_tets(mesh.neighbors);
        for (auto& row : mesh.neighbors)
            for (int& n : row)
                if (n != kNoTet) n = old2new_tets[n];
    }
    for (int& t : mesh.required_tets) t = old2new_tets[t];
    return maps;
}

}  // namespace hdimesh::volume
