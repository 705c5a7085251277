// Size fields: constant, the paper's benchmark cylinders against hand values and the reference
// checker, the background mesh reproducing linear functions, clamping and gradation.

#include "volume/size/size_fields.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <thread>
#include <vector>

#include "common/errors.h"
#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/mesh/boundary.h"
#include "volume/size/size_spec.h"

using namespace hdimesh;

namespace
{

double linear(const Vec3& p) { return 0.1 + 0.2 * p.x() + 0.3 * p.y() + 0.4 * p.z(); }

std::vector<double> linear_sizes(const TetMesh& mesh)
{
    std::vector<double> sizes;
    for (const Vec3& p : mesh.points) sizes.push_back(linear(p));
    return sizes;
}

}  // namespace

TEST_CASE("constant size")
{
    const ConstantSize field(0.25);
    CHECK(field.size({0, 0, 0}) == 0.25);
    CHECK(field.size({-7, 3, 1e9}) == 0.25);
    CHECK_THROWS_AS(ConstantSize(0.0), InputError);
    CHECK_THROWS_AS(ConstantSize(-1.0), InputError);
    CHECK_THROWS_AS(ConstantSize(std::nan("")), InputError);
}

TEST_CASE("benchmark cases by name")
{
    const auto a = benchmark_case('A');
    CHECK(a.dmin == 0.03);
    CHECK(a.r == 0.03);
    CHECK(a.dmax == doctest::Approx(1.0 / 3));
    CHECK(a.R == 1.0);
    CHECK(benchmark_case('e').r == 0.7);
    CHECK(benchmark_case('D').dmin == 0.01);
    CHECK_THROWS_AS(benchmark_case('F'), InputError);
    CHECK_THROWS_AS(BenchmarkSize({0.5, 0.1, 0.1, 1.0}), InputError);  // dmin > dmax
    CHECK_THROWS_AS(BenchmarkSize({0.01, -0.1}), InputError);
}

TEST_CASE("benchmark field: hand values of case A")
{
    // dmin = 0.03, r = 0.03, dmax = 1/3, R = 1; h_c = (1 - d) dmin + d dmax with d = |rho - r|
    const BenchmarkSize field(benchmark_case('A'));
    // origin: every axis at distance 0, d = 0.03: 0.97 * 0.03 + 0.03 / 3 = 0.0391
    CHECK(field.size({0, 0, 0}) == doctest::Approx(0.0391).epsilon(1e-14));
    // on the x cylinder's surface (rho_x = r): d = 0, h = dmin
    CHECK(field.size({0, 0.03, 0}) == doctest::Approx(0.03).epsilon(1e-14));
    CHECK(field.size({0.5, 0, -0.03}) == doctest::Approx(0.03).epsilon(1e-14));
    // (0.5, 0.5, 0): rho = 0.5 for the x and y axes, d = 0.47: 0.53 * 0.03 + 0.47 / 3
    CHECK(field.size({0.5, 0.5, 0}) == doctest::Approx(0.0159 + 0.47 / 3).epsilon(1e-14));
    // far from every axis: clamped to dmax
    CHECK(field.size({0.9, 0.9, 0.9}) == doctest::Approx(1.0 / 3).epsilon(1e-14));
}

