#include "coupling/adapt_request.h"

#include <cstdio>

#include "common/buffer_io.h"
#include "common/errors.h"
#include "common/sol_io.h"
#include "common/stage_timer.h"
#include "volume/check/boundary_repair.h"
#include "volume/check/check.h"
#include "volume/check/quality_report.h"
#include "volume/io/tet_io.h"
#include "volume/size/size_fields.h"

namespace hdimesh::coupling
{

namespace
{

/// The adaptation's options as the request's switches and verbosity ask.
AdaptOptions adapt_options(const AdaptRequest& request)
{
    AdaptOptions options;
    apply_switches(request.switches, options);
    options.verbosity = request.verbosity;
    options.optimizer.verbosity = request.verbosity;
    options.max_passes = request.max_passes;
    options.progress = request.progress;
    options.messages = request.messages;
    options.geometry = request.geometry;
    return options;
}

/// The surface's sizes and the fill's settings; its volume is then adapted with `options`.
VolumeFromSurfaceOptions fill_options(const AdaptRequest& request, const AdaptOptions& options,
                                      int points)
{
    const volume::SizeSpec& size = request.size;
    if (!size.any() && request.sol.empty() && !(request.hausd > 0) && !request.keep_surface &&
        !request.bounds_given)
        throw InputError(
            "no size field: give hsiz, sol (sizes at the vertices), hausd or bench_field (or "
            "keep_surface)");
    SolSizing from_file;
    if (!request.sol.empty()) from_file = read_sol_sizing(request.sol, points);
    // the surface pass and the front place points by sizes alone
    if (!size.vertex_metrics.empty() || !from_file.metrics.empty())
        throw InputError(
            "anisotropic metrics need a tet mesh input: a surface is remeshed and filled by "
            "sizes only");
    VolumeFromSurfaceOptions o;
    o.sizing.hsiz = size.hsiz;
    o.sizing.hausd = request.hausd;
    o.sizing.vertex_sizes = request.sol.empty() ? size.vertex_sizes : from_file.sizes;
    if (size.benchmark != 0)
        o.sizing.field =
            std::make_shared<volume::BenchmarkSize>(volume::benchmark_case(size.benchmark));
    o.sizing.hmin = size.hmin;
    o.sizing.hmax = size.hmax;
    o.sizing.hgrad = request.surface_hgrad;
    o.keep_surface = request.keep_surface;
    o.refine = !request.switches.noinsert;
    o.optimize = !request.switches.no_optimize;
    o.adapt = options;
    o.check.workers = options.workers;
    o.remesh.features = options.features;
    o.repair.strict = request.strict;
    o.source = request.source;
    return o;
}

AdaptResult fill_surface(const surface::TriangleSoup& soup, const AdaptRequest& request,
                         const AdaptOptions& options)
{
    if (request.switches.optim) throw InputError("optim needs a tet mesh, not a surface");
    if (!request.fields.empty())
        throw InputError(
            "fields are carried from a tet mesh, not a surface (no tets to "
            "interpolate in)");
    const VolumeFromSurfaceOptions o =
        fill_options(request, options, static_cast<int>(soup.points.size()));
    VolumeFromSurfaceReport report;
    AdaptResult result;
    result.mesh = mesh_volume_from_surface(soup, o, &report);
    result.field = report.field;
    result.repairs = report.repairs;
    for (const std::string& line : result.repairs)
        emit(request.messages, MessageKind::Trace, "adapt: %s\n", line.c_str());
    if (request.verbosity >= 1)
        emit(request.messages, MessageKind::Report, "input %s (a surface)\n%s",
             request.source.c_str(), format_volume_from_surface_report(report).c_str());
    return result;
}

void report_transfer(const AdaptRequest& request, const AdaptResult& result)
{
    const volume::TransferReport& t = result.transfer;
    char farthest[64] = "";
    if (t.outside > 0)
        std::snprintf(farthest, sizeof farthest, ", at most %.3g away", t.max_outside_distance);
    emit(request.messages, MessageKind::Report,
         "fields: %d carried to %d vertices (%d outside the input, extrapolated from the "
         "nearest tet%s; %d from their own region's tet at an interface) in "
         "%.3f s, %.1f %% of the adaptation's %.3f s\n",
         static_cast<int>(t.fields.size()), t.vertices, t.outside, farthest, t.other_region,
         result.transfer_seconds,
         result.adapt_seconds > 0 ? 100.0 * result.transfer_seconds / result.adapt_seconds : 0.0,
         result.adapt_seconds);
}

AdaptResult adapt_tets(volume::TetMesh mesh, const AdaptRequest& request, AdaptOptions options)
{
    if (request.keep_surface) throw InputError("keep_surface applies to a surface input");
    options.hausd = request.hausd;
    AdaptResult result;
    result.repairs = volume::prepare_tet_input(mesh, request.source, request.strict);
    for (const std::string& line : result.repairs)
        emit(request.messages, MessageKind::Trace, "adapt: %s: %s\n", request.source.c_str(),
             line.c_str());
    if (request.check && request.verbosity >= 1)
        emit(request.messages, MessageKind::Report, "check input: clean\n");
    // with bounds alone the input keeps its own sizes within them (make_size_field)
    if (!request.size.any() && request.sol.empty() && !request.bounds_given &&
        !request.switches.optim)
        throw InputError(
            "no size field: give hsiz, sol (sizes at the vertices) or bench_field "
            "(or optim)");
    volume::SizeSpec spec = request.size;
    if (!request.sol.empty())
    {
        SolSizing sizing = volume::read_vertex_sizing(request.sol, mesh);
        spec.vertex_sizes = std::move(sizing.sizes);
        spec.vertex_metrics = std::move(sizing.metrics);
    }
    result.field = volume::make_size_field(spec, mesh);
    // the input as it is before adapt changes it, kept only when fields are to be carried
    std::unique_ptr<volume::TransferSource> transfer_source;
    WallStopwatch transfer_clock;
    if (!request.fields.empty())
    {
        // fields of the wrong size are refused before the adaptation runs, not after
        volume::check_vertex_fields(request.fields, mesh.num_vertices());
        transfer_source = std::make_unique<volume::TransferSource>(mesh);
    }
    result.transfer_seconds = transfer_clock.seconds();
    if (request.verbosity >= 1)
        emit(request.messages, MessageKind::Report, "input %s\n%s", request.source.c_str(),
             volume::format_quality_table(volume::compute_quality_report(mesh, result.field.get()))
                 .c_str());
    WallStopwatch adapt_clock;
    const AdaptReport report = adapt(mesh, *result.field, options);
    result.adapt_seconds = adapt_clock.seconds();
    // -v 1 is a summary; at -v 2 the pass rows were reported as they ran
    if (request.verbosity >= 1)
        emit(request.messages, MessageKind::Report, "%s",
             format_adapt_report(report, false).c_str());
    if (transfer_source)
    {
        transfer_clock.restart();
        volume::TransferOptions transfer_options;
        transfer_options.workers = options.workers;
        result.transfer =
            volume::transfer_fields(*transfer_source, request.fields, mesh, transfer_options);
        result.transfer_seconds += transfer_clock.seconds();
        if (request.verbosity >= 1) report_transfer(request, result);
    }
    result.mesh = std::move(mesh);
    return result;
}

}  // namespace

bool is_surface_format(const std::string& path)
{
    const std::string ext = io::lower_extension(path);
    return ext == ".obj" || ext == ".off" || ext == ".stl" || ext == ".ply";
}

AdaptInput read_adapt_input(const std::string& path)
{
    AdaptInput input;
    if (is_surface_format(path))
    {
        input.surface = surface::read_triangle_soup(path);
        input.is_surface = true;
        return input;
    }
    return adapt_input_from_mesh(volume::read_mesh(path));
}

AdaptInput adapt_input_from_mesh(volume::TetMesh mesh)
{
    AdaptInput input;
    if (mesh.num_live_tets() > 0 || mesh.triangles.empty())
    {
        input.mesh = std::move(mesh);
        return input;
    }
    input.surface = triangle_soup(mesh);
    input.is_surface = true;
    return input;
}

AdaptResult run_adapt(AdaptInput input, const AdaptRequest& request)
{
    if (!(request.hausd >= 0)) throw InputError("hausd must not be negative (0: none)");
    if (request.threads < 0)
        throw InputError("threads must be at least 1 (0: the cores present), got " +
                         std::to_string(request.threads));
    if (request.tets_per_block < 0)
        throw InputError("tets per block must be at least 0 (0: no blocks), got " +
                         std::to_string(request.tets_per_block));
    // one pool for the whole run: its threads start once, not per loop
    Workers workers(request.threads > 0 ? request.threads : default_thread_count());
    AdaptOptions options = adapt_options(request);
    options.workers = &workers;
    options.tets_per_block = request.tets_per_block;
    AdaptResult result = input.is_surface ? fill_surface(input.surface, request, options)
                                          : adapt_tets(std::move(input.mesh), request, options);
    const auto violations = volume::check_mesh(result.mesh);
    if (request.check && request.verbosity >= 1)
        emit(request.messages, MessageKind::Report, "check output: %s%s",
             violations.empty() ? "clean\n" : "\n", volume::format_violations(violations).c_str());
    if (!violations.empty())
        throw Error("adaptation produced an invalid mesh:\n" +
                    volume::format_violations(violations));
    return result;
}

}  // namespace hdimesh::coupling
