// The paper's Table 3 for our runs: data/sphere480.mesh adapted to the three-cylinder field,
// cases A-E, whole pipeline (refine, project, optimize), Release, one thread unless asked.
//
//   bench_adapt [--cases ACE] [--no-projection] [--no-optimize] [--verbose] [--threads N]
//
// --verbose prints the optimizer's per-sweep tables (operators, attempts, successes, time).
//
// Prints one row per case (tets, CPU and wall time, output tets per CPU second, min Qe,
// % Qe >= 0.5, % Qt >= 0.66, % edges too long, boundary distance to the unit sphere, checker
// verdict) and the CPU time split.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "common/parallel.h"
#include "coupling/adapt.h"
#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/check/quality_report.h"
#include "volume/io/tet_io.h"
#include "volume/size/size_fields.h"

using namespace hdimesh;

namespace
{

/// FNV-1a over the live tets and the coordinates' bits: equal digests mean bitwise equal
/// meshes, so a speed change that should not change the output can be checked at a glance.
std::uint64_t mesh_digest(const TetMesh& mesh)
{
    std::uint64_t h = 1469598103934665603ull;
    auto add = [&](const void* data, std::size_t size) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) h = (h ^ bytes[i]) * 1099511628211ull;
    };
    for (const auto& p : mesh.points) add(p.data(), 3 * sizeof(double));
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_dead(t)) add(mesh.tets[t].data(), sizeof(TetVertices));
    return h;
}

}  // namespace

int main(int argc, char** argv)
{
    std::string cases = "AC";
    coupling::AdaptOptions options;
    options.verbosity = 0;
    int threads = 1;
    for (int i = 1; i < argc; ++i)
    {
        if (!std::strcmp(argv[i], "--cases") && i + 1 < argc)
            cases = argv[++i];
        else if (!std::strcmp(argv[i], "--no-projection"))
            options.project = false;
        else if (!std::strcmp(argv[i], "--no-optimize"))
            options.optimize = false;
        else if (!std::strcmp(argv[i], "--verbose"))
            options.optimizer.verbosity = 2;
        else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc && std::atoi(argv[i + 1]) >= 1)
            threads = std::atoi(argv[++i]);
        else
        {
            std::fprintf(stderr,
                         "usage: bench_adapt [--cases ABCDE] [--no-projection] [--no-optimize] "
                         "[--verbose] [--threads N >= 1]\n");
            return 2;
        }
    }
    Workers workers(threads);
    options.workers = &workers;
    const TetMesh input = read_mesh(std::string(HDIMESH_DATA_DIR) + "/sphere480.mesh");
    std::printf("sphere480 (%d tets) adapted; projection %s, optimization %s; %d thread%s\n\n",
                input.num_live_tets(), options.project ? "on" : "off",
                options.optimize ? "on" : "off", threads, threads == 1 ? "" : "s");
    // CPU time of the adapting thread is the figure of record (the machine may be shared);
    // wall time is printed beside it
    std::printf("%-4s %10s %9s %8s %8s %9s %8s %9s %10s %9s %8s  %s\n", "case", "tets", "vertices",
                "cpu s", "wall s", "tets/cpu-s", "min Qe", "Qe>=0.5", "Qt>=0.66", "too long",
                "max|r-1|", "checker");
    std::string splits, digests;
    for (char c : cases)
    {
        TetMesh mesh = input;
        const BenchmarkSize field(benchmark_case(c));
        const coupling::AdaptReport report = coupling::adapt(mesh, field, options);
        const QualityReport q = compute_quality_report(mesh, &field);
        const auto violations = check_mesh(mesh);
        std::printf("%-4c %10d %9d %8.2f %8.2f %9.0f %8.4f %8.2f%% %9.2f%% %8.3f%% %8.1e  %s\n", c,
                    q.tets, q.vertices, report.cpu_seconds_total, report.seconds_total,
                    q.tets / report.cpu_seconds_total, q.min_qe, q.percent_qe_ge_05,
                    q.percent_qt_ge_066, q.percent_too_long,
                    fixtures::max_unit_sphere_deviation(mesh),
                    violations.empty() ? "clean" : "VIOLATIONS");
        std::fflush(stdout);
        char line[200];
        std::snprintf(line, sizeof line,
                      "%c: cpu refine %.2f s, project %.2f s, optimize %.2f s, other %.2f s; %zu "
                      "passes, %s\n",
                      c, report.cpu_seconds_refine, report.cpu_seconds_project,
                      report.cpu_seconds_optimize,
                      report.cpu_seconds_total - report.cpu_seconds_refine -
                          report.cpu_seconds_project - report.cpu_seconds_optimize,
                      report.passes.size(), report.converged ? "converged" : "NOT converged");
        splits += line;
        std::snprintf(line, sizeof line, "%c: %016llx\n", c,
                      static_cast<unsigned long long>(mesh_digest(mesh)));
        digests += line;
    }
    std::printf("\ntime split\n%s", splits.c_str());
    std::printf("\nmesh digests (FNV-1a of tets and point bits)\n%s", digests.c_str());
    return 0;
}
