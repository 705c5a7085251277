// The paper's Table 3 for our runs: data/sphere480.mesh adapted to the three-cylinder field,
// cases A-E, whole pipeline (refine, project, optimize), single thread, Release.
//
//   bench_adapt [--cases ACE] [--no-projection] [--no-optimize]
//
// Prints one row per case (tets, time, output tets/s, min Qe, % Qe >= 0.5, % Qt >= 0.66,
// boundary distance to the unit sphere, checker verdict) and the time split.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "coupling/adapt.h"
#include "fixtures.h"
#include "volume/check.h"
#include "volume/quality_report.h"
#include "volume/size_fields.h"
#include "volume/tet_io.h"

using namespace hdimesh;

int main(int argc, char** argv)
{
    std::string cases = "AC";
    coupling::AdaptOptions options;
    options.verbosity = 0;
    for (int i = 1; i < argc; ++i)
    {
        if (!std::strcmp(argv[i], "--cases") && i + 1 < argc) cases = argv[++i];
        else if (!std::strcmp(argv[i], "--no-projection")) options.project = false;
        else if (!std::strcmp(argv[i], "--no-optimize")) options.optimize = false;
        else
        {
            std::fprintf(stderr, "usage: bench_adapt [--cases ABCDE] [--no-projection] [--no-optimize]\n");
            return 2;
        }
    }
    const TetMesh input = read_mesh(std::string(HDIMESH_DATA_DIR) + "/sphere480.mesh");
    std::printf("sphere480 (%d tets) adapted; projection %s, optimization %s\n\n",
                input.num_live_tets(), options.project ? "on" : "off",
                options.optimize ? "on" : "off");
    std::printf("%-4s %10s %9s %9s %8s %8s %9s %10s %8s  %s\n", "case", "tets", "vertices",
                "time s", "tets/s", "min Qe", "Qe>=0.5", "Qt>=0.66", "max|r-1|", "checker");
    std::string splits;
    for (char c : cases)
    {
        TetMesh mesh = input;
        const BenchmarkSize field(benchmark_case(c));
        const coupling::AdaptReport report = coupling::adapt(mesh, field, options);
        const QualityReport q = compute_quality_report(mesh, &field);
        const auto violations = check_mesh(mesh);
        std::printf("%-4c %10d %9d %9.2f %8.0f %8.4f %8.2f%% %9.2f%% %8.1e  %s\n", c, q.tets,
                    q.vertices, report.seconds_total, q.tets / report.seconds_total, q.min_qe,
                    q.percent_qe_ge_05, q.percent_qt_ge_066, fixtures::max_unit_sphere_deviation(mesh),
                    violations.empty() ? "clean" : "VIOLATIONS");
        std::fflush(stdout);
        char line[200];
        std::snprintf(line, sizeof line,
                      "%c: refine %.2f s, project %.2f s, optimize %.2f s, other %.2f s; %zu passes, %s\n",
                      c, report.seconds_refine, report.seconds_project, report.seconds_optimize,
                      report.seconds_total - report.seconds_refine - report.seconds_project -
                          report.seconds_optimize,
                      report.passes.size(), report.converged ? "converged" : "NOT converged");
        splits += line;
    }
    std::printf("\ntime split\n%s", splits.c_str());
    return 0;
}