TEST_CASE("benchmark field: equal to ../shared/tools/meshstat.py size_field for all cases")
{
    // Reference values printed by the independent checker's size_field() (numpy), once.
    const std::vector<Vec3> points = {{0, 0, 0},         {0, 0.03, 0},      {0.5, 0.5, 0},
                                      {0.9, 0.9, 0.9},   {0.1, -0.2, 0.35}, {-0.7, 0.05, 0.02},
                                      {0.3, 0.31, -0.05}};
    const std::vector<std::pair<char, std::vector<double>>> expected = {
        {'A',
         {0.039099999999999996, 0.03, 0.17256666666666665, 0.3333333333333333, 0.08872739531749363,
          0.03723499991497466, 0.11315523170952299}},
        {'B',
         {0.013233333333333333, 0.013233333333333333, 0.16843333333333332, 0.3333333333333333,
          0.07906619793915987, 0.024178699543068234, 0.10510466090648787}},
        {'C',
         {0.121, 0.1119, 0.09066666666666667, 0.3250803025278549, 0.04941499998742118,
          0.10466500008502533, 0.03125523170952299}},
        {'D',
         {0.10699999999999998, 0.0973, 0.07466666666666666, 0.3245361466505706, 0.0306951098767017,
          0.08958796712359843, 0.011337994239821214}},
        {'E',
         {0.2363333333333333, 0.2266333333333333, 0.012297859250317062, 0.19520281331723732,
          0.1059934997358401, 0.010092362106816634, 0.09684956685453797}},
    };
    for (const auto& [name, values] : expected)
    {
        const BenchmarkSize field(benchmark_case(name));
        for (std::size_t i = 0; i < points.size(); ++i)
        {
            INFO("case " << name << " point " << i);
            CHECK(field.size(points[i]) == doctest::Approx(values[i]).epsilon(1e-14));
        }
    }
}

TEST_CASE("background mesh reproduces a linear function exactly inside")
{
    const TetMesh mesh = fixtures::box_mesh(4, 0.2, 11);
    REQUIRE(check_mesh(mesh).empty());
    const BackgroundMeshSize field(mesh, linear_sizes(mesh));
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < 2000; ++i)
    {
        const Vec3 p(unit(rng), unit(rng), unit(rng));
        CHECK(field.size(p) == doctest::Approx(linear(p)).epsilon(1e-12));
        const auto location = field.locator().locate(p);
        REQUIRE(location.has_value());
        CHECK(*std::min_element(location->weights.begin(), location->weights.end()) >= -1e-12);
        CHECK(mesh.tets[location->tet] == location->vertices);
    }
    // at the vertices, the given sizes
    for (int v = 0; v < mesh.num_vertices(); ++v)
        CHECK(field.size(mesh.points[v]) == doctest::Approx(linear(mesh.points[v])).epsilon(1e-12));
}

TEST_CASE("background mesh outside: the size at the nearest boundary point")
{
    // The unit box; a point beyond a face takes the value at its projection on the face, a
    // point beyond a corner the corner's value (linear data, planar faces: exact).
    const TetMesh mesh = fixtures::box_mesh(3, 0.2, 2);
    const BackgroundMeshSize field(mesh, linear_sizes(mesh));
    CHECK_FALSE(field.locator().locate({1.5, 0.4, 0.3}).has_value());
    CHECK(field.size({1.5, 0.4, 0.3}) == doctest::Approx(linear({1.0, 0.4, 0.3})).epsilon(1e-12));
    CHECK(field.size({0.2, -3.0, 0.7}) == doctest::Approx(linear({0.2, 0.0, 0.7})).epsilon(1e-12));
    CHECK(field.size({2, 2, 2}) == doctest::Approx(linear({1, 1, 1})).epsilon(1e-12));
    CHECK(field.size({-1, -1, -1}) == doctest::Approx(linear({0, 0, 0})).epsilon(1e-12));
    const BoundaryPoint q = field.locator().nearest_boundary_point({0.5, 0.5, 1.25});
    CHECK(q.distance == doctest::Approx(0.25));
    CHECK((q.point - Vec3(0.5, 0.5, 1.0)).norm() < 1e-12);
}

