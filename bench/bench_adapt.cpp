// The paper's Table 3 for our runs: data/sphere480.mesh adapted to the three-cylinder field,
// cases A-E, whole pipeline (refine, project, optimize), Release; each case at 1 and 2 threads
// unless asked.
//
//   bench_adapt [--cases ACE] [--no-projection] [--no-optimize] [--verbose] [--threads N[,M...]]
//               [--block-tets N] [--dmin-factor X]
//
// --dmin-factor scales each case's dmin (the scale sweep: C, E, E at 0.5).
//
// --threads: the thread counts each case runs at (default 1,2); every count must give the same
// mesh, else the bench names the case and exits 1. --verbose prints the optimizer's per-sweep
// tables (operators, attempts, successes, time).
//
// Prints one row per case (tets, CPU time of the first count's run, wall time of the adapt call
// at each count, output tets per CPU second, min Qe, % Qe >= 0.5, % Qt >= 0.66, % edges too
// long, boundary distance to the unit sphere, checker verdict), the CPU time split and the mesh
// digests.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

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

/// "1,2" -> {1, 2}; empty when a count is not an integer >= 1.
std::vector<int> parse_thread_counts(const char* text)
{
    std::vector<int> counts;
    for (const char* p = text; *p;)
    {
        char* end = nullptr;
        const long n = std::strtol(p, &end, 10);
        if (end == p || n < 1 || n > 1024 || (*end != ',' && *end != '\0') ||
            (*end == ',' && end[1] == '\0'))
            return {};
        counts.push_back(static_cast<int>(n));
        p = *end == ',' ? end + 1 : end;
    }
    return counts;
}

}  // namespace

int main(int argc, char** argv)
{
    std::string cases = "AC";
    coupling::AdaptOptions options;
    options.verbosity = 0;
    std::vector<int> thread_counts = {1, 2};
    double dmin_factor = 1.0;  // the scale sweep: E with dmin halved is E at --dmin-factor 0.5
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
        else if (!std::strcmp(argv[i], "--dmin-factor") && i + 1 < argc &&
                 (dmin_factor = std::atof(argv[i + 1])) > 0)
            ++i;
        else if (!std::strcmp(argv[i], "--block-tets") && i + 1 < argc)
            options.tets_per_block = std::max(0, std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc &&
                 !(thread_counts = parse_thread_counts(argv[i + 1])).empty())
            ++i;
        else
        {
            std::fprintf(stderr,
                         "usage: bench_adapt [--cases ABCDE] [--no-projection] [--no-optimize] "
                         "[--verbose] [--threads N[,M...] each >= 1, default 1,2] "
                         "[--block-tets N, default 65536, 0: no blocks] [--dmin-factor X]\n");
            return 2;
        }
    }
    // one pool per count, made once: its threads start before the first case, not inside it
    std::vector<std::unique_ptr<Workers>> pools;
    for (int n : thread_counts) pools.push_back(std::make_unique<Workers>(n));
    const TetMesh input = read_mesh(std::string(HDIMESH_DATA_DIR) + "/sphere480.mesh");
    std::string counts_text;
    for (int n : thread_counts)
        counts_text += (counts_text.empty() ? "" : ", ") + std::to_string(n);
    std::printf("sphere480 (%d tets) adapted; projection %s, optimization %s; threads %s\n\n",
                input.num_live_tets(), options.project ? "on" : "off",
                options.optimize ? "on" : "off", counts_text.c_str());
    // CPU time of the adapting thread in the first count's run is the figure of record (the
    // machine may be shared); the adapt call's wall time at each count is printed beside it
    std::printf("%-4s %10s %9s %8s", "case", "tets", "vertices", "cpu s");
    for (int n : thread_counts)
    {
        const std::string title = "wall " + std::to_string(n) + "t";
        std::printf(" %8s", title.c_str());
    }
    std::printf(" %9s %8s %9s %10s %9s %8s  %s\n", "tets/cpu-s", "min Qe", "Qe>=0.5", "Qt>=0.66",
                "too long", "max|r-1|", "checker");
    std::string splits, digests;
    bool all_equal = true;
    for (char c : cases)
    {
        BenchmarkFieldParams params = benchmark_case(c);
        params.dmin *= dmin_factor;
        const BenchmarkSize field(params);
        // the first count's mesh and report make the row; the others give a wall time and a
        // digest that must equal the first's
        TetMesh mesh = input;
        options.workers = pools[0].get();
        const coupling::AdaptReport report = coupling::adapt(mesh, field, options);
        const std::uint64_t digest = mesh_digest(mesh);
        std::vector<double> walls = {report.seconds_total};
        for (std::size_t k = 1; k < pools.size(); ++k)
        {
            TetMesh other = input;
            options.workers = pools[k].get();
            walls.push_back(coupling::adapt(other, field, options).seconds_total);
            if (mesh_digest(other) != digest)
            {
                std::fprintf(stderr,
                             "bench_adapt: case %c: %d threads give another mesh than %d "
                             "(digest %016llx, not %016llx)\n",
                             c, thread_counts[k], thread_counts[0],
                             static_cast<unsigned long long>(mesh_digest(other)),
                             static_cast<unsigned long long>(digest));
                all_equal = false;
            }
        }
        const QualityReport q = compute_quality_report(mesh, &field);
        const auto violations = check_mesh(mesh);
        std::printf("%-4c %10d %9d %8.2f", c, q.tets, q.vertices, report.cpu_seconds_total);
        for (double wall : walls) std::printf(" %8.2f", wall);
        std::printf(
            " %9.0f %8.4f %8.2f%% %9.2f%% %8.3f%% %8.1e  %s\n", q.tets / report.cpu_seconds_total,
            q.min_qe, q.percent_qe_ge_05, q.percent_qt_ge_066, q.percent_too_long,
            fixtures::max_unit_sphere_deviation(mesh), violations.empty() ? "clean" : "VIOLATIONS");
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
                      static_cast<unsigned long long>(digest));
        digests += line;
    }
    std::printf("\ntime split\n%s", splits.c_str());
    std::printf("\nmesh digests (FNV-1a of tets and point bits)\n%s", digests.c_str());
    if (!all_equal)
    {
        std::fprintf(stderr, "bench_adapt: FAILED: the mesh depends on the thread count\n");
        return 1;
    }
    return 0;
}
