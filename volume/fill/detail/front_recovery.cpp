// When the advancing front is stuck: the small leftover groups go to the small-cavity stages,
// and a retreat clears the tets around the open faces (volume/fill/detail/front_mesher.h).
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include "volume/fill/detail/cavity_stages.h"
#include "volume/fill/detail/front_mesher.h"
#include "volume/mesh/predicates.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume::detail::front_mesher
{

/// Closes the small groups of the front left over by the small-cavity stages; returns how many.
int FrontMesher::close_leftovers()
{
    const int n = static_cast<int>(points_.size());
    const std::vector<int> group = front_vertex_groups();
    auto root = [&group](int v) { return group[v]; };
    std::vector<int> open;
    for (int f = 0; f < static_cast<int>(front_.vertices.size()); ++f)
        if (front_.alive[f]) open.push_back(f);
    // groups in the order of their smallest face id
    std::vector<std::pair<int, int>> by_group;  // (root, face)
    for (int f : open) by_group.push_back({root(front_.vertices[f][0]), f});
    std::stable_sort(by_group.begin(), by_group.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    CavityOptions cavity_options;
    cavity_options.max_exhaustive_points = options_.max_leftover_points;
    int closed = 0;
    std::vector<int> group_faces, group_vertices;
    for (std::size_t i = 0; i < by_group.size();)
    {
        std::size_t j = i;
        group_faces.clear();
        while (j < by_group.size() && by_group[j].first == by_group[i].first)
            group_faces.push_back(by_group[j++].second);
        i = j;
        group_vertices.clear();
        for (int f : group_faces)
            for (int v : front_.vertices[f]) group_vertices.push_back(v);
        std::sort(group_vertices.begin(), group_vertices.end());
        group_vertices.erase(std::unique(group_vertices.begin(), group_vertices.end()),
                             group_vertices.end());
        if (static_cast<int>(group_vertices.size()) > options_.max_leftover_points) continue;
        std::vector<Vec3> group_points;
        for (int v : group_vertices) group_points.push_back(points_[v]);
        auto local = [&](int v) {
            return static_cast<int>(
                std::lower_bound(group_vertices.begin(), group_vertices.end(), v) -
                group_vertices.begin());
        };
        std::vector<Triangle> outward;
        for (int f : group_faces)
        {
            const Triangle& t = front_.vertices[f];
            outward.push_back({local(t[0]), local(t[2]), local(t[1])});
        }
        CavityFill fill;
        if (!detail::fill_small_cavity(group_points, outward, cavity_options, fill)) continue;
        // The group is closed, but another part of the front might lie inside it; and a tet
        // flat in doubles would fail the checker's volume test (a sliver is kept: a flat pocket
        // has no other fill, the optimizer takes it apart).
        const int m = static_cast<int>(group_vertices.size());
        std::vector<Vec3> fill_points = group_points;
        fill_points.insert(fill_points.end(), fill.new_points.begin(), fill.new_points.end());
        bool clear = true;
        for (const TetVertices& t : fill.tets)
            if (!(signed_volume(fill_points[t[0]], fill_points[t[1]], fill_points[t[2]],
                                fill_points[t[3]]) > 0))
                clear = false;
        for (int v = 0; v < n && clear; ++v)
        {
            if (front_.valence[v] == 0 ||
                std::binary_search(group_vertices.begin(), group_vertices.end(), v))
                continue;
            fill_points.push_back(points_[v]);
            const int probe = static_cast<int>(fill_points.size()) - 1;
            for (const TetVertices& t : fill.tets)
                if (point_in_tet(fill_points, probe, t))
                {
                    clear = false;
                    break;
                }
            fill_points.pop_back();
        }
        if (!clear) continue;
        std::vector<int> global(m + fill.new_points.size());
        for (int k = 0; k < m; ++k) global[k] = group_vertices[k];
        for (std::size_t k = 0; k < fill.new_points.size(); ++k)
        {
            global[m + k] = static_cast<int>(points_.size());
            points_.push_back(fill.new_points[k]);
            front_.valence.push_back(0);
            component_.push_back(0);
            in_grid_.push_back(0);
            layer_.push_back(0);
        }
        for (const TetVertices& t : fill.tets)
            tets_.push_back({global[t[0]], global[t[1]], global[t[2]], global[t[3]]});
        for (int f : group_faces) remove_face(f);
        ++closed;
    }
    return closed;
}

/// Netgen's RemoveProblem: removes every tet with a vertex on an open face and the new points
/// nothing uses any more; the freed faces rejoin the front with their failures forgotten.
bool FrontMesher::retreat()
{
    const int n = static_cast<int>(points_.size());
    std::vector<std::uint8_t> on_front(n, 0);
    for (int v = 0; v < n; ++v) on_front[v] = front_.valence[v] > 0;
    // later rounds also clear the tets one layer beyond: a wider region re-advances more
    // volume and strands more faces than it frees
    const int rings = std::min(retreat_rounds_, kRetreatRings);
    for (int ring = 0; ring < rings; ++ring)
    {
        std::vector<std::uint8_t> grown = on_front;
        for (const TetVertices& t : tets_)
            if (on_front[t[0]] || on_front[t[1]] || on_front[t[2]] || on_front[t[3]])
                for (int v : t) grown[v] = 1;
        on_front.swap(grown);
    }
    std::vector<TetVertices> kept;
    kept.reserve(tets_.size());
    std::vector<TetVertices> removed;
    for (const TetVertices& t : tets_)
    {
        if (on_front[t[0]] || on_front[t[1]] || on_front[t[2]] || on_front[t[3]])
            removed.push_back(t);
        else
            kept.push_back(t);
    }
    if (removed.empty()) return false;
    tets_.swap(kept);
    for (const TetVertices& t : removed)
        for (int i = 0; i < 4; ++i)
        {
            const auto& fv = tet::kFaceVertices[i];
            const Triangle outward{t[fv[0]], t[fv[1]], t[fv[2]]};
            const int g = front_.find(outward);
            if (g >= 0)
            {
                assert(same_orientation(outward, front_.vertices[g]));
                front_.remove(g);
            }
            else
            {
                const Triangle inward{outward[0], outward[2], outward[1]};
                const int lowest =
                    std::min({layer_[inward[0]], layer_[inward[1]], layer_[inward[2]]});
                front_.add(inward, lowest, face_size(inward), order_key(inward));
            }
        }
    // every surviving face starts over: heap, grid and components rebuilt from the front
    front_.heap.clear();
    for (int f = 0; f < static_cast<int>(front_.vertices.size()); ++f)
        if (front_.alive[f])
        {
            front_.fail[f] = 0;
            front_.push(f);
        }
    compute_components();
    build_grid();
    return true;
}

}  // namespace hdimesh::volume::detail::front_mesher
