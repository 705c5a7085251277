// The bisection pattern table (volume/refine/refine_patterns.h), checked independently of the
// generator: counts, the paper's code, and every entry re-proven in exact integer arithmetic
// on a reference tet and in floating point on random tets.
//
//                 3
//                /|\          local points: 0-3 vertices, 4+e midpoint of edge e
//               / | \         (e0 = 01, e1 = 02, e2 = 03, e3 = 12, e4 = 13, e5 = 23),
//              /  8  \        10 the Steiner point (centroid)
//             6   |   9
//            /    |    \      .
//           0--5--|-----2
//            \    |    /
//             4   |   7
//              \  |  /
//               \ | /
//                 1

#include "volume/refine/refine_patterns.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <random>
#include <set>

#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/mesh/tet_tables.h"

using namespace hdimesh;

namespace
{

using IPoint = std::array<long long, 3>;

/// The reference tet scaled by 4: midpoints and the centroid are integer points.
std::array<IPoint, kPatternNumLocalPoints> integer_points()
{
    std::array<IPoint, kPatternNumLocalPoints> p{};
    p[0] = {0, 0, 0};
    p[1] = {4, 0, 0};
    p[2] = {0, 4, 0};
    p[3] = {0, 0, 4};
    for (int e = 0; e < 6; ++e)
        for (int k = 0; k < 3; ++k)
            p[pattern_midpoint(e)][k] =
                (p[tet::kEdgeVertices[e][0]][k] + p[tet::kEdgeVertices[e][1]][k]) / 2;
    p[kPatternSteinerPoint] = {1, 1, 1};
    return p;
}

long long orient(const IPoint& a, const IPoint& b, const IPoint& c, const IPoint& d)
{
    const long long b0 = b[0] - a[0], b1 = b[1] - a[1], b2 = b[2] - a[2];
    const long long c0 = c[0] - a[0], c1 = c[1] - a[1], c2 = c[2] - a[2];
    const long long d0 = d[0] - a[0], d1 = d[1] - a[1], d2 = d[2] - a[2];
    return b0 * (c1 * d2 - c2 * d1) - b1 * (c0 * d2 - c2 * d0) + b2 * (c0 * d1 - c1 * d0);
}

using Tri = std::array<int, 3>;

/// Same triangle, same orientation, smallest point first.
Tri rotate_smallest_first(Tri t)
{
    while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
    return t;
}

/// The face triangulation written from the header's definition of the diagonal bits, as an
/// independent reading of the key (corner c, other vertices a < b; bit 0: a to mid(cb)).
std::multiset<Tri> expected_boundary(int mask, int diagonals)
{
    std::multiset<Tri> out;
    auto add = [&](int x, int y, int z) { out.insert(rotate_smallest_first({x, y, z})); };
    for (int f = 0; f < 4; ++f)
    {
        const auto& v = tet::kFaceVertices[f];
        std::array<int, 3> mid;  // midpoint of edge v[k] v[k+1] or -1
        int split = 0;
        for (int k = 0; k < 3; ++k)
        {
            const int e = tet::kEdgeOfVertices[v[k]][v[(k + 1) % 3]];
            mid[k] = ((mask >> e) & 1) ? pattern_midpoint(e) : -1;
            split += mid[k] >= 0;
        }
        if (split == 0) add(v[0], v[1], v[2]);
        if (split == 1)
            for (int k = 0; k < 3; ++k)
                if (mid[k] >= 0)
                    add(v[k], mid[k], v[(k + 2) % 3]), add(mid[k], v[(k + 1) % 3], v[(k + 2) % 3]);
        if (split == 3)
        {
            for (int k = 0; k < 3; ++k) add(v[k], mid[k], mid[(k + 2) % 3]);
            add(mid[0], mid[1], mid[2]);
        }
        if (split == 2)
        {
            int k = 0;
            while (!(mid[k] >= 0 && mid[(k + 2) % 3] >= 0)) ++k;
            const int c = v[k], a = v[(k + 1) % 3], b = v[(k + 2) % 3];
            const int mca = mid[k], mcb = mid[(k + 2) % 3];
            add(c, mca, mcb);
            const int start = ((diagonals >> f) & 1) ? std::max(a, b) : std::min(a, b);
            if (start == a)
                add(mca, a, mcb), add(a, b, mcb);
            else
                add(mca, a, b), add(mca, b, mcb);
        }
    }
    return out;
}

int popcount(int x)
{
    int n = 0;
    for (; x; x &= x - 1) ++n;
    return n;
}

/// Three split edges sharing one vertex.
bool is_star(int mask)
{
    if (popcount(mask) != 3) return false;
    for (int v = 0; v < 4; ++v)
    {
        int at_v = 0;
        for (int e = 0; e < 6; ++e)
            if (tet::kEdgeVertices[e][0] == v || tet::kEdgeVertices[e][1] == v) at_v |= 1 << e;
        if (mask == at_v) return true;
    }
    return false;
}

/// Four split edges forming a cycle: the two unsplit edges are opposite.
bool is_four_cycle(int mask)
{
    if (popcount(mask) != 4) return false;
    const int unsplit = 63 & ~mask;
    for (int e = 0; e < 3; ++e)
        if (unsplit == ((1 << e) | (1 << tet::opposite_edge(e)))) return true;
    return false;
}

}  // namespace

