// Size fields and the measures built on them, at scale: evaluations per second of the
// benchmark and background-mesh fields (inside and outside the mesh), then the time of the
// quality report, the mesh checker and the gradation on a jittered Kuhn box of about 4M tets.
//
//   bench_size_field [n]     n^3 cubes of 6 tets (default 88: 4.09M tets)
//
// Times are process CPU seconds (single-threaded code on a shared machine).

#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "volume/check.h"
#include "volume/quality_report.h"
#include "volume/size_fields.h"
#include "volume/tet_mesh.h"

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

/// [0,1]^3 as n^3 cubes of 6 Kuhn tets, interior vertices jittered by up to 0.2 cells.
TetMesh jittered_box(int n)
{
    TetMesh mesh;
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const double h = 1.0 / n;
    auto id = [n](int i, int j, int k) { return i + (n + 1) * (j + (n + 1) * k); };
    for (int k = 0; k <= n; ++k)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i)
            {
                Vec3 p(i * h, j * h, k * h);
                if (i > 0 && i < n && j > 0 && j < n && k > 0 && k < n)
                    p += 0.2 * h * Vec3(unit(rng), unit(rng), unit(rng));
                mesh.add_vertex(p);
            }
    const int kuhn[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
    mesh.tets.reserve(6L * n * n * n);
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                for (const auto& tet : kuhn)
                {
                    TetVertices v;
                    for (int c = 0; c < 4; ++c)
                        v[c] = id(i + (tet[c] & 1), j + ((tet[c] >> 1) & 1), k + ((tet[c] >> 2) & 1));
                    if (signed_volume6(mesh.points[v[0]], mesh.points[v[1]], mesh.points[v[2]], mesh.points[v[3]]) < 0)
                        std::swap(v[2], v[3]);
                    mesh.add_tet(v);
                }
    mesh.build_adjacency();
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        for (int f = 0; f < 4; ++f)
            if (mesh.neighbors[t][f] == kNoTet)
            {
                static constexpr int faces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
                mesh.add_triangle({mesh.tets[t][faces[f][0]], mesh.tets[t][faces[f][1]], mesh.tets[t][faces[f][2]]}, 1);
            }
    return mesh;
}

/// Evaluations per second of field over the points (the sum keeps the calls alive).
double evaluations_per_second(const SizeField& field, const std::vector<Vec3>& points, double& checksum)
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
    TetMesh mesh = jittered_box(n);
    std::printf("mesh: %d^3 Kuhn cubes, %d tets, %d vertices, %zu boundary triangles (built in %.2f s)\n\n", n,
                mesh.num_live_tets(), mesh.num_vertices(), mesh.triangles.size(), seconds_since(start));

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
    std::printf("%-40s %14.3g\n", "benchmark (case A)", evaluations_per_second(benchmark, inner, checksum));
    std::printf("%-40s %14.3g\n", "background mesh, random points inside",
                evaluations_per_second(background, inner, checksum));
    std::printf("%-40s %14.3g\n", "background mesh, points outside", evaluations_per_second(background, outer, checksum));
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

    std::printf("edges %ld, min Qe %.4f, Qt >= 0.66: %.2f %% (benchmark) / %.2f %% (background), violations %zu\n",
                shape.edges, shape.min_qe, with_benchmark.percent_qt_ge_066, with_background.percent_qt_ge_066,
                violations.size());
    std::printf("(checksum %.6g)\n", checksum);
    return violations.empty() ? 0 : 1;
}
