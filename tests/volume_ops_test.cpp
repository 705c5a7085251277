// The optimization operators on small drawn configurations: each legal case must raise the
// worst quality, conserve the volume, keep the boundary and leave a valid mesh (check_mesh,
// which also compares the maintained adjacency with a recomputed one); each illegal case must
// leave the mesh bit for bit as it was.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/check/quality_report.h"
#include "volume/mesh/blocks.h"
#include "volume/mesh/tet_tables.h"
#include "volume/mesh/tet_topology.h"
#include "volume/optimize/collapse.h"
#include "volume/optimize/edge_removal.h"
#include "volume/optimize/edge_split.h"
#include "volume/optimize/face_removal.h"
#include "volume/optimize/smooth.h"
#include "volume/size/size_fields.h"

using namespace hdimesh;

namespace
{

using fixtures::mesh_from_tets;

void require_valid(const TetMesh& mesh)
{
    const auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    REQUIRE(violations.empty());
}

/// The boundary as sorted coordinate triples, so it compares across renumbering.
std::vector<std::array<double, 9>> boundary_signature(const TetMesh& mesh)
{
    std::vector<std::array<double, 9>> result;
    for (const auto& tri : mesh.triangles)
    {
        std::array<Triangle, 1> sorted_tri = {tri};
        std::sort(sorted_tri[0].begin(), sorted_tri[0].end());
        std::array<double, 9> key{};
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c) key[3 * k + c] = mesh.points[sorted_tri[0][k]][c];
        result.push_back(key);
    }
    std::sort(result.begin(), result.end());
    return result;
}

double live_worst(const TetMesh& mesh)
{
    double worst = 1e300;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_dead(t)) worst = std::min(worst, mesh.quality(t));
    return worst;
}

/// Local edge of tet t joining vertices a and b.
int local_edge(const TetMesh& mesh, int t, int a, int b)
{
    return tet::kEdgeOfVertices[local_index(mesh, t, a)][local_index(mesh, t, b)];
}

const double kRoot3 = std::sqrt(3.0);
const double kPi = 3.14159265358979323846;

/*  Three tets around the vertical edge a-b, ring r0 r1 r2 (an equilateral triangle in z = 0,
    counter-clockwise seen from b):

             b (0,0,H)
            /|\
      r1 --/-|-\-- r0        shell tets (a, b, r_i, r_i+1)
            \|/
             a (0,0,-H)      r2 behind                                                       */
TetMesh three_tet_shell(double height, double r0_z = 0.0)
{
    return mesh_from_tets({{0, 0, -height},
                           {0, 0, height},
                           {1, 0, r0_z},
                           {-0.5, kRoot3 / 2, 0},
                           {-0.5, -kRoot3 / 2, 0}},
                          {{0, 1, 2, 3}, {0, 1, 3, 4}, {0, 1, 4, 2}});
}

}  // namespace

TEST_CASE("edge shell: ordered ring, closed around an interior edge, open on the boundary")
{
    const TetMesh mesh = three_tet_shell(1.5);
    EdgeShell shell;
    REQUIRE(edge_shell(mesh, 1, 0, 1, shell));
    CHECK(shell.closed);
    REQUIRE(shell.tets.size() == 3);
    REQUIRE(shell.ring.size() == 3);
    for (std::size_t i = 0; i < 3; ++i)
    {
        const int t = shell.tets[i];
        const auto& p = mesh.points;
        const int c = shell.ring[i], d = shell.ring[(i + 1) % 3];
        CHECK(local_index(mesh, t, c) >= 0);
        CHECK(local_index(mesh, t, d) >= 0);
        CHECK(signed_volume(p[0], p[1], p[c], p[d]) > 0);
    }
    // the ring edge r0-r1 is on the boundary: its shell is the single tet 0
    REQUIRE(edge_shell(mesh, 0, 2, 3, shell));
    CHECK_FALSE(shell.closed);
    CHECK(shell.tets.size() == 1);
    CHECK(shell.ring.size() == 2);

    std::vector<int> ball;
    vertex_ball(mesh, 2, 0, ball);
    CHECK(ball.size() == 3);
    vertex_ball(mesh, 0, 2, ball);
    CHECK(ball.size() == 2);
}

TEST_CASE("3-2 flip: a long edge through a triangle is removed and the worst tet improves")
{
    TetMesh mesh = three_tet_shell(1.5);
    OperatorContext context(mesh, nullptr);
    const double volume = mesh.total_volume();
    const auto boundary = boundary_signature(mesh);
    const double worst_before = live_worst(mesh);

    const auto result = remove_edge(mesh, context, 0, local_edge(mesh, 0, 0, 1));
    REQUIRE(result.removed);
    CHECK(result.ring_size == 3);
    CHECK(mesh.num_live_tets() == 2);
    CHECK(live_worst(mesh) == doctest::Approx(result.worst_after));
    CHECK(live_worst(mesh) > worst_before + 0.5);  // 0.37 -> 0.98
    CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-12));
    CHECK(boundary_signature(mesh) == boundary);
    require_valid(mesh);
    // the vertex map points at live tets containing each vertex
    for (int v = 0; v < mesh.num_vertices(); ++v)
    {
        const int t = context.vertex_tet[v];
        REQUIRE(t >= 0);
        CHECK_FALSE(mesh.is_dead(t));
        CHECK(local_index(mesh, t, v) >= 0);
    }
}

