// surfremesh: remesh a triangle surface to a size on its own HDI-backed model, keeping ridges,
// corners, open boundaries and refs. Prints a before/after quality table.
//
// Size: --hsiz H (uniform), --sol F (a size per input vertex, Medit .sol), or curvature-adaptive
// with --hausd D. With none of them, the size is curvature-adaptive with hausd = 0.002 × the
// bounding-box diagonal and hmax = the input's mean edge length × 2 (so a default run never
// coarsens beyond twice the input's resolution and never ignores the model's scale).

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "apps/cli.h"
#include "surface/remesh_surface.h"
#include "surface/sizing.h"
#include "common/errors.h"
#include "surface/surface_io.h"
#include "surface/surface_quality.h"

using namespace hdimesh;
using namespace hdimesh::surface;

namespace
{

void write_stats(const std::string& path, const QualityReport& before, const QualityReport& after,
                 const SurfaceRemeshResult& result, double seconds)
{
    const std::string temp = path + ".tmp";
    {
        std::ofstream out(temp);
        if (!out) throw IoError(path + ": cannot open for writing");
        auto report = [&](const char* name, const QualityReport& r, bool last) {
            out << "  \"" << name << "\": {\"vertices\": " << r.vertices << ", \"triangles\": " << r.faces
                << ", \"qe_min\": " << r.qe_min << ", \"qe_mean\": " << r.qe_mean
                << ", \"percent_qe_ge_0_7\": " << r.percent_qe_ge_07 << ", \"min_angle_deg\": " << r.min_angle_deg
                << ", \"max_angle_deg\": " << r.max_angle_deg
                << ", \"percent_all_angles_ge_25\": " << r.percent_all_angles_ge_25
                << ", \"percent_qt_ge_0_66\": " << r.percent_qt_ge_066
                << ", \"hausdorff_to_input\": " << r.hausdorff_to_model
                << ", \"hausdorff_from_input\": " << r.hausdorff_from_model << "}" << (last ? "\n" : ",\n");
        };
        out << "{\n";
        out << "  \"diagonal\": " << result.diagonal << ",\n  \"size\": " << result.uniform_size
            << ",\n  \"adaptive\": " << (result.adaptive ? "true" : "false") << ",\n  \"seconds\": " << seconds
            << ",\n  \"ridge_edges\": " << result.features.ridge_edges << ",\n  \"corners\": " << result.features.corners
            << ",\n";
        report("before", before, false);
        report("after", after, true);
        out << "}\n";
        if (!out) throw IoError(path + ": write failed");
    }
    if (std::rename(temp.c_str(), path.c_str()) != 0) throw IoError(path + ": cannot rename into place");
}

}  // namespace

int main(int argc, char** argv)
{
    return cli::run("surfremesh", [&]() {
        std::string input, output, sol, stats;
        double hsiz = 0, hausd = 0, hmin = 0, hmax = 0, hgrad = 1.3, ridge_angle = 45;
        bool use_hdi = false, has_hsiz = false, has_sol = false, has_hausd = false, no_ridges = false, has_hmax = false;
        int verbosity = 1, iterations = 8;
        cli::CommandLine cmd("surfremesh", "Remesh a triangle surface (OBJ, OFF, STL, PLY, Medit .mesh) to a size.");
        cmd.positional("IN", &input, "input surface");
        cmd.option("-o", &output, "output surface (format by extension)");
        cmd.option("--hsiz", &hsiz, "uniform target edge length", &has_hsiz);
        cmd.option("--sol", &sol, "Medit .sol with a target size per input vertex", &has_sol);
        cmd.option("--hausd", &hausd, "geometric tolerance: curvature-adaptive size (default 0.002*diag)", &has_hausd);
        cmd.option("--hmin", &hmin, "smallest size");
        cmd.option("--hmax", &hmax, "largest size", &has_hmax);
        cmd.option("--hgrad", &hgrad, "size gradation (default 1.3; <= 1: none)");
        cmd.option("--ridge-angle", &ridge_angle, "ridge detection angle in degrees (default 45)");
        cmd.flag("--hdi", &use_hdi, "smooth vertices on the HDI model instead of the input facets (experimental)");
        cmd.flag("--no-ridges", &no_ridges, "detect no ridges (open boundaries are still kept)");
        cmd.option("--iterations", &iterations, "remeshing iterations (default 8)");
        cmd.option("--stats", &stats, "write the before/after figures as JSON");
        cmd.option("-v", &verbosity, "verbosity (0 quiet, 1 table, 2 per iteration, 3 refinement details)");
        cmd.parse(argc, argv);
        if (output.empty()) throw InputError("missing -o OUT");
        if ((has_hsiz ? 1 : 0) + (has_sol ? 1 : 0) + (has_hausd ? 1 : 0) > 1)
            throw InputError("give at most one of --hsiz, --sol, --hausd");
        if (has_hsiz && !(hsiz > 0)) throw InputError("--hsiz must be positive");

        ReadReport read_report;
        SurfaceMesh mesh = read_surface(input, &read_report);
        for (const auto& w : read_report.warnings) std::cerr << "surfremesh: " << w << "\n";
        const SurfaceMesh original = mesh;

        SurfaceRemeshSettings settings;
        settings.features.detect_ridges = !no_ridges;
        settings.features.ridge_angle_deg = ridge_angle;
        settings.sizing.hsiz = has_hsiz ? hsiz : 0.0;
        settings.sizing.hausd = has_hausd ? hausd : 0.0;
        settings.sizing.hmin = hmin;
        settings.sizing.hmax = hmax;
        settings.sizing.hgrad = hgrad;
        settings.iterations = iterations;
        settings.use_hdi = use_hdi;
        settings.verbosity = verbosity > 1 ? verbosity - 1 : 0;
        if (has_sol) settings.input_sizes = read_medit_sol(sol, mesh.n_vertices());
        if (!has_hsiz && !has_sol && !has_hausd && !has_hmax) settings.sizing.hmax = 2.0 * mean_edge_length(mesh);

        const auto start = std::chrono::steady_clock::now();
        const SurfaceRemeshResult result = remesh_surface(mesh, settings);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        write_surface(mesh, output);

        if (verbosity > 0 || !stats.empty())
        {
            const double uniform = result.adaptive ? 0.0 : result.uniform_size;
            QualityReport before = measure_quality(original, uniform > 0 ? uniform : result.uniform_size);
            QualityReport after = measure_quality(mesh, uniform);
            const auto d = hausdorff_distance(mesh, original);
            after.hausdorff_to_model = d[0];
            after.hausdorff_from_model = d[1];
            if (verbosity > 0)
            {
                std::printf("surfremesh: %s -> %s in %.2f s (%s size %.4g, diag %.4g)\n", input.c_str(), output.c_str(),
                            seconds, result.adaptive ? "adaptive, mean" : "uniform", result.uniform_size, result.diagonal);
                std::printf("features: %zu ridge edges, %zu boundary edges, %zu corners, %zu curves (%zu noise chains dropped)\n",
                            result.features.ridge_edges, result.features.boundary_edges, result.features.corners,
                            result.features.curves, result.features.dropped_ridge_chains);
                std::printf("%s", format_quality_table(before, after).c_str());
            }
            if (!stats.empty()) write_stats(stats, before, after, result, seconds);
        }
        return 0;
    });
}
