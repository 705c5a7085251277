// The mesh checker: every violation kind provoked on a tiny mesh built here, and the clean
// fixtures accepted as they are. Also the boundary helpers the checker stands on.

#include "volume/check/check.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "fixtures.h"
#include "volume/check/boundary_repair.h"
#include "volume/mesh/boundary.h"
#include "volume/mesh/tet_tables.h"

using namespace hdimesh;

namespace
{

int count_kind(const std::vector<MeshViolation>& violations, const std::string& kind)
{
    return static_cast<int>(std::count_if(violations.begin(), violations.end(),
                                          [&](const MeshViolation& v) { return v.kind == kind; }));
}

bool has(const std::vector<MeshViolation>& violations, const std::string& kind, int element)
{
    return std::any_of(violations.begin(), violations.end(), [&](const MeshViolation& v) {
        return v.kind == kind && v.element == element;
    });
}

/// Adds tet v, swapping two vertices when it comes out negative.
int add_positive(TetMesh& mesh, TetVertices v, int ref = 0)
{
    const auto& p = mesh.points;
    if (signed_volume6(p[v[0]], p[v[1]], p[v[2]], p[v[3]]) < 0) std::swap(v[2], v[3]);
    return mesh.add_tet(v, ref);
}

/// The first interior tet face of a mesh with adjacency: (tet, local face, neighbour).
std::array<int, 3> some_interior_face(const TetMesh& mesh)
{
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        for (int f = 0; f < 4; ++f)
            if (mesh.neighbors[t][f] != kNoTet) return {t, f, mesh.neighbors[t][f]};
    return {-1, -1, -1};
}

/// A tet with no boundary face (box_mesh(3) has some around its centre).
int some_interior_tet(const TetMesh& mesh)
{
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (std::none_of(mesh.neighbors[t].begin(), mesh.neighbors[t].end(),
                         [](int n) { return n == kNoTet; }))
            return t;
    return -1;
}

}  // namespace

TEST_CASE("the clean fixtures pass the checker")
{
    for (const TetMesh& mesh :
         {fixtures::single_tet(), fixtures::regular_tet(), fixtures::kuhn_cube(),
          fixtures::box_mesh(3), fixtures::box_mesh(4, 0.2, 7)})
    {
        const auto violations = check_mesh(mesh);
        INFO(format_violations(violations));
        CHECK(violations.empty());
    }
    CHECK(format_violations({}) == "no violations\n");
}

TEST_CASE("a flipped tet: non-positive volume, overlapping faces, volume mismatch")
{
    // An interior tet of a 3x3x3 box listed with two vertices swapped: its volume is negative,
    // each of its faces is now listed the same way as by the neighbour across it, and the sum of
    // signed volumes falls short of the volume the (untouched) boundary encloses by 2|V|.
    TetMesh mesh = fixtures::box_mesh(3);
    const int t = some_interior_tet(mesh);
    REQUIRE(t >= 0);
    std::swap(mesh.tets[t][2], mesh.tets[t][3]);
    mesh.build_adjacency();
    const auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    CHECK(has(violations, "non_positive_volume", t));
    CHECK(count_kind(violations, "non_positive_volume") == 1);
    CHECK(count_kind(violations, "face_same_orientation") == 4);
    CHECK(count_kind(violations, "volume_mismatch") == 1);
    CHECK(count_kind(violations, "missing_boundary_triangle") == 0);
}

TEST_CASE("a degenerate tet is reported as non-positive")
{
    // four coplanar points: volume exactly 0
    TetMesh mesh;
    mesh.add_vertex({0, 0, 0});
    mesh.add_vertex({1, 0, 0});
    mesh.add_vertex({0, 1, 0});
    mesh.add_vertex({1, 1, 0});
    mesh.add_tet({0, 1, 2, 3});
    fixtures::rebuild_boundary(mesh);
    CHECK(has(check_mesh(mesh), "non_positive_volume", 0));
}