TEST_CASE("3-2 flip refused: non-convex ring, constrained face, different refs, no gain")
{
    SUBCASE("r0 lifted above b: the new tet over the ring would be inverted")
    {
        // the plane r0 r1 r2 passes above b, so (r0, r1, r2, b) is negative
        TetMesh mesh = three_tet_shell(1.0, 4.0);
        OperatorContext context(mesh, nullptr);
        const auto tets = mesh.tets;
        const auto result = remove_edge(mesh, context, 0, local_edge(mesh, 0, 0, 1));
        CHECK_FALSE(result.removed);
        CHECK(result.worst_after <= 0);
        CHECK(mesh.tets == tets);
    }
    SUBCASE("an interface triangle through the edge")
    {
        TetMesh mesh = three_tet_shell(1.5);
        mesh.add_triangle({0, 1, 3}, 7);  // the face shared by tets 0 and 1
        OperatorContext context(mesh, nullptr);
        const auto tets = mesh.tets;
        CHECK_FALSE(remove_edge(mesh, context, 0, local_edge(mesh, 0, 0, 1)).removed);
        CHECK(mesh.tets == tets);
    }
    SUBCASE("tets of two refs")
    {
        TetMesh mesh = three_tet_shell(1.5);
        mesh.tet_refs[2] = 2;
        OperatorContext context(mesh, nullptr);
        const auto tets = mesh.tets;
        CHECK_FALSE(remove_edge(mesh, context, 0, local_edge(mesh, 0, 0, 1)).removed);
        CHECK(mesh.tets == tets);
    }
    SUBCASE("a boundary edge (open shell)")
    {
        TetMesh mesh = three_tet_shell(1.5);
        OperatorContext context(mesh, nullptr);
        const auto tets = mesh.tets;
        CHECK_FALSE(remove_edge(mesh, context, 0, local_edge(mesh, 0, 0, 2)).removed);
        CHECK(mesh.tets == tets);
    }
    SUBCASE("a short edge: the two new tets would be worse (0.54 -> flat)")
    {
        TetMesh mesh = three_tet_shell(0.3);
        OperatorContext context(mesh, nullptr);
        const auto tets = mesh.tets;
        const auto result = remove_edge(mesh, context, 0, local_edge(mesh, 0, 0, 1));
        CHECK_FALSE(result.removed);
        CHECK(result.worst_after < result.worst_before);
        CHECK(mesh.tets == tets);
    }
    SUBCASE("a size field that forbids nothing here still allows it; ring chords are checked")
    {
        TetMesh mesh = three_tet_shell(1.5);
        const ConstantSize field(0.5);  // every ring edge (length 1.73) is already too long
        OperatorContext context(mesh, &field);
        // a 3-ring has no chord: the removal only deletes an edge, it is allowed
        CHECK(remove_edge(mesh, context, 0, local_edge(mesh, 0, 0, 1)).removed);
        require_valid(mesh);
    }
}

/*  Edge removal with a ring of m = 6 around a long vertical edge a-b (a hexagon of radius 1
    in z = 0, slightly perturbed so no two triangulations tie):

        r2 ---- r1
       /   \ b /  \          the shell's 6 tets are needles (edge a-b = 3);
     r3 ---- + ---- r0       the best of the 14 triangulations of the hexagon gives 8 tets
       \   / a \  /
        r4 ---- r5                                                                          */
