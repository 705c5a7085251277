// Multi-face removal (and the 2-3 flip it generalizes) on small drawn configurations: every
// legal case must raise the worst quality, conserve the volume, keep the boundary and leave a
// valid mesh (check_mesh, which also compares the maintained adjacency with a recomputed one);
// every refused case must leave the mesh bit for bit as it was.

#include "volume/optimize/face_removal.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/mesh/tet_tables.h"
#include "volume/mesh/tet_topology.h"
#include "volume/size/size_fields.h"

using namespace hdimesh;

namespace
{

const double kPi = 3.14159265358979323846;

using fixtures::mesh_from_tets;

/*  A sandwich: a polygon (vertices 0..n-1, counter-clockwise seen from above) triangulated by
    `faces` (counter-clockwise seen from above), the apex b above it and a below:

              b                   every face (x, y, z) gets the tets
            / | \                     lower (x, z, y, a)  = tet 2i
        ---+--|--+---  polygon        upper (x, y, z, b)  = tet 2i + 1
            \ | /
              a                   a = vertex n, b = vertex n + 1                            */
TetMesh sandwich_mesh(const std::vector<Vec3>& polygon, const std::vector<Triangle>& faces,
                      const Vec3& a, const Vec3& b)
{
    std::vector<Vec3> points = polygon;
    const int ia = static_cast<int>(points.size());
    points.push_back(a);
    points.push_back(b);
    std::vector<TetVertices> tets;
    for (const auto& [x, y, z] : faces)
    {
        tets.push_back({x, z, y, ia});
        tets.push_back({x, y, z, ia + 1});
    }
    return mesh_from_tets(points, tets);
}

/// The seed of face i of a sandwich: its lower tet, and the local face opposite a.
constexpr int kApexLocal = 3;

std::vector<Vec3> regular_polygon(int n, double radius = 1.0)
{
    std::vector<Vec3> result;
    for (int i = 0; i < n; ++i)
        result.push_back(
            {radius * std::cos(2 * kPi * i / n), radius * std::sin(2 * kPi * i / n), 0});
    return result;
}

void require_valid(const TetMesh& mesh)
{
    const auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    REQUIRE(violations.empty());
}

double live_worst(const TetMesh& mesh)
{
    double worst = 1e300;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_dead(t)) worst = std::min(worst, mesh.quality(t));
    return worst;
}

/// The boundary as sorted vertex triples (operators never renumber vertices).
std::vector<Triangle> boundary_faces(const TetMesh& mesh)
{
    std::vector<Triangle> result;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t)) continue;
        for (int f = 0; f < 4; ++f)
            if (mesh.neighbors[t][f] == kNoTet) result.push_back(sorted_face(mesh, t, f));
    }
    std::sort(result.begin(), result.end());
    return result;
}

/// Everything an operator could touch, to compare "unchanged" bit for bit.
struct Snapshot
{
    std::vector<Vec3> points;
    std::vector<TetVertices> tets, neighbors;
    std::vector<int> tet_refs;
    explicit Snapshot(const TetMesh& m)
        : points(m.points), tets(m.tets), neighbors(m.neighbors), tet_refs(m.tet_refs)
    {
    }
    bool same_as(const TetMesh& m) const
    {
        return points == m.points && tets == m.tets && neighbors == m.neighbors &&
               tet_refs == m.tet_refs;
    }
};

/// A committed removal: the figures the result reports and the invariants of the mesh.
void require_sound_removal(const TetMesh& mesh, const MultiFaceRemovalResult& result,
                           double volume_before, int tets_before,
                           const std::vector<Triangle>& boundary_before)
{
    REQUIRE(result.removed);
    const int k = result.faces_removed;
    CHECK(result.tets_removed == 2 * k);
    CHECK(result.tets_created == k + 2);
    CHECK(mesh.num_live_tets() == tets_before + (k + 2) - 2 * k);
    CHECK(result.worst_after > result.worst_before);
    CHECK(mesh.total_volume() == doctest::Approx(volume_before).epsilon(1e-12));
    CHECK(boundary_faces(mesh) == boundary_before);
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_dead(t)) CHECK(mesh.volume(t) > 0);
    require_valid(mesh);
}

/// The best worst new quality over all choices of faces, and how many faces it removes.
struct BruteForce
{
    double best = -1e300;
    std::vector<int> face_counts;  // sizes of the sets that reach it
};

