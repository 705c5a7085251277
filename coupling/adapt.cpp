#include "coupling/adapt.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>

#include "common/stage_timer.h"
#include "volume/reorder.h"

namespace hdimesh::coupling
{

using namespace volume;

namespace
{

constexpr int kStallPasses = 3;          // refinement stops when the splits have not decreased
constexpr double kStallFraction = 1e-3;  // over this many passes and are this few per tet

double min_quality(const TetMesh& mesh)
{
    double worst = 1.0;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_dead(t)) worst = std::min(worst, mesh.quality(t));
    return worst;
}

std::string format_pass_row(const AdaptPassReport& p)
{
    char row[160];
    std::snprintf(row, sizeof row, "%5d %10d %10d %10d %9d %9d %8.4f %8.3f\n", p.pass,
                  p.edges_split, p.tets, p.vertices, p.projected, p.shortened, p.min_quality,
                  p.seconds);
    return row;
}

const char* kPassHeader =
    " pass     split       tets   vertices projected shortened   min Qe     time\n";

}  // namespace

AdaptReport adapt(TetMesh& mesh, const SizeField& field, const AdaptOptions& options)
{
    AdaptReport report;
    const Stopwatch clock;
    if (!mesh.has_adjacency()) mesh.build_adjacency();

    std::unique_ptr<BoundaryProjector> projector;
    if (options.project)
    {
        const StageTimer timer(report.seconds_project, report.cpu_seconds_project);
        projector = std::make_unique<BoundaryProjector>(mesh, options.projection);
    }
    if (options.verbosity >= 2) std::cout << kPassHeader;

    // refinement passes, each followed by projection and local repair
    report.converged = !options.refine;
    for (int pass = 1; options.refine && pass <= options.max_passes; ++pass)
    {
        AdaptPassReport row;
        row.pass = pass;
        const Stopwatch pass_clock;

        RefinePassResult refined;
        {
            const StageTimer timer(report.seconds_refine, report.cpu_seconds_refine);
            refined = refine_pass(mesh, field);
        }
        row.edges_split = refined.report.edges_split;
        if (row.edges_split == 0)
        {
            report.converged = true;
            break;
        }

        if (projector)
        {
            const StageTimer timer(report.seconds_project, report.cpu_seconds_project);
            const ProjectionReport moved = projector->project(mesh, refined.new_boundary_vertices);
            row.projected = moved.projected;
            row.shortened = moved.shortened;
        }
        if (options.optimize)
        {
            const StageTimer timer(report.seconds_optimize, report.cpu_seconds_optimize);
            row.min_quality =
                improve_bad_elements(mesh, field, options.optimizer).min_quality_after;
        }
        else
        {
            row.min_quality = min_quality(mesh);
        }

        row.tets = mesh.num_live_tets();
        row.vertices = mesh.num_vertices();
        row.seconds = pass_clock.wall_seconds();
        report.passes.push_back(row);
        if (options.verbosity >= 2) std::cout << format_pass_row(row) << std::flush;
        if (options.verbosity >= 1 && isatty(STDERR_FILENO))
            std::fprintf(stderr, "\radapt: pass %d, %d tets", pass, row.tets);
        // A few splits a pass that no longer decrease: the long edges left are where a split
        // does not shorten them (beside a kept triangle longer than the size); more passes only
        // stack slivers there.
        const int n = static_cast<int>(report.passes.size());
        if (n > kStallPasses &&
            row.edges_split <= kStallFraction * static_cast<double>(mesh.num_live_tets()) &&
            row.edges_split >= report.passes[n - 1 - kStallPasses].edges_split)
        {
            report.stalled = true;
            break;
        }
    }

    if (options.verbosity >= 1 && isatty(STDERR_FILENO) && !report.passes.empty())
        std::fprintf(stderr, "\radapt: final optimization...\n");

    // the final optimization, then the moves the guard had shortened
    if (options.optimize)
    {
        const StageTimer timer(report.seconds_optimize, report.cpu_seconds_optimize);
        mesh.compact();  // renumbering needs a compact mesh; the passes leave it so, this makes
                         // sure
        renumber_spatially(mesh);
        optimize_mesh(mesh, field, options.optimizer);
    }
    if (projector)
    {
        {
            const StageTimer timer(report.seconds_project, report.cpu_seconds_project);
            report.final_projection = projector->project_all(mesh);
        }
        if (options.optimize &&
            report.final_projection.shortened + report.final_projection.projected > 0)
        {
            const StageTimer timer(report.seconds_optimize, report.cpu_seconds_optimize);
            // the moved boundary vertices reshape tets the final optimization had lifted above
            // its target: bring them back there, not only above the passes' "bad" threshold
            OptimizeOptions repair = options.optimizer;
            repair.bad_quality = std::max(repair.bad_quality, repair.target_quality);
            improve_bad_elements(mesh, field, repair);
        }
    }
    if (!mesh.has_adjacency()) mesh.build_adjacency();
    report.seconds_total = clock.wall_seconds();
    report.cpu_seconds_total = clock.cpu_seconds();
    return report;
}

std::string format_adapt_report(const AdaptReport& report, bool with_passes)
{
    std::ostringstream out;
    if (with_passes)
    {
        out << kPassHeader;
        for (const auto& p : report.passes) out << format_pass_row(p);
    }
    char line[256];
    const double rest = report.seconds_total - report.seconds_refine - report.seconds_project -
                        report.seconds_optimize;
    std::snprintf(line, sizeof line,
                  "time: total %.3f s = refine %.3f + project %.3f + optimize %.3f + other %.3f\n",
                  report.seconds_total, report.seconds_refine, report.seconds_project,
                  report.seconds_optimize, rest);
    out << line;
    std::snprintf(line, sizeof line,
                  "cpu:  total %.3f s = refine %.3f + project %.3f + optimize %.3f + other %.3f\n",
                  report.cpu_seconds_total, report.cpu_seconds_refine, report.cpu_seconds_project,
                  report.cpu_seconds_optimize,
                  report.cpu_seconds_total - report.cpu_seconds_refine -
                      report.cpu_seconds_project - report.cpu_seconds_optimize);
    out << line;
    out << (report.converged ? "sizes: no edge too long\n"
            : report.stalled
                ? "sizes: refinement stopped with a few edges too long that splitting does not "
                  "shorten\n"
                : "sizes: refinement stopped at the pass cap with edges too long\n");
    return out.str();
}

}  // namespace hdimesh::coupling