TEST_CASE("patterns: 239 configurations, one per (mask, admissible diagonals)")
{
    int expected = 0;
    for (int mask = 0; mask < 64; ++mask)
        expected += 1 << popcount(faces_with_two_split_edges(mask));
    CHECK(expected == 239);
    CHECK(kNumRefinePatterns == 239);

    std::set<std::pair<int, int>> keys;
    for (int i = 0; i < kNumRefinePatterns; ++i)
    {
        const RefinePattern& p = refine_pattern(i);
        CHECK((p.diagonals & ~faces_with_two_split_edges(p.mask)) == 0);
        CHECK(find_refine_pattern(p.mask, p.diagonals) == i);
        keys.insert({p.mask, p.diagonals});
    }
    CHECK(keys.size() == 239u);
    // a diagonal bit on a face without a quad names no configuration
    CHECK(find_refine_pattern(0, 1) == -1);
    CHECK(find_refine_pattern(63, 2) == -1);
    CHECK(find_refine_pattern(64, 0) == -1);
}

TEST_CASE("patterns: exactly 14 need a Steiner point, 8 stars and 6 four-cycles, 9..12 tets")
{
    int stars = 0, cycles = 0;
    for (int i = 0; i < kNumRefinePatterns; ++i)
    {
        const RefinePattern& p = refine_pattern(i);
        bool uses_point_10 = false;
        for (int k = 0; k < p.num_tets; ++k)
            for (int v : p.tets[k]) uses_point_10 = uses_point_10 || v == kPatternSteinerPoint;
        CHECK(uses_point_10 == p.steiner);
        if (!p.steiner) continue;
        CHECK(p.num_tets >= 9);
        CHECK(p.num_tets <= 12);
        CHECK((is_star(p.mask) || is_four_cycle(p.mask)));
        stars += is_star(p.mask);
        cycles += is_four_cycle(p.mask);
    }
    CHECK(stars == 8);
    CHECK(cycles == 6);
}

TEST_CASE("patterns: every entry is a tetrahedralization of its prescribed boundary (exact)")
{
    const auto P = integer_points();
    const long long parent = orient(P[0], P[1], P[2], P[3]);
    REQUIRE(parent == 64);
    for (int i = 0; i < kNumRefinePatterns; ++i)
    {
        const RefinePattern& p = refine_pattern(i);
        CAPTURE(p.mask);
        CAPTURE(p.diagonals);
        long long volume = 0;
        std::map<Tri, int> chain;
        for (int k = 0; k < p.num_tets; ++k)
        {
            const auto& t = p.tets[k];
            const long long o = orient(P[t[0]], P[t[1]], P[t[2]], P[t[3]]);
            CHECK(o > 0);
            volume += o;
            for (const auto& fv : tet::kFaceVertices)
            {
                const Tri face = rotate_smallest_first({t[fv[0]], t[fv[1]], t[fv[2]]});
                const Tri back = rotate_smallest_first({face[0], face[2], face[1]});
                auto it = chain.find(back);
                if (it != chain.end())
                {
                    if (--it->second == 0) chain.erase(it);
                }
                else
                    ++chain[face];
            }
        }
        CHECK(volume == parent);
        std::multiset<Tri> boundary;
        for (const auto& [tri, count] : chain)
            for (int c = 0; c < count; ++c) boundary.insert(tri);
        const std::multiset<Tri> expected = expected_boundary(p.mask, p.diagonals);
        CHECK(boundary == expected);
        std::multiset<Tri> stored;
        for (int k = 0; k < p.num_triangles; ++k)
            stored.insert(
                rotate_smallest_first({p.triangles[k][0], p.triangles[k][1], p.triangles[k][2]}));
        CHECK(stored == expected);
    }
}