/// Every connected set of faces containing `seed`, over a sandwich built by sandwich_mesh:
/// the polygon edges are the directed face edges whose reverse is not in the set.
BruteForce brute_force_best(const TetMesh& mesh, const std::vector<Triangle>& faces, int seed,
                            int ia, int ib)
{
    const int n = static_cast<int>(faces.size());
    auto shares_edge = [&](int i, int j) {
        int common = 0;
        for (int u : faces[i])
            for (int v : faces[j]) common += (u == v);
        return common == 2;
    };
    BruteForce result;
    std::vector<std::pair<double, int>> values;  // (worst, faces) of every connected set
    for (int mask = 0; mask < (1 << n); ++mask)
    {
        if (!(mask & (1 << seed))) continue;
        // connected: flood from the seed inside the mask
        int reached = 1 << seed;
        for (bool grew = true; grew;)
        {
            grew = false;
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j)
                    if ((reached & (1 << i)) && (mask & (1 << j)) && !(reached & (1 << j)) &&
                        shares_edge(i, j))
                    {
                        reached |= 1 << j;
                        grew = true;
                    }
        }
        if (reached != mask) continue;
        std::vector<std::array<int, 2>> directed;
        for (int i = 0; i < n; ++i)
            if (mask & (1 << i))
                for (int k = 0; k < 3; ++k)
                    directed.push_back({faces[i][k], faces[i][(k + 1) % 3]});
        double worst = 1e300;
        for (const auto& [u, v] : directed)
        {
            const bool inner = std::find(directed.begin(), directed.end(),
                                         std::array<int, 2>{v, u}) != directed.end();
            if (inner) continue;
            const auto& p = mesh.points;
            worst = std::min(worst, tet_quality(p[u], p[v], p[ia], p[ib]));
        }
        values.push_back({worst, __builtin_popcount(static_cast<unsigned>(mask))});
        result.best = std::max(result.best, worst);
    }
    // the worst new tet may sit outside the choice (a bottleneck every set shares): several
    // sets can tie, any of them is a right answer
    for (const auto& [worst, count] : values)
        if (worst == result.best) result.face_counts.push_back(count);
    return result;
}

}  // namespace

/*  k = 1: two flat tets on an equilateral triangle x y z, apexes a below and b above.
    Every edge of the face is on the boundary, so the sandwich is the face alone and the
    removal must be exactly the 2-3 flip of remove_face (same tets in the same slots).

            b (0,0,h)
          / | \
        x---|---z
          \ | /
            a (0,0,-h)                                                                       */
TEST_CASE("multi-face removal, k = 1: the same tets as the 2-3 flip")
{
    for (const double h : {0.2, 0.5})
    {
        CAPTURE(h);
        const TetMesh start = sandwich_mesh(regular_polygon(3), {{0, 1, 2}}, {0, 0, -h}, {0, 0, h});
        TetMesh flipped = start, removed = start;
        OperatorContext flip_context(flipped, nullptr), multi_context(removed, nullptr);
        const auto flip = remove_face(flipped, flip_context, 0, kApexLocal);
        const auto multi = remove_multi_face(removed, multi_context, 0, kApexLocal);
        CHECK(multi.legal);
        CHECK(multi.sandwich_size == 1);
        CHECK(multi.faces_removed == 1);
        CHECK(multi.removed == flip.removed);
        CHECK(multi.worst_before == flip.worst_before);
        CHECK(multi.worst_after == flip.worst_after);
        CHECK(removed.tets == flipped.tets);
        CHECK(removed.neighbors == flipped.neighbors);
        if (multi.removed)
            require_sound_removal(removed, multi, start.total_volume(), 2, boundary_faces(start));
        else
            CHECK(Snapshot(start).same_as(removed));
    }
}

/*  k = 2: a square split by the diagonal r0-r2, and ab crossing exactly that diagonal:

              r1                      the 2-3 flip of either face would make the flat tet
            /    \                    (r0, r2, a, b): refused. Removing both faces (the 4-4
         r2 -- ab -- r0               flip) gives four tets (ri, ri+1, a, b), one per side.
            \    /
              r3          a = (0,0,-h) below, b = (0,0,h) above                             */
