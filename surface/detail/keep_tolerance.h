#pragma once
// Witnessed operators: a flip, collapse, shift or snap simulated first and refused when a model
// point around ends farther from the output than max(tolerance, before), or the changed
// triangles' samples (edge midpoints, centroids) stray farther from the model than before
// beyond the tolerance. The stages after the first refinement use them so as not to undo what
// it reached.

#include <cstddef>
#include <memory>

#include "surface/detail/point_grid.h"
#include "surface/detail/remesh_run.h"
#include "surface/remesh_surface.h"

namespace hdimesh::surface::detail
{

/// After the loop, a collapse for the reference size may leave edges up to this times it (Qt ≥
/// 0.69)...
inline constexpr double kReferenceCollapseLength = 1.45;
/// ... and no triangle with an angle under this (they happen beside ridges, where nothing repairs
/// them).
inline constexpr double kReferenceCollapseMinAngle = 30.0;

/// What a change in the repair stages after the polish must keep.
enum class Keep
{
    Nothing,              // the plain operator
    Tolerance,            // no model point around ends farther than max(tolerance, before), and
                          // the changed triangles' samples stray no farther than before beyond it
    ToleranceAndLengths,  // the same, and no new edge short for the reference size
};

/// What a tolerance-keeping collapse is for (its limits on the new triangles).
enum class CollapseFor
{
    Repair,  // of a needle: the worst Qe around must rise, new edges within the Qt band
    Budget,  // of a short edge: new edges up to kReferenceCollapseLength of the reference size,
             // no angle under kReferenceCollapseMinAngle, no quality gain asked
    Raise,   // as Repair, and a curve vertex along its own curve too (a triangle squeezed
             // between two curves, on a short curve edge)
};

class ToleranceKeeper
{
public:
    ToleranceKeeper(RemeshRun& run, const ToleranceOptions& options) : run_(run), options_(options)
    {
    }
    ToleranceKeeper(const ToleranceKeeper&) = delete;
    ToleranceKeeper& operator=(const ToleranceKeeper&) = delete;

    /// The size an edge is judged against for the short-edge budget.
    double reference_size(EdgeHandle e) const;
    /// The live edges short for the reference size (Qt < 0.66).
    std::size_t count_short_edges() const;
    /// The model points in a grid of cells of about one size, built on first use.
    const PointGrid& model_point_grid();
    /// The limits of a witnessed move of v (a snap, a curve fit).
    void set_move_limits(VertexHandle v, const Vec3d* target, double margin,
                         WitnessedMoveOptions& limits);
    /// try_snap_vertex within the limits of a witnessed move.
    bool try_snap(VertexHandle v, const Vec3d& target, bool raise_min_angle);
    /// A quality flip of e that keeps the tolerance.
    bool flip_keeping_tolerance(EdgeHandle e);
    /// A collapse of h (try_collapse with the limits of `purpose`) that keeps the tolerance.
    bool collapse_keeping_tolerance(HalfedgeHandle h, CollapseFor purpose = CollapseFor::Repair);
    /// Whether moving v to `after` keeps what `keep` asks.
    bool move_keeps(VertexHandle v, const Vec3d& after, Keep keep);
    /// A shift of v (shift_vertex) that keeps what `keep` asks.
    bool shift(VertexHandle v, const ShiftOptions& options, Keep keep);

private:
    RemeshRun& run_;
    SurfaceMesh& mesh_ = run_.mesh;
    OperatorContext& ctx_ = run_.ctx;
    const ToleranceOptions& options_;
    std::unique_ptr<PointGrid>
        model_point_grid_;  // of options_.model_points, built at the first use
};

/// What a stage after the loop works with: the run, the witnessed operators and the tolerance.
class ToleranceStage
{
protected:
    ToleranceStage(RemeshRun& run, ToleranceKeeper& keeper, const ToleranceOptions& tolerance)
        : run_(run), keeper_(keeper), tolerance_(tolerance)
    {
    }
    // Not copyable: the stages keep references to one another.
    ToleranceStage(const ToleranceStage&) = delete;
    ToleranceStage& operator=(const ToleranceStage&) = delete;

    RemeshRun& run_;
    SurfaceMesh& mesh_ = run_.mesh;
    OperatorContext& ctx_ = run_.ctx;
    RemeshReport& report_ = run_.report;
    ToleranceKeeper& keeper_;
    const ToleranceOptions& tolerance_;
};

}  // namespace hdimesh::surface::detail
