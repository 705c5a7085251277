#include "coupling/adapt.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>

#include "common/errors.h"
#include "common/messages.h"
#include "common/size_quality.h"
#include "common/stage_timer.h"
#include "coupling/boundary_map.h"
#include "coupling/detail/boundary_floor.h"
#include "surface/features.h"
#include "surface/hdi_projection.h"
#include "surface/surface_model.h"
#include "surface/surface_quality.h"
#include "volume/mesh/blocks.h"
#include "volume/mesh/reorder.h"
#include "volume/size/size_fields.h"

namespace hdimesh::coupling
{

using namespace volume;

namespace
{

// Surface passes at most, another while the volume's splits changed more than this fraction of
// the triangles the last one left (a few too long edges are no reason to remesh it all again).
constexpr int kSurfaceRounds = 3;
constexpr int kFloorRounds = 3;  // boundary slides, each followed by a repair
constexpr int kBandRings =
    1;  // the second block round: the tets the first left at its cuts and these rings around them
constexpr double kSurfaceRepeatFraction = 0.01;
constexpr int kMetricPassSweeps = 2;     // repair sweeps after each refinement pass in a metric
constexpr int kStallPasses = 3;          // refinement stops when the splits have not decreased
constexpr double kStallFraction = 1e-3;  // over this many passes and are this few per tet

double min_quality(const TetMesh& mesh, Workers* workers)
{
    // (a minimum is the same in any order; the chunks fold in order all the same)
    return parallel_reduce(
        workers, mesh.tets.size(), 1.0,
        [&](std::size_t first, std::size_t last) {
            double worst = 1.0;
            for (std::size_t t = first; t < last; ++t)
                if (!mesh.is_dead(static_cast<int>(t)))
                    worst = std::min(worst, mesh.quality(static_cast<int>(t)));
            return worst;
        },
        [](double a, double b) { return std::min(a, b); });
}

std::string format_pass_row(const AdaptPassReport& p)
{
    char row[160];
    std::snprintf(row, sizeof row, "%5d %10d %10d %10d %9d %9d %8.4f %8.3f\n", p.pass,
                  p.edges_split, p.tets, p.vertices, p.projected, p.shortened, p.min_quality,
                  p.seconds);
    return row;
}

/// The surface pass's settings: the field's size, a constant when it is one at every boundary
/// vertex (the uniform sizing, with its curvature cap); the distance bound when --hausd gives one.
surface::SurfaceRemeshSettings surface_settings(const surface::SurfaceMesh& boundary,
                                                const SizeField& field, const AdaptOptions& options)
{
    surface::SurfaceRemeshSettings settings = options.surface_settings;
    settings.features = options.features;
    if (!settings.messages) settings.messages = options.messages;
    double lo = std::numeric_limits<double>::max(), hi = 0.0;
    for (auto v : boundary.vertices())
    {
        const double h = field.size(surface::to_point(boundary.point(v)));
        lo = std::min(lo, h);
        hi = std::max(hi, h);
    }
    settings.input_sizes.clear();
    settings.sizing.hsiz = 0.0;
    settings.size_field = nullptr;
    if (lo == hi)
        settings.sizing.hsiz = lo;
    else
        settings.size_field = &field;  // field outlives the pass
    if (options.hausd > 0.0) settings.sizing.hausd = options.hausd;
    settings.keep_classification = true;  // classified once, before the model is built
    return settings;
}

const char* kPassHeader =
    " pass     split       tets   vertices projected shortened   min Qe     time\n";

}  // namespace

void apply_switches(const AdaptSwitches& switches, AdaptOptions& options)
{
    const bool insert = !switches.noinsert && !switches.optim;
    options.refine = insert;
    options.optimize = !switches.no_optimize;
    options.project = !switches.no_projection;
    // the surface pass splits and collapses
    options.surface = !switches.nosurf && insert;
    options.slide_boundary = !switches.nosurf && !switches.nomove;
    options.optimizer.swap = !switches.noswap;
    options.optimizer.move = !switches.nomove;
    options.surface_settings.swap = !switches.noswap;  // Mmg's switches hold on both meshes
    options.surface_settings.move = !switches.nomove;
    options.optimizer.split = insert;
    options.optimizer.collapse = insert;  // a collapse removes a vertex
    options.features.detect_ridges = !switches.no_ridges;
    options.features.ridge_angle_deg = switches.ridge_angle;
}

namespace
{

/// What the stages of one adapt() run share: the mesh, the fields, the boundary's models, the
/// report. Each stage is a free function below that reads and changes it.
struct AdaptState
{
    AdaptState(TetMesh& mesh, const SizeField& field, const AdaptOptions& options)
        : mesh(mesh), field(field), volume_field(&field), options(options)
    {
        optimizer = options.optimizer;
        // no surface pass coarsens the boundary in a metric (classify_boundary): the collapses do
        optimizer.flat_boundary_moves = field.anisotropic() && options.optimizer.collapse;
        if (!optimizer.messages) optimizer.messages = options.messages;
        if (!optimizer.workers) optimizer.workers = options.workers;
    }