TEST_CASE("multi-face removal, k = 2: both faces of a square go where the 2-3 flip cannot")
{
    const std::vector<Triangle> faces = {{0, 1, 2}, {0, 2, 3}};
    TetMesh mesh = sandwich_mesh(regular_polygon(4), faces, {0, 0, -0.25}, {0, 0, 0.25});
    OperatorContext context(mesh, nullptr);
    const double volume = mesh.total_volume();
    const auto boundary = boundary_faces(mesh);
    const double worst_before = live_worst(mesh);

    {
        TetMesh copy = mesh;
        OperatorContext copy_context(copy, nullptr);
        const auto flip = remove_face(copy, copy_context, 0, kApexLocal);
        CHECK_FALSE(flip.removed);
        CHECK(flip.worst_after <= 0);
    }
    const auto evaluated = evaluate_multi_face_removal(mesh, context, 0, kApexLocal);
    const auto result = remove_multi_face(mesh, context, 0, kApexLocal);
    CHECK(evaluated.worst_after == result.worst_after);
    CHECK(result.sandwich_size == 2);
    CHECK(result.faces_removed == 2);
    require_sound_removal(mesh, result, volume, 4, boundary);
    CHECK(live_worst(mesh) == doctest::Approx(result.worst_after));
    CHECK(live_worst(mesh) > worst_before + 0.2);
    // every new tet holds the new edge ab
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_dead(t))
        {
            CHECK(local_index(mesh, t, 4) >= 0);
            CHECK(local_index(mesh, t, 5) >= 0);
        }
}

/*  k = 3: a regular pentagon fanned from r0, ab through its centre (inside f2), seeded at
    each of the three faces in turn:

        r3 ------- r2          h = 0.3: the six old tets reach 0.24 at worst; the 2-3 flip
        / \   f2  / \          of f2 alone would give 0.32 (thin tets over the chords r0-r2,
       / f1 \   / f3 \         r0-r3); removing f1, f2, f3 gives the five tets over the
     r4 ------ r0 ---- r1      pentagon's sides, 0.74.                                       */
TEST_CASE("multi-face removal, k = 3: a fanned pentagon becomes five tets around ab")
{
    const std::vector<Triangle> faces = {{0, 3, 4}, {0, 2, 3}, {0, 1, 2}};
    const double h = 0.3;
    for (int seed = 0; seed < 3; ++seed)
    {
        CAPTURE(seed);
        TetMesh mesh = sandwich_mesh(regular_polygon(5), faces, {0, 0, -h}, {0, 0, h});
        OperatorContext context(mesh, nullptr);
        const double volume = mesh.total_volume();
        const auto boundary = boundary_faces(mesh);
        const double worst_before = live_worst(mesh);

        const auto result = remove_multi_face(mesh, context, 2 * seed, kApexLocal);
        CHECK(result.sandwich_size == 3);
        CHECK(result.faces_removed == 3);
        require_sound_removal(mesh, result, volume, 6, boundary);
        CHECK(mesh.num_live_tets() == 5);
        CHECK(live_worst(mesh) == doctest::Approx(result.worst_after));
        CHECK(live_worst(mesh) > worst_before + 0.4);
        CHECK(result.worst_before == doctest::Approx(worst_before));
        // the tets hold the 5 sides, not the chords: no tet has both r0 and r2, or r0 and r3
        for (int t = 0; t < mesh.num_tet_slots(); ++t)
        {
            if (mesh.is_dead(t)) continue;
            const bool has0 = local_index(mesh, t, 0) >= 0;
            CHECK_FALSE((has0 && local_index(mesh, t, 2) >= 0));
            CHECK_FALSE((has0 && local_index(mesh, t, 3) >= 0));
        }
    }
}

/*  A perturbed heptagon r0..r6 (counter-clockwise, radius about 1) cut into a strip of five
    faces, each sharing one edge with the next; ab crosses the middle face f2:

              r2 ------ r1
             /  \   f0    \            f0 (r0 r1 r2) - f1 (r0 r2 r6) - f2 (r2 r3 r6)
           r3 f2  \         r0                       - f3 (r3 r5 r6) - f4 (r3 r4 r5)
           | \      \   f1  /
           |f4 \  f3  \    /         the dynamic program must find the best of all connected
           r4 -- r5 ---- r6          sets of faces containing f2 (brute force), for several
                                     heights of the apexes (more faces pay as ab grows)     */