TEST_CASE("a broken adjacency link is stale on one side and asymmetric on the other")
{
    //   t --face f--> n      we cut t's link; n still points to t
    TetMesh mesh = fixtures::kuhn_cube();
    const auto [t, f, n] = some_interior_face(mesh);
    REQUIRE(t >= 0);
    mesh.neighbors[t][f] = kNoTet;
    auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    CHECK(has(violations, "adjacency_stale", t));
    CHECK(count_kind(violations, "adjacency_stale") == 1);
    CHECK(has(violations, "adjacency_asymmetric", n));
    CHECK(count_kind(violations, "adjacency_asymmetric") == 1);

    // a link to a tet that is not across that face: stale, and that tet does not link back
    mesh = fixtures::kuhn_cube();
    int stranger = -1;
    for (int u = 0; u < mesh.num_tet_slots(); ++u)
        if (u != t && std::find(mesh.neighbors[t].begin(), mesh.neighbors[t].end(), u) ==
                          mesh.neighbors[t].end())
            stranger = u;
    REQUIRE(stranger >= 0);
    mesh.neighbors[t][f] = stranger;
    violations = check_mesh(mesh);
    CHECK(has(violations, "adjacency_stale", t));
    CHECK(has(violations, "adjacency_asymmetric", t));

    // a link to a dead slot
    mesh = fixtures::kuhn_cube();
    mesh.neighbors[t][f] = 99;
    CHECK(has(check_mesh(mesh), "adjacency_asymmetric", t));
}

TEST_CASE("a missing boundary triangle leaves a hole: three open edges")
{
    //   the boundary of the 2x2x2 box without one triangle:
    //        +-----+
    //        |\ hole     each edge of the removed triangle now has a single
    //        | \   |     boundary triangle
    //        +-----+
    TetMesh mesh = fixtures::box_mesh(2);
    const Triangle removed = mesh.triangles.front();
    mesh.triangles.erase(mesh.triangles.begin());
    mesh.triangle_refs.erase(mesh.triangle_refs.begin());
    auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    CHECK(count_kind(violations, "missing_boundary_triangle") == 1);
    CHECK(count_kind(violations, "open_boundary_edge") == 3);
    CHECK(violations.size() == 4);
    CHECK(violations.front().message.find("not in the triangles") != std::string::npos);

    // an open surface is fine when a closed boundary is not required, the missing face is not
    CheckOptions open;
    open.require_closed_boundary = false;
    violations = check_mesh(mesh, open);
    CHECK(count_kind(violations, "open_boundary_edge") == 0);
    CHECK(count_kind(violations, "missing_boundary_triangle") == 1);

    // repair_boundary puts it back, outward
    CHECK(repair_boundary(mesh).added_boundary == 1);
    CHECK(check_mesh(mesh).empty());
    Triangle added = mesh.triangles.back();
    std::rotate(added.begin(), std::find(added.begin(), added.end(), removed[0]), added.end());
    CHECK(added == removed);
}

TEST_CASE("repair_boundary rebuilds a boundary from nothing")
{
    TetMesh mesh = fixtures::box_mesh(2, 0.2);
    mesh.triangles.clear();
    mesh.triangle_refs.clear();
    CHECK(count_kind(check_mesh(mesh), "missing_boundary_triangle") == 48);
    CHECK(repair_boundary(mesh).added_boundary == 48);
    CHECK(check_mesh(mesh).empty());
    CHECK_FALSE(repair_boundary(mesh).any());
}

TEST_CASE("an extra tet on the same side of a face: overlap")
{
    //        3                 tet A = (0,1,2,3); tet B = (0,1,2,4) with 4 inside A:
    //       /|\                both lie above the face (0,1,2) and list it the same way
    //      / 4 \ .
    //     0-----2
    //      \   /
    //        1
    TetMesh mesh = fixtures::single_tet();
    const int inner = mesh.add_vertex({0.2, 0.2, 0.2});
    const int b = add_positive(mesh, {0, 1, 2, inner});
    mesh.build_adjacency();
    const auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    CHECK(has(violations, "face_same_orientation", b));
    CHECK(count_kind(violations, "non_positive_volume") == 0);
}

TEST_CASE("a face shared by three tets")
{
    // The Kuhn cube's interior face gets a third tet, with its apex outside the cube.
    TetMesh mesh = fixtures::kuhn_cube();
    const auto [t, f, n] = some_interior_face(mesh);
    const auto& fv = tet::kFaceVertices[f];
    const int apex = mesh.add_vertex({2, 2, -1});
    const int third =
        add_positive(mesh, {mesh.tets[t][fv[0]], mesh.tets[t][fv[1]], mesh.tets[t][fv[2]], apex});
    mesh.build_adjacency();
    const auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    CHECK(count_kind(violations, "face_shared_by_more_than_two") == 1);
    CHECK(has(violations, "face_shared_by_more_than_two", std::min({t, n, third})));
}

