// The optimization driver on jittered Kuhn boxes: the worst quality never drops, the boundary
// and the volume stay, the mesh comes back compact, valid and with its adjacency, too-short
// edges are collapsed without creating too-long ones, and the output is bitwise reproducible.

#include "volume/optimize/optimize.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <set>
#include <vector>

#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/mesh/tet_tables.h"
#include "volume/size/size_fields.h"

using namespace hdimesh;

namespace
{

void require_valid(const TetMesh& mesh)
{
    const auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    REQUIRE(violations.empty());
    REQUIRE(mesh.has_adjacency());
    REQUIRE(mesh.num_live_tets() == mesh.num_tet_slots());  // compact
}

std::vector<std::array<double, 9>> boundary_signature(const TetMesh& mesh)
{
    std::vector<std::array<double, 9>> result;
    for (auto tri : mesh.triangles)
    {
        std::sort(tri.begin(), tri.end(), [&](int a, int b) {
            const auto& pa = mesh.points[a];
            const auto& pb = mesh.points[b];
            return std::lexicographical_compare(pa.data(), pa.data() + 3, pb.data(), pb.data() + 3);
        });
        std::array<double, 9> key{};
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c) key[3 * k + c] = mesh.points[tri[k]][c];
        result.push_back(key);
    }
    std::sort(result.begin(), result.end());
    return result;
}

double worst(const TetMesh& mesh)
{
    double w = 1e300;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_dead(t)) w = std::min(w, mesh.quality(t));
    return w;
}

struct EdgeCounts
{
    long edges = 0, too_short = 0, too_long = 0;
};

EdgeCounts count_edges(const TetMesh& mesh, const SizeField& field)
{
    std::set<std::pair<int, int>> edges;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_dead(t))
            for (const auto& ev : tet::kEdgeVertices)
            {
                const int a = mesh.tets[t][ev[0]], b = mesh.tets[t][ev[1]];
                edges.insert({std::min(a, b), std::max(a, b)});
            }
    EdgeCounts counts;
    for (const auto& [a, b] : edges)
    {
        const Vec3& pa = mesh.points[a];
        const Vec3& pb = mesh.points[b];
        const double length = (pb - pa).norm(), target = edge_target_size(field, pa, pb);
        ++counts.edges;
        counts.too_short += is_too_short(length, target);
        counts.too_long += is_too_long(length, target);
    }
    return counts;
}

long successes(const OptimizeReport& report)
{
    long sum = 0;
    for (const auto& op : report.operators) sum += op.successes;
    return sum;
}

}  // namespace

TEST_CASE("improve_bad_elements: a strongly jittered box loses its worst tets")
{
    TetMesh mesh = fixtures::box_mesh(5, 0.24, 11);
    const ConstantSize field(0.2);
    const double before = worst(mesh);
    OptimizeOptions options;
    options.bad_quality = 0.45;  // the jitter keeps Qe above 0.3: call "bad" what is below 0.45
    REQUIRE(before < options.bad_quality);
    const double volume = mesh.total_volume();
    const auto boundary = boundary_signature(mesh);
    const long too_long_before = count_edges(mesh, field).too_long;

    const OptimizeReport report = improve_bad_elements(mesh, field, options);
    require_valid(mesh);
    CHECK(report.min_quality_before == doctest::Approx(before));
    CHECK(report.min_quality_after == doctest::Approx(worst(mesh)));
    CHECK(worst(mesh) > before);
    CHECK(successes(report) > 0);
    CHECK(report.sweeps >= 1);
    CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-12));
    CHECK(boundary_signature(mesh) == boundary);
    CHECK(count_edges(mesh, field).too_long <= too_long_before);
}

TEST_CASE("optimize_mesh: too-short edges collapse, nothing becomes too long, quality holds")
{
    // box edges are 0.2 (axes) to 0.35 (cube diagonals); h = 0.45 makes the axis edges short
    TetMesh mesh = fixtures::box_mesh(5, 0.15, 3);
    const ConstantSize field(0.45);
    const EdgeCounts counts_before = count_edges(mesh, field);
    REQUIRE(counts_before.too_short > 0);
    REQUIRE(counts_before.too_long == 0);
    const double volume = mesh.total_volume();
    const auto boundary = boundary_signature(mesh);
    const double before = worst(mesh);
    const int vertices_before = mesh.num_vertices();

    OptimizeOptions options;
    const OptimizeReport report = optimize_mesh(mesh, field, options);
    require_valid(mesh);
    const EdgeCounts counts_after = count_edges(mesh, field);
    CHECK(mesh.num_vertices() < vertices_before);
    CHECK(counts_after.too_short < counts_before.too_short);
    CHECK(counts_after.too_long == 0);
    CHECK(report.operators.size() >= 4);
    // a collapse may create tets down to collapse_min_quality; the worst is never below that
    CHECK(worst(mesh) >= std::min(before, options.collapse_min_quality));
    CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-12));
    CHECK(boundary_signature(mesh) == boundary);
    // every boundary vertex is still there, and still not interior
    for (const auto& tri : mesh.triangles)
        for (int v : tri) CHECK(mesh.vertex_classes[v] != VertexClass::Interior);
}

TEST_CASE("optimize_mesh without collapse never lowers the worst tet")
{
    TetMesh mesh = fixtures::box_mesh(4, 0.24, 5);
    const ConstantSize field(0.25);
    const double before = worst(mesh);
    OptimizeOptions options;
    options.collapse = false;
    optimize_mesh(mesh, field, options);
    require_valid(mesh);
    CHECK(worst(mesh) > before);
}