TEST_CASE("edge removal, ring of 6: the dynamic program finds the best of all triangulations")
{
    std::vector<Vec3> points = {{0.02, 0.01, -1.5}, {-0.01, 0.02, 1.5}};
    const int m = 6;
    for (int i = 0; i < m; ++i)
    {
        const double angle = 2 * kPi * i / m + 0.03 * std::sin(3.0 * i + 1);
        const double radius = 1.0 + 0.05 * std::cos(5.0 * i);
        points.push_back(
            {radius * std::cos(angle), radius * std::sin(angle), 0.04 * std::sin(7.0 * i)});
    }
    std::vector<TetVertices> tets;
    for (int i = 0; i < m; ++i) tets.push_back({0, 1, 2 + i, 2 + (i + 1) % m});
    TetMesh mesh = mesh_from_tets(points, tets);
    OperatorContext context(mesh, nullptr);

    // brute force: every triangulation of the convex ring polygon, by recursion on the chord
    // (0, m-1); the worst new tet of each
    const auto& p = mesh.points;
    std::function<double(int, int)> best = [&](int i, int j) -> double {
        if (j - i < 2) return 1e300;
        double value = -1e300;
        for (int k = i + 1; k < j; ++k)
        {
            const Vec3 &ri = p[2 + i], &rk = p[2 + k], &rj = p[2 + j];
            value = std::max(value, std::min({best(i, k), best(k, j), tet_quality(ri, rk, rj, p[1]),
                                              tet_quality(ri, rj, rk, p[0])}));
        }
        return value;
    };
    const double brute_force = best(0, m - 1);

    const double volume = mesh.total_volume();
    const double worst_before = live_worst(mesh);
    const auto result = remove_edge(mesh, context, 3, local_edge(mesh, 3, 0, 1));
    REQUIRE(result.removed);
    CHECK(result.ring_size == m);
    CHECK(result.worst_after == doctest::Approx(brute_force).epsilon(1e-14));
    CHECK(mesh.num_live_tets() == 2 * (m - 2));
    CHECK(live_worst(mesh) == doctest::Approx(result.worst_after));
    CHECK(live_worst(mesh) > worst_before);
    CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-12));
    require_valid(mesh);
}

/*  Two flat tets on an equilateral triangle x y z (side sqrt 3, in z = 0), apexes p below and
    q above at height h:

            q (0,0,h)
          / | \            2-3: the tets (x,y,p,q), (y,z,p,q), (z,x,p,q) around p-q
        x---|---z
          \ | /
            p (0,0,-h)                                                                       */
TEST_CASE("2-3 flip: flat tet pair becomes three tets around the apex edge")
{
    auto pair_mesh = [](double h, double q_shift) {
        return mesh_from_tets(
            {{1, 0, 0}, {-0.5, kRoot3 / 2, 0}, {-0.5, -kRoot3 / 2, 0}, {0, 0, -h}, {q_shift, 0, h}},
            {{0, 1, 2, 4}, {0, 2, 1, 3}});
    };
    SUBCASE("legal and better (h = 0.2: 0.27 -> 0.37)")
    {
        TetMesh mesh = pair_mesh(0.2, 0.0);
        OperatorContext context(mesh, nullptr);
        const double volume = mesh.total_volume();
        const double worst_before = live_worst(mesh);
        const auto boundary = boundary_signature(mesh);
        const int face = local_index(mesh, 0, 4);  // tet 0's face opposite q is x y z
        const auto result = remove_face(mesh, context, 0, face);
        REQUIRE(result.removed);
        CHECK(mesh.num_live_tets() == 3);
        CHECK(live_worst(mesh) > worst_before + 0.05);
        CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-12));
        CHECK(boundary_signature(mesh) == boundary);
        require_valid(mesh);
    }
    SUBCASE("legal but no gain (h = 0.5: 0.59 -> 0.55)")
    {
        TetMesh mesh = pair_mesh(0.5, 0.0);
        OperatorContext context(mesh, nullptr);
        const auto tets = mesh.tets;
        const auto result = remove_face(mesh, context, 0, local_index(mesh, 0, 4));
        CHECK_FALSE(result.removed);
        CHECK(result.worst_after < result.worst_before);
        CHECK(mesh.tets == tets);
    }
    SUBCASE("illegal: the segment p-q misses the triangle")
    {
        TetMesh mesh = pair_mesh(0.2, 3.0);
        OperatorContext context(mesh, nullptr);
        const auto tets = mesh.tets;
        const auto result = remove_face(mesh, context, 0, local_index(mesh, 0, 4));
        CHECK_FALSE(result.removed);
        CHECK(result.worst_after <= 0);
        CHECK(mesh.tets == tets);
    }
    SUBCASE("illegal: a boundary face, and a listed interior triangle")
    {
        TetMesh mesh = pair_mesh(0.2, 0.0);
        OperatorContext plain(mesh, nullptr);
        CHECK_FALSE(remove_face(mesh, plain, 0, local_index(mesh, 0, 0)).removed);
        mesh.add_triangle({0, 1, 2}, 3);
        OperatorContext constrained(mesh, nullptr);
        const auto tets = mesh.tets;
        CHECK_FALSE(remove_face(mesh, constrained, 0, local_index(mesh, 0, 4)).removed);
        CHECK(mesh.tets == tets);
    }
    SUBCASE("illegal: the new edge p-q would be too long")
    {
        TetMesh mesh = pair_mesh(0.2, 0.0);
        const ConstantSize field(0.2);  // p-q = 0.4 > 1.515 * 0.2
        OperatorContext context(mesh, &field);
        CHECK_FALSE(remove_face(mesh, context, 0, local_index(mesh, 0, 4)).removed);
    }
}

