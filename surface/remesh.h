#pragma once
// The surface remesher's move-and-split step (pmp-style loop on a model): split too-long edges,
// collapse too-short ones, flip toward valence 6, George's nodal shifting with projection onto
// the model, repeated. Vertex classes, curves and refs are kept: features survive by
// construction. surfremesh's whole pipeline (refinement to a tolerance, cleanup) is
// remesh_surface (surface/remesh_surface.h).

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "common/messages.h"
#include "surface/local_ops.h"
#include "surface/projector.h"
#include "surface/surface_mesh.h"

namespace hdimesh::hdi
{
class HdiSurface;
}

namespace hdimesh::surface
{

struct RemeshOptions
{
    /// Target edge length at a point (required). Edges longer than 4/3 of it are split, shorter
    /// than 4/5 collapsed, which keeps Qt = min(h/L, L/h) ≥ 0.75 where the loop converges.
    std::function<double(const Vec3d&)> size;
    /// Optional: the same size told a model face near the point (ProjectedPoint::face, e.g.
    /// SizeMap::at): used instead of `size` when given, for the look-ups of a size on the model.
    std::function<double(const Vec3d&, int face_hint)> size_near;
    /// Rounds of split, collapse, flip and shift (docs/tuning.md).
    int iterations = 8;
    /// Operators refuse a change whose new triangles stray farther from the model (≤ 0: none).
    double max_model_distance = 0.0;
    /// The smallest angle a split across a crease may leave (replaces limits' own, which is the
    /// single operator's): in the remesher the flips after each split resolve such caps.
    double min_angle_across_crease_deg = 4.0;
    OperatorLimits limits;
    int verbosity = 0;  // > 0: one line per iteration (a Trace message)
    /// Where the verbose lines go (empty: dropped).
    MessageSink messages;
};

struct RemeshReport
{
    int iterations = 0;
    std::size_t splits = 0, collapses = 0, flips = 0, removals = 0, shifts = 0,
                refinement_splits = 0;
    std::size_t refinement_snaps = 0;  // vertices moved onto far model points
    /// One line per stage that stopped at its work bound or floor (the pipeline went on).
    std::vector<std::string> notes;
};

/// Remeshes `mesh` (classified by detect_features, or carrying the properties of
/// surface_mesh.h) on `model` by `options.iterations` rounds of the loop. Hooks see every
/// change; handles stay valid until the final garbage collection at the end of the call.
RemeshReport remesh(SurfaceMesh& mesh, const RemeshOptions& options, const Projector& model,
                    const SurfaceHooks& hooks = {});

/// The same on an HDI model (through HdiProjector): the entry point of the coupling code.
RemeshReport remesh(SurfaceMesh& mesh, const RemeshOptions& options, const hdi::HdiSurface& model,
                    const SurfaceHooks& hooks = {});

}  // namespace hdimesh::surface