TEST_CASE("nearest boundary point: never farther than the nearest boundary vertex")
{
    // brute force over every boundary vertex and triangle: the grid search must find a point
    // at most as far as the nearest boundary vertex and no nearer than the true nearest point
    const TetMesh mesh = fixtures::box_mesh(4, 0.2, 6);
    const TetLocator locator(mesh);
    const auto boundary = tet_boundary_faces(mesh);
    std::mt19937 rng(12);
    std::uniform_real_distribution<double> range(-2.0, 3.0);
    for (int i = 0; i < 500; ++i)
    {
        const Vec3 p(range(rng), range(rng), range(rng));
        double nearest_vertex = 1e300, nearest_point = 1e300;
        for (const auto& tri : boundary)
            for (int v : tri)
                nearest_vertex = std::min(nearest_vertex, (mesh.points[v] - p).norm());
        // the nearest point of the box [0,1]^3 (its boundary is planar, whatever the jitter inside)
        const Vec3 clamped = p.cwiseMax(Vec3::Zero()).cwiseMin(Vec3::Ones());
        nearest_point = (clamped - p).norm();
        const BoundaryPoint q = locator.nearest_boundary_point(p);
        if (nearest_point == 0.0) continue;  // inside: not this function's case
        CHECK(q.distance <= nearest_vertex * (1 + 1e-12));
        CHECK(q.distance >= nearest_point * (1 - 1e-12));
        CHECK((q.point - p).norm() == doctest::Approx(q.distance));
        const double weight_sum = q.weights[0] + q.weights[1] + q.weights[2];
        CHECK(weight_sum == doctest::Approx(1.0));
    }
}

TEST_CASE("background mesh on a non-convex domain (an L-shaped notch)")
{
    //   y                the box [0,1]^3 (4^3 cubes) without the cubes of x > 0.5, y > 0.5:
    //   1 +----+         walks that start near the notch must go around it
    //     |    |
    // 0.5 |    +----+
    //     |         |
    //   0 +---------+ x
    TetMesh mesh = fixtures::box_mesh(4, 0.0);
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        const auto& v = mesh.tets[t];
        const Vec3 c =
            0.25 * (mesh.points[v[0]] + mesh.points[v[1]] + mesh.points[v[2]] + mesh.points[v[3]]);
        if (c.x() > 0.5 && c.y() > 0.5) mesh.kill_tet(t);
    }
    mesh.compact();
    fixtures::rebuild_boundary(mesh);
    REQUIRE(check_mesh(mesh).empty());
    const BackgroundMeshSize field(mesh, linear_sizes(mesh));
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int inside = 0;
    for (int i = 0; i < 3000; ++i)
    {
        const Vec3 p(unit(rng), unit(rng), unit(rng));
        if (p.x() > 0.5 && p.y() > 0.5) continue;
        ++inside;
        REQUIRE(field.locator().locate(p).has_value());
        CHECK(field.size(p) == doctest::Approx(linear(p)).epsilon(1e-12));
    }
    CHECK(inside > 2000);
    // in the notch, nearer the x = 0.5 wall than the y = 0.5 wall
    CHECK_FALSE(field.locator().locate({0.6, 0.8, 0.5}).has_value());
    CHECK(field.size({0.6, 0.8, 0.5}) == doctest::Approx(linear({0.5, 0.8, 0.5})).epsilon(1e-12));
}

TEST_CASE("background mesh: queries from several threads agree with one thread")
{
    const TetMesh mesh = fixtures::box_mesh(4, 0.2, 4);
    const BackgroundMeshSize field(mesh, linear_sizes(mesh));
    std::vector<Vec3> points;
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> range(-0.3, 1.3);
    for (int i = 0; i < 4000; ++i) points.emplace_back(range(rng), range(rng), range(rng));
    std::vector<double> serial(points.size()), parallel(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) serial[i] = field.size(points[i]);
    std::vector<std::thread> threads;
    for (int k = 0; k < 4; ++k)
        threads.emplace_back([&, k] {
            for (std::size_t i = k; i < points.size(); i += 4) parallel[i] = field.size(points[i]);
        });
    for (auto& thread : threads) thread.join();
    CHECK(serial == parallel);
}