    TetMesh& mesh;
    const SizeField& field;  ///< the caller's
    /// The field the volume follows: the caller's, or after a surface pass, `graded`
    const SizeField* volume_field;
    std::unique_ptr<BackgroundMeshSize> graded;
    const AdaptOptions& options;
    OptimizeOptions optimizer;  ///< options.optimizer, its messages to options.messages
    /// The input boundary, classified once (its surface is the surface pass's model; its tet
    /// ids go stale); empty when there is no surface pass
    std::optional<BoundaryMap> input;
    surface::SurfaceRemeshSettings settings;  ///< the surface pass's
    /// The input boundary's model (HDI, and the surface pass's), built once for both meshes
    std::unique_ptr<BoundaryModel> model;
    std::unique_ptr<BoundaryProjector> projector;
    AdaptReport report;
};

/// A size far below the model's scale would run until memory is gone.
void refuse_unreachable_size(const AdaptState& s)
{
    if (!s.options.refine && !s.options.surface) return;
    const double expected = expected_tet_count(s.mesh, s.field);
    if (expected <= kMaxTets) return;
    char text[200];
    std::snprintf(text, sizeof text,
                  "the size field asks for about %.3g tets, more than the %.3g a mesh can hold: "
                  "the size is far below the model's scale",
                  expected, kMaxTets);
    throw InputError(text);
}

/// One classification of the input boundary, given to both meshes before either model is
/// built from it; without projection the polyhedron is kept, so there is no surface pass.
void classify_boundary(AdaptState& s)
{
    if (!s.options.surface || !s.options.project) return;
    const StageTimer timer(s.report.seconds_surface, s.report.cpu_seconds_surface);
    s.report.surface_refusal = coupled_surface_refusal(s.mesh);
    if (!s.report.surface_refusal.empty() || s.mesh.num_live_tets() == 0) return;
    s.input = extract_boundary(s.mesh);
    s.settings = surface_settings(s.input->surface, s.field, s.options);
    surface::detect_features(s.input->surface, surface::feature_options(s.settings));
    write_back(*s.input, s.mesh);
}

/// The HDI model of the input boundary, onto which new boundary vertices are projected.
void build_projector(AdaptState& s)
{
    if (!s.options.project) return;
    const StageTimer timer(s.report.seconds_project, s.report.cpu_seconds_project);
    const TetMesh& boundary = s.options.geometry ? *s.options.geometry : s.mesh;
    s.model =
        std::make_unique<BoundaryModel>(boundary, s.options.features, s.options.projection.model);
    ProjectionOptions projection = s.options.projection;
    projection.workers = s.options.workers;
    projection.keep_flat = s.field.anisotropic();
    s.projector = std::make_unique<BoundaryProjector>(*s.model, projection);
}

/// One refinement pass: split the edges too long for `split_field`, project the new boundary
/// vertices, repair around them for `target`.
AdaptPassReport refinement_pass(AdaptState& s, const SizeField& split_field,
                                const SizeField& target, int pass,
                                const RefinePassOptions& refine_options)
{
    AdaptPassReport row;
    row.pass = pass;
    const Stopwatch pass_clock;
    RefinePassResult refined;
    {
        const StageTimer timer(s.report.seconds_refine, s.report.cpu_seconds_refine);
        refined = volume::refine_pass(s.mesh, split_field, refine_options);
    }
    row.edges_split = refined.report.edges_split;
    row.deferred_edges = refined.report.deferred_edges;
    if (row.edges_split == 0) return row;
    if (s.projector)
    {
        const StageTimer timer(s.report.seconds_project, s.report.cpu_seconds_project);
        const ProjectionReport moved = s.projector->project(s.mesh, refined.new_boundary_vertices);
        row.projected = moved.projected;
        row.shortened = moved.shortened;
    }
    if (s.options.optimize)
    {
        const StageTimer timer(s.report.seconds_optimize, s.report.cpu_seconds_optimize);
        // in a metric the passes' tets are far from its shapes until the sizes are reached:
        // sweeps to convergence would redo most of the mesh each pass (the final one does)
        OptimizeOptions repair = s.optimizer;
        if (target.anisotropic())
            repair.max_sweeps = std::min(repair.max_sweeps, kMetricPassSweeps);
        row.min_quality = improve_bad_elements(s.mesh, target, repair).min_quality_after;
    }
    else
    {
        row.min_quality = min_quality(s.mesh, s.options.workers);
    }
    row.tets = s.mesh.num_live_tets();
    row.vertices = s.mesh.num_vertices();
    row.seconds = pass_clock.wall_seconds();
    return row;
}

/// A few splits a pass that no longer decrease: the long edges left are where a split does not
/// shorten them (beside a kept triangle longer than the size); more passes only stack slivers
/// there. Only the passes since `first` count (a surface pass came before them).
bool refinement_stalled(const AdaptState& s, int first)
{
    const std::vector<AdaptPassReport>& passes = s.report.passes;
    const int n = static_cast<int>(passes.size());
    return n - first + 1 > kStallPasses &&
           passes.back().edges_split <=
               kStallFraction * static_cast<double>(s.mesh.num_live_tets()) &&
           passes.back().edges_split >= passes[n - 1 - kStallPasses].edges_split;
}

enum class StageEnd
{
    Converged,  ///< no edge too long
    Stalled,    ///< refinement_stalled
    Capped      ///< options.max_passes reached
};

/// Refinement passes, numbered from `pass` on (advanced past the last), until no edge is too
/// long for `split_field` (or they stall, or reach pass `last`). `refine_options` carries
/// what holds between passes (the adjacency) into the next stage.
StageEnd refine_stage(AdaptState& s, const SizeField& split_field, const SizeField& target,
                      int& pass, int last, RefinePassOptions& refine_options)
{
    const int first = pass;
    refine_options.first_candidate_vertex = 0;  // a stage's first pass measures every edge
    for (; pass < last; ++pass)
    {
        const int vertices_before = s.mesh.num_vertices();
        const AdaptPassReport row = refinement_pass(s, split_field, target, pass, refine_options);
        if (row.edges_split == 0) return StageEnd::Converged;
        // the pass left the adjacency, and projection and repair keep it. Repair never makes
        // an edge too long for the target, so at the target's own stage only the edges of
        // the new vertices need measuring next (at a coarser one it may lengthen edges
        // already too long for the target: every edge is measured again)
        refine_options.adjacency_valid = true;
        if (&split_field == &target && row.deferred_edges == 0)
            refine_options.first_candidate_vertex = vertices_before;
        s.report.passes.push_back(row);
        if (s.options.verbosity >= 2)
            emit(s.options.messages, MessageKind::Report, "%s", format_pass_row(row).c_str());
        if (s.options.progress) s.options.progress("pass " + std::to_string(pass), row.tets);
        if (s.options.verbosity >= 1)
            emit(s.options.messages, MessageKind::Progress, "adapt: pass %d, %d tets", pass,
                 row.tets);
        if (refinement_stalled(s, first))
        {
            ++pass;
            return StageEnd::Stalled;
        }
    }
    return StageEnd::Capped;
}

/// Refinement passes until no edge is too long for `target` (or they stall, or reach the
/// cap), in `stages` stages of coarser fields first (AdaptOptions::refine_stages).
void refine_to_field(AdaptState& s, const SizeField& target, int stages = 1)
{
    s.report.converged = !s.options.refine;
    s.report.stalled = false;
    if (!s.options.refine) return;
    int pass = static_cast<int>(s.report.passes.size()) + 1;
    const int last = pass + s.options.max_passes;
    RefinePassOptions refine_options;  // the first pass builds the adjacency
    refine_options.workers = s.options.workers;
    for (int k = std::max(stages, 1) - 1; k > 0; --k)
        refine_stage(s, ScaledSize(target, std::pow(s.options.refine_stage_factor, k)), target,
                     pass, last, refine_options);
    const StageEnd end = refine_stage(s, target, target, pass, last, refine_options);
    s.report.converged = end == StageEnd::Converged;
    s.report.stalled = end == StageEnd::Stalled;
}

/// One model on both sides: smooth vertices go onto the projection's HDI surface where the
/// input's facets are too coarse for the tolerance, trusted as far from their chords as those
/// are from the smooth surface; elsewhere the facets are the finer model.
void build_surface_model(AdaptState& s)
{
    const StageTimer timer(s.report.seconds_surface, s.report.cpu_seconds_surface);
    const surface::SurfaceMesh& input = s.input->surface;
    s.report.surface_triangles_before = static_cast<int>(input.n_faces());
    s.settings.model_surface = &input;
    s.settings.model = &s.model->build_surface_model(
        input, s.settings.hdi_projection,
        surface::distance_tolerance(s.settings, surface::bounding_box_diagonal(input)));
}

/// The boundary remeshed on the input's model, every change mirrored into the tets; the
/// refinement's later splits on the boundary land on the same model. Returns the sizes the
/// surface reached (the field's, or finer where the tolerance asked), by tet vertex.
std::vector<double> remesh_boundary(AdaptState& s)
{
    s.mesh.compact();
    if (!s.mesh.has_adjacency()) s.mesh.build_adjacency();
    BoundaryMap boundary = extract_boundary(s.mesh);
    const surface::SurfaceHooks hooks =
        make_hooks(s.mesh, boundary, s.options.mirror, &s.report.mirror);
    surface::remesh_surface(boundary.surface, s.settings, hooks);
    s.model->place_on_surface_model();
    write_back(boundary, s.mesh);
    std::vector<double> surface_size(s.mesh.num_vertices(), 0.0);
    const surface::SurfaceProperties props(boundary.surface);
    for (auto v : boundary.surface.vertices())
        surface_size[boundary.tet_vertex_of(v)] = boundary.surface.property(props.vertex_size, v);
    s.report.surface_remeshed = true;
    return surface_size;
}

/// The volume grades from the boundary's sizes to the field's (Mmg's hgrad) where the tolerance
/// made them finer than the field's band, so the tets between that boundary and a coarse
/// interior keep their shape. `surface_size` is by vertex before the compaction `maps`.
void grade_from_boundary(AdaptState& s, const std::vector<double>& surface_size,
                         const CompactionMaps& maps)
{
    std::vector<double> sizes = sample_vertex_sizes(s.mesh, s.field);
    bool finer = false;
    for (std::size_t old = 0; old < maps.old2new_verts.size(); ++old)
    {
        const int v = maps.old2new_verts[old];
        // (within the field's band the tets keep the field: its edges are not too short)
        if (v < 0 || !(surface_size[old] > 0.0) ||
            !(surface_size[old] < kSizeQualityThreshold * sizes[v]))
            continue;
        sizes[v] = surface_size[old];
        finer = true;
    }
    s.volume_field = &s.field;
    s.graded.reset();
    if (!finer) return;
    grade_vertex_sizes(s.mesh, sizes, std::max(1.0, s.settings.sizing.hgrad));
    s.graded = std::make_unique<BackgroundMeshSize>(s.mesh, std::move(sizes));
    s.volume_field = s.graded.get();
}

/// One surface pass, then the volume's splits to the graded field (the surface's bands and the
/// refills may leave a few edges too long on either side). True when those splits changed the
/// boundary enough to call for another pass; the optimization after does not change it.
bool surface_round(AdaptState& s)
{
    if (s.options.progress) s.options.progress("surface", s.mesh.num_live_tets());
    int remeshed = 0;
    {
        const StageTimer timer(s.report.seconds_surface, s.report.cpu_seconds_surface);
        const std::vector<double> surface_size = remesh_boundary(s);
        const CompactionMaps maps = s.mesh.compact();
        grade_from_boundary(s, surface_size, maps);
        remeshed = static_cast<int>(s.mesh.triangles.size());
    }
    ++s.report.surface_passes;
    refine_to_field(s, *s.volume_field);
    s.report.surface_triangles_after = static_cast<int>(s.mesh.triangles.size());
    return s.report.surface_triangles_after - remeshed > kSurfaceRepeatFraction * remeshed;
}

/// Per vertex: the vertices of the tets at a cut vertex that the final optimization would still
/// work on: below the target quality, or with a too-short edge it could collapse.
std::vector<char> left_at_cuts(const TetMesh& mesh, const SizeField& field,
                               const std::vector<char>& cuts, const OptimizeOptions& optimizer)
{
    std::vector<char> seeds(mesh.num_vertices(), 0);
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        const auto& tv = mesh.tets[t];
        if (mesh.is_dead(t) || std::none_of(tv.begin(), tv.end(), [&](int v) { return cuts[v]; }))
            continue;
        bool left = mesh.quality(t) < optimizer.target_quality;
        for (int e = 0; e < 6 && !left && optimizer.collapse; ++e)
        {
            const int a = tv[tet::kEdgeVertices[e][0]], b = tv[tet::kEdgeVertices[e][1]];
            left = measure_edge(field, mesh.points[a], mesh.points[b]).too_short();
        }
        if (left)
            for (int v : tv) seeds[v] = 1;
    }
    return seeds;
}

/// The final optimization, on a mesh renumbered along a space-filling curve; a large mesh in
/// blocks (volume/mesh/blocks.h), on the run's threads: once with the cuts frozen, then the
/// tets at those cuts cut elsewhere, then the few tets left bad where both rounds' cuts meet.
void optimize(AdaptState& s)
{
    if (!s.options.optimize) return;
    if (s.options.progress) s.options.progress("optimize", s.mesh.num_live_tets());
    const StageTimer timer(s.report.seconds_optimize, s.report.cpu_seconds_optimize);
    s.mesh.compact();  // renumbering needs a compact mesh; the passes leave it so, this makes sure
    renumber_spatially(s.mesh);
    const int blocks = volume::block_count(s.mesh.num_live_tets(), s.options.tets_per_block);
    if (blocks <= 1)
    {
        optimize_mesh(s.mesh, *s.volume_field, s.optimizer);
        return;
    }
    OptimizeOptions in_block = s.optimizer;  // a block runs on one thread, silent
    in_block.workers = nullptr;
    in_block.verbosity = 0;
    in_block.messages = nullptr;
    in_block.leave_required_vertex_balls = true;
    const auto work = [&](TetMesh& block, int) { optimize_mesh(block, *s.volume_field, in_block); };
    // (the renumbering put the tets in Morton order already: the first round cuts runs of ids)
    const std::vector<char> cuts = volume::run_in_blocks(
        s.mesh, volume::contiguous_blocks(s.mesh, blocks), s.options.workers, work);
    // the tets a block left (stuck against a cut, or with an edge too short there) and their
    // neighbours, cut elsewhere
    const std::vector<char> band = volume::tets_near(
        s.mesh, left_at_cuts(s.mesh, *s.volume_field, cuts, s.optimizer), kBandRings);
    const long long band_tets = std::count(band.begin(), band.end(), 1);
    volume::run_in_blocks(
        s.mesh,
        volume::morton_blocks(s.mesh, volume::block_count(band_tets, s.options.tets_per_block), 1,
                              &band),
        s.options.workers, work);
    // where both rounds' cuts meet
    OptimizeOptions repair = s.optimizer;
    repair.bad_quality = std::max(repair.bad_quality, repair.target_quality);
    improve_bad_elements(s.mesh, *s.volume_field, repair);
}

/// After a surface pass the boundary lies on the model already; else the refinement's
/// shortened moves are finished, and the tets they reshape brought back to the final
/// optimization's target, not only above the passes' "bad" threshold.
void finish(AdaptState& s)
{
    if (s.projector && !s.report.surface_remeshed)
    {
        {
            const StageTimer timer(s.report.seconds_project, s.report.cpu_seconds_project);
            s.report.final_projection = s.projector->project_all(s.mesh);
        }
        if (s.options.optimize &&
            s.report.final_projection.shortened + s.report.final_projection.projected > 0)
        {
            const StageTimer timer(s.report.seconds_optimize, s.report.cpu_seconds_optimize);
            OptimizeOptions repair = s.optimizer;
            repair.bad_quality = std::max(repair.bad_quality, repair.target_quality);
            improve_bad_elements(s.mesh, *s.volume_field, repair);
        }
    }
    if (!s.mesh.has_adjacency()) s.mesh.build_adjacency();
}

/// Tets still under the floor whose boundary vertices can slide along the model to better
/// shapes (the optimizer keeps the boundary fixed), then the tets around them repaired.
void raise_floor(AdaptState& s)
{
    // (in a metric the optimizer moves flat boundary vertices in their planes already)
    if (!s.model || !s.options.optimize || !s.options.slide_boundary || s.field.anisotropic())
        return;
    const StageTimer timer(s.report.seconds_optimize, s.report.cpu_seconds_optimize);
    const detail::BoundaryFloorOptions floor;
    OptimizeOptions repair = s.optimizer;
    repair.bad_quality = floor.floor;
    for (int round = 0; round < kFloorRounds; ++round)
    {
        if (detail::raise_boundary_floor(s.mesh, *s.model, floor).moves == 0) break;
        improve_bad_elements(s.mesh, *s.volume_field, repair);
    }
}

}  // namespace