TEST_CASE("multi-face removal: the dynamic program finds the best connected set of faces")
{
    const std::vector<Triangle> faces = {{0, 1, 2}, {0, 2, 6}, {2, 3, 6}, {3, 5, 6}, {3, 4, 5}};
    std::vector<Vec3> polygon;
    for (int i = 0; i < 7; ++i)
    {
        const double angle = 2 * kPi * i / 7 + 0.05 * std::sin(3.0 * i + 1);
        const double radius = 1.0 + 0.06 * std::cos(5.0 * i);
        polygon.push_back(
            {radius * std::cos(angle), radius * std::sin(angle), 0.02 * std::sin(7.0 * i)});
    }
    const Vec3 centre = (polygon[2] + polygon[3] + polygon[6]) / 3.0;
    int largest_choice = 0;
    for (const double h : {0.05, 0.15, 0.3, 0.45, 0.7, 1.0})
    {
        CAPTURE(h);
        TetMesh mesh = sandwich_mesh(polygon, faces, centre + Vec3(0.03, 0.01, -h),
                                     centre + Vec3(-0.02, 0.02, h));
        OperatorContext context(mesh, nullptr);
        const BruteForce expected = brute_force_best(mesh, faces, 2, 7, 8);
        const double volume = mesh.total_volume();
        const auto boundary = boundary_faces(mesh);
        const auto result = remove_multi_face(mesh, context, 4, kApexLocal);
        CHECK(result.legal);
        CHECK(result.sandwich_size == 5);
        CHECK(result.worst_after == doctest::Approx(expected.best).epsilon(1e-14));
        INFO("faces removed " << result.faces_removed);
        CHECK(std::count(expected.face_counts.begin(), expected.face_counts.end(),
                         result.faces_removed) > 0);
        largest_choice = std::max(largest_choice, result.faces_removed);
        if (result.removed)
            require_sound_removal(mesh, result, volume, 10, boundary);
        else
            CHECK((result.worst_after <= 0 || result.worst_after <= result.worst_before + 1e-6));
    }
    CHECK(largest_choice >= 3);  // the heights above reach beyond the 4-4 flip
}

/*  An inner vertex: a hexagon fanned around its centre c, every face sandwiched between a and
    b (ab crosses f0 near c). The faces around c form a cycle, not a tree: removing all six
    would delete c. The tree grown from f0 makes the link where the cycle closes a wall, so a
    choice holding both faces across it would list that edge once each way, and one of its two
    new tets would be inverted: the best choice keeps c on the polygon.

          h2 ---- h1
         /  \ f1 /  \          fi = (c, hi, hi+1)
       h3 f2  c  f0  h0        ab passes through (0.3, 0.1), inside f0
         \  / f4 \  /
          h4 ---- h5      (f3 left of c below, f5 right)                                   */
TEST_CASE("multi-face removal around an inner vertex: the cycle of faces is never closed")
{
    std::vector<Vec3> points = regular_polygon(6);
    points.push_back({0, 0, 0});  // c = 6
    std::vector<Triangle> faces;
    for (int i = 0; i < 6; ++i) faces.push_back({6, i, (i + 1) % 6});
    for (const double h : {0.1, 0.2, 0.4})
    {
        CAPTURE(h);
        TetMesh mesh = sandwich_mesh(points, faces, {0.3, 0.1, -h}, {0.3, 0.1, h});
        OperatorContext context(mesh, nullptr);
        const double volume = mesh.total_volume();
        const auto boundary = boundary_faces(mesh);
        const auto result = remove_multi_face(mesh, context, 0, kApexLocal);
        CHECK(result.legal);
        CHECK(result.sandwich_size == 6);
        CHECK(result.faces_removed < 6);
        // flat apexes (h 0.1, 0.2: 2 and 3 faces, worst 0.21 -> 0.30 and 0.33 -> 0.41) pay;
        // at h = 0.4 the old tets are already better than any choice
        CHECK(result.removed == (h < 0.3));
        if (!result.removed) continue;
        require_sound_removal(mesh, result, volume, 12, boundary);
        bool c_used = false;
        for (int t = 0; t < mesh.num_tet_slots(); ++t)
            c_used |= !mesh.is_dead(t) && local_index(mesh, t, 6) >= 0;
        CHECK(c_used);
    }
}

