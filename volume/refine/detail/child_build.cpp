#include "volume/refine/detail/child_build.h"

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "volume/mesh/tet_tables.h"
#include "volume/refine/refine_patterns.h"

namespace hdimesh::volume::detail
{

namespace
{

bool local_point_on_face(int point, int face)
{
    if (point < 4) return point != face;
    if (point == kPatternSteinerPoint) return false;
    const auto& ev = tet::kEdgeVertices[point - 4];
    return ev[0] != face && ev[1] != face;
}

ChildBuild make_child_build(std::vector<std::array<std::uint8_t, 4>> tets, bool new_point)
{
    ChildBuild b;
    b.tets = std::move(tets);
    b.new_point = new_point;
    const int n = static_cast<int>(b.tets.size());
    b.link.assign(4 * n, 0);
    std::vector<std::array<int, 4>> keys;  // sorted face points, child face
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < 4; ++k)
        {
            const auto& fv = tet::kFaceVertices[k];
            std::array<int, 3> f = {b.tets[i][fv[0]], b.tets[i][fv[1]], b.tets[i][fv[2]]};
            std::sort(f.begin(), f.end());
            keys.push_back({f[0], f[1], f[2], 4 * i + k});
        }
    std::sort(keys.begin(), keys.end());
    for (std::size_t j = 0; j < keys.size(); ++j)
    {
        const bool with_next =
            j + 1 < keys.size() &&
            std::equal(keys[j].begin(), keys[j].begin() + 3, keys[j + 1].begin());
        if (with_next)
        {
            b.link[keys[j][3]] = keys[j + 1][3];
            b.link[keys[j + 1][3]] = keys[j][3];
            ++j;
            continue;
        }
        int face = 0;
        while (!(local_point_on_face(keys[j][0], face) && local_point_on_face(keys[j][1], face) &&
                 local_point_on_face(keys[j][2], face)))
            ++face;
        b.link[keys[j][3]] = -(1 + face);
        b.on_parent_face[face].push_back(keys[j][3]);
    }
    return b;
}

}  // namespace

PatternBuilds::PatternBuilds()
{
    for (int i = 0; i < kNumRefinePatterns; ++i)
    {
        const RefinePattern& p = refine_pattern(i);
        std::vector<std::array<std::uint8_t, 4>> tets, cone_tets;
        for (int k = 0; k < p.num_tets; ++k)
            tets.push_back({p.tets[k][0], p.tets[k][1], p.tets[k][2], p.tets[k][3]});
        for (int k = 0; k < p.num_triangles;
             ++k)  // outward triangle (u, v, w): tet (u, w, v, apex)
            cone_tets.push_back({p.triangles[k][0], p.triangles[k][2], p.triangles[k][1],
                                 static_cast<std::uint8_t>(kPatternSteinerPoint)});
        table.push_back(make_child_build(std::move(tets), p.steiner));
        cone.push_back(make_child_build(std::move(cone_tets), true));
    }
}

const PatternBuilds& pattern_builds()
{
    static const PatternBuilds builds;
    return builds;
}

}  // namespace hdimesh::volume::detail