TEST_CASE("background mesh: independent of the mesh it was built from")
{
    TetMesh mesh = fixtures::box_mesh(2);
    const BackgroundMeshSize field(mesh, linear_sizes(mesh));
    mesh.points.assign(mesh.points.size(), Vec3(5, 5, 5));
    mesh.tets.clear();
    CHECK(field.size({0.3, 0.2, 0.1}) == doctest::Approx(linear({0.3, 0.2, 0.1})).epsilon(1e-12));
}

TEST_CASE("background mesh: a field built where another was answers with its own sizes")
{
    // size() remembers recent answers per thread, keyed by the field: a new field in the same
    // storage, asked the same point, must not get the old field's answer.
    const TetMesh mesh = fixtures::box_mesh(2);
    const Vec3 p(0.3, 0.2, 0.1);
    std::optional<BackgroundMeshSize> field;
    field.emplace(mesh, linear_sizes(mesh));
    const double first = field->size(p);
    CHECK(field->size(p) == first);  // asked again: the remembered answer, the same value
    field.reset();
    field.emplace(mesh, std::vector<double>(mesh.num_vertices(), 2.0));
    CHECK(field->size(p) == doctest::Approx(2.0).epsilon(1e-12));
}

TEST_CASE("background mesh: bad input is an InputError naming what is wrong")
{
    const TetMesh mesh = fixtures::box_mesh(2);
    std::vector<double> sizes = linear_sizes(mesh);
    sizes.pop_back();
    CHECK_THROWS_AS(BackgroundMeshSize(mesh, sizes), InputError);
    sizes = linear_sizes(mesh);
    sizes[4] = -1.0;
    CHECK_THROWS_WITH_AS(BackgroundMeshSize(mesh, sizes), doctest::Contains("vertex 4"),
                         InputError);
    CHECK_THROWS_AS(BackgroundMeshSize(TetMesh{}, {}), InputError);
    TetMesh flipped = fixtures::single_tet();
    std::swap(flipped.tets[0][0], flipped.tets[0][1]);
    CHECK_THROWS_WITH_AS(BackgroundMeshSize(flipped, {1, 1, 1, 1}), doctest::Contains("tet 0"),
                         InputError);
}

TEST_CASE("clamped size")
{
    auto inner = std::make_shared<BenchmarkSize>(benchmark_case('A'));
    const ClampedSize clamped(inner, 0.05, 0.2);
    CHECK(clamped.size({0, 0.03, 0}) == 0.05);                         // 0.03 raised to hmin
    CHECK(clamped.size({0.9, 0.9, 0.9}) == 0.2);                       // 1/3 lowered to hmax
    CHECK(clamped.size({0.5, 0.5, 0}) == inner->size({0.5, 0.5, 0}));  // 0.1726 kept
    CHECK_THROWS_AS(ClampedSize(inner, 0.3, 0.2), InputError);
    CHECK_THROWS_AS(ClampedSize(nullptr, 0.1, 0.2), InputError);
}

