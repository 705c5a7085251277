#pragma once
// The tets' edges, each once, for one refinement pass: refinement's private machinery.

#include <algorithm>
#include <vector>

#include "volume/mesh/tet_mesh.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume::detail
{

/// The tets' edges, each once, filed under its lower vertex (compressed rows); a slot number
/// indexes per-edge data. Only edges whose higher vertex is >= first_vertex are kept (refine()
/// skips edges that a previous pass already found short enough).
class EdgeTable
{
public:
    EdgeTable(const TetMesh& mesh, int first_vertex)
    {
        const int nv = mesh.num_vertices();
        const bool adjacency = mesh.has_adjacency();
        // with adjacency, far fewer than the 6 edges per tet are left to deduplicate
        auto listed = [&](int t, int e) { return !adjacency || mesh.lists_edge(t, e); };
        auto has_new_vertex = [first_vertex](const TetVertices& t) {
            return t[0] != kDeadTet && std::max({t[0], t[1], t[2], t[3]}) >= first_vertex;
        };
        first_.assign(nv + 1, 0);
        const int nt = mesh.num_tet_slots();
        for (int ti = 0; ti < nt; ++ti)
        {
            const auto& t = mesh.tets[ti];
            if (!has_new_vertex(t)) continue;
            for (int e = 0; e < 6; ++e)
            {
                const auto& ev = tet::kEdgeVertices[e];
                if (std::max(t[ev[0]], t[ev[1]]) >= first_vertex && listed(ti, e))
                    ++first_[std::min(t[ev[0]], t[ev[1]]) + 1];
            }
        }
        for (int v = 0; v < nv; ++v) first_[v + 1] += first_[v];
        upper_.resize(first_[nv]);
        {
            std::vector<int> fill(first_.begin(), first_.end() - 1);
            for (int ti = 0; ti < nt; ++ti)
            {
                const auto& t = mesh.tets[ti];
                if (!has_new_vertex(t)) continue;
                for (int e = 0; e < 6; ++e)
                {
                    const auto& ev = tet::kEdgeVertices[e];
                    const int a = std::min(t[ev[0]], t[ev[1]]), b = std::max(t[ev[0]], t[ev[1]]);
                    if (b >= first_vertex && listed(ti, e)) upper_[fill[a]++] = b;
                }
            }
        }
        // sort and deduplicate each row, compacting in place
        int write = 0, begin = first_[0];
        for (int v = 0; v < nv; ++v)
        {
            const int end = first_[v + 1];
            for (int i = begin + 1; i < end; ++i)  // rows are short: insertion sort
            {
                const int x = upper_[i];
                int j = i;
                for (; j > begin && upper_[j - 1] > x; --j) upper_[j] = upper_[j - 1];
                upper_[j] = x;
            }
            const auto last = std::unique(upper_.begin() + begin, upper_.begin() + end);
            first_[v] = write;
            for (auto it = upper_.begin() + begin; it != last; ++it) upper_[write++] = *it;
            begin = end;
        }
        first_[nv] = write;
        upper_.resize(write);
        upper_.shrink_to_fit();
    }

    /// Slot of edge ab, or -1 when it is not in the table.
    int find(int a, int b) const
    {
        if (a > b) std::swap(a, b);
        for (int s = first_[a], end = first_[a + 1]; s < end; ++s)
        {
            if (upper_[s] >= b) return upper_[s] == b ? s : -1;
        }
        return -1;
    }

    int num_edges() const { return static_cast<int>(upper_.size()); }
    int row_begin(int v) const { return first_[v]; }
    int row_end(int v) const { return first_[v + 1]; }
    int upper(int slot) const { return upper_[slot]; }

private:
    std::vector<int> first_;  // first slot of each vertex's row, size nv + 1
    std::vector<int> upper_;  // the higher vertex of each slot, sorted in each row
};

}  // namespace hdimesh::volume::detail
