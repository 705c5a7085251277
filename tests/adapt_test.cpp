#include "coupling/adapt.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/check/quality_report.h"
#include "volume/io/tet_io.h"
#include "volume/size/size_fields.h"

using namespace hdimesh;

namespace
{

const TetMesh& sphere480()
{
    static const TetMesh mesh = read_mesh(fixtures::data_path("sphere480.mesh"));
    return mesh;
}

}  // namespace

TEST_CASE("refinement alone keeps the polyhedron: case A, no projection, no optimization")
{
    TetMesh mesh = sphere480();
    const double volume_before = mesh.total_volume();
    CHECK(volume_before == doctest::Approx(4.00715).epsilon(1e-5));
    coupling::AdaptOptions options;
    options.project = false;
    options.optimize = false;
    options.verbosity = 0;
    const BenchmarkSize field(benchmark_case('A'));
    const coupling::AdaptReport report = coupling::adapt(mesh, field, options);

    CHECK(report.converged);
    const auto violations = check_mesh(mesh);
    CHECK_MESSAGE(violations.empty(), format_violations(violations));
    CHECK(std::abs(mesh.total_volume() - volume_before) <= 1e-9 * volume_before);
    const QualityReport q = compute_quality_report(mesh, &field);
    CHECK(q.percent_too_long == 0.0);
    CHECK(q.min_qe > 0.0);
}

TEST_CASE("the whole pipeline on the sphere: boundary on the unit sphere, sizes and shapes met")
{
    TetMesh mesh = sphere480();
    coupling::AdaptOptions options;
    options.verbosity = 0;
    options.hausd = 0.01;  // a 0.2 chord strays 0.005 from the unit sphere: within the bound
    const ConstantSize field(0.2);
    const coupling::AdaptReport report = coupling::adapt(mesh, field, options);

    CHECK(report.converged);
    const auto violations = check_mesh(mesh);
    CHECK_MESSAGE(violations.empty(), format_violations(violations));
    const QualityReport q = compute_quality_report(mesh, &field);
    CHECK(q.percent_too_long == 0.0);
    CHECK(q.min_qe >= 0.3);
    CHECK(q.percent_qe_ge_05 >= 99.0);
    CHECK(q.percent_qt_ge_066 >= 99.0);
    // every boundary vertex was projected onto the HDI model of the input sphere
    CHECK(fixtures::max_unit_sphere_deviation(mesh) <= 1e-3);
    // the volume now approaches the sphere's 4/3 pi, beyond the inscribed polyhedron's
    CHECK(mesh.total_volume() > sphere480().total_volume());
}

TEST_CASE("adapt is deterministic: the same input gives bitwise the same mesh")
{
    const ConstantSize field(0.3);
    coupling::AdaptOptions options;
    options.verbosity = 0;
    TetMesh first = sphere480(), second = sphere480();
    coupling::adapt(first, field, options);
    coupling::adapt(second, field, options);
    REQUIRE(first.num_vertices() == second.num_vertices());
    REQUIRE(first.tets.size() == second.tets.size());
    CHECK(first.tets == second.tets);
    bool same_points = true;
    for (int v = 0; v < first.num_vertices(); ++v)
        same_points = same_points && first.points[v] == second.points[v];
    CHECK(same_points);
}

TEST_CASE("adapt's time split: CPU stages add up, refs and classes survive the renumbering")
{
    // adapt renumbers the mesh along a space-filling curve before the final optimization:
    // the boundary keeps its refs and every vertex of a boundary triangle keeps a boundary class
    TetMesh mesh = sphere480();
    coupling::AdaptOptions options;
    options.verbosity = 0;
    options.project = false;
    const ConstantSize field(0.3);
    const coupling::AdaptReport report = coupling::adapt(mesh, field, options);

    CHECK(report.converged);
    CHECK(report.cpu_seconds_total > 0.0);
    CHECK(report.cpu_seconds_refine > 0.0);
    CHECK(report.cpu_seconds_optimize > 0.0);
    const double stages =
        report.cpu_seconds_refine + report.cpu_seconds_project + report.cpu_seconds_optimize;
    CHECK(stages <= report.cpu_seconds_total * (1 + 1e-9) + 1e-6);
    CHECK(format_adapt_report(report).find("cpu:") != std::string::npos);

    const auto violations = check_mesh(mesh);
    CHECK_MESSAGE(violations.empty(), format_violations(violations));
    CHECK(std::abs(mesh.total_volume() - sphere480().total_volume()) <=
          1e-9 * sphere480().total_volume());
    std::vector<int> input_refs = sphere480().triangle_refs, output_refs = mesh.triangle_refs;
    std::sort(input_refs.begin(), input_refs.end());
    input_refs.erase(std::unique(input_refs.begin(), input_refs.end()), input_refs.end());
    std::sort(output_refs.begin(), output_refs.end());
    output_refs.erase(std::unique(output_refs.begin(), output_refs.end()), output_refs.end());
    CHECK(output_refs == input_refs);
    for (const auto& tri : mesh.triangles)
        for (int v : tri) CHECK(mesh.vertex_classes[v] != VertexClass::Interior);
    const QualityReport q = compute_quality_report(mesh, &field);
    CHECK(q.percent_too_long == 0.0);
    CHECK(q.min_qe >= 0.3);
}

TEST_CASE("required triangles come out of adapt bit for bit, still required")
{
    //   the box's bottom face (z = 0, 8 triangles) required; a size 0.12 refines the rest
    TetMesh mesh = fixtures::box_mesh(2);
    std::vector<std::array<Vec3, 3>> kept;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    {
        const auto& t = mesh.triangles[i];
        if (std::all_of(t.begin(), t.end(), [&](int v) { return mesh.points[v].z() == 0.0; }))
        {
            mesh.required_triangles.push_back(static_cast<int>(i));
            kept.push_back({mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]});
        }
    }
    REQUIRE(kept.size() == 8u);
    coupling::AdaptOptions options;
    options.verbosity = 0;
    const ConstantSize field(0.12);
    coupling::adapt(mesh, field, options);

    const auto violations = check_mesh(mesh);
    CHECK_MESSAGE(violations.empty(), format_violations(violations));
    REQUIRE(mesh.required_triangles.size() == kept.size());
    for (std::size_t k = 0; k < kept.size(); ++k)
    {
        const auto& t = mesh.triangles[mesh.required_triangles[k]];
        for (int c = 0; c < 3; ++c) CHECK(mesh.points[t[c]] == kept[k][c]);
    }
    CHECK(mesh.num_live_tets() > 1000);
}
