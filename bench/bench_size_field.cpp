// Size fields and the measures built on them, at scale: evaluations per second of the
// benchmark and background-mesh fields (inside and outside the mesh), then the time of the
// quality report, the mesh checker and the gradation on a jittered Kuhn box of about 4M tets.
//
//   bench_size_field [n]     n^3 cubes of 6 tets (default 88: 4.09M tets)
//
// Times are process CPU seconds (single-threaded code on a shared machine).

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>
#include <vector>

#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/check/quality_report.h"
#include "volume/mesh/tet_mesh.h"
#include "volume/size/size_fields.h"

using namespace hdimesh;

namespace
{

/// Process CPU seconds: the machine is shared, so wall time would measure the neighbours too.
struct CpuClock
{
    using time_point = std::clock_t;
    static time_point now() { return std::clock(); }
};

double seconds_since(std::clock_t start) { return double(std::clock() - start) / CLOCKS_PER_SEC; }

/// Evaluations per second of field over the points (the sum keeps the calls alive).
double evaluations_per_second(const SizeField& field, const std::vector<Vec3>& points,
                              double& checksum)
{
    const auto start = CpuClock::now();
    for (const Vec3& p : points) checksum += field.size(p);
    return points.size() / seconds_since(start);
}

}  // namespace

int main(int argc, char** argv)
{
    const int n = argc > 1 ? std::atoi(argv[1]) : 88;
    auto start = CpuClock::now();
    TetMesh mesh = fixtures::box_mesh(n, 0.2);
    std::printf(
        "mesh: %d^3 Kuhn cubes, %d tets, %d vertices, %zu boundary triangles (built in %.2f s)\n\n",
        n, mesh.num_live_tets(), mesh.num_vertices(), mesh.triangles.size(), seconds_since(start));

    std::mt19937 rng(7);
    std::uniform_real_distribution<double> inside(0.0, 1.0), around(-0.5, 1.5);
    const int samples = 1000000;
    std::vector<Vec3> inner, outer;
    for (int i = 0; i < samples; ++i) inner.emplace_back(inside(rng), inside(rng), inside(rng));
    while (static_cast<int>(outer.size()) < samples / 10)
    {
        const Vec3 p(around(rng), around(rng), around(rng));
        if (p.minCoeff() < 0 || p.maxCoeff() > 1) outer.push_back(p);
    }

    double checksum = 0.0;
    const BenchmarkSize benchmark(benchmark_case('A'));
    std::vector<double> sizes(mesh.num_vertices());
    for (int v = 0; v < mesh.num_vertices(); ++v) sizes[v] = benchmark.size(mesh.points[v]);
    start = CpuClock::now();
    const BackgroundMeshSize background(mesh, sizes);
    const double build_seconds = seconds_since(start);

    std::printf("%-40s %14s\n", "size field", "evals/CPU s");
    std::printf("%-40s %14.3g\n", "benchmark (case A)",
                evaluations_per_second(benchmark, inner, checksum));
    std::printf("%-40s %14.3g\n", "background mesh, random points inside",
                evaluations_per_second(background, inner, checksum));
    std::printf("%-40s %14.3g\n", "background mesh, points outside",
                evaluations_per_second(background, outer, checksum));
    std::printf("%-40s %14.2f s\n\n", "background mesh construction (CPU)", build_seconds);

    std::printf("%-40s %10s\n", "operation on the whole mesh", "CPU s");
    start = CpuClock::now();
    const QualityReport shape = compute_quality_report(mesh, nullptr);
    std::printf("%-40s %10.2f\n", "quality report, no field", seconds_since(start));
    start = CpuClock::now();
    const QualityReport with_benchmark = compute_quality_report(mesh, &benchmark);
    std::printf("%-40s %10.2f\n", "quality report, benchmark field", seconds_since(start));
    start = CpuClock::now();
    const QualityReport with_background = compute_quality_report(mesh, &background);
    std::printf("%-40s %10.2f\n", "quality report, background field", seconds_since(start));
    start = CpuClock::now();
    const auto violations = check_mesh(mesh);
    std::printf("%-40s %10.2f\n", "check_mesh", seconds_since(start));
    start = CpuClock::now();
    grade_vertex_sizes(mesh, sizes, 1.3);
    std::printf("%-40s %10.2f\n\n", "grade_vertex_sizes (hgrad 1.3)", seconds_since(start));

    std::printf(
        "edges %ld, min Qe %.4f, Qt >= 0.66: %.2f %% (benchmark) / %.2f %% (background), "
        "violations %zu\n",
        shape.edges, shape.min_qe, with_benchmark.percent_qt_ge_066,
        with_background.percent_qt_ge_066, violations.size());
    std::printf("(checksum %.6g)\n", checksum);
    return violations.empty() ? 0 : 1;
}