AdaptReport adapt(TetMesh& mesh, const SizeField& field, const AdaptOptions& options)
{
    const Stopwatch clock;
    AdaptState state(mesh, field, options);
    if (!mesh.has_adjacency()) mesh.build_adjacency();
    refuse_unreachable_size(state);
    classify_boundary(state);
    build_projector(state);
    if (options.verbosity >= 2) emit(options.messages, MessageKind::Report, "%s", kPassHeader);
    refine_to_field(state, field, options.refine_stages);
    if (options.verbosity >= 1 && !state.report.passes.empty())
        emit(options.messages, MessageKind::Progress, "adapt: surface and final optimization...\n");
    // the surface pass places its points by sizes alone: in a metric the boundary, classified
    // all the same, is refined by the splits, landing on the model, and shaped by the volume's
    // operators
    const bool surface_pass = state.input && !field.anisotropic();
    if (state.input && !surface_pass)
        state.report.surface_refusal = "a metric: the boundary is split in it, not remeshed";
    if (state.input) build_surface_model(state);
    // (the splits land on the one model; HDI alone strays on stretched boundary triangles)
    if (state.input && !surface_pass) state.model->place_on_surface_model();
    for (int round = 0; surface_pass && round < kSurfaceRounds; ++round)
        if (!surface_round(state)) break;
    optimize(state);
    finish(state);
    raise_floor(state);
    state.report.seconds_total = clock.wall_seconds();
    state.report.cpu_seconds_total = clock.cpu_seconds();
    return std::move(state.report);
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
    if (report.surface_remeshed)
    {
        std::snprintf(line, sizeof line, "surface: %d triangles -> %d, on the input's model%s\n",
                      report.surface_triangles_before, report.surface_triangles_after,
                      report.surface_passes > 1
                          ? (", " + std::to_string(report.surface_passes) + " passes").c_str()
                          : "");
        out << line << report.mirror.format();
    }
    else if (!report.surface_refusal.empty())
    {
        out << "surface: kept (" << report.surface_refusal << ")\n";
    }
    if (!report.passes.empty())
    {
        int most = 0;
        for (const auto& p : report.passes) most = std::max(most, p.tets);
        std::snprintf(line, sizeof line, "refinement: %d passes, %d tets at most\n",
                      static_cast<int>(report.passes.size()), most);
        out << line;
    }
    const double rest = report.seconds_total - report.seconds_surface - report.seconds_refine -
                        report.seconds_project - report.seconds_optimize;
    std::snprintf(line, sizeof line,
                  "time: total %.3f s = surface %.3f + refine %.3f + project %.3f + optimize %.3f "
                  "+ other %.3f\n",
                  report.seconds_total, report.seconds_surface, report.seconds_refine,
                  report.seconds_project, report.seconds_optimize, rest);
    out << line;
    std::snprintf(line, sizeof line,
                  "cpu:  total %.3f s = surface %.3f + refine %.3f + project %.3f + optimize %.3f "
                  "+ other %.3f\n",
                  report.cpu_seconds_total, report.cpu_seconds_surface, report.cpu_seconds_refine,
                  report.cpu_seconds_project, report.cpu_seconds_optimize,
                  report.cpu_seconds_total - report.cpu_seconds_surface -
                      report.cpu_seconds_refine - report.cpu_seconds_project -
                      report.cpu_seconds_optimize);
    out << line;
    out << (report.converged ? "sizes: no edge too long\n"
            : report.stalled
                ? "sizes: refinement stopped with a few edges too long that splitting does not "
                  "shorten\n"
                : "sizes: refinement stopped at the pass cap with edges too long\n");
    return out.str();
}

}  // namespace hdimesh::coupling
