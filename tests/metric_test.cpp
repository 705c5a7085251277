// Anisotropic metrics (common/metric.h, volume/size/metric_fields.h): the file orders, the
// refusals of what is not a metric, lengths and quality in a metric, gradation, and adapt on a
// small box to a constant and a varying metric, the checker clean on every output.

#include "common/metric.h"

#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "common/errors.h"
#include "common/sol_io.h"
#include "coupling/adapt.h"
#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/io/tet_io.h"
#include "volume/mesh/geometry.h"
#include "volume/mesh/tet_tables.h"
#include "volume/size/metric_fields.h"
#include "volume/size/size_fields.h"
#include "volume/size/size_spec.h"

using namespace hdimesh;
using namespace hdimesh::volume;

namespace
{

const fixtures::ScratchDir& scratch()
{
    static const fixtures::ScratchDir dir("hdimesh_metric_test");
    return dir;
}

std::string write_text(const std::string& name, const std::string& text)
{
    const std::string path = scratch().file(name);
    std::ofstream(path) << text;
    return path;
}

/// A tensor .sol of n copies of the six values `m6`.
std::string tensor_sol(const std::string& name, int n, const std::string& m6)
{
    std::string text =
        "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n" + std::to_string(n) + "\n1 3\n";
    for (int v = 0; v < n; ++v) text += m6 + "\n";
    return write_text(name, text + "End\n");
}

Metric diagonal(double hx, double hy, double hz)
{
    return Vec3(1 / (hx * hx), 1 / (hy * hy), 1 / (hz * hz)).asDiagonal();
}

/// Share of the mesh's edges whose length in `field` lies in [1/√2, √2].
double share_in_unit_range(const TetMesh& mesh, const SizeField& field)
{
    long in = 0, all = 0;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t)) continue;
        for (const auto& e : tet::kEdgeVertices)
        {
            const EdgeInField edge = measure_edge(field, mesh.points[mesh.tets[t][e[0]]],
                                                  mesh.points[mesh.tets[t][e[1]]]);
            in += edge.in_field() >= std::sqrt(0.5) && edge.in_field() <= std::sqrt(2.0);
            ++all;
        }
    }
    return static_cast<double>(in) / all;
}

}  // namespace

TEST_CASE("metrics: Medit's order (m11 m12 m22 m13 m23 m33) and Gmsh's row-major nine")
{
    const double m6[6] = {1, 2, 3, 4, 5, 6};
    const Metric m = metric_from_medit(m6);
    CHECK(m(0, 0) == 1);
    CHECK(m(0, 1) == 2);
    CHECK(m(1, 1) == 3);
    CHECK(m(0, 2) == 4);
    CHECK(m(1, 2) == 5);
    CHECK(m(2, 2) == 6);
    CHECK(m == m.transpose());
    const auto back = metric_to_medit(m);
    for (int k = 0; k < 6; ++k) CHECK(back[k] == m6[k]);
    const double m9[9] = {1, 2, 4, 2, 3, 5, 4, 5, 6};
    std::string problem;
    CHECK(metric_from_row_major(m9, &problem) == m);
    CHECK(problem.empty());
    const double skew[9] = {1, 2, 4, 2.5, 3, 5, 4, 5, 6};
    metric_from_row_major(skew, &problem);
    CHECK(problem == "not symmetric");
}

TEST_CASE("metrics: NaN and indefinite matrices are no metric")
{
    CHECK(metric_problem(isotropic_metric(0.1)).empty());
    Metric nan = Metric::Identity();
    nan(1, 2) = nan(2, 1) = std::nan("");
    CHECK(metric_problem(nan) == "not finite");
    const double indefinite[6] = {1, 2, 1, 0, 0, 1};  // eigenvalues -1, 1, 3
    CHECK(metric_problem(metric_from_medit(indefinite)).find("not positive definite") == 0);
}

