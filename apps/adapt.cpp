// adapt: adapts a tet mesh and its boundary to a size field, or meshes the volume a closed
// surface bounds (parse -> read -> coupling::run_adapt -> write).
#include <filesystem>
#include <iostream>

#include "common/buffer_io.h"
#include "common/parallel.h"
#include "common/sol_io.h"
#include "coupling/adapt_request.h"
#include "size_flags.h"
#include "volume/check/quality_report.h"
#include "volume/io/tet_io.h"
#include "volume/size/metric_fields.h"

using namespace hdimesh;
using namespace hdimesh::volume;

int main(int argc, char** argv)
{
    return cli::run("adapt", [&] {
        std::string input, output, stats_path, field_path;
        cli::SizeFlags size;
        coupling::AdaptSwitches switches;
        bool check = false, keep_surface = false, has_hausd = false, strict = false;
        bool memory_set = false, anisotropic = false;
        double hausd = 0;
        int verbosity = 1, memory_mb = 0, max_passes = 40, threads = default_thread_count();
        // (a named default: GCC 12 warns of the temporary's vectors as maybe uninitialized)
        const coupling::AdaptRequest defaults;
        int block_tets = defaults.tets_per_block;

        cli::CommandLine cl("adapt",
                            "Adapts a tetrahedral mesh and its boundary to a size field; the\n"
                            "boundary follows a meshfree (HDI) model of the input surface.\n"
                            "Given a closed surface instead, checks it, remeshes it to the size\n"
                            "and fills the volume it bounds with tets (nested shells make voids,\n"
                            "disjoint ones separate regions with refs 1, 2, ...).\n"
                            "mmg3d's command line works too: its spelling of an option is listed\n"
                            "beside ours, and its options without a counterpart are refused.");
        cli::add_mmg_files(
            cl, &input,
            "input tet mesh (.mesh .meshb .msh) or closed surface (.obj .off .stl .ply, "
            "or a mesh file with triangles and no tets); without an extension, as "
            "Mmg: IN.meshb if it exists, else IN.mesh",
            &output,
            "output mesh (.mesh .meshb .msh .vtu); default, as Mmg: IN less its "
            "extension plus .o.mesh (.o.meshb, .o.msh for those inputs); without an "
            "extension, the input's");
        size.add_to(cl, true);
        size.add_mmg_aliases(cl, true);
        cl.option("--hausd", &hausd,
                  "the boundary's distance bound to the input surface (a surface input: "
                  "curvature-adaptive sizes keeping it). A tet input with no size given but "
                  "this, -hmin, -hmax or -hgrad keeps its own sizes within them (Mmg grades "
                  "the boundary's curvature sizes inward instead)",
                  &has_hausd);
        cl.alias("-hausd", "--hausd");
        cl.option("--ridge-angle", &switches.ridge_angle,
                  "ridge detection angle in degrees on the boundary (default 45)");
        cl.alias("-ar", "--ridge-angle");
        cl.option("--field", &field_path,
                  "a .sol/.solb of fields at the input's vertices (one or several scalars, "
                  "vectors, symmetric tensors) carried onto the output, each output vertex by "
                  "P1 interpolation in the input tet of its region (outside the input: the "
                  "nearest tet's, extrapolated); written to OUT less its extension plus "
                  ".field.sol (.field.solb), in the file's layout; a .vtu or .msh output also "
                  "gets them as point data ($NodeData) field1, field2, ... Or a .msh with "
                  "$NodeData sections on the input's nodes (the input .msh itself, or a view "
                  "of it): carried under their names into a .msh or .vtu output, and for "
                  "another output to OUT less its extension plus .field.msh");
        cl.alias("-field", "--field");
        cl.option("--stats", &stats_path, "write the final quality report as JSON");
        cl.flags({
            {"--check", &check, "print the mesh checker's verdict on the input and output"},
            {"--no-optimize", &switches.no_optimize, "refinement (and projection) only"},
            {"--no-projection", &switches.no_projection,
             "keep the boundary as the input polyhedron"},
            {"--noswap", &switches.noswap, "no edge/face removal during optimization"},
            {"--nomove", &switches.nomove, "no vertex smoothing during optimization"},
            {"--noinsert", &switches.noinsert,
             "tet input: no vertex inserted or removed, as Mmg (no refinement, no collapse, "
             "and no surface remeshing, which splits and collapses)"},
            {"--nosurf", &switches.nosurf,
             "tet input: keep the boundary (only split and projected), no surface remeshing"},
            {"--optim", &switches.optim, "optimize only: keep the sizes of the input mesh"},
            {"--no-ridges", &switches.no_ridges,
             "detect no ridges by angle (declared ridges, region borders and open boundaries "
             "are still kept)"},
            {"--keep-surface", &keep_surface,
             "surface input: its triangles are the boundary, exactly (no remeshing)"},
            {"-A", &anisotropic,
             "anisotropic, as Mmg: a tensor --sol is a metric with or without it; OUT.sol "
             "gets the metric at the output's vertices (as it does whenever --sol is given)"},
            {"--strict", &strict,
             "refuse a defective input instead of repairing it: a tet input's triangles that "
             "are not the tets' boundary; a surface input's degenerate or duplicated "
             "triangles, pinched vertices, holes, crossings, tiny shells"},
        });
        for (const char* name : {"noswap", "nomove", "noinsert", "nosurf", "optim"})
            cl.alias(std::string("-") + name, std::string("--") + name);
        cl.alias("-nr", "--no-ridges");
        cl.verbosity("-v", &verbosity, 2,
                     "0 silent, 1 summary (default), 2 a table per pass; Mmg's -1..10 clamped "
                     "to these (N optional, as Mmg)");
        cli::add_memory_limit(cl, &memory_mb, &memory_set);
        cl.option("--max-passes", &max_passes, "refinement passes at most (default 40)");
        cl.option("--threads", &threads,
                  "threads to use (default: the cores present, here " +
                      std::to_string(default_thread_count()) +
                      "); the output is the same bytes for any count");
        cl.option("--block-tets", &block_tets,
                  "tets per block of the decomposition the final optimization runs on, in "
                  "parallel (default " +
                      std::to_string(block_tets) +
                      "; 0: none); the output depends on it, never on --threads");
        cli::refuse_mmg_options(cl, cli::MmgTool::mmg3d);
        cl.parse(argc, argv);
        if (memory_set) cli::limit_memory_mb(memory_mb);
        if (threads < 1)
            throw cli::UsageError("--threads must be at least 1, got " + std::to_string(threads));
        if (block_tets < 0)
            throw cli::UsageError("--block-tets must be at least 0, got " +
                                  std::to_string(block_tets));
        if (!(switches.ridge_angle > 0 && switches.ridge_angle < 180))
            throw cli::UsageError("--ridge-angle must be between 0 and 180 degrees");
        input = cli::mmg_input_name(input);
        output = cli::mmg_output_name(output, input);
        cli::refuse_mmg_parameter_file(input, ".mmg3d");
        // Mmg's defaults when no size is given: the sizes beside the input (X.sol), else the
        // input's own edge lengths once a bound or hausd asks for an adaptation
        const bool optim_only = switches.optim;
        if (!size.any() && !optim_only)
        {
            size.sol = cli::mmg_default_sol(input);
            size.sol_set = !size.sol.empty();
            if (size.sol_set && verbosity >= 1)
                std::cerr << "adapt: sizes from " << size.sol << " (Mmg's default beside " << input
                          << ")\n";
            size.own_sizes =
                !size.sol_set && (has_hausd || size.hmin > 0 || size.hmax_set || size.hgrad_set);
        }

        if (has_hausd && !(hausd > 0)) throw cli::UsageError("--hausd must be positive");
        coupling::AdaptRequest request;
        request.size = size.spec();
        if (size.sol_set) request.sol = size.sol;
        request.bounds_given = size.own_sizes;
        request.surface_hgrad = size.hgrad;
        request.hausd = has_hausd ? hausd : 0.0;
        request.switches = switches;
        request.keep_surface = keep_surface;
        request.strict = strict;
        request.max_passes = max_passes;
        request.threads = threads;
        request.tets_per_block = block_tets;
        request.verbosity = verbosity;
        request.messages = cli::print_messages();
        request.check = check;
        request.source = input;
        coupling::AdaptInput in = coupling::read_adapt_input(input);
        // (the library refuses these too; on the command line they are usage errors)
        if (keep_surface && !in.is_surface)
            throw cli::UsageError("--keep-surface applies to a surface input");
        if (optim_only && in.is_surface)
            throw cli::UsageError("--optim needs a tet mesh, not a surface");
        // the fields by name: a .msh's $NodeData names, field1, field2, ... for a .sol
        const bool msh_fields = io::lower_extension(field_path) == ".msh";
        Solutions solutions;
        std::vector<PointField> fields;
        if (!field_path.empty())
        {
            if (in.is_surface)
                throw cli::UsageError("--field needs a tet mesh input, not a surface");
            if (msh_fields)
                fields = read_point_fields(field_path, in.mesh);
            else
                solutions = read_solutions(field_path, in.mesh.num_vertices());
            for (const Solution& solution : solutions.solutions)
                fields.push_back({"field" + std::to_string(fields.size() + 1),
                                  sol_components(solution.type), solution.values});
            for (PointField& field : fields)  // (the values come back carried)
                request.fields.push_back({field.components, std::move(field.values)});
        }
        const coupling::AdaptResult result = coupling::run_adapt(std::move(in), request);

        if (verbosity >= 1 || !stats_path.empty())  // (a report of a large mesh takes a while)
        {
            volume::QualityReportOptions quality_options;
            quality_options.kept_surface = keep_surface;
            const QualityReport quality =
                compute_quality_report(result.mesh, result.field.get(), quality_options);
            if (verbosity >= 1)
                std::cout << "output " << output << "\n" << format_quality_table(quality);
            if (!stats_path.empty()) write_quality_json(quality, stats_path);
        }
        for (std::size_t k = 0; k < fields.size(); ++k)
            fields[k].values = result.transfer.fields[k].values;
        const std::string out_ext = io::lower_extension(output);
        // in F's format beside OUT, unless OUT is a .msh already holding F's $NodeData
        if (!field_path.empty() && !(msh_fields && out_ext == ".msh"))
        {
            const std::string field_output =
                std::filesystem::path(output).replace_extension("").string() + ".field" +
                io::lower_extension(field_path);
            if (msh_fields)
            {
                WriteOptions field_options;
                field_options.point_fields = fields;
                write_mesh(result.mesh, field_output, field_options);
            }
            else
            {
                // F's layout: its solutions' types in its order, its format (.sol or .solb)
                Solutions carried;
                carried.num_vertices = result.mesh.num_vertices();
                for (std::size_t k = 0; k < fields.size(); ++k)
                    carried.solutions.push_back({solutions.solutions[k].type, fields[k].values});
                write_solutions(carried, field_output);
            }
            if (verbosity >= 1) std::cout << "fields " << field_output << "\n";
        }
        // as Mmg: the field at the output's vertices beside it, where the next round starts
        if (size.sol_set || anisotropic)
        {
            const bool binary = io::lower_extension(size.sol) == ".solb";
            const std::string sol_output =
                std::filesystem::path(output).replace_extension(binary ? ".solb" : ".sol").string();
            write_solutions(volume::field_at_vertices(result.mesh, *result.field), sol_output);
            if (verbosity >= 1) std::cout << "sizes " << sol_output << "\n";
        }
        WriteOptions write_options;
        if (out_ext == ".vtu" || out_ext == ".msh") write_options.point_fields = std::move(fields);
        write_mesh(result.mesh, output, write_options);  // last: a failed run leaves no output
        return 0;
    });
}