/*  Smoothing in a 3x3x3 Kuhn box whose interior vertex (1/3,1/3,1/3) is pushed toward a
    corner: its ball holds the worst tets; smoothing must raise the ball's worst quality and
    keep the boundary vertices where they are.                                              */
TEST_CASE("smoothing: an interior vertex pushed off-centre comes back, boundary stays")
{
    TetMesh mesh = fixtures::box_mesh(3);
    const int v = 1 + 4 * (1 + 4 * 1);  // (1,1,1) of the 4x4x4 grid
    REQUIRE(mesh.vertex_classes[v] == VertexClass::Interior);
    mesh.points[v] = Vec3(0.2, 0.2, 0.25);
    require_valid(mesh);
    OperatorContext context(mesh, nullptr);
    const double volume = mesh.total_volume();
    const auto boundary = boundary_signature(mesh);
    const double worst_before = live_worst(mesh);

    SUBCASE("nodal shifting alone")
    {
        SmoothOptions options;
        options.optimization_based = false;
        const auto result = smooth_vertex(mesh, context, v, options);
        REQUIRE(result.moved);
        CHECK(result.worst_after > result.worst_before);
    }
    SUBCASE("optimization-based move alone")
    {
        SmoothOptions options;
        options.nodal_shifting = false;
        const auto result = smooth_vertex(mesh, context, v, options);
        REQUIRE(result.moved);
        CHECK(result.worst_after > result.worst_before);
    }
    SUBCASE("both")
    {
        const auto result = smooth_vertex(mesh, context, v);
        REQUIRE(result.moved);
        CHECK(result.worst_after > result.worst_before);
        // a second pass cannot make it worse
        const double after_first = live_worst(mesh);
        smooth_vertex(mesh, context, v);
        CHECK(live_worst(mesh) >= after_first);
    }
    CHECK(live_worst(mesh) > worst_before);
    CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-12));
    CHECK(boundary_signature(mesh) == boundary);
    require_valid(mesh);

    // boundary vertices never move
    const Vec3 corner = mesh.points[0];
    CHECK_FALSE(smooth_vertex(mesh, context, 0).moved);
    CHECK(mesh.points[0] == corner);
}

TEST_CASE("smoothing refuses a move that makes an edge too long")
{
    TetMesh mesh = fixtures::box_mesh(3);
    const int v = 1 + 4 * (1 + 4 * 1);
    mesh.points[v] = Vec3(0.2, 0.2, 0.25);
    // every edge around v stays below 1.515 * h only while v stays near the far corner
    const ConstantSize field(0.18);
    OperatorContext context(mesh, &field);
    std::vector<int> ball;
    vertex_ball(mesh, context.vertex_tet[v], v, ball);
    auto too_long_edges = [&] {
        int count = 0;
        for (int t : ball)
            for (int w : mesh.tets[t])
                if (w != v) count += context.too_long(mesh.points[v], mesh.points[w]);
        return count;
    };
    const int before = too_long_edges();
    smooth_vertex(mesh, context, v);
    CHECK(too_long_edges() <= before);
    require_valid(mesh);
}

/// The smallest dihedral angle over the tets around vertex v, in degrees.
double ball_smallest_dihedral(const TetMesh& mesh, const OperatorContext& context, int v)
{
    std::vector<int> ball;
    vertex_ball(mesh, context.vertex_tet[v], v, ball);
    double smallest = 180;
    for (int t : ball)
    {
        const auto& tv = mesh.tets[t];
        const auto& p = mesh.points;
        for (double angle : dihedral_angles_deg(p[tv[0]], p[tv[1]], p[tv[2]], p[tv[3]]))
            smallest = std::min(smallest, angle);
    }
    return smallest;
}

/*  A strongly jittered 5x5x5 Kuhn box: every interior vertex smoothed in turn. Each move must
    raise its ball's worst Qe and may not take the ball's smallest dihedral angle below
    min(its old value, 20 degrees).                                                          */
TEST_CASE("smoothing never trades a ball's smallest dihedral angle for Qe")
{
    TetMesh mesh = fixtures::box_mesh(5, 0.3, 11);
    require_valid(mesh);
    OperatorContext context(mesh, nullptr);
    const double volume = mesh.total_volume();
    const SmoothOptions options;
    int moved = 0;
    for (int v = 0; v < mesh.num_vertices(); ++v)
    {
        if (!context.constraints.is_free_vertex(v)) continue;
        const double before = ball_smallest_dihedral(mesh, context, v);
        const auto result = smooth_vertex(mesh, context, v, options);
        if (!result.moved) continue;
        ++moved;
        CHECK(result.worst_after > result.worst_before);
        CHECK(ball_smallest_dihedral(mesh, context, v) >=
              std::min(before, options.min_dihedral_deg));
    }
    CHECK(moved > 10);
    CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-12));
    require_valid(mesh);
}