TEST_CASE("multi-face removal refused: the mesh stays bit for bit the same")
{
    const std::vector<Triangle> square = {{0, 1, 2}, {0, 2, 3}};
    auto square_mesh = [&](const Vec3& b, const Vec3& a = {0, 0, -0.25}) {
        return sandwich_mesh(regular_polygon(4), square, a, b);
    };
    auto refuse = [](TetMesh& mesh, OperatorContext& context, int t, int f) {
        const Snapshot before(mesh);
        const auto result = remove_multi_face(mesh, context, t, f);
        CHECK_FALSE(result.removed);
        CHECK(before.same_as(mesh));
        return result;
    };

    SUBCASE("a boundary face")
    {
        TetMesh mesh = square_mesh({0, 0, 0.25});
        OperatorContext context(mesh, nullptr);
        // tet 0 = (r0, r2, r1, a): its face opposite r0, (r2, r1, a), is on the hull
        const auto result = refuse(mesh, context, 0, local_index(mesh, 0, 0));
        CHECK_FALSE(result.legal);
    }
    SUBCASE("the seed face between two refs (an interface)")
    {
        TetMesh mesh = square_mesh({0, 0, 0.25});
        mesh.tet_refs[1] = 2;  // the upper tet of face 0
        OperatorContext context(mesh, nullptr);
        CHECK_FALSE(refuse(mesh, context, 0, kApexLocal).legal);
    }
    SUBCASE("the second face's tets of another ref: only the flat 2-3 flip is left")
    {
        TetMesh mesh = square_mesh({0, 0, 0.25});
        mesh.tet_refs[2] = mesh.tet_refs[3] = 2;
        OperatorContext context(mesh, nullptr);
        const auto result = refuse(mesh, context, 0, kApexLocal);
        CHECK(result.legal);
        CHECK(result.sandwich_size == 1);
        CHECK(result.worst_after <= 0);
    }
    SUBCASE("a listed triangle on the face (r0, r2, a) between the two faces")
    {
        TetMesh mesh = square_mesh({0, 0, 0.25});
        mesh.add_triangle({0, 2, 4}, 5);
        OperatorContext context(mesh, nullptr);
        CHECK(refuse(mesh, context, 0, kApexLocal).sandwich_size == 1);
    }
    SUBCASE("the diagonal r0-r2 is a feature edge")
    {
        TetMesh mesh = square_mesh({0, 0, 0.25});
        mesh.edges.push_back({0, 2});
        mesh.edge_refs.push_back(1);
        OperatorContext context(mesh, nullptr);
        CHECK(refuse(mesh, context, 0, kApexLocal).sandwich_size == 1);
    }
    SUBCASE("ab misses the square: some new tet would be inverted")
    {
        TetMesh mesh = square_mesh({2.5, 0.3, 0.25});
        OperatorContext context(mesh, nullptr);
        const auto result = refuse(mesh, context, 0, kApexLocal);
        CHECK(result.legal);
        CHECK(result.sandwich_size == 2);
        CHECK(result.worst_after <= 0);
    }
    SUBCASE("the new edge ab would be too long for the size field")
    {
        TetMesh mesh = square_mesh({0, 0, 0.25});
        const ConstantSize field(0.2);  // ab = 0.5 > 1.515 * 0.2
        OperatorContext context(mesh, &field);
        const auto result = refuse(mesh, context, 0, kApexLocal);
        CHECK(result.faces_removed == 2);
        CHECK(result.worst_after > result.worst_before);
    }
    SUBCASE("no gain: apexes far from the square, ab = 3 would make needles (0.76 -> 0.46)")
    {
        TetMesh mesh = square_mesh({0, 0, 1.5}, {0, 0, -1.5});
        OperatorContext context(mesh, nullptr);
        const auto result = refuse(mesh, context, 0, kApexLocal);
        CHECK(result.legal);
        CHECK(result.worst_after <= result.worst_before);
    }
    /*  ab already an edge: three tets around the vertical edge x-y, ring r0 r1 r2. The face
        (x, y, r0) lies between the tets with apexes a = r1 and b = r2, but r1-r2 is a ring
        edge (the seed's sandwich is only that face: x-y's shell has 3 tets, not 4).

                 y
                /|\
          r1 --/-|-\-- r0
                \|/
                 x     r2 behind                                                             */
    SUBCASE("ab is already an edge")
    {
        const double s = std::sqrt(3.0) / 2;
        TetMesh mesh =
            mesh_from_tets({{0, 0, -1.5}, {0, 0, 1.5}, {1, 0, 0}, {-0.5, s, 0}, {-0.5, -s, 0}},
                           {{0, 1, 2, 3}, {0, 1, 3, 4}, {0, 1, 4, 2}});
        OperatorContext context(mesh, nullptr);
        const auto result = refuse(mesh, context, 0, local_index(mesh, 0, 3));  // opposite r1
        // the new tets around an existing edge cannot all be positive: the geometry refuses
        // first, and the edge test (a ball walk) is not even needed
        CHECK(result.worst_after <= 0);
        CHECK_FALSE(remove_face(mesh, context, 0, local_index(mesh, 0, 3)).removed);
    }
}