TEST_CASE("patterns: on random positive tets every child is positive and volumes add up")
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> coord(-1.0, 1.0);
    for (int trial = 0; trial < 20; ++trial)
    {
        std::array<Vec3, kPatternNumLocalPoints> p;
        do
        {
            for (int k = 0; k < 4; ++k) p[k] = Vec3(coord(rng), coord(rng), coord(rng));
        } while (signed_volume(p[0], p[1], p[2], p[3]) < 0.02);
        for (int e = 0; e < 6; ++e)
            p[pattern_midpoint(e)] =
                0.5 * (p[tet::kEdgeVertices[e][0]] + p[tet::kEdgeVertices[e][1]]);
        p[kPatternSteinerPoint] = 0.25 * (p[0] + p[1] + p[2] + p[3]);
        const double parent = signed_volume(p[0], p[1], p[2], p[3]);
        for (int i = 0; i < kNumRefinePatterns; ++i)
        {
            const RefinePattern& pattern = refine_pattern(i);
            double sum = 0;
            for (int k = 0; k < pattern.num_tets; ++k)
            {
                const auto& t = pattern.tets[k];
                const double v = signed_volume(p[t[0]], p[t[1]], p[t[2]], p[t[3]]);
                CHECK(v > 0);
                sum += v;
            }
            CHECK(sum == doctest::Approx(parent).epsilon(1e-12));
        }
    }
}

TEST_CASE("patterns: the paper's code is unique and its example 20,8,20,7 is a valid configuration")
{
    std::set<int> codes;
    for (int i = 0; i < kNumRefinePatterns; ++i)
    {
        const RefinePattern& p = refine_pattern(i);
        CHECK(p.paper_code == paper_pattern_code(p.mask, p.diagonals));
        codes.insert(p.paper_code);
    }
    CHECK(codes.size() == 239u);

    // the paper's example: FaceCode(F0..F3) = 20, 8, 20, 7
    CHECK(20 + 8 * 64 + 20 * 4096 + 7 * 262144 == 1917460);
    int found = -1;
    for (int i = 0; i < kNumRefinePatterns; ++i)
        if (refine_pattern(i).paper_code == 1917460) found = i;
    REQUIRE(found >= 0);
    const RefinePattern& example = refine_pattern(found);
    const std::array<int, 4> face_codes = {20, 8, 20, 7};
    for (int i = 0; i < 4; ++i)
        CHECK(paper_face_code(example.mask, example.diagonals, kPaperFaceToOurs[i]) ==
              face_codes[i]);
    // all three edges of our face 3 split (F3 = 7), one on face 0 (F1 = 8): edges 0,1,2,3
    CHECK(example.mask == 0b001111);
    CHECK_FALSE(example.steiner);

    // every face code is one of the paper's 11 face patterns: 0, three one-split, six
    // two-split (2 per corner), 7
    std::set<int> face_patterns;
    for (int i = 0; i < kNumRefinePatterns; ++i)
        for (int f = 0; f < 4; ++f)
            face_patterns.insert(
                paper_face_code(refine_pattern(i).mask, refine_pattern(i).diagonals, f));
    CHECK(face_patterns.size() == 11u);
}

TEST_CASE("patterns: each Schönhardt configuration as a mesh on a regular tet passes the checker")
{
    // forced diagonal choices: the 14 twisted ones, built with the Steiner point at the centroid
    const TetMesh parent = fixtures::regular_tet();
    for (int i = 0; i < kNumRefinePatterns; ++i)
    {
        const RefinePattern& pattern = refine_pattern(i);
        if (!pattern.steiner) continue;
        CAPTURE(pattern.mask);
        CAPTURE(pattern.diagonals);
        TetMesh mesh;
        std::array<int, kPatternNumLocalPoints> id;
        id.fill(-1);
        const auto& P = parent.points;
        const auto& pv = parent.tets[0];
        for (int k = 0; k < 4; ++k) id[k] = mesh.add_vertex(P[pv[k]]);
        for (int e = 0; e < 6; ++e)
            if ((pattern.mask >> e) & 1)
                id[pattern_midpoint(e)] = mesh.add_vertex(
                    0.5 * (P[pv[tet::kEdgeVertices[e][0]]] + P[pv[tet::kEdgeVertices[e][1]]]));
        id[kPatternSteinerPoint] =
            mesh.add_vertex(0.25 * (P[pv[0]] + P[pv[1]] + P[pv[2]] + P[pv[3]]));
        for (int k = 0; k < pattern.num_tets; ++k)
        {
            const auto& t = pattern.tets[k];
            mesh.add_tet({id[t[0]], id[t[1]], id[t[2]], id[t[3]]});
        }
        for (int k = 0; k < pattern.num_triangles; ++k)
        {
            const auto& t = pattern.triangles[k];
            mesh.add_triangle({id[t[0]], id[t[1]], id[t[2]]}, 1);
        }
        mesh.build_adjacency();
        mesh.classify_vertices();
        const auto violations = check_mesh(mesh);
        CHECK_MESSAGE(violations.empty(), format_violations(violations));
        CHECK(mesh.total_volume() == doctest::Approx(parent.total_volume()).epsilon(1e-12));
    }
}