/// A regular tet of edge 1 (v0..v3) split into four tets by the interior point p (vertex 4).
TetMesh regular_tet_star(const std::function<Vec3(const std::vector<Vec3>&)>& place)
{
    TetMesh base = fixtures::regular_tet();
    std::vector<Vec3> points = base.points;
    points.push_back(place(base.points));
    std::vector<TetVertices> tets;
    for (int f = 0; f < 4; ++f)
    {
        TetVertices t = base.tets[0];
        t[f] = 4;  // P replaces the vertex opposite face f: positive, as P is inside
        tets.push_back(t);
    }
    return mesh_from_tets(points, tets);
}

/*  A regular tet split by P, pushed from the centroid toward the midpoint M of edge v0-v1:

            v3
           /|\          the tets on the faces (v0 v1 v2) and (v0 v1 v3) are the two worst,
          / | \         tied: each one's own gradient pushes P toward the other's face, so
        v0--P--v2       only a direction raising both (their bisector, back toward the
          \ M /         centroid) improves the worst of the ball
            v1                                                                               */
TEST_CASE("smoothing: the max-min move raises two tied worst tets at once")
{
    TetMesh mesh = regular_tet_star([](const std::vector<Vec3>& q) {
        const Vec3 centroid = 0.25 * (q[0] + q[1] + q[2] + q[3]);
        return Vec3(centroid + 0.8 * (0.5 * (q[0] + q[1]) - centroid));
    });
    REQUIRE(mesh.vertex_classes[4] == VertexClass::Interior);
    require_valid(mesh);
    const double volume = mesh.total_volume();
    const auto boundary = boundary_signature(mesh);
    SmoothOptions options;
    options.nodal_shifting = false;

    SUBCASE("the worst tet's gradient alone is blocked by its tied twin")
    {
        options.active_band = 0;
        OperatorContext context(mesh, nullptr);
        CHECK_FALSE(smooth_vertex(mesh, context, 4, options).moved);
    }
    SUBCASE("the common ascent of the nearly worst tets moves P")
    {
        OperatorContext context(mesh, nullptr);
        const auto result = smooth_vertex(mesh, context, 4, options);
        REQUIRE(result.moved);
        CHECK(result.worst_after > 4 * result.worst_before);  // about 0.10 -> 0.44
        CHECK(live_worst(mesh) == doctest::Approx(result.worst_after));
    }
    CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-12));
    CHECK(boundary_signature(mesh) == boundary);
    require_valid(mesh);
}

/*  A regular tet of edge 1 split by P just above the centre of face (v1 v2 v3), with h = 1:
    the edges P-v1, P-v2, P-v3 are too short already (about 0.58), P-v0 is not (0.8). The
    best shapes are at the centroid, where P-v0 = 0.61 would be too short; the move must stop
    at the band's edge (P-v0 = 0.66 h) instead of short of it or past it.

            v0
           /|\
          / | \        P slides up the axis v0 - centre(v1 v2 v3)
        v1--P--v3
            v2                                                                               */
TEST_CASE("smoothing: a point the sizes refuse is pulled back into the size band")
{
    TetMesh mesh = regular_tet_star([](const std::vector<Vec3>& q) {
        const Vec3 face_centre = (q[1] + q[2] + q[3]) / 3.0;
        return Vec3(face_centre + 0.05 * (q[0] - face_centre));
    });
    const ConstantSize field(1.0);
    const Vec3 v0 = mesh.points[0];
    REQUIRE_FALSE(is_too_short((mesh.points[4] - v0).norm(), 1.0));
    const double volume = mesh.total_volume();
    const auto boundary = boundary_signature(mesh);

    // the best the band allows: P on the axis at 0.66 h from v0 (by symmetry)
    const Vec3 centroid =
        0.25 * (mesh.points[0] + mesh.points[1] + mesh.points[2] + mesh.points[3]);
    const Vec3 band_edge = v0 + (kSizeQualityThreshold / (centroid - v0).norm()) * (centroid - v0);
    TetMesh at_band_edge = mesh;
    at_band_edge.points[4] = band_edge;
    const double best_in_band = live_worst(at_band_edge);

    SmoothOptions without;
    without.size_projection = false;
    TetMesh unprojected = mesh;
    OperatorContext unprojected_context(unprojected, &field);
    for (int pass = 0; pass < 3; ++pass)
        smooth_vertex(unprojected, unprojected_context, 4, without);

    OperatorContext context(mesh, &field);
    for (int pass = 0; pass < 3; ++pass) smooth_vertex(mesh, context, 4);
    const double length = (mesh.points[4] - v0).norm();
    CHECK_FALSE(is_too_short(length, 1.0));
    CHECK(length < kSizeQualityThreshold * 1.01);  // at the band's edge
    CHECK(live_worst(mesh) > live_worst(unprojected));
    CHECK(live_worst(mesh) == doctest::Approx(best_in_band).epsilon(0.01));
    CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-12));
    CHECK(boundary_signature(mesh) == boundary);
    require_valid(mesh);
    require_valid(unprojected);
}