TEST_CASE("the switches turn operators off")
{
    TetMesh mesh = fixtures::box_mesh(4, 0.24, 5);
    const TetMesh original = mesh;
    const ConstantSize field(0.45);
    OptimizeOptions options;
    options.swap = options.move = options.collapse = options.split = false;
    const OptimizeReport report = optimize_mesh(mesh, field, options);
    CHECK(successes(report) == 0);
    CHECK(mesh.tets == original.tets);
    CHECK(mesh.points == original.points);

    options.swap = true;  // swaps only: vertices stay exactly where they were
    optimize_mesh(mesh, field, options);
    require_valid(mesh);
    CHECK(mesh.points == original.points);
}

/*  A tall octahedron, apexes (0,0,+-2), equator (+-1,0,0) (0,+-1,0), meshed as the four tets
    around its axis: every vertex on the boundary, every tet a needle with two boundary faces,
    so no vertex of them may move. Here the axis' removal would fix them too; with the swaps off
    only the last stage, the split of the axis, can.

            (0,0,2)
             /|\
            / | \         axis: the one interior edge
      (-1,0,0)-+-(1,0,0)
            \ | /
             \|/
            (0,0,-2)                                                                         */
TEST_CASE("optimize_mesh: a bad tet with no free vertex gets its interior edge split")
{
    TetMesh mesh = fixtures::mesh_from_tets(
        {{0, 0, -2}, {0, 0, 2}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}},
        {{0, 1, 2, 3}, {0, 1, 3, 4}, {0, 1, 4, 5}, {0, 1, 5, 2}});
    const ConstantSize field(2.0);  // nothing too long: refinement would not touch the axis
    const double volume = mesh.total_volume();
    const auto boundary = boundary_signature(mesh);
    const double before = worst(mesh);
    REQUIRE(before < 0.4);
    OptimizeOptions options;
    options.swap = false;

    SUBCASE("without the split nothing changes")
    {
        options.split = false;
        optimize_mesh(mesh, field, options);
        CHECK(worst(mesh) == before);
        CHECK(mesh.num_vertices() == 6);
    }
    SUBCASE("the split raises the worst tet")
    {
        const OptimizeReport report = optimize_mesh(mesh, field, options);
        CHECK(report.operators.back().name == "edge split");
        CHECK(report.operators.back().successes == 1);
        CHECK(mesh.num_vertices() == 7);
        CHECK(mesh.num_live_tets() == 8);
        CHECK(worst(mesh) > before + 0.15);
    }
    require_valid(mesh);
    CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-12));
    CHECK(boundary_signature(mesh) == boundary);
}

/*  A regular tet of edge 1 split by an interior point P just above the centre of face
    (v1 v2 v3) into four tets. No position of P gives a tet of Qe 0.5 (the centroid gives about
    0.45), while removing P gives back the regular tet: the sweep below 0.5 collapses P
    (none of its edges is too short for h = 0.8, so the short-edge collapse leaves it).

            v0
           /|\
          / | \
        v1--P--v3
            v2                                                                               */
TEST_CASE("improve sweep: a free vertex whose every position is worse than its removal goes")
{
    TetMesh base = fixtures::regular_tet();
    std::vector<Vec3> points = base.points;
    const Vec3 face_centre = (points[1] + points[2] + points[3]) / 3.0;
    points.push_back(face_centre + 0.3 * (points[0] - face_centre));
    std::vector<TetVertices> tets;
    for (int f = 0; f < 4; ++f)
    {
        TetVertices t = base.tets[0];
        t[f] = 4;  // P replaces the vertex opposite face f: positive, as P is inside
        tets.push_back(t);
    }
    TetMesh mesh = fixtures::mesh_from_tets(points, tets);
    const ConstantSize field(0.8);
    REQUIRE(count_edges(mesh, field).too_short == 0);
    const double volume = mesh.total_volume();
    const auto boundary = boundary_signature(mesh);
    OptimizeOptions options;
    options.bad_quality = 0.5;

    SUBCASE("without collapses P stays")
    {
        options.collapse = false;
        improve_bad_elements(mesh, field, options);
        CHECK(mesh.num_live_tets() == 4);
        CHECK(worst(mesh) < 0.5);
    }
    SUBCASE("with them P is removed and the regular tet comes back")
    {
        improve_bad_elements(mesh, field, options);
        CHECK(mesh.num_live_tets() == 1);
        CHECK(mesh.num_vertices() == 4);
        CHECK(worst(mesh) == doctest::Approx(1.0));
    }
    require_valid(mesh);
    CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-12));
    CHECK(boundary_signature(mesh) == boundary);
}

TEST_CASE("deterministic: the same input gives a bitwise identical output")
{
    const TetMesh input = fixtures::box_mesh(5, 0.2, 17);
    const ConstantSize field(0.4);
    TetMesh first = input, second = input;
    optimize_mesh(first, field);
    optimize_mesh(second, field);
    CHECK(first.tets == second.tets);
    CHECK(first.points == second.points);
    CHECK(first.neighbors == second.neighbors);
    improve_bad_elements(first, field);
    improve_bad_elements(second, field);
    CHECK(first.tets == second.tets);
    CHECK(first.points == second.points);
}