TEST_CASE("gradation bounds every edge's size ratio")
{
    // random sizes over two decades on a jittered box: after grading with hgrad, every edge
    // (i, j) has h_j <= h_i + (hgrad - 1) |x_i - x_j|, no size grew, the smallest stayed
    const TetMesh mesh = fixtures::box_mesh(5, 0.2, 8);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> exponent(-2.0, 0.0);
    std::vector<double> sizes(mesh.num_vertices());
    for (double& h : sizes) h = std::pow(10.0, exponent(rng));
    const std::vector<double> original = sizes;
    const double hgrad = 1.3;
    grade_vertex_sizes(mesh, sizes, hgrad);

    int lowered = 0;
    for (int v = 0; v < mesh.num_vertices(); ++v)
    {
        CHECK(sizes[v] <= original[v]);
        CHECK(sizes[v] > 0.0);
        lowered += sizes[v] < original[v];
    }
    CHECK(lowered > 0);
    const int smallest =
        static_cast<int>(std::min_element(original.begin(), original.end()) - original.begin());
    CHECK(sizes[smallest] == original[smallest]);
    for (const auto& e : unique_tet_edges(mesh))
    {
        const double length = (mesh.points[e[0]] - mesh.points[e[1]]).norm();
        CHECK(sizes[e[1]] <= sizes[e[0]] + (hgrad - 1) * length * (1 + 1e-12));
        CHECK(sizes[e[0]] <= sizes[e[1]] + (hgrad - 1) * length * (1 + 1e-12));
    }
    // a fixed point: grading again changes nothing
    std::vector<double> again = sizes;
    grade_vertex_sizes(mesh, again, hgrad);
    CHECK(again == sizes);
    // the largest sizes that satisfy the bound: some edge is tight at every lowered vertex
    const VertexGraph graph = vertex_graph(mesh);
    for (int v = 0; v < mesh.num_vertices(); ++v)
    {
        if (sizes[v] == original[v]) continue;
        bool tight = false;
        for (int n = graph.start[v]; n < graph.start[v + 1]; ++n)
        {
            const int w = graph.neighbors[n];
            const double length = (mesh.points[w] - mesh.points[v]).norm();
            tight |= std::abs(sizes[w] + (hgrad - 1) * length - sizes[v]) < 1e-12;
        }
        CHECK(tight);
    }
}

TEST_CASE("gradation leaves graded sizes alone and checks its input")
{
    const TetMesh mesh = fixtures::box_mesh(3);
    std::vector<double> sizes = linear_sizes(mesh);  // slope 0.54 per unit length < hgrad - 1
    const std::vector<double> original = sizes;
    grade_vertex_sizes(mesh, sizes, 1.6);
    CHECK(sizes == original);
    // hgrad = 1: every vertex of the connected mesh takes the global minimum
    grade_vertex_sizes(mesh, sizes, 1.0);
    for (double h : sizes) CHECK(h == doctest::Approx(0.1));
    CHECK_THROWS_AS(grade_vertex_sizes(mesh, sizes, 0.5), InputError);
    std::vector<double> short_list(3, 1.0);
    CHECK_THROWS_AS(grade_vertex_sizes(mesh, short_list, 1.3), InputError);
}

TEST_CASE("sample_vertex_sizes")
{
    const TetMesh mesh = fixtures::box_mesh(2);
    const auto sizes = sample_vertex_sizes(mesh, BenchmarkSize(benchmark_case('C')));
    REQUIRE(sizes.size() == mesh.points.size());
    CHECK(sizes[13] == BenchmarkSize(benchmark_case('C')).size(mesh.points[13]));
}

TEST_CASE("size spec: the options as the apps and Python give them")
{
    const TetMesh mesh = fixtures::box_mesh(2, 0.0, 1);
    SizeSpec spec;
    spec.vertex_sizes = linear_sizes(mesh);
    const auto field = make_size_field(spec, mesh);
    for (const Vec3& p : mesh.points) CHECK(field->size(p) == doctest::Approx(linear(p)));
    spec.hmax = 0.3;  // a clamp over the vertex sizes
    CHECK(make_size_field(spec, mesh)->size(Vec3(1, 1, 1)) == doctest::Approx(0.3));
    spec.hsiz = 0.2;
    CHECK_THROWS_WITH_AS(make_size_field(spec, mesh), doctest::Contains("only one of"), InputError);
    SizeSpec wrong_count;
    wrong_count.vertex_sizes = {0.1, 0.2};
    CHECK_THROWS_WITH_AS(make_size_field(wrong_count, mesh), doctest::Contains("2 vertex sizes"),
                         InputError);
    SizeSpec gentle;
    gentle.hsiz = 0.2;
    gentle.hgrad = 0.9;
    CHECK_THROWS_WITH_AS(make_size_field(gentle, mesh), doctest::Contains("hgrad"), InputError);
    SizeSpec none;  // the input's own sizes: its mean edge length about each vertex
    CHECK(make_size_field(none, mesh)->size(mesh.points[0]) > 0);
}