/*  An octahedron of half-height H, apexes a = (0,0,-H) and b = (0,0,H), equator r0..r3 =
    (1,0,0) (0,1,0) (-1,0,0) (0,-1,0), meshed as the four tets around the axis a-b: all six
    vertices on the boundary, each tet with two boundary faces meeting at an equator edge.

             b
            /|\           the axis is the only interior edge; splitting it at m gives the
      r2 - / m \ - r0     eight tets (a, m, ri, ri+1), (m, b, ri, ri+1)
            \ | /
             \|/
             a                                                                               */
TetMesh axis_octahedron(double half_height)
{
    return mesh_from_tets(
        {{0, 0, -half_height}, {0, 0, half_height}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}},
        {{0, 1, 2, 3}, {0, 1, 3, 4}, {0, 1, 4, 5}, {0, 1, 5, 2}});
}

TEST_CASE("interior edge split: a tall octahedron's needles around its axis")
{
    SUBCASE("legal: the axis is split, the new point interior, the worst tet better")
    {
        TetMesh mesh = axis_octahedron(2.0);
        require_valid(mesh);
        OperatorContext context(mesh, nullptr);
        const double volume = mesh.total_volume();
        const auto boundary = boundary_signature(mesh);
        const double worst_before = live_worst(mesh);
        const auto result = split_interior_edge(mesh, context, 0);
        REQUIRE(result.split);
        CHECK(result.worst_before == doctest::Approx(worst_before));
        CHECK(mesh.num_live_tets() == 8);
        CHECK(live_worst(mesh) == doctest::Approx(result.worst_after));
        CHECK(live_worst(mesh) > worst_before + 0.15);  // about 0.35 -> 0.55
        const int m = result.new_vertex;
        REQUIRE(m == 6);
        CHECK(mesh.vertex_classes[m] == VertexClass::Interior);
        CHECK(context.constraints.is_free_vertex(m));
        CHECK(std::abs(mesh.points[m][0]) < 1e-9);  // on the axis, by symmetry
        CHECK(std::abs(mesh.points[m][1]) < 1e-9);
        CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-12));
        CHECK(boundary_signature(mesh) == boundary);
        require_valid(mesh);
    }
    SUBCASE("refused: nothing better (a squat octahedron's tets are good already)")
    {
        TetMesh mesh = axis_octahedron(0.5);
        OperatorContext context(mesh, nullptr);
        const auto tets = mesh.tets;
        const auto points = mesh.points;
        CHECK_FALSE(split_interior_edge(mesh, context, 0).split);
        CHECK(mesh.tets == tets);
        CHECK(mesh.points == points);
    }
    SUBCASE("refused: the axis is a listed feature edge")
    {
        TetMesh mesh = axis_octahedron(2.0);
        mesh.edges.push_back({0, 1});
        mesh.edge_refs.push_back(0);
        OperatorContext context(mesh, nullptr);
        const auto tets = mesh.tets;
        CHECK_FALSE(split_interior_edge(mesh, context, 0).split);
        CHECK(mesh.tets == tets);
        CHECK(mesh.num_vertices() == 6);
    }
    SUBCASE("refused: the shell holds two tet refs")
    {
        TetMesh mesh = axis_octahedron(2.0);
        mesh.tet_refs[2] = 7;
        OperatorContext context(mesh, nullptr);
        const auto tets = mesh.tets;
        CHECK_FALSE(split_interior_edge(mesh, context, 0).split);
        CHECK(mesh.tets == tets);
        CHECK(mesh.num_vertices() == 6);
    }
}

/*  A regular tet v0 v1 v2 v3 split by an interior point P close to v0 into four tets
    (P with each face). The edge P-v0 is far too short for h = 1:

            v3
           /|\          collapse P -> v0: the three tets of edge P-v0 die, the fourth
          / P \         becomes (v0, v1, v2, v3) again — quality 1.
        v0--|--v2
          \ | /
            v1                                                                               */
