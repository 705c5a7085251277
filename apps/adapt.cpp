// adapt: adapts a tet mesh and its boundary to a size field (parse -> read -> adapt -> write).
#include "coupling/adapt.h"

#include <cstdio>
#include <iostream>

#include "common/errors.h"
#include "size_flags.h"
#include "volume/check.h"
#include "volume/quality_report.h"
#include "volume/tet_io.h"

using namespace hdimesh;
using namespace hdimesh::volume;

int main(int argc, char** argv)
{
    return cli::run("adapt", [&] {
        std::string input, output, stats_path;
        cli::SizeFlags size;
        bool check = false, no_optimize = false, no_projection = false, optim_only = false;
        bool noswap = false, nomove = false, noinsert = false;
        int verbosity = 1;
        coupling::AdaptOptions options;

        cli::CommandLine cl("adapt",
                            "Adapts a tetrahedral mesh and its boundary to a size field; the\n"
                            "boundary follows a meshfree (HDI) model of the input surface.");
        cl.positional("IN", &input, "input tet mesh (.mesh .meshb .msh)");
        cl.option("-o", &output, "output mesh (.mesh .meshb .msh .vtu)");
        size.add_to(cl, true);
        cl.option("--stats", &stats_path, "write the final quality report as JSON");
        cl.flags({
            {"--check", &check, "print the mesh checker's verdict on the input and output"},
            {"--no-optimize", &no_optimize, "refinement (and projection) only"},
            {"--no-projection", &no_projection, "keep the boundary as the input polyhedron"},
            {"--noswap", &noswap, "no edge/face removal during optimization"},
            {"--nomove", &nomove, "no vertex smoothing during optimization"},
            {"--noinsert", &noinsert, "no refinement (no vertex insertion)"},
            {"--optim", &optim_only, "optimize only: keep the sizes of the input mesh"},
        });
        cl.option("-v", &verbosity, "0 silent, 1 summary (default), 2 a table per pass");
        cl.option("--max-passes", &options.max_passes, "refinement passes at most (default 40)");
        cl.parse(argc, argv);
        if (output.empty()) throw InputError("missing -o OUT (see --help)");

        TetMesh mesh = read_mesh(input);
        if (const auto violations = check_mesh(mesh); !violations.empty())
            throw InputError(input + ": the input mesh is not valid:\n" +
                             format_violations(violations));
        if (check && verbosity >= 1) std::cout << "check input: clean\n";

        if (!size.any() && !optim_only)
            throw InputError("no size field: give --hsiz, --sol or --bench-field (or --optim)");
        const std::shared_ptr<const SizeField> field = size.make(mesh);
        options.refine = !noinsert && !optim_only;
        options.optimize = !no_optimize;
        options.project = !no_projection;
        options.optimizer.swap = !noswap;
        options.optimizer.move = !nomove;
        options.optimizer.collapse = !optim_only;
        options.verbosity = verbosity;
        options.optimizer.verbosity = verbosity;

        if (verbosity >= 1)
        {
            std::cout << "input " << input << "\n"
                      << format_quality_table(compute_quality_report(mesh, field.get()));
        }
        const coupling::AdaptReport report = coupling::adapt(mesh, *field, options);

        const auto violations = check_mesh(mesh);
        if (check && verbosity >= 1)
            std::cout << "check output: " << (violations.empty() ? "clean\n" : "\n")
                      << format_violations(violations);
        if (!violations.empty())
            throw InputError("adaptation produced an invalid mesh (not written):\n" +
                             format_violations(violations));

        const QualityReport quality = compute_quality_report(mesh, field.get());
        if (verbosity >= 1)
        {
            // -v 1 is a summary; at -v 2 the pass rows were printed as they ran
            std::cout << coupling::format_adapt_report(report, false);
            std::cout << "output " << output << "\n" << format_quality_table(quality);
        }
        write_mesh(mesh, output);
        if (!stats_path.empty()) write_quality_json(quality, stats_path);
        return 0;
    });
}
