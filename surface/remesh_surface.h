#pragma once
// surfremesh's pipeline: the move-and-split loop (remesh), then edges still too short for a
// reference size collapsed, a refinement where the output strays from the model farther than a
// tolerance (both ways: chords off the model, model points far from the output), a polish and a
// cleanup of the worst triangles, and a last refinement, the changes after it keeping the
// tolerance. Each stage's settings are its own struct; SurfaceRemeshSettings fills them all from
// an input surface.

#include <cstddef>
#include <vector>

#include "common/size_field.h"
#include "surface/features.h"
#include "surface/hdi_projection.h"
#include "surface/remesh.h"
#include "surface/sizing.h"
#include "surface/surface_mesh.h"

namespace hdimesh::surface
{

/// What the stages after the loop keep: the distance between the output and the model both
/// ways, measured at model points, and a reference size for the short edges they may make.
struct ToleranceOptions
{
    /// Geometric tolerance (> 0: on): after the loop, a triangle whose centroid or edge
    /// midpoints stray farther from the model, or that is the closest triangle to a point of
    /// `model_points` (the input vertices) farther away, has its longest edge split (projected
    /// onto the model), down to edges of min_length_ratio times the local size. The sizes alone
    /// miss a short crease or a spike narrower than an edge.
    double tolerance = 0.0;
    std::vector<Vec3d> model_points;
    /// Per model point: a smooth one (a split may put its new vertex onto it; a curve point
    /// only asks for a split at the projected midpoint). Empty: all smooth.
    std::vector<char> model_point_smooth;
    /// The shortest edge a refinement split or a witnessed move makes, times the size.
    double min_length_ratio = 0.3;
    /// > 0 (a uniform size): the size the short-edge budget and the witnessed moves' band are
    /// judged against; edges shorter than 0.66 of it are collapsed after the loop when no new
    /// edge gets longer than 1.45 of it and no angle under 30°. ≤ 0: the local size.
    double reference_size = 0.0;
    /// > 0: after the polish, before splitting, the refinement moves a vertex of the triangle
    /// nearest a far model point (or an end of a chord far from the model) toward it
    /// (try_snap_vertex) when no triangle of its star gets an angle under this (the curve fit
    /// and the angle repair too). ≤ 0: no snaps, fits or repair moves.
    double snap_min_angle_deg = 25.0;
    /// > 0: no refinement split of an edge shorter than twice this (a tolerance the model
    /// cannot reach, e.g. an HDI model off a coarse input's spikes, would split without end).
    double min_split_length = 0.0;
};

/// The refinement to the tolerance (ToleranceOptions).
struct ToleranceRefinementOptions
{
    int rounds = 12;
    /// A call stops when this fraction of the edges is shorter than 0.66 of the reference size
    /// (ToleranceOptions::reference_size, else the local size); ≥ 1: never.
    double short_edge_budget = 0.006;
    /// The same for the refinements after the polish, which only a repair of small angles that
    /// keeps the tolerance follows (no cleanup that would undo the splits). < 0: the same as
    /// short_edge_budget.
    double final_short_edge_budget = -1.0;
    /// The work bound of all the refinement calls of a pipeline together: splits, snaps and
    /// flips up to min_work plus this many times the faces at the first call (< 0: none). At
    /// the bound the refinement stops with a note (RemeshReport::notes), the pipeline goes on.
    double work_per_face = 20.0;
    std::size_t min_work = 4096;  // a coarse input may need many times its faces
};

/// The shape polish after the first refinement: quality flips and smart shifts.
struct PolishOptions
{
    int passes = 3;
    /// It works where a triangle misses this Qe (its vertices, and edges at them; ≥ 1:
    /// everywhere): the loop left the rest well shaped, and a smart shift only raises the worst
    /// Qe of its ball anyway.
    double below_quality = 0.7;
};

/// The worst-triangle cleanup, the angle repair and the needle slides.
struct CleanupOptions
{
    /// They work on triangles with a smaller angle than this.
    double angle_deg = 27.0;
    int rounds = 8;
    /// The last stage raises the triangles under this Qe before those under the polish's goal,
    /// in at most raise_rounds rounds each (0: no such stage).
    double room_quality = 0.8;
    int raise_rounds = 6;
};

/// Every stage's settings, for remesh_surface on a given model.
struct SurfaceRemeshOptions
{
    RemeshOptions loop;  // its size is required
    /// The mesh is not the model's own input (e.g. a refined boundary whose new vertices were
    /// placed on another model): first every vertex onto this model, where the hooks allow.
    bool project_first = false;
    ToleranceOptions tolerance;
    ToleranceRefinementOptions refinement;
    PolishOptions polish;
    CleanupOptions cleanup;
};

/// The pipeline on `model`: `mesh` classified by detect_features, or carrying the properties of
/// surface_mesh.h. Hooks see every change; handles stay valid until the final garbage
/// collection at the end of the call.
RemeshReport remesh_surface(SurfaceMesh& mesh, const SurfaceRemeshOptions& options,
                            const Projector& model, const SurfaceHooks& hooks = {});

/// Everything surfremesh needs, for one library call from an input surface.
/// The most triangles a surface may reach: OpenMesh numbers its 3·F halfedges in 32 bits.
inline constexpr double kMaxTriangles = 7.0e8;

struct SurfaceRemeshSettings
{
    FeatureOptions features;
    /// The mesh already carries its classes and curves (detect_features ran on it): keep them.
    bool keep_classification = false;
    /// Set: the model, its curvature sizes and the tolerance's points come from this classified
    /// surface (the input the mesh was derived from, e.g. before a refinement), whose curve ids
    /// the mesh's must match; input_sizes are then per vertex of it. It must outlive the call.
    const SurfaceMesh* model_surface = nullptr;
    /// Set: the model itself, built by the caller on model_surface (which must then be set), so
    /// that the caller places its own points on the same geometry; hdi_model and use_hdi are
    /// then ignored (attach_hdi_projection is the caller's). It must outlive the call.
    const SurfaceModel* model = nullptr;
    /// Set: smooth vertices go onto this HDI model of the model's surface (use_hdi with a model
    /// built already, e.g. the coupling's projection's), which must outlive the call.
    const hdi::HdiSurface* hdi_model = nullptr;
    /// Its trust bound: see HdiProjectionOptions.
    HdiProjectionOptions hdi_projection;
    SizingOptions sizing;  // hsiz > 0: uniform; else curvature from hausd (default 0.002·diag)
    std::vector<double>
        input_sizes;  // non-empty: a size per input vertex (--sol), bounded and graded
    /// Non-empty: per input vertex, an upper bound on whatever size is chosen there (a thin
    /// part's, surface/thickness.h), graded with it; infinity where none.
    std::vector<double> input_size_bounds;
    /// Set: the size anywhere (a volume's size field, already bounded and graded); it wins
    /// over hsiz and input_sizes. It must outlive the call.
    const SizeField* size_field = nullptr;
    int iterations = 8;  // RemeshOptions::iterations
    /// The kinds of change allowed (OperatorLimits::insert, swap, move; Mmg's -noinsert,
    /// -noswap, -nomove).
    bool insert = true, swap = true, move = true;
    /// With a uniform size: refine below it where the curvature needs it to stay within
    /// hausd (if given) or this fraction of the bbox diagonal (≤ 0: strictly uniform).
    double uniform_hausd_fraction = 0.0016;
    double uniform_size_floor = 0.85;  // ... but never below this fraction of hsiz
    /// ... or of this one when the curvature asks for edges too short for hsiz (Qt < 0.66) on
    /// more than this fraction of the area: the tolerance then wins over the size (a coarse
    /// size), the refinement to it has no short-edge budget.
    double coarse_size_floor = 0.2;
    double tolerance_wins_area_fraction = 0.05;
    /// Smooth vertices on the HDI model instead of the input facets. Off by default: it is
    /// slower and its projections near ridges leave slivers (docs/tuning.md).
    bool use_hdi = false;
    /// ... but on by default for a coarse input: when most of its area is on facets that may
    /// stray farther than the tolerance from the smooth surface they sample (the coupling's
    /// rule: coarse_input_options), trusted a quarter of an edge off.
    bool hdi_for_coarse_input = true;
    double max_model_distance = -1.0;  // < 0: from hausd (or 0.002·diag for a uniform size)
    /// Split where the output strays from the input by more than hausd (or, for a uniform size,
    /// uniform_hausd_fraction·diag) either way (ToleranceOptions::tolerance).
    bool refine_to_tolerance = true;
    double refine_short_edge_budget = 0.006;  // ToleranceRefinementOptions::short_edge_budget
    /// ToleranceRefinementOptions::final_short_edge_budget: the quality target allows 1 % of the
    /// edges under Qt 0.66, less 0.1 % for the repair (docs/tuning.md).
    double refine_final_short_edge_budget = 0.009;
    int verbosity = 0;
    /// Where the verbose lines go (Trace messages; empty: dropped).
    MessageSink messages;
};

struct SurfaceRemeshResult
{
    FeatureSummary features;
    RemeshReport report;
    double diagonal = 0.0;
    double uniform_size = 0.0;  // the size used when uniform, else the mean of the input sizes
    bool adaptive = false;
};

/// The distance between output and model that remesh_surface refines to, both ways: hausd when
/// given, else uniform_hausd_fraction of the diagonal for a uniform size, else 0.002 of it.
double distance_tolerance(const SurfaceRemeshSettings& settings, double diagonal);

/// The feature options remesh_surface classifies with: settings.features, with a corner
/// spacing of half the size when it sets none.
FeatureOptions feature_options(const SurfaceRemeshSettings& settings);

/// Detects features of `mesh`, builds the model from it, chooses the sizes and remeshes it in
/// place. The vertex size property of the result holds the target size at each vertex. Hooks
/// see every change (the coupling's mirror into the tets).
SurfaceRemeshResult remesh_surface(SurfaceMesh& mesh, const SurfaceRemeshSettings& settings,
                                   const SurfaceHooks& hooks = {});

}  // namespace hdimesh::surface
