#pragma once
// The local operators of the surface remesher: edge split, edge collapse, edge flip, vertex
// removal and George's nodal shifting. Each checks in layers — topology (OpenMesh's own
// is_collapse_ok / is_flip_ok), vertex classes, the hooks' veto, geometry (no folded or turned
// triangle, distance to the model), quality — and only then commits and calls the on_* hook.
// A refusal is an OpResult with the layer that refused, never an exception.

#include <array>
#include <functional>
#include <vector>

#include "surface/projector.h"
#include "surface/surface_mesh.h"

namespace hdimesh::surface
{

/// Callbacks the coupling code uses to veto surface changes the tets cannot follow and to
/// mirror accepted ones. Every member is optional. allow_* are asked after the surface's own
/// checks pass; on_* are called right after the change is committed (before garbage collection).
struct SurfaceHooks
{
    /// Split of edge e with the new vertex at `point`.
    std::function<bool(const SurfaceMesh&, EdgeHandle e, const Vec3d& point)> allow_split;
    /// Edge (a, b) was split by `inserted`.
    std::function<void(const SurfaceMesh&, VertexHandle a, VertexHandle b, VertexHandle inserted)>
        on_split;
    /// Collapse of halfedge h: its from-vertex goes away, its to-vertex stays.
    std::function<bool(const SurfaceMesh&, HalfedgeHandle h)> allow_collapse;
    std::function<void(const SurfaceMesh&, VertexHandle removed, VertexHandle kept)> on_collapse;
    /// Flip of edge e (a, b) to (c, d).
    std::function<bool(const SurfaceMesh&, EdgeHandle e)> allow_flip;
    std::function<void(const SurfaceMesh&, VertexHandle a, VertexHandle b, VertexHandle c,
                       VertexHandle d)>
        on_flip;
    /// Move of v to `point`.
    std::function<bool(const SurfaceMesh&, VertexHandle v, const Vec3d& point)> allow_move;
    std::function<void(const SurfaceMesh&, VertexHandle v, const Vec3d& old_point)> on_move;
    /// Removal of v and retriangulation of its hole: allow_* is told the triangles it would
    /// add (outward, as the mesh will have them), on_* the faces it added.
    std::function<bool(const SurfaceMesh&, VertexHandle v,
                       const std::vector<std::array<VertexHandle, 3>>& new_triangles)>
        allow_remove_vertex;
    std::function<void(const SurfaceMesh&, VertexHandle removed,
                       const std::vector<FaceHandle>& new_faces)>
        on_remove_vertex;
};

/// Why an operator did or did not act.
enum class OpStatus
{
    Done,
    Topology,  // OpenMesh refuses, or the configuration is not manifold-safe
    Class,     // would move a corner, take a ridge vertex off its curve, cross a feature
    Hook,      // vetoed by an allow_* hook
    Geometry,  // a triangle would fold or turn too much, or leave the model
    Quality,   // legal but not better
    Disabled,  // this kind of change is turned off (OperatorLimits::insert, swap, move)
};

struct OpResult
{
    OpStatus status = OpStatus::Topology;
    VertexHandle vertex;  // the inserted vertex (split), the kept one (collapse)
    bool done() const { return status == OpStatus::Done; }
};

/// An operator's answer when the layer `why` refuses: nothing changed, no vertex.
inline OpResult refused(OpStatus why)
{
    OpResult result;
    result.status = why;
    return result;
}

/// Geometric limits shared by every operator.
struct OperatorLimits
{
    double max_normal_turn_deg = 35.0;  // a changed triangle may turn at most this much
    double max_model_distance = 0.0;    // > 0: new edge midpoints / centroids must stay this close
    double min_new_quality = 0.05;      // no operator creates a triangle with a lower Qe
    /// A split whose new vertex, on the model, turns its triangles past the turn limit (a chord
    /// across a crease the features dropped) leaves no triangle with a smaller angle than this.
    double min_angle_across_crease_deg = 10.0;
    /// Smooth shifts put George's ideal points in the model's tangent plane at the vertex (on
    /// the HDI model, its diffuse plane: method.md §5) instead of the ball's own plane; one
    /// projection more per shift.
    bool shift_in_model_plane = false;
    /// Which kinds of change are allowed at all (Mmg's -noinsert, -noswap, -nomove): splits,
    /// collapses and removals (a vertex more or less), flips, vertex moves.
    bool insert = true, swap = true, move = true;
};

/// Everything an operator needs; the remesher builds one per call.
struct OperatorContext
{
    SurfaceMesh& mesh;
    SurfaceProperties props;
    const Projector& model;  // must outlive the context
    /// A copy: a context built with `{}` (no hooks) would otherwise keep a reference to a
    /// temporary (ASan: stack-use-after-scope in a test that did).
    const SurfaceHooks hooks;
    OperatorLimits limits;