TEST_CASE("a reversed boundary triangle: inward, and inconsistent with its neighbours")
{
    TetMesh mesh = fixtures::kuhn_cube();
    std::swap(mesh.triangles[3][1], mesh.triangles[3][2]);
    const auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    CHECK(has(violations, "boundary_triangle_reversed", 3));
    CHECK(count_kind(violations, "boundary_edge_same_direction") == 3);
}

TEST_CASE("triangles that are not boundary faces")
{
    TetMesh mesh = fixtures::kuhn_cube();
    const int extra = mesh.add_triangle({0, 1, 2}, 5);  // 0,1,2 are not the corners of one tet face
    mesh.add_triangle(mesh.triangles[0], 1);            // a duplicate
    const auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    CHECK(has(violations, "triangle_not_a_tet_face", extra));
    CHECK(count_kind(violations, "duplicate_triangle") == 1);
}

TEST_CASE("interior triangles: allowed between refs, reported inside one ref")
{
    //  two refs meet at the face between tets t and n: an interface triangle there is fine
    TetMesh mesh = fixtures::kuhn_cube();
    const auto [t, f, n] = some_interior_face(mesh);
    const auto& fv = tet::kFaceVertices[f];
    const int tri =
        mesh.add_triangle({mesh.tets[t][fv[0]], mesh.tets[t][fv[1]], mesh.tets[t][fv[2]]}, 9);
    auto violations = check_mesh(mesh);
    CHECK(has(violations, "interior_triangle", tri));
    CheckOptions lenient;
    lenient.allow_interior_triangles = true;
    CHECK(check_mesh(mesh, lenient).empty());
    mesh.tet_refs[n] = 2;
    violations = check_mesh(mesh);
    INFO(format_violations(violations));
    CHECK(violations.empty());
}

TEST_CASE("a pinched boundary: two tets sharing only a vertex")
{
    //        3   5          tets (0,1,2,3) and (0,4,5,6) meet at vertex 0 only:
    //        |  /           the link of 0 on the boundary is two triangles' worth of
    //   2----0----4         cycles, not one
    //       / |
    //      1   6
    TetMesh mesh;
    mesh.add_vertex({0, 0, 0});
    mesh.add_vertex({1, 0, 0});
    mesh.add_vertex({0, 1, 0});
    mesh.add_vertex({0, 0, 1});
    mesh.add_vertex({-1, 0, 0});
    mesh.add_vertex({0, -1, 0});
    mesh.add_vertex({0, 0, -1});
    add_positive(mesh, {0, 1, 2, 3});
    add_positive(mesh, {0, 4, 5, 6});
    fixtures::rebuild_boundary(mesh);
    const auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    CHECK(has(violations, "nonmanifold_boundary_vertex", 0));
    CHECK(violations.size() == 1);
}

TEST_CASE("a non-manifold boundary edge: two tets sharing only an edge")
{
    TetMesh mesh;
    mesh.add_vertex({0, 0, 0});
    mesh.add_vertex({1, 0, 0});
    mesh.add_vertex({0, 1, 0});
    mesh.add_vertex({0, 0, 1});
    mesh.add_vertex({0, -1, 0});
    mesh.add_vertex({0, 0, -1});
    add_positive(mesh, {0, 1, 2, 3});
    add_positive(mesh, {0, 1, 4, 5});
    fixtures::rebuild_boundary(mesh);
    const auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    CHECK(count_kind(violations, "nonmanifold_boundary_edge") == 1);
    CHECK(count_kind(violations, "volume_mismatch") == 0);
}

TEST_CASE("ids out of range, NaN coordinates and wrong array sizes")
{
    TetMesh mesh = fixtures::kuhn_cube();
    mesh.points[7].x() = std::numeric_limits<double>::quiet_NaN();
    mesh.add_triangle({0, 1, 42});
    mesh.tet_refs.pop_back();
    auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    CHECK(has(violations, "nan_coordinate", 7));
    CHECK(has(violations, "triangle_vertex_out_of_range",
              static_cast<int>(mesh.triangles.size()) - 1));
    CHECK(has(violations, "array_size", -1));

    mesh = fixtures::kuhn_cube();
    mesh.tets[2][1] = -5;
    mesh.edges.push_back({0, 100});
    mesh.edge_refs.push_back(0);
    mesh.corners.push_back(8);
    violations = check_mesh(mesh);
    CHECK(has(violations, "tet_vertex_out_of_range", 2));
    CHECK(has(violations, "edge_vertex_out_of_range", 0));
    CHECK(has(violations, "entity_index_out_of_range", -1));
}