/*  Wherever the 2-3 flip succeeds, multi-face removal must succeed too, at least as well (the
    2-3 flip is its k = 1 choice, so it can replace remove_face in a driver). Over the strip of
    five faces drawn above, with apexes placed at random (fixed seed) and every face as seed;
    each flip is tried on a copy.                                                            */
TEST_CASE("multi-face removal succeeds wherever the 2-3 flip does")
{
    const std::vector<Triangle> faces = {{0, 1, 2}, {0, 2, 6}, {2, 3, 6}, {3, 5, 6}, {3, 4, 5}};
    std::vector<Vec3> polygon;
    for (int i = 0; i < 7; ++i)
    {
        const double angle = 2 * kPi * i / 7 + 0.05 * std::sin(3.0 * i + 1);
        polygon.push_back({std::cos(angle), std::sin(angle), 0.02 * std::sin(7.0 * i)});
    }
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int flips = 0, larger = 0;
    for (int trial = 0; trial < 300; ++trial)
    {
        const Vec3 axis(0.7 * unit(random), 0.7 * unit(random), 0);
        const double below = 0.55 + 0.5 * unit(random), above = 0.55 + 0.5 * unit(random);
        const Vec3 a = axis + Vec3(0.2 * unit(random), 0.2 * unit(random), -below);
        const Vec3 b = axis + Vec3(0.2 * unit(random), 0.2 * unit(random), above);
        const TetMesh mesh = sandwich_mesh(polygon, faces, a, b);
        const OperatorContext context(mesh, nullptr);
        for (int seed = 0; seed < 5; ++seed)
        {
            TetMesh copy = mesh;
            OperatorContext copy_context = context;
            const auto flip = remove_face(copy, copy_context, 2 * seed, kApexLocal);
            if (!flip.removed) continue;
            ++flips;
            const auto multi = evaluate_multi_face_removal(mesh, context, 2 * seed, kApexLocal);
            CAPTURE(trial);
            CAPTURE(seed);
            CHECK(multi.legal);
            CHECK(multi.worst_after >= flip.worst_after);
            CHECK(multi.worst_after > multi.worst_before + 1e-6);
            larger += multi.faces_removed > 1;
        }
    }
    MESSAGE(flips << " 2-3 flips; multi-face removal takes more faces in " << larger);
    CHECK(flips > 20);
    CHECK(larger > 0);
}

/*  Every interior face of a jittered 4x4x4 Kuhn box, a few sweeps: each removal must keep the
    mesh valid, conserve its volume and boundary, and never lower the global worst quality.  */
TEST_CASE("multi-face removal over every face of a jittered box")
{
    for (const std::uint32_t seed : {1u, 2u, 3u})
    {
        CAPTURE(seed);
        TetMesh mesh = fixtures::box_mesh(4, 0.24, seed);
        OperatorContext context(mesh, nullptr);
        const double volume = mesh.total_volume();
        const auto boundary = boundary_faces(mesh);
        double worst = live_worst(mesh);
        const double worst_start = worst;
        int removals = 0, beyond_flips = 0;
        for (int sweep = 0; sweep < 3; ++sweep)
        {
            const int slots = mesh.num_tet_slots();
            for (int t = 0; t < slots; ++t)
                for (int f = 0; f < 4; ++f)
                {
                    if (mesh.is_dead(t) || mesh.neighbors[t][f] == kNoTet) continue;
                    const auto result = remove_multi_face(mesh, context, t, f);
                    if (!result.removed) continue;
                    ++removals;
                    beyond_flips += result.faces_removed >= 3;
                    const double now = live_worst(mesh);
                    REQUIRE(now >= worst);
                    worst = now;
                }
        }
        MESSAGE("seed " << seed << ": " << removals << " removals (" << beyond_flips
                        << " with k >= 3), worst " << worst_start << " -> " << worst);
        CHECK(removals > 0);
        CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-12));
        CHECK(boundary_faces(mesh) == boundary);
        require_valid(mesh);
    }
}