TEST_CASE("metrics: a tensor .sol is read as metrics, and bad ones are refused by vertex")
{
    const SolSizing ok = read_sol_sizing(tensor_sol("ok.sol", 3, "100 0 100 0 0 10000"), 3);
    CHECK(ok.sizes.empty());
    REQUIRE(ok.metrics.size() == 18);
    CHECK(ok.metrics[5] == 10000);
    // the second vertex's is indefinite
    std::string text =
        "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n2\n1 3\n1 0 1 0 0 1\n1 2 1 0 0 "
        "1\nEnd\n";
    CHECK_THROWS_WITH_AS(read_sol_sizing(write_text("indefinite.sol", text), 2),
                         doctest::Contains("the metric at vertex 2 is not positive definite"),
                         InputError);
    CHECK_THROWS_AS(read_sol_sizing(tensor_sol("nan.sol", 2, "1 0 nan 0 0 1"), 2), InputError);
    CHECK_THROWS_AS(read_sol_sizing(tensor_sol("count.sol", 2, "1 0 1 0 0 1"), 3), InputError);
    CHECK_THROWS_AS(read_sol_sizing(tensor_sol("short.sol", 2, "1 0 1 0 0"), 2), InputError);
    text = "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n1\n1 2\n1 0 0\nEnd\n";
    CHECK_THROWS_WITH_AS(read_sol_sizing(write_text("vector.sol", text), 1),
                         doctest::Contains("vector"), InputError);
    CHECK_THROWS_AS(metrics_from_medit({1, 0, 1, 0, 0}, 1, "array"), InputError);
}

TEST_CASE("metrics: lengths and quality; a tet regular in its metric has quality 1")
{
    const TetMesh regular = fixtures::regular_tet();
    const auto& t = regular.tets[0];
    const Vec3 a = regular.points[t[0]], b = regular.points[t[1]], c = regular.points[t[2]],
               d = regular.points[t[3]];
    const double edge = (b - a).norm();
    CHECK(metric_tet_quality(isotropic_metric(edge), a, b, c, d) ==
          doctest::Approx(tet_quality(a, b, c, d)));
    // stretched 100x along z: regular again in the metric that shrinks z by 100
    const Vec3 s(1, 1, 100);
    const Metric m = diagonal(1, 1, 100);
    CHECK(metric_tet_quality(m, a.cwiseProduct(s), b.cwiseProduct(s), c.cwiseProduct(s),
                             d.cwiseProduct(s)) == doctest::Approx(1.0).epsilon(1e-9));
    CHECK(mmg_tet_quality(m / (edge * edge), a.cwiseProduct(s), b.cwiseProduct(s),
                          c.cwiseProduct(s),
                          d.cwiseProduct(s)) == doctest::Approx(1.0).epsilon(1e-9));
    CHECK(metric_length(m, Vec3(0, 0, 100)) == doctest::Approx(1.0));
    // the sizes; bounds and intersection act on them direction by direction
    const Metric sized = diagonal(0.1, 0.5, 2.0);
    const Vec3 sizes = metric_sizes(sized);
    CHECK(sizes[0] == doctest::Approx(0.1));
    CHECK(sizes[2] == doctest::Approx(2.0));
    const Vec3 bounded = metric_sizes(bound_metric(sized, 0.2, 1.0));
    CHECK(bounded[0] == doctest::Approx(0.2));
    CHECK(bounded[1] == doctest::Approx(0.5));
    CHECK(bounded[2] == doctest::Approx(1.0));
    const Metric both = intersect_metrics(diagonal(0.1, 1, 1), diagonal(1, 0.2, 1));
    CHECK(both.isApprox(diagonal(0.1, 0.2, 1), 1e-12));
    CHECK(metric_exp(metric_log(sized)).isApprox(sized, 1e-12));
}

TEST_CASE("metrics: an isotropic metric measures as the size it is, and grades as sizes do")
{
    TetMesh mesh = fixtures::box_mesh(3);
    std::vector<double> sizes;
    std::vector<Metric> metrics;
    for (const Vec3& p : mesh.points)
    {
        sizes.push_back(0.05 + 0.5 * p.x());
        metrics.push_back(isotropic_metric(sizes.back()));
    }
    const BackgroundMeshMetric field(mesh, metrics);
    CHECK(field.anisotropic());
    // at a vertex the metric is the vertex's
    CHECK(field.metric(mesh.points[5]).isApprox(metrics[5], 1e-9));
    const Vec3 a(0.1, 0.2, 0.3), b(0.3, 0.25, 0.35);
    const Metric mid = field.metric(0.5 * (a + b));
    CHECK(measure_edge(field, a, b).in_field() == doctest::Approx(metric_length(mid, b - a)));
    std::vector<double> graded_sizes = sizes;
    grade_vertex_sizes(mesh, graded_sizes, 1.3);
    grade_vertex_metrics(mesh, metrics, 1.3);
    for (std::size_t v = 0; v < sizes.size(); ++v)
        CHECK(metric_sizes(metrics[v])[0] == doctest::Approx(graded_sizes[v]).epsilon(1e-6));
}

