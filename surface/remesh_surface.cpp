#include "surface/remesh_surface.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>

#include "common/errors.h"
#include "common/messages.h"
#include "common/size_quality.h"
#include "common/stage_timer.h"
#include "surface/detail/change_log.h"
#include "surface/detail/cleanup.h"
#include "surface/detail/keep_tolerance.h"
#include "surface/detail/remesh_run.h"
#include "surface/detail/tolerance_refinement.h"
#include "surface/hdi_projection.h"
#include "surface/surface_model.h"
#include "surface/surface_quality.h"

namespace hdimesh::surface
{
namespace
{

// The curvature-adaptive size refines to this fraction of hausd, to end within hausd.
constexpr double kAdaptiveToleranceMargin = 0.8;
// Where the tolerance is the contract (no size to keep, or a size the curvature overrules):
// the refinement's edges down to this fraction of the local size (ToleranceOptions).
constexpr double kContractMinLengthRatio = 0.15;
// No refinement split makes an edge shorter than this fraction of the diagonal (or half the
// input's shortest edge): below it the tolerance is out of the model's reach.
constexpr double kSplitFloorOfDiagonal = 1e-4;

// Verbose: how many edges miss their size (Qt < 0.66 against the local size) after a stage.
void report_stage(const detail::RemeshRun& run, const detail::ToleranceKeeper& keeper,
                  const char* stage)
{
    if (run.options.verbosity <= 0) return;
    std::size_t short_edges = 0, long_edges = 0, edges = 0;
    for (auto e : run.mesh.edges())
    {
        if (run.mesh.status(e).deleted()) continue;
        ++edges;
        const double length = run.mesh.calc_edge_length(e), size = run.edge_size(e);
        if (is_too_short(length, size))
            ++short_edges;
        else if (is_too_long(length, size))
            ++long_edges;
    }
    hdimesh::emit(run.options.messages, hdimesh::MessageKind::Trace,
                  "remesh: after %s (%.2f s, cpu %.3f s): %zu edges, %zu too short, %zu too long, "
                  "%zu short for the reference\n",
                  stage, run.clock.wall_seconds(), run.clock.cpu_seconds(), edges, short_edges,
                  long_edges, keeper.count_short_edges());
}

// The fraction of the area of `mesh` whose faces' mean vertex size is under `limit`.
double area_fraction_below(const SurfaceMesh& mesh, const std::vector<double>& vertex_sizes,
                           double limit)
{
    double total = 0.0, below = 0.0;
    for (auto f : mesh.faces())
    {
        double mean = 0.0;
        for (auto v : mesh.fv_range(f)) mean += vertex_sizes[v.idx()] / 3.0;
        const double area = mesh.calc_face_area(f);
        total += area;
        if (mean < limit) below += area;
    }
    return total > 0.0 ? below / total : 0.0;
}

/// Each input triangle's area over an equilateral triangle's of the size at its centroid.
double expected_triangle_count(const SurfaceMesh& input,
                               const std::function<double(const Vec3d&)>& size)
{
    double count = 0.0;
    for (auto f : input.faces())
    {
        const double h = size(input.calc_face_centroid(f));
        count += input.calc_face_area(f) / (0.25 * std::sqrt(3.0) * h * h);
    }
    return count;
}

// Verbose: the CPU time of the fixed costs before the remesher starts (features, model, sizes).
void report_setup(const SurfaceRemeshSettings& settings, const Stopwatch& clock, const char* stage)
{
    if (settings.verbosity > 0)
        hdimesh::emit(settings.messages, hdimesh::MessageKind::Trace,
                      "remesh_surface: after %s (%.2f s, cpu %.3f s)\n", stage,
                      clock.wall_seconds(), clock.cpu_seconds());
}

// A size far below the model's scale would run until memory is gone: refused.
void refuse_count(double expected, const char* what, double diagonal)
{
    if (expected <= kMaxTriangles) return;
    char text[240];
    std::snprintf(text, sizeof text,
                  "%s asks for about %.3g triangles, more than the %.3g a surface can hold: "
                  "it is far below the model's scale (diagonal %.3g)",
                  what, expected, kMaxTriangles, diagonal);
    throw InputError(text);
}

// The sizes to remesh to: uniform (capped where the curvature needs finer edges for the
// tolerance), per input vertex, or curvature-adaptive; `coarse`: the tolerance wins over the
// uniform size.
SizeMap choose_sizes(const SurfaceMesh& input, const SurfaceModel& model,
                     const SurfaceRemeshSettings& settings, SurfaceRemeshResult& result,
                     bool& coarse)
{
    SizeMap sizes = SizeMap::uniform(settings.sizing.hsiz);
    coarse = false;
    if (settings.sizing.hsiz > 0.0 && settings.uniform_hausd_fraction > 0.0)
    {
        // A uniform size, but no coarser than the curvature allows for the tolerance: a fillet
        // narrower than h would otherwise be cut by chords (the Hausdorff target).
        SizingOptions capped = settings.sizing;
        capped.hmax = settings.sizing.hsiz;
        capped.hausd = distance_tolerance(settings, result.diagonal);
        std::vector<double> local = curvature_sizes(input, model, capped);
        // Where the tolerance needs edges too short for the size on a few places, the size
        // wins (a short-edge budget); on much of the surface, the tolerance does (Mmg's hausd
        // over hsiz), the size an upper bound.
        coarse = area_fraction_below(input, local, kSizeQualityThreshold * settings.sizing.hsiz) >
                 settings.tolerance_wins_area_fraction;
        const double size_floor = coarse ? settings.coarse_size_floor : settings.uniform_size_floor;
        // Never below the floor (edges shorter than 0.66·hsiz fail the size criterion); on ridges
        // down to half of it: a curved ridge must stay within its tolerance. Open boundaries of
        // scans zig-zag, so their turning is no curvature to follow.
        OpenMesh::VPropHandleT<VertexClass> input_class;
        input.get_property_handle(input_class, property_names::vertex_class);
        for (auto v : input.vertices())
        {
            const bool ridge = input.property(input_class, v) == VertexClass::Ridge;
            const double floor = (ridge ? 0.5 : 1.0) * size_floor * settings.sizing.hsiz;
            local[v.idx()] = std::max(local[v.idx()], floor);
        }
        const double hsiz = settings.sizing.hsiz;
        const bool all_uniform =
            std::all_of(local.begin(), local.end(), [hsiz](double s) { return s >= hsiz; });
        if (!all_uniform) sizes = SizeMap::per_input_vertex(model, std::move(local));
    }
    if (!settings.input_sizes.empty())
    {
        if (settings.input_sizes.size() != input.n_vertices())
            throw InputError("remesh_surface: " + std::to_string(settings.input_sizes.size()) +
                             " sizes for " + std::to_string(input.n_vertices()) + " vertices");
        std::vector<double> graded = settings.input_sizes;
        bound_and_grade(input, graded, settings.sizing);
        sizes = SizeMap::per_input_vertex(model, std::move(graded));
        result.adaptive = true;
    }
    else if (!(settings.sizing.hsiz > 0.0) && !settings.size_field)
    {
        sizes = SizeMap::per_input_vertex(model, curvature_sizes(input, model, settings.sizing));
        result.adaptive = true;
    }
    if (!settings.input_size_bounds.empty())
    {
        if (settings.input_size_bounds.size() != input.n_vertices())
            throw InputError(
                "remesh_surface: " + std::to_string(settings.input_size_bounds.size()) +
                " size bounds for " + std::to_string(input.n_vertices()) + " vertices");
        std::vector<double> bounded(input.n_vertices());
        bool binds = false;
        for (auto v : input.vertices())
        {
            const double s =
                sizes.is_uniform() ? sizes.uniform_size() : sizes.vertex_sizes()[v.idx()];
            binds = binds || settings.input_size_bounds[v.idx()] < s;
            bounded[v.idx()] = std::min(s, settings.input_size_bounds[v.idx()]);
        }
        // untouched when no bound binds: the uniform path stays uniform
        if (binds)
        {
            bound_and_grade(input, bounded, settings.sizing);
            sizes = SizeMap::per_input_vertex(model, std::move(bounded));
        }
    }
    return sizes;
}

// Each vertex's first hint of the model face it lies on.
void set_model_face_hints(SurfaceMesh& mesh, const SurfaceModel& model,
                          const SurfaceRemeshSettings& settings)
{
    const SurfaceProperties props(mesh);
    if (settings.model_surface)
    {
        // Another surface: each vertex's first hint is the input face it lies nearest.
        for (auto v : mesh.vertices())
            mesh.property(props.vertex_model_face, v) = model.closest_on_input(mesh.point(v)).face;
    }
    else
    {
        // The remeshed surface starts as the model's own input: each vertex's first hint is
        // a face of its own (the model numbers the input faces in iteration order).
        int model_face = 0;
        for (auto f : mesh.faces())
        {
            for (auto v : mesh.fv_range(f)) mesh.property(props.vertex_model_face, v) = model_face;
            ++model_face;
        }
    }
}

// The points the tolerance is measured at: the input's vertices, and on a faceted model its
// edge midpoints.
void add_model_points(const SurfaceMesh& input, const SurfaceModel& model,
                      ToleranceOptions& tolerance)
{
    OpenMesh::VPropHandleT<VertexClass> input_class;
    OpenMesh::EPropHandleT<int> input_curve;
    input.get_property_handle(input_class, property_names::vertex_class);
    input.get_property_handle(input_curve, property_names::edge_curve);
    tolerance.model_points.reserve(input.n_vertices() + input.n_edges());
    tolerance.model_point_smooth.reserve(input.n_vertices() + input.n_edges());
    for (auto v : input.vertices())
    {
        if (input.is_isolated(v)) continue;
        tolerance.model_points.push_back(input.point(v));
        tolerance.model_point_smooth.push_back(input.property(input_class, v) ==
                                               VertexClass::Smooth);
    }
    // Edge midpoints too (the Hausdorff samples of the input): a crease the features dropped
    // is farthest from the output between its vertices. With a uniform size too: the
    // short-edge budget then goes to those creases (docs/tuning.md). Not on a smooth
    // model: a chord's midpoint is off it.
    if (!model.has_smooth_projection())
        for (auto e : input.edges())
        {
            const auto h = input.halfedge_handle(e, 0);
            const Vec3d mid = 0.5 * (input.point(input.from_vertex_handle(h)) +
                                     input.point(input.to_vertex_handle(h)));
            tolerance.model_points.push_back(mid);
            tolerance.model_point_smooth.push_back(input.property(input_curve, e) == kNoCurve &&
                                                   !input.is_boundary(e));
        }
}

// The stages' settings after the loop's: the tolerance, its points, the budgets.
void set_tolerance_options(const SurfaceMesh& input, const SurfaceModel& model,
                           const SurfaceRemeshSettings& settings, double diagonal, bool coarse,
                           SurfaceRemeshOptions& options)
{
    options.tolerance.tolerance = distance_tolerance(settings, diagonal);
    // The refinement's floor: 1e-4 of the diagonal, lower only for an input with shorter edges.
    double shortest = diagonal;
    for (auto e : input.edges()) shortest = std::min(shortest, input.calc_edge_length(e));
    options.tolerance.min_split_length = std::min(kSplitFloorOfDiagonal * diagonal, 0.5 * shortest);
    if (settings.refine_to_tolerance && options.tolerance.tolerance > 0.0)
        add_model_points(input, model, options.tolerance);
    if (!settings.refine_to_tolerance) options.tolerance.tolerance = 0.0;
    options.tolerance.reference_size = coarse ? 0.0 : settings.sizing.hsiz;
    options.refinement.short_edge_budget = coarse ? 1.0 : settings.refine_short_edge_budget;
    // Where the tolerance wins over the size, it is the contract: the refinement's splits may
    // go below the size's floor, as in the curvature-adaptive mode.
    if (coarse) options.tolerance.min_length_ratio = kContractMinLengthRatio;
    options.refinement.final_short_edge_budget =
        std::max(settings.refine_final_short_edge_budget, options.refinement.short_edge_budget);
    if (!(settings.sizing.hsiz > 0.0) && settings.input_sizes.empty() && !settings.size_field)
    {
        // Curvature-adaptive: the tolerance is the contract (no size target to keep), with a
        // margin for the samples the refinement does not look at (input edge midpoints, centroids).
        options.tolerance.tolerance *= kAdaptiveToleranceMargin;
        options.refinement.short_edge_budget = 1.0;
        options.refinement.final_short_edge_budget = 1.0;
        options.tolerance.min_length_ratio = kContractMinLengthRatio;
        options.refinement.rounds = 20;
    }
}

}  // namespace

RemeshReport remesh_surface(SurfaceMesh& mesh, const SurfaceRemeshOptions& options,
                            const Projector& model, const SurfaceHooks& hooks)
{
    if (!options.loop.size) throw InputError("remesh: no size function given");
    // The stages share the operators' context (its hooks note each change for their caches),
    // the sizes and the report.
    detail::ChangeLog log;
    detail::RemeshRun run(mesh, options.loop, model, log.wrap(hooks));
    detail::ToleranceKeeper keeper(run, options.tolerance);
    detail::ToleranceRefinement refinement(run, keeper, log, options.tolerance, options.refinement);
    detail::Cleanup cleanup(run, keeper, log, options.tolerance, options.cleanup);
    auto stage_done = [&](const char* stage) { report_stage(run, keeper, stage); };

    if (options.project_first)
    {
        ShiftOptions onto_model;  // no step toward the ideal point: the projection alone
        onto_model.step = 0.0;
        onto_model.smart = false;
        for (auto v : mesh.vertices()) shift_vertex(run.ctx, v, onto_model);
    }
    // The sizes into band: split, collapse, flip, shift.
    run.update_sizes();
    detail::run_iterations(run);
    stage_done("iterations");
    // Against a uniform size, the loop's bound on new edges (to converge) left short ones.
    cleanup.collapse_short_for_reference();
    stage_done("reference collapses");
    // Where the sizes alone stray from the model; no snaps yet: the polish would move them back.
    refinement.refine(false);
    stage_done("refinement");
    // Quality flips and smart shifts where a triangle misses the quality goal.
    cleanup.polish(options.polish);
    stage_done("polish");
    // The worst triangles: flips, collapses, removals, shifts.
    cleanup.cleanup_worst_triangles();
    stage_done("cleanup");
    // Short edges the polish and cleanup made, so the final budget goes to far places.
    cleanup.collapse_short_keeping_tolerance();
    stage_done("budget collapses");
    // Curve vertices onto an open boundary's stair corners first: the budget then goes elsewhere.
    cleanup.fit_curves();
    // The polish moved vertices; the cleanup after new splits may again: a last refinement.
    if (refinement.refine(true) > 0)
    {
        cleanup.cleanup_worst_triangles(detail::Keep::Tolerance);
        refinement.refine(true);
    }
    // A needle at a narrow corner between two curves: its curve vertex slid, the only cure.
    cleanup.slide_curve_vertices_of_needles();
    // Where the tolerance is the contract, the refinement has the last word after the slides.
    if (options.refinement.short_edge_budget >= 1.0) refinement.refine(true);
    // The last splits may leave needles: a repair that keeps what they reached.
    cleanup.repair_small_angles();
    // Again after the last splits, whose chords may cut the next zig.
    cleanup.fit_curves();
    stage_done("final refinement");
    // Right triangles beside ridges, which George's balance keeps: the worst Qe of each star,
    // first toward a higher goal (the fair triangles beside a poor one make room for it).
    cleanup.raise_poor_triangles(options.cleanup.room_quality, detail::Keep::Tolerance);
    cleanup.raise_poor_triangles(options.polish.below_quality, detail::Keep::Tolerance);
    stage_done("quality raise");
    refinement.note_bounds_reached();
    mesh.garbage_collection();
    return run.report;
}

double distance_tolerance(const SurfaceRemeshSettings& settings, double diagonal)
{
    if (settings.sizing.hausd > 0.0) return settings.sizing.hausd;
    if (settings.sizing.hsiz > 0.0) return settings.uniform_hausd_fraction * diagonal;
    return 0.002 * diagonal;
}

FeatureOptions feature_options(const SurfaceRemeshSettings& settings)
{
    FeatureOptions features = settings.features;
    if (features.min_corner_spacing <= 0.0)
    {
        const double h = settings.sizing.hsiz > 0.0   ? settings.sizing.hsiz
                         : settings.sizing.hmin > 0.0 ? settings.sizing.hmin
                                                      : 0.0;
        features.min_corner_spacing = 0.5 * h;
    }
    return features;
}

SurfaceRemeshResult remesh_surface(SurfaceMesh& mesh, const SurfaceRemeshSettings& settings,
                                   const SurfaceHooks& hooks)
{
    SurfaceRemeshResult result;
    // Verbose: the CPU time of the fixed costs before the remesher starts (features, model, sizes).
    const Stopwatch clock;
    if (!settings.keep_classification)
        result.features = detect_features(mesh, feature_options(settings));
    report_setup(settings, clock, "features");
    // The model's surface: the mesh itself, or the input it was derived from (a coupled pass on
    // a refined boundary stays on the input's geometry).
    const SurfaceMesh& input = settings.model_surface ? *settings.model_surface : mesh;
    result.diagonal = bounding_box_diagonal(input);
    std::optional<SurfaceModel> own_model;
    if (!settings.model)
    {
        own_model.emplace(input);
        if (settings.hdi_model)
            attach_hdi_projection(*own_model, *settings.hdi_model, settings.hdi_projection);
        else if (settings.use_hdi)
            attach_hdi_projection(*own_model, input, settings.hdi_projection);
        else if (settings.hdi_for_coarse_input)
            attach_hdi_projection(
                *own_model, input,
                coarse_input_options(settings.hdi_projection,
                                     distance_tolerance(settings, result.diagonal)));
    }
    else if (!settings.model_surface)
    {
        throw InputError("remesh_surface: a model without the surface it was built on");
    }
    const SurfaceModel& model = settings.model ? *settings.model : *own_model;
    report_setup(settings, clock, "model");
    if (settings.sizing.hausd > 0.0)
    {
        // the tolerance's own sizes (h = sqrt(3 hausd / k)): the refinement would chase them
        SizingOptions tolerance_only = settings.sizing;
        tolerance_only.hsiz = 0.0;
        const std::vector<double> local = curvature_sizes(input, model, tolerance_only);
        const SizeMap tolerance_sizes = SizeMap::per_input_vertex(model, local);
        refuse_count(
            expected_triangle_count(
                input, [&tolerance_sizes](const Vec3d& p) { return tolerance_sizes.at(p); }),
            "the distance bound", result.diagonal);
    }

    bool coarse = false;  // the tolerance wins over the uniform size
    const SizeMap sizes = choose_sizes(input, model, settings, result, coarse);
    result.uniform_size = settings.sizing.hsiz > 0.0 ? settings.sizing.hsiz : sizes.uniform_size();

    SurfaceRemeshOptions options;
    options.loop.size = [&sizes](const Vec3d& p) { return sizes.at(p); };
    options.loop.size_near = [&sizes](const Vec3d& p, int face_hint) {
        return sizes.at(p, face_hint);
    };
    if (settings.size_field)
    {
        const SizeField& field = *settings.size_field;
        options.loop.size = [&field](const Vec3d& p) { return field.size(to_point(p)); };
        options.loop.size_near = [&field](const Vec3d& p, int) { return field.size(to_point(p)); };
        result.adaptive = true;
    }
    set_model_face_hints(mesh, model, settings);
    // A size far below the model's scale would run until memory is gone.
    refuse_count(expected_triangle_count(input, options.loop.size), "the size", result.diagonal);
    options.loop.iterations = settings.iterations;
    options.loop.limits.shift_in_model_plane = model.has_smooth_projection();
    options.loop.limits.insert = settings.insert;
    options.loop.limits.swap = settings.swap;
    options.loop.limits.move = settings.move;
    options.loop.verbosity = settings.verbosity;
    options.loop.messages = settings.messages;
    if (settings.max_model_distance >= 0.0)
        options.loop.max_model_distance = settings.max_model_distance;
    else if (settings.sizing.hausd > 0.0)
        options.loop.max_model_distance = settings.sizing.hausd;
    else
        options.loop.max_model_distance = 0.002 * result.diagonal;
    set_tolerance_options(input, model, settings, result.diagonal, coarse, options);
    options.project_first = settings.model_surface != nullptr;
    report_setup(settings, clock, "sizes and model points");
    result.report = remesh_surface(mesh, options, model, hooks);
    return result;
}

}  // namespace hdimesh::surface
