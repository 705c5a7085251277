// surfremesh: remesh a triangle surface to a size on its own HDI-backed model, keeping ridges,
// corners, open boundaries and refs. Prints a before/after quality table.
//
// Size: --hsiz H (uniform), --sol F (a size per input vertex, Medit .sol), or curvature-adaptive
// with --hausd D. With none of them, the size is curvature-adaptive with hausd = 0.002 × the
// bounding-box diagonal and hmax = the input's mean edge length × 2 (so a default run never
// coarsens beyond twice the input's resolution and never ignores the model's scale).

#include <cstdio>
#include <iostream>

#include "apps/cli.h"
#include "common/atomic_file.h"
#include "common/errors.h"
#include "common/sol_io.h"
#include "common/stage_timer.h"
#include "surface/remesh_surface.h"
#include "surface/sizing.h"
#include "surface/surface_io.h"
#include "surface/surface_quality.h"

using namespace hdimesh;
using namespace hdimesh::surface;

namespace
{

void write_stats(const std::string& path, const QualityReport& before, const QualityReport& after,
                 const SurfaceRemeshResult& result, double seconds)
{
    write_file_atomically(path, [&](std::ostream& out) {
        auto report = [&](const char* name, const QualityReport& r, bool last) {
            out << "  \"" << name << "\": {\"vertices\": " << r.vertices
                << ", \"triangles\": " << r.faces << ", \"qe_min\": " << r.qe_min
                << ", \"qe_mean\": " << r.qe_mean
                << ", \"percent_qe_ge_0_7\": " << r.percent_qe_ge_07
                << ", \"min_angle_deg\": " << r.min_angle_deg
                << ", \"max_angle_deg\": " << r.max_angle_deg
                << ", \"percent_all_angles_ge_25\": " << r.percent_all_angles_ge_25
                << ", \"percent_qt_ge_0_66\": " << r.percent_qt_ge_066
                << ", \"hausdorff_to_input\": " << r.hausdorff_to_model
                << ", \"hausdorff_from_input\": " << r.hausdorff_from_model << "}"
                << (last ? "\n" : ",\n");
        };
        out << "{\n";
        out << "  \"diagonal\": " << result.diagonal << ",\n  \"size\": " << result.uniform_size
            << ",\n  \"adaptive\": " << (result.adaptive ? "true" : "false")
            << ",\n  \"seconds\": " << seconds
            << ",\n  \"ridge_edges\": " << result.features.ridge_edges
            << ",\n  \"corners\": " << result.features.corners << ",\n";
        report("before", before, false);
        report("after", after, true);
        out << "}\n";
    });
}

/// The size an input already has at each vertex: the mean length of its edges there.
std::vector<double> mean_incident_edge_lengths(const SurfaceMesh& mesh)
{
    std::vector<double> sizes(mesh.n_vertices(), 0.0);
    for (const auto v : mesh.vertices())
    {
        double sum = 0;
        int count = 0;
        for (const auto w : mesh.vv_range(v))
        {
            sum += (mesh.point(w) - mesh.point(v)).norm();
            ++count;
        }
        if (count == 0 || !(sum > 0))
            throw InputError("input surface: vertex " + std::to_string(v.idx() + 1) +
                             " has no edge to take its size from (--optim)");
        sizes[v.idx()] = sum / count;
    }
    return sizes;
}

}  // namespace