TEST_CASE("collapse of a too-short edge: interior point near a corner merges into it")
{
    TetMesh base = fixtures::regular_tet();
    const auto& q = base.points;
    const Vec3 centroid = 0.25 * (q[0] + q[1] + q[2] + q[3]);
    const Vec3 p = q[0] + 0.1 * (centroid - q[0]);
    std::vector<Vec3> points = {q[0], q[1], q[2], q[3], p};
    std::vector<TetVertices> tets;
    for (int f = 0; f < 4; ++f)
    {
        TetVertices t = base.tets[0];
        t[f] = 4;  // P replaces the vertex opposite face f: positive, as P is inside
        tets.push_back(t);
    }
    TetMesh mesh = mesh_from_tets(points, tets);
    REQUIRE(mesh.vertex_classes[4] == VertexClass::Interior);
    const ConstantSize field(1.0);
    REQUIRE(is_too_short((p - q[0]).norm(), 1.0));

    SUBCASE("legal: P onto v0")
    {
        OperatorContext context(mesh, &field);
        const double volume = mesh.total_volume();
        const auto boundary = boundary_signature(mesh);
        const double worst_before = live_worst(mesh);
        const auto result = collapse_edge(mesh, context, 4, 0);
        REQUIRE(result.collapsed);
        CHECK(mesh.num_live_tets() == 1);
        CHECK(live_worst(mesh) == doctest::Approx(1.0));
        CHECK(live_worst(mesh) > worst_before);
        CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-12));
        CHECK(boundary_signature(mesh) == boundary);
        CHECK(context.vertex_tet[4] == -1);
        require_valid(mesh);
        mesh.compact();
        CHECK(mesh.num_vertices() == 4);
        require_valid(mesh);
    }
    SUBCASE("illegal: a boundary vertex never moves")
    {
        OperatorContext context(mesh, &field);
        const auto tets = mesh.tets;
        CHECK_FALSE(collapse_edge(mesh, context, 0, 4).collapsed);
        CHECK(mesh.tets == tets);
    }
    SUBCASE("illegal: the ball holds two tet refs")
    {
        mesh.tet_refs[1] = 5;
        OperatorContext context(mesh, &field);
        const auto tets = mesh.tets;
        CHECK_FALSE(collapse_edge(mesh, context, 4, 0).collapsed);
        CHECK(mesh.tets == tets);
    }
    SUBCASE("illegal: P onto itself")
    {
        OperatorContext context(mesh, &field);
        CHECK_FALSE(collapse_edge(mesh, context, 4, 4).collapsed);
    }
}

/*  Kuhn box 3x3x3, collapses of the interior vertex v = (1,1,1) (grid units) onto neighbours:
    onto (1,0,0) (a face diagonal) some re-attached tets come out flat; onto (2,2,1) they are
    positive but worse than the floor 0.3; onto (0,1,1) (an axis step) they stay >= 0.3.     */
TEST_CASE("collapse in a Kuhn box: flat, below the floor, and legal")
{
    TetMesh mesh = fixtures::box_mesh(3);
    auto grid = [](int i, int j, int k) { return i + 4 * (j + 4 * k); };
    const int v = grid(1, 1, 1);
    OperatorContext context(mesh, nullptr);
    const auto tets = mesh.tets;
    const double volume = mesh.total_volume();

    const auto flat = collapse_edge(mesh, context, v, grid(1, 0, 0));
    CHECK_FALSE(flat.collapsed);
    CHECK(flat.worst_after < 1e-9);
    CHECK(mesh.tets == tets);

    const auto poor = collapse_edge(mesh, context, v, grid(2, 2, 1));
    CHECK_FALSE(poor.collapsed);
    CHECK(poor.worst_after > 0);
    CHECK(poor.worst_after < 0.3);
    CHECK(mesh.tets == tets);

    const double worst_before = live_worst(mesh);
    const auto legal = collapse_edge(mesh, context, v, grid(0, 1, 1));
    REQUIRE(legal.collapsed);
    CHECK(legal.worst_after >= 0.3);
    CHECK(live_worst(mesh) >= std::min(worst_before, 0.3));
    CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-12));
    require_valid(mesh);
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_dead(t)) CHECK(local_index(mesh, t, v) < 0);
}

namespace
{

/// One fixed sweep of every operator over a mesh: for each tet slot present at the start (in
/// order, if still alive), edge removal on its six edges, then multi-face removal on its four
/// faces, then smoothing and size equalization of its vertices, then a collapse of each of its
/// edges that is too short (the first end onto the second).
void sweep_all_operators(TetMesh& mesh, OperatorContext& context,
                         const EdgeRemovalOptions& edge_options = {})
{
    const int slots = mesh.num_tet_slots();
    for (int t = 0; t < slots; ++t)
    {
        if (mesh.is_dead(t)) continue;
        bool replaced = false;
        for (int e = 0; e < 6 && !replaced; ++e)
            replaced = remove_edge(mesh, context, t, e, edge_options).removed;
        for (int f = 0; f < 4 && !replaced; ++f)
            replaced = remove_multi_face(mesh, context, t, f).removed;
        if (replaced) continue;
        for (int v : TetVertices(mesh.tets[t]))
        {
            smooth_vertex(mesh, context, v);
            if (context.field != nullptr) equalize_edge_sizes(mesh, context, v);
        }
        for (int e = 0; e < 6 && !mesh.is_dead(t); ++e)
        {
            const int a = mesh.tets[t][tet::kEdgeVertices[e][0]];
            const int b = mesh.tets[t][tet::kEdgeVertices[e][1]];
            if (context.too_short(mesh.points[a], mesh.points[b]))
                collapse_edge(mesh, context, a, b);
        }
    }
}

}  // namespace