    OperatorContext(SurfaceMesh& m, const Projector& p, const SurfaceHooks& h,
                    OperatorLimits l = {})
        : mesh(m), props(m), model(p), hooks(h), limits(l)
    {
    }
    VertexClass vertex_class(VertexHandle v) const { return mesh.property(props.vertex_class, v); }
    int vertex_curve(VertexHandle v) const { return mesh.property(props.vertex_curve, v); }
    int edge_curve(EdgeHandle e) const { return mesh.property(props.edge_curve, e); }
    bool is_feature(EdgeHandle e) const { return edge_curve(e) != kNoCurve || mesh.is_boundary(e); }
    /// The model face v was last projected onto (-1: unknown): the hint of projections near v.
    int model_face(VertexHandle v) const { return mesh.property(props.vertex_model_face, v); }
    /// Whether p (a point of a triangle at `near`) is within `distance` of the smooth model.
    bool near_model(const Vec3d& p, VertexHandle near, double distance) const
    {
        return model.near_model(p, distance, model_face(near));
    }
    /// Distance from p (a point of a triangle at `near`) to the smooth model, searched from its
    /// face.
    double distance_to_model(const Vec3d& p, VertexHandle near) const
    {
        return model.distance_to_surface(p, model_face(near));
    }
    /// distance_to_model when beyond `tolerance`, else 0: most points of a tolerance check are
    /// proven near by near_model's short descent; only the others are measured.
    double distance_beyond(const Vec3d& p, VertexHandle near, double tolerance) const
    {
        return near_model(p, near, tolerance) ? 0.0 : distance_to_model(p, near);
    }
};

/// The last layers of every vertex move, once its geometry and quality passed: the caller's
/// allow_move, then the move (with `model_face` as v's new hint when ≥ 0) and on_move.
/// Done with `vertex` = v, or Hook with nothing changed.
inline OpResult commit_move(OperatorContext& ctx, VertexHandle v, const Vec3d& point,
                            int model_face)
{
    OpResult result;
    if (!ctx.limits.move) return refused(OpStatus::Disabled);
    if (ctx.hooks.allow_move && !ctx.hooks.allow_move(ctx.mesh, v, point))
    {
        result.status = OpStatus::Hook;
        return result;
    }
    const Vec3d old_point = ctx.mesh.point(v);
    ctx.mesh.set_point(v, point);
    if (model_face >= 0) ctx.mesh.property(ctx.props.vertex_model_face, v) = model_face;
    if (ctx.hooks.on_move) ctx.hooks.on_move(ctx.mesh, v, old_point);
    result.status = OpStatus::Done;
    result.vertex = v;
    return result;
}

/// Splits e at its midpoint projected onto the model (onto the edge's curve for a feature
/// edge). The new vertex gets the edge's class, curve and the mean size of the ends.
/// `at` (smooth edges only): put the new vertex there instead, a point of the model (an input
/// vertex the edge passes far from); refused like a projection that jumps too far.
OpResult try_split(OperatorContext& ctx, EdgeHandle e, const Vec3d* at = nullptr);

/// Collapses h (from-vertex removed, onto the to-vertex). Refused when a remaining edge would
/// become longer than max_new_length (≤ 0: no bound), or when the from-vertex is a corner, or a
/// curve vertex not collapsing along its own curve.
/// `require_quality_gain`: the worst Qe around must rise (used by the final cleanup).
/// `min_new_angle_deg` > 0: no changed triangle may get a smaller angle than this.
OpResult try_collapse(OperatorContext& ctx, HalfedgeHandle h, double max_new_length,
                      bool require_quality_gain = false, double min_new_angle_deg = 0.0);
/// Every layer of try_collapse (the shape layers below, the distance to the model, the hook's
/// veto), without committing: Done when try_collapse would commit. Each layer reads the stars of
/// h's two ends only (the remesher's collapse passes rely on it to skip an unchanged refusal).
OpStatus collapse_status(const OperatorContext& ctx, HalfedgeHandle h, double max_new_length,
                         bool require_quality_gain = false, double min_new_angle_deg = 0.0);
/// try_collapse's layers up to its distance to the model (class, length, topology, geometry,
/// quality), without committing: Done when they pass. A caller with an expensive check of its
/// own runs it after these (the collapse then re-checks them and commits).
OpStatus collapse_shape_status(const OperatorContext& ctx, HalfedgeHandle h, double max_new_length,
                               bool require_quality_gain = false, double min_new_angle_deg = 0.0);

/// What a flip must improve.
enum class FlipGoal
{
    Valence,  // pmp rule: valence deviation from 6 (4 on a boundary) decreases, quality kept
    Quality,  // the worst Qe of the two triangles rises
    /// The pair comes nearer the model (the farthest of the edge midpoint and the two centroids
    /// drops by a quarter: a chord across a crease turned along it) and keeps half its worst Qe.
    /// Its triangles may turn past the turn limit when each follows the model's normal under
    /// its centroid within it (a pair folded over a crease, laid onto the crease's sides).
    Distance,
};
OpResult try_flip(OperatorContext& ctx, EdgeHandle e, FlipGoal goal);

/// OpenMesh's topology test of a flip (TriConnectivity::is_flip_ok: not a boundary edge, the two
/// opposite vertices distinct and not yet joined by an edge), with the same answer, read through
/// the mesh's inline accessors (see flip_edge.cpp for why).
bool flip_topology_ok(const SurfaceMesh& mesh, EdgeHandle e);

/// The number of edges at v (OpenMesh's valence(v)), by the inline circulator.
int ring_valence(const SurfaceMesh& mesh, VertexHandle v);

/// Removes a smooth interior vertex of valence 3..8 and fills its hole with the triangulation of
/// the ring maximizing the worst Qe (dynamic program over the ring polygon); kept only if the
/// worst Qe of the area rises.
OpResult try_remove_vertex(OperatorContext& ctx, VertexHandle v);

struct ShiftOptions
{
    double step = 0.5;  // α: fraction of the way to the optimal point (0: only onto the model)
    bool smart = true;  // reject a move that lowers the worst Qe of the ball
    /// The caller's last layer (empty: none): asked with the point a trial would commit, after
    /// every layer of the shift passed; false refuses the shift (no smaller step is tried).
    std::function<bool(const Vec3d& point)> accept;
};
/// George's nodal shifting: the ideal point of each outer edge (apex of the equilateral
/// triangle on it, in the tangent plane), weights 1/Qe², P += α(P_opt − P), then projection
/// onto the model. Ridge/boundary vertices move along their curve toward the balanced point of
/// their two curve neighbours; corners never move.
OpResult shift_vertex(OperatorContext& ctx, VertexHandle v, const ShiftOptions& options = {});

struct SlideOptions
{
    /// Band of the star's edge lengths after the move (≤ 0: no bound); an edge already out of
    /// it may not get farther out. The narrow-corner cure allows a longer edge than the loop's
    /// 4/3·h: one long edge costs less than a needle at a corner.
    double min_length = 0.0, max_length = 0.0;
    /// > 0: the moved faces' centroids and edge midpoints stay within the larger of this and
    /// their worst distance before from the model (the refinement's tolerance); ≤ 0: within
    /// OperatorLimits::max_model_distance (if set).
    double tolerance = 0.0;
    int samples = 16;           // trial points toward each curve neighbour
    double min_gain_deg = 0.1;  // the worst angle must rise by at least this
};
/// Slides a ridge or boundary vertex along its curve (trial points toward its two curve
/// neighbours, up to 0.8 of the way, projected onto the curve) to the legal trial where the
/// worst angle of its star is largest; done when that angle beats the present one by
/// min_gain_deg. A trial is legal when no face turns past the operator limit, the edges keep
/// the band and the moved chords stay near the model. The cure for the narrow triangle at a
/// corner between two curves that open up away from it.
OpResult slide_curve_vertex(OperatorContext& ctx, VertexHandle v, const SlideOptions& options = {});

struct RelocateOptions
{
    /// Band of the star's edge lengths after the move, as SlideOptions's (≤ 0: no bound).
    double min_length = 0.0, max_length = 0.0;
    /// The star's faces under this Qe fall short by the difference: their summed shortfall
    /// must fall by min_gain (the worst Qe rise by it when none falls short), the worst Qe
    /// staying above min(its value, goal) - worst_slack.
    double goal = 0.7;
    double min_gain = 0.005;
    double worst_slack = 0.05;
    /// Halvings of the compass search that refines the best trial of a smooth vertex (0: none).
    int search_steps = 4;
    /// The caller's last layer (empty: none; the tolerance's witnesses), asked of the legal
    /// trials from the best down until one passes (at most three are asked).
    std::function<bool(const Vec3d& point)> accept;
};
/// Moves v to the trial point where the worst Qe of its star is largest: a smooth vertex tries
/// the apex of the equilateral triangle on each outer edge of its ball and George's point
/// (in the tangent plane, at three steps, projected onto the model), a curve vertex points
/// along its curve toward both curve neighbours. The cure where George's weighted balance sits
/// still: a right triangle beside a ridge whose opposite faces pull the other way.
OpResult relocate_vertex(OperatorContext& ctx, VertexHandle v, const RelocateOptions& options = {});

/// The limits of a vertex move judged against the model points around it (the snap and the
/// curve fit of the refinement).
struct WitnessedMoveOptions
{
    /// Distance to the model that counts as near, both ways (the refinement's tolerance).
    double tolerance = 0.0;
    /// No triangle of the star gets an angle under this (a star that had one already: under its
    /// worst).
    double min_angle_deg = 30.0;
    /// The star's edges stay within [min_length, max_length] (≤ 0: no bound); an edge out of the
    /// band before may not get farther out.
    double min_length = 0.0, max_length = 0.0;
    /// > 0: an edge already under min_length may get shorter, down to this, when no edge of the
    /// star newly leaves the band (the size quality counts the edges out of it).
    double floor_length = 0.0;
    /// Model points around the star: the snap lets none end farther from the output near v than
    /// the larger of the tolerance and its distance before; the curve fit minimizes their excess.
    std::vector<Vec3d> witnesses;
};

struct SnapOptions : WitnessedMoveOptions
{
    /// An angle repair instead: the target need not come near; the move must raise the star's
    /// smallest angle, with the same distance checks (it keeps what the refinement reached).
    bool raise_min_angle = false;
};
/// Moves v onto `target`, a point of the model the output passes far from (a smooth vertex onto
/// a model point; a ridge or boundary vertex onto a point of its own curve, between its two
/// curve neighbours; corners never), or when that is refused part of the way (3/4, 1/2, 0.35,
/// projected back onto the model). Accepted when the target comes within the tolerance of the
/// star's 2-ring, no triangle of the star turns past 60° or folds against the model, the star
/// keeps its angles and edge lengths (options), its centroids and edge midpoints stay within
/// max(tolerance, worst before) of the model, and no witness ends farther from the output.
/// Costs no vertex and no short edge, unlike a split. A refusal reports the full move's layer.
OpResult try_snap_vertex(OperatorContext& ctx, VertexHandle v, const Vec3d& target,
                         const SnapOptions& options);

}  // namespace hdimesh::surface