int main(int argc, char** argv)
{
    return cli::run("surfremesh", [&]() {
        std::string input, output, stats;
        cli::SizeOptions size;
        double hausd = 0, ridge_angle = 45;
        bool use_hdi = false, has_hausd = false, no_ridges = false, optim = false;
        bool noinsert = false, noswap = false, nomove = false, strict = false;
        bool memory_set = false;
        int verbosity = 1, iterations = 8, memory_mb = 0;
        cli::CommandLine cmd("surfremesh",
                             "Remesh a triangle surface (OBJ, OFF, STL, PLY, Medit .mesh) to a "
                             "size.\nmmgs's command line works too: its spelling of an option "
                             "is listed beside ours,\nand its options without a counterpart are "
                             "refused.");
        cli::add_mmg_files(cmd, &input,
                           "input surface; without an extension, as Mmg: IN.meshb if it exists, "
                           "else IN.mesh",
                           &output,
                           "output surface (format by extension); default, as Mmg: IN less its "
                           "extension plus .o.mesh; without an extension, the input's");
        size.add_to(cmd, true);
        size.add_mmg_aliases(cmd, true);
        cmd.option("--hausd", &hausd,
                   "geometric tolerance: curvature-adaptive size (default 0.002*diag)", &has_hausd);
        cmd.alias("-hausd", "--hausd");
        cmd.option("--ridge-angle", &ridge_angle, "ridge detection angle in degrees (default 45)");
        cmd.alias("-ar", "--ridge-angle");
        cmd.flags({
            {"--hdi", &use_hdi,
             "smooth vertices on the HDI model instead of the input facets (a coarse input "
             "gets it by default)"},
            {"--no-ridges", &no_ridges, "detect no ridges (open boundaries are still kept)"},
            {"--optim", &optim,
             "keep the input's sizes (the mean length of the edges at each vertex), as Mmg's "
             "-optim"},
            {"--noinsert", &noinsert, "no vertex inserted or removed (no split or collapse)"},
            {"--noswap", &noswap, "no edge flip"},
            {"--nomove", &nomove, "no vertex moved"},
            {"--strict", &strict,
             "refuse a defective input (degenerate or duplicated triangles, inconsistent "
             "orientation, pinched vertices or edges) instead of repairing it"},
        });
        for (const char* name : {"noinsert", "noswap", "nomove"})
            cmd.alias(std::string("-") + name, std::string("--") + name);
        cmd.alias("-nr", "--no-ridges");
        cmd.alias("-optim", "--optim");
        cmd.option("--iterations", &iterations, "remeshing iterations (default 8)");
        cmd.option("--stats", &stats, "write the before/after figures as JSON");
        cmd.verbosity("-v", &verbosity, 3,
                      "verbosity (0 quiet, 1 table, 2 per iteration, 3 refinement details); "
                      "Mmg's -1..10 clamped to these (N optional, as Mmg)");
        cli::add_memory_limit(cmd, &memory_mb, &memory_set);
        cli::refuse_mmg_options(cmd, cli::MmgTool::mmgs);
        cmd.parse(argc, argv);
        if (memory_set) cli::limit_memory_mb(memory_mb);
        input = cli::mmg_input_name(input);
        output = cli::mmg_output_name(output, input);
        cli::refuse_mmg_parameter_file(input, ".mmgs");
        if (!size.hsiz_set && !size.sol_set && !has_hausd && !optim)
        {
            // Mmg reads the sizes beside the input when none is given
            size.sol = cli::mmg_default_sol(input);
            size.sol_set = !size.sol.empty();
            if (size.sol_set && verbosity >= 1)
                std::cerr << "surfremesh: sizes from " << size.sol << " (Mmg's default beside "
                          << input << ")\n";
        }
        const bool has_hsiz = size.hsiz_set, has_sol = size.sol_set;
        if (int(has_hsiz) + int(has_sol) + int(has_hausd) + int(optim) > 1)
            throw InputError("give at most one of --hsiz, --sol, --hausd, --optim");
        if (has_hsiz && !(size.hsiz > 0)) throw InputError("--hsiz must be positive");
        if (!(ridge_angle > 0 && ridge_angle < 180))
            throw cli::UsageError("--ridge-angle must be between 0 and 180 degrees");

        ReadReport read_report;
        SoupRepairOptions repair;
        repair.strict = strict;
        SurfaceMesh mesh = read_surface(input, &read_report, repair);
        for (const auto& w : read_report.notes) std::cerr << "surfremesh: " << w << "\n";
        const SurfaceMesh original = mesh;

        SurfaceRemeshSettings settings;
        settings.features.detect_ridges = !no_ridges;
        settings.features.ridge_angle_deg = ridge_angle;
        settings.sizing.hsiz = has_hsiz ? size.hsiz : 0.0;
        settings.sizing.hausd = has_hausd ? hausd : 0.0;
        settings.sizing.hmin = size.hmin;
        settings.sizing.hmax = size.hmax;
        // default 1.3; <= 1: no gradation
        settings.sizing.hgrad = size.hgrad_set ? size.hgrad : 1.3;
        settings.iterations = iterations;
        settings.use_hdi = use_hdi;
        settings.insert = !noinsert;
        settings.swap = !noswap;
        settings.move = !nomove;
        settings.verbosity = verbosity > 1 ? verbosity - 1 : 0;
        settings.messages = cli::print_messages();
        if (has_sol)
            settings.input_sizes = read_sol_sizes(size.sol, static_cast<int>(mesh.n_vertices()));
        if (optim) settings.input_sizes = mean_incident_edge_lengths(mesh);
        if (!has_hsiz && !has_sol && !has_hausd && !optim && !size.hmax_set)
            settings.sizing.hmax = 2.0 * mean_edge_length(mesh);

        const WallStopwatch stopwatch;
        const SurfaceRemeshResult result = remesh_surface(mesh, settings);
        const double seconds = stopwatch.seconds();
        for (const auto& note : result.report.notes) std::cerr << "surfremesh: " << note << "\n";

        // Everything that could fail runs before the output is written.
        if (verbosity > 0 || !stats.empty())
        {
            const double uniform = result.adaptive ? 0.0 : result.uniform_size;
            QualityReport before =
                measure_quality(original, uniform > 0 ? uniform : result.uniform_size);
            QualityReport after = measure_quality(mesh, uniform);
            const auto d = hausdorff_distance(mesh, original);
            after.hausdorff_to_model = d[0];
            after.hausdorff_from_model = d[1];
            if (verbosity > 0)
            {
                std::printf("surfremesh: %s -> %s in %.2f s (%s size %.4g, diag %.4g)\n",
                            input.c_str(), output.c_str(), seconds,
                            result.adaptive ? "adaptive, mean" : "uniform", result.uniform_size,
                            result.diagonal);
                std::printf(
                    "features: %zu ridge edges, %zu boundary edges, %zu corners, %zu curves (%zu "
                    "noise chains dropped)\n",
                    result.features.ridge_edges, result.features.boundary_edges,
                    result.features.corners, result.features.curves,
                    result.features.dropped_ridge_chains);
                std::printf("%s", format_quality_table(before, after).c_str());
            }
            if (!stats.empty()) write_stats(stats, before, after, result, seconds);
        }
        write_surface(mesh, output);
        return 0;
    });
}
