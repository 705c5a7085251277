#pragma once
// adapt(): the paper's coupled adaptation of a tet mesh and its boundary to a size field.
//
//   classify           the input boundary's features (one detector, both meshes)
//   model  = HDI model of the input boundary                 (once)
//   repeat                                                    (refinement passes)
//       refine_pass        split every too-long edge, patterns from the 239-table
//       project            new boundary vertices onto the model, never inverting a tet
//       improve_bad        remove elements below Qe 0.2 around the changes
//   until no edge is too long
//   surface pass       the boundary remeshed on the input's model to the field (split,
//                      collapse, flip, shift; coarsening too), every change mirrored into the
//                      tets; the field then grades from the boundary's sizes where the
//                      tolerance made them finer; refinement passes again for what it left long,
//                      their new boundary vertices onto the surface pass's model
//   optimize_mesh      collapse too-short edges, swap and smooth to the end
//   project_all        (no surface pass) finish the moves that were shortened, improve again

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/messages.h"
#include "common/parallel.h"
#include "common/size_field.h"
#include "coupling/boundary_projection.h"
#include "coupling/mirror.h"
#include "surface/remesh_surface.h"
#include "volume/mesh/tet_mesh.h"
#include "volume/optimize/optimize.h"
#include "volume/refine/refine.h"

namespace hdimesh::coupling
{

struct AdaptOptions
{
    bool refine = true;    ///< split too-long edges (--noinsert turns it off)
    bool optimize = true;  ///< improve after each pass and at the end (--no-optimize)
    bool project = true;   ///< keep boundary vertices on the HDI model (--no-projection)
    int max_passes = 40;   ///< refinement passes at most
    /// The first refinement reaches the field in stages: to refine_stage_factor^k times its
    /// size for k = refine_stages - 1 down to 0 (the field itself). A stage's long edges are
    /// split together, mostly whole tets at once (the table's 1:8 pattern), which leaves far
    /// fewer short edges for the optimizer to collapse than splitting each edge as soon as it
    /// is too long (figures: docs/tuning.md). 1: one stage.
    int refine_stages = 3;
    double refine_stage_factor = 1.6;
    /// Remesh the boundary to the field on the input's model, mirrored into the tets (off:
    /// --nosurf, the boundary is only split and projected). Skipped, with the reason in the
    /// report, when coupled_surface_refusal() refuses the mesh.
    bool surface = true;
    /// Last, boundary vertices of tets under the quality floor slide along the model
    /// (coupling/detail/boundary_floor.h; off with --nosurf or --nomove).
    bool slide_boundary = true;
    /// > 0: the boundary's distance bound to the input (--hausd); else the surface remesher's
    /// default (0.0016 of the diagonal for a uniform size, 0.002 otherwise).
    double hausd = 0.0;
    /// The surface pass's settings; its sizes (hsiz, or the field itself) and hausd come from
    /// the field and `hausd`.
    surface::SurfaceRemeshSettings surface_settings;
    /// The boundary's features, found once for both meshes: the HDI model's and the surface
    /// pass's (surface_settings.features is set from it).
    hdi::FeatureOptions features;
    MirrorOptions mirror;
    /// The boundary the HDI model is fitted to (its triangles, refs, ridges and corners) when
    /// the mesh is a piece of the domain (a rank's part) whose own boundary has cuts; null:
    /// the mesh's boundary.
    std::shared_ptr<const volume::TetMesh> geometry;
    volume::OptimizeOptions optimizer;
    ProjectionOptions projection;
    /// 0 silent; 1 a progress line per pass; 2 also a table row per pass as the passes run
    /// (and the optimizer's and surface pass's own lines, at their verbosity).
    int verbosity = 1;
    /// Where those lines go (Progress and Report messages); empty: nowhere.
    MessageSink messages;
    /// Told after each refinement pass ("pass 3") and as the surface pass and the final
    /// optimization start, with the live tet count; it may throw to stop the run.
    std::function<void(const std::string& stage, int tets)> progress;
    /// The run's thread pool (common/parallel.h), owned by the caller; null: one thread. The
    /// output does not depend on its thread count.
    Workers* workers = nullptr;
    /// The grain of the decomposition the mutating stages run on (volume/mesh/blocks.h): a
    /// mesh of n tets is cut into about n / tets_per_block blocks; 0: no blocks. The output
    /// depends on it, never on the thread count.
    int tets_per_block = 65536;
};

/// One refinement pass: what it split, the mesh after it, what the projection did.
struct AdaptPassReport
{
    int pass = 0;
    int edges_split = 0;
    int tets = 0, vertices = 0;        ///< after the pass
    int projected = 0, shortened = 0;  ///< new boundary vertices (ProjectionReport's counts)
    int deferred_edges = 0;            ///< RefinePassReport::deferred_edges
    double min_quality = 0;
    double seconds = 0;
};

struct AdaptReport
{
    std::vector<AdaptPassReport> passes;
    bool converged = false;  ///< no edge too long when refinement stopped
    /// Refinement stopped early: a few splits a pass, not decreasing (see adapt()).
    bool stalled = false;
    double seconds_refine = 0, seconds_project = 0, seconds_optimize = 0, seconds_total = 0;
    /// The same split in CPU time of the calling thread: on a shared machine wall time
    /// measures the neighbours too.
    double cpu_seconds_refine = 0, cpu_seconds_project = 0, cpu_seconds_optimize = 0,
           cpu_seconds_total = 0;
    ProjectionReport final_projection;
    /// The surface pass: why it did not run (empty: it ran, or options.surface was off).
    std::string surface_refusal;
    bool surface_remeshed = false;
    int surface_triangles_before = 0, surface_triangles_after = 0;
    /// Surface passes run: another follows while the volume's splits change the boundary.
    int surface_passes = 0;
    MirrorStatistics mirror;
    double seconds_surface = 0, cpu_seconds_surface = 0;
};

/// Mmg's switches, as the tools and the Python module take them.
struct AdaptSwitches
{
    bool noinsert = false;  ///< no vertex inserted or removed: no split, collapse or surface pass
    bool noswap = false, nomove = false;  ///< no edge/face removal; no smoothing
    bool nosurf = false;                  ///< keep the boundary (only split and projected)
    bool optim = false;        ///< optimize only, at the input's sizes (no split or collapse)
    bool no_optimize = false;  ///< refinement (and projection) only
    bool no_projection = false;
    bool no_ridges = false;     ///< no ridge found by angle (declared ones kept)
    double ridge_angle = 45.0;  ///< degrees
};

/// `options` as the switches ask, for a tet input (refine, optimize, surface, the optimizer's
/// operators, the features of the surface pass and of the boundary model).
void apply_switches(const AdaptSwitches& switches, AdaptOptions& options);

/// Adapts mesh in place. \pre mesh passes check_mesh (positive tets, closed boundary).
/// Throws InputError when the boundary cannot carry a surface model.
/// Ids are not kept: the output is compact and, before the final optimization, renumbered
/// along a space-filling curve (volume/mesh/reorder.h); refs, boundary triangles, feature edges,
/// corners and vertex classes are carried. A solver that needs to transfer fields maps them
/// by position (e.g. volume/mesh/point_locator.h on the old mesh), not by id.
AdaptReport adapt(volume::TetMesh& mesh, const SizeField& field, const AdaptOptions& options = {});

/// The time split and the size verdict, preceded by the per-pass table when with_passes.
std::string format_adapt_report(const AdaptReport& report, bool with_passes = true);

}  // namespace hdimesh::coupling