TEST_CASE("metrics: make_size_field reads vertex metrics; hgrad and hmin/hmax act on them")
{
    const TetMesh mesh = fixtures::box_mesh(2);
    SizeSpec spec;
    for (int v = 0; v < mesh.num_vertices(); ++v)
        for (double x : {400.0, 0.0, 4.0, 0.0, 0.0, 4.0}) spec.vertex_metrics.push_back(x);
    spec.hmin = 0.1;
    const auto field = make_size_field(spec, mesh);
    REQUIRE(field->anisotropic());
    CHECK(metric_sizes(field->metric(Vec3(0.5, 0.5, 0.5)))[0] == doctest::Approx(0.1));
    spec.hsiz = 0.3;
    CHECK_THROWS_AS(make_size_field(spec, mesh), InputError);
    spec.hsiz = 0;
    spec.vertex_metrics[1] = std::nan("");
    CHECK_THROWS_AS(make_size_field(spec, mesh), InputError);
    spec.vertex_metrics.pop_back();
    CHECK_THROWS_AS(make_size_field(spec, mesh), InputError);
}

TEST_CASE("metrics: adapt to a constant anisotropic metric stretches the tets along it")
{
    TetMesh mesh = fixtures::box_mesh(2);
    const FunctionMetric field([](const Vec3&) { return diagonal(0.5, 0.5, 0.05); });
    coupling::AdaptOptions options;
    coupling::adapt(mesh, field, options);
    CHECK(check_mesh(mesh).empty());
    CHECK(mesh.total_volume() == doctest::Approx(1.0).epsilon(0.01));
    CHECK(share_in_unit_range(mesh, field) > 0.5);
    // the edges are short across z and long along x, y: the mean extents tell
    double along = 0, across = 0;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t)) continue;
        for (const auto& e : tet::kEdgeVertices)
        {
            const Vec3 d = mesh.points[mesh.tets[t][e[1]]] - mesh.points[mesh.tets[t][e[0]]];
            along += std::abs(d.x()) + std::abs(d.y());
            across += 2 * std::abs(d.z());
        }
    }
    CHECK(along > 4 * across);
}

TEST_CASE("metrics: adapt to a layer metric, then OUT's metric is the field at its vertices")
{
    TetMesh mesh = fixtures::box_mesh(3);
    const FunctionMetric field([](const Vec3& p) {
        const double hz = 0.02 + 0.3 * std::abs(p.z() - 0.5);
        return diagonal(0.25, 0.25, hz);
    });
    coupling::adapt(mesh, field, {});
    CHECK(check_mesh(mesh).empty());
    CHECK(share_in_unit_range(mesh, field) > 0.6);
    const Solutions out = field_at_vertices(mesh, field);
    REQUIRE(out.solutions.size() == 1);
    CHECK(out.solutions[0].type == SolType::Tensor);
    CHECK(out.solutions[0].values.size() == 6u * mesh.num_vertices());
    const Metric first = metric_from_medit(out.solutions[0].values.data());
    CHECK(first.isApprox(field.metric(mesh.points[0]), 1e-12));
}

TEST_CASE("metrics: a Gmsh $NodeData of 9 components is a metric, row-major and symmetric")
{
    const TetMesh mesh = fixtures::box_mesh(1);
    const int n = mesh.num_vertices();
    WriteOptions options;
    PointField metric{"metric", 9, {}};
    for (int v = 0; v < n; ++v)
        for (double x : {100.0, 1.0, 2.0, 1.0, 50.0, 3.0, 2.0, 3.0, 400.0})
            metric.values.push_back(x + v);
    options.point_fields = {metric};
    const std::string path = scratch().file("metric.msh");
    write_mesh(mesh, path, options);
    const SolSizing sizing = read_vertex_sizing(path, mesh);
    REQUIRE(sizing.metrics.size() == 6u * n);
    const Metric last = metric_from_medit(&sizing.metrics[6 * (n - 1)]);
    CHECK(last(0, 0) == 100.0 + n - 1);
    CHECK(last(1, 2) == 3.0 + n - 1);
    CHECK(last(2, 2) == 400.0 + n - 1);
    metric.values[9 * 2 + 1] += 0.5;  // m12 != m21 at vertex 3
    options.point_fields = {metric};
    write_mesh(mesh, path, options);
    CHECK_THROWS_WITH_AS(read_vertex_sizing(path, mesh),
                         doctest::Contains("the metric at vertex 3 is not symmetric"), InputError);
    options.point_fields = {PointField{"vector", 3, std::vector<double>(3 * n, 1.0)}};
    write_mesh(mesh, path, options);
    CHECK_THROWS_AS(read_vertex_sizing(path, mesh), InputError);
}