/*  The optimizer's caches (tet qualities per slot, recent vertex balls) must be invisible: the
    same sweep of every operator over the same jittered box, once with a plain context and once
    with the caches on, gives bitwise the same mesh. (A debug build also checks every cached
    quality and ball against a fresh one as it is served.)                                   */
TEST_CASE("operator context caches: the same operators give bitwise the same mesh")
{
    const TetMesh input = fixtures::box_mesh(4, 0.24, 7);
    const ConstantSize field(0.42);  // the axis edges (0.25) are too short: collapses happen
    TetMesh plain = input, cached = input;
    plain.build_adjacency();
    cached.build_adjacency();
    OperatorContext plain_context(plain, &field);
    OperatorContext cached_context(cached, &field);
    cached_context.enable_caches();

    for (int round = 0; round < 2; ++round)
    {
        sweep_all_operators(plain, plain_context);
        sweep_all_operators(cached, cached_context);
    }
    CHECK(plain.tets == cached.tets);
    CHECK(plain.points == cached.points);
    CHECK(plain.neighbors == cached.neighbors);
    CHECK(plain_context.touched == cached_context.touched);
    // the sweep did change the mesh (collapses and moves), and left it valid and whole
    CHECK(cached.num_live_tets() < input.num_live_tets());
    CHECK(cached.points != input.points);
    require_valid(cached);
    CHECK(cached.total_volume() == doctest::Approx(input.total_volume()).epsilon(1e-12));
    CHECK(boundary_signature(cached) == boundary_signature(input));
    for (int t = 0; t < cached.num_tet_slots(); ++t)
        if (!cached.is_dead(t)) CHECK(cached_context.quality(cached, t) == cached.quality(t));
}

/*  Edge removal with exact_worst_after = false prunes the ring program at the shell's worst:
    on every edge of a jittered box it removes exactly the same edges, with the same new tets
    and the same worst_after, as the exact program; a refusal reports -infinity.           */
TEST_CASE("edge removal: the pruned program removes the same edges as the exact one")
{
    TetMesh exact = fixtures::box_mesh(4, 0.24, 5);  // < 0.25: every tet starts positive
    exact.build_adjacency();
    TetMesh pruned = exact;
    OperatorContext exact_context(exact, nullptr), pruned_context(pruned, nullptr);
    EdgeRemovalOptions pruning;
    pruning.exact_worst_after = false;
    const double worst_before = live_worst(exact);
    long removed = 0, refused = 0;
    for (int t = 0; t < exact.num_tet_slots(); ++t)
        for (int e = 0; e < 6; ++e)
        {
            if (exact.is_dead(t)) break;
            const auto a = remove_edge(exact, exact_context, t, e);
            const auto b = remove_edge(pruned, pruned_context, t, e, pruning);
            REQUIRE(a.removed == b.removed);
            CHECK(a.worst_before == b.worst_before);
            if (a.removed)
            {
                ++removed;
                CHECK(a.worst_after == b.worst_after);
                CHECK(a.worst_after > a.worst_before);
            }
            else if (a.ring_size > 0 && a.worst_before > 0)
            {
                ++refused;
                CHECK(b.worst_after == -std::numeric_limits<double>::infinity());
            }
        }
    CHECK(removed > 0);
    CHECK(refused > 0);
    CHECK(exact.tets == pruned.tets);
    CHECK(exact.neighbors == pruned.neighbors);
    require_valid(pruned);
    CHECK(live_worst(pruned) >= worst_before);
}

TEST_CASE("constraints: a required triangle's vertices neither move nor slide, a rank's cut too")
{
    TetMesh mesh = fixtures::box_mesh(2);
    mesh.build_adjacency();
    std::vector<int> listed;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
        if (mesh.points[mesh.triangles[i][0]][2] == 0.0 &&
            mesh.points[mesh.triangles[i][1]][2] == 0.0 &&
            mesh.points[mesh.triangles[i][2]][2] == 0.0)
            listed.push_back(static_cast<int>(i));
    REQUIRE(listed.size() == 8);
    const MeshConstraints before(mesh);
    // (the middle of the bottom face is a flat surface vertex: a collapse may slide it)
    int middle = -1;
    for (int v = 0; v < mesh.num_vertices(); ++v)
        if (mesh.points[v] == Vec3(0.5, 0.5, 0.0)) middle = v;
    REQUIRE(middle >= 0);
    CHECK(before.is_surface_vertex(middle));
    for (int i : listed) mesh.triangle_refs[i] = kRankCutRef;
    mesh.required_triangles = listed;
    const MeshConstraints after(mesh);
    for (int i : listed)
        for (int v : mesh.triangles[i])
        {
            CHECK_FALSE(after.is_free_vertex(v));
            CHECK_FALSE(after.is_surface_vertex(v));
        }
}