TEST_CASE("dead tets are ignored, and a killed tet opens the boundary")
{
    TetMesh mesh = fixtures::box_mesh(2);
    mesh.kill_tet(0);
    auto violations = check_mesh(mesh);
    // the faces tet 0 shared are now boundary faces with no triangle; its stale links too
    CHECK(count_kind(violations, "missing_boundary_triangle") > 0);
    mesh.compact();
    fixtures::rebuild_boundary(mesh);
    violations = check_mesh(mesh);
    INFO(format_violations(violations));
    CHECK(violations.empty());
}

TEST_CASE("unused and coincident vertices")
{
    //  two separate Kuhn cubes side by side whose touching corners are distinct vertices at
    //  the same points: each cube alone is clean, together they hide a crack at x = 1
    TetMesh mesh = fixtures::kuhn_cube();
    const TetMesh right = fixtures::kuhn_cube();
    const int offset = mesh.num_vertices();
    for (const Vec3& p : right.points) mesh.add_vertex(p + Vec3(1, 0, 0));
    for (const auto& t : right.tets)
        mesh.add_tet({t[0] + offset, t[1] + offset, t[2] + offset, t[3] + offset});
    for (const auto& tri : right.triangles)
        mesh.add_triangle({tri[0] + offset, tri[1] + offset, tri[2] + offset}, 1);
    mesh.build_adjacency();
    auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    CHECK(count_kind(violations, "coincident_vertices") == 4);
    CHECK(violations.size() == 4);
    CheckOptions quiet;
    quiet.report_coincident_vertices = false;
    CHECK(check_mesh(mesh, quiet).empty());

    // an isolated vertex: reported only on request
    mesh = fixtures::kuhn_cube();
    const int lonely = mesh.add_vertex({5, 5, 5});
    CHECK(check_mesh(mesh).empty());
    CheckOptions strict;
    strict.report_unused_vertices = true;
    violations = check_mesh(mesh, strict);
    CHECK(has(violations, "unused_vertex", lonely));
    CHECK(violations.size() == 1);
}

TEST_CASE("format_violations: counts per kind, then the first lines")
{
    std::vector<MeshViolation> many;
    for (int i = 0; i < 30; ++i)
        many.push_back({"non_positive_volume", i, "tet " + std::to_string(i)});
    many.push_back({"volume_mismatch", -1, "sums differ"});
    const std::string text = format_violations(many, 5);
    CHECK(text.find("31 violations: non_positive_volume 30 volume_mismatch 1") == 0);
    CHECK(text.find("... and 26 more") != std::string::npos);
}

TEST_CASE("boundary helpers: faces, edges, enclosed volume on the jittered box")
{
    const TetMesh mesh = fixtures::box_mesh(3, 0.2, 3);
    const auto boundary = tet_boundary_faces(mesh);
    CHECK(boundary.size() == 6u * 9u * 2u);
    CHECK(enclosed_volume(mesh.points, boundary) == doctest::Approx(1.0).epsilon(1e-13));
    CHECK(mesh.total_volume() == doctest::Approx(1.0).epsilon(1e-13));
    // Kuhn subdivision of n^3 cubes: axis edges 3n(n+1)^2, one diagonal per square 3n^2(n+1),
    // one body diagonal per cube
    const int n = 3;
    const auto edges = unique_tet_edges(mesh);
    CHECK(edges.size() ==
          static_cast<std::size_t>(3 * n * (n + 1) * (n + 1) + 3 * n * n * (n + 1) + n * n * n));
    CHECK(std::is_sorted(edges.begin(), edges.end()));
    for (const auto& e : edges) CHECK(e[0] < e[1]);
    const FaceGroups groups = group_tet_faces(mesh);
    // Euler: V - E + F - T = 1 for a ball
    CHECK(mesh.num_vertices() - static_cast<int>(edges.size()) + groups.num_faces() -
              mesh.num_live_tets() ==
          1);
    const VertexGraph graph = vertex_graph(mesh);
    CHECK(graph.neighbors.size() == 2 * edges.size());
}
