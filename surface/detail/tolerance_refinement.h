#pragma once
// The two-sided tolerance refinement: triangles whose centroid or edge midpoints leave the model,
// and triangles closest to a model point they pass far from, get their longest edge split (or,
// after the polish, a vertex snapped), farthest first, within a budget of short edges. Its
// caches (the output's triangles, the proofs that a model point is near, the model points in
// space order, the output tree) live across its calls and are kept up to date from the change log.

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "surface/detail/change_log.h"
#include "surface/detail/closest_point_tree.h"
#include "surface/detail/keep_tolerance.h"
#include "surface/detail/vector_room.h"

namespace hdimesh::surface::detail
{

// A model point farther than the tolerance from the output, and its closest output face (the
// first in the output tree's order among equally close ones; reused in the next round only
// when alone, where no order among ties is involved).
struct FarHit
{
    double distance;
    std::size_t point;
    FaceHandle face;
    bool alone;                 // no other face within the distance and a margin (kAloneMargin)
    std::uint32_t measured_in;  // the refinement round of the search
};

// ToleranceRefinement::refine's per-element scratch, all zero between rounds.
struct RefineScratch
{
    std::vector<double> edge_error;
    std::vector<std::size_t> edge_target;
    std::vector<EdgeHandle> marked;  // the edges with edge_error > 0
    std::vector<char> near_change, face_seen, edge_seen, snapped_now;
    std::vector<VertexHandle> changed;  // the vertices with near_change set
    std::vector<VertexHandle> snapped;  // the vertices with snapped_now set
    std::vector<int> triangle_of;       // (assigned whole when used)

    void grow(std::size_t vertices, std::size_t edges, std::size_t faces)
    {
        if (edge_error.size() < edges)
        {
            detail::resize_with_room(edge_error, edges, 0.0);
            detail::resize_with_room(edge_target, edges, std::size_t{0});
            detail::resize_with_room(edge_seen, edges, char{0});
        }
        if (near_change.size() < vertices)
        {
            detail::resize_with_room(near_change, vertices, char{0});
            detail::resize_with_room(snapped_now, vertices, char{0});
        }
        if (face_seen.size() < faces) detail::resize_with_room(face_seen, faces, char{0});
    }
    // The end of a round: the entries it set back to zero (near_change, face_seen and
    // edge_seen are cleared where they are used).
    void clear_round()
    {
        for (const EdgeHandle e : marked) edge_error[e.idx()] = 0.0, edge_target[e.idx()] = 0;
        marked.clear();
        for (const VertexHandle v : snapped) snapped_now[v.idx()] = 0;
        snapped.clear();
    }
};

// The edges short for the reference size (count_short_edges) while a refinement runs:

class ToleranceRefinement : private ToleranceStage
{
public:
    ToleranceRefinement(RemeshRun& run, ToleranceKeeper& keeper, ChangeLog& log,
                        const ToleranceOptions& tolerance,
                        const ToleranceRefinementOptions& options);

    /// One call of the refinement (rounds until nothing changes, the rounds or the budget run
    /// out); after_polish: the final budget, and snaps before splits. The number of changes.
    std::size_t refine(bool after_polish);

    /// The notes of the bounds reached (work, floor), one line each, into the report.
    void note_bounds_reached();

private:
    // One call of refine: its settings, and what a round hands on to the next.
    struct RefineCall
    {
        bool after_polish = false;
        bool snap = false;  // a far point is first offered a snap (after the polish)
        double budget = 0.0;
        std::vector<VertexHandle> split_vertices;  // of the last round (and ends of its flips)
        std::vector<VertexHandle> revisit;         // ends of the last round's candidates not tried
        std::vector<FarHit> far_known;             // the hits of the points still far after it
    };
    // A round's changes (splits and distance flips), splits, and the budget's counts.
    struct RoundCounts
    {
        std::size_t done = 0, splits = 0, short_edges = 0, edges = 0;
    };
    // An edge to split and its distance from the model.
    using EdgeCandidate = std::pair<double, EdgeHandle>;

    std::size_t refine_round(int round, RefineCall& call);
    void mark_near_changes(RefineCall& call);
    void mark_near_change(VertexHandle v);
    void prepare_round_caches();
    void check_chords(bool first_round);
    void check_face(FaceHandle f);
    void check_edge(EdgeHandle e);
    bool raise_error(EdgeHandle e, double distance);
    void mark_edge(EdgeHandle e, double distance, std::size_t target);
    void mark_longest(FaceHandle f, double distance, std::size_t target);
    bool snapped_end(EdgeHandle e) const;
    void note_snap(VertexHandle v, RefineCall& call);
    std::vector<std::size_t> unproven_points(bool first_round, const std::vector<FarHit>& far_known,
                                             std::vector<FarHit>& far_hits);
    void search_far_points(const std::vector<std::size_t>& unproven, std::vector<FarHit>& far_hits);
    std::size_t snap_or_mark_far_points(const std::vector<FarHit>& far_hits, RefineCall& call);
    std::vector<EdgeCandidate> split_candidates();
    std::size_t snap_chord_ends(const std::vector<EdgeCandidate>& candidates, RefineCall& call);
    std::size_t split_farthest(const std::vector<EdgeCandidate>& candidates, RefineCall& call,
                               RoundCounts& counts);
    bool flip_toward_model(EdgeHandle e, RefineCall& call);
    OpResult split_candidate(EdgeHandle e, double error, bool snap);
    void settle_new_vertices(const RefineCall& call);

    OpResult split_toward(EdgeHandle e, const Vec3d& target, bool part_of_the_way);
    OpResult split_beside(EdgeHandle e);
    bool clear_of_floor(EdgeHandle e, const Vec3d& p) const;
    EdgeHandle nearest_curve_edge(FaceHandle f, std::size_t point) const;
    VertexHandle snap_toward(std::size_t point, FaceHandle face, bool smooth_point);
    VertexHandle snap_vertex_of_edge(EdgeHandle e, const Vec3d& target);
    VertexHandle snap_one_of(std::vector<VertexHandle> vertices, const Vec3d& target,
                             bool smooth_point);
    FaceHandle near_face_around(const Vec3d& p, FaceHandle f) const;
    VertexHandle vertex_toward(const Vec3d& p, FaceHandle f) const;
    template <class Visit>
    bool any_outgoing(VertexHandle v, Visit visit) const;
    bool near_by_face_of(std::size_t i);
    void set_point_face(std::size_t i, FaceHandle f, bool proves_near);
    void rebuild_output_tree();
    void update_face_points();
    const std::vector<std::size_t>& model_points_in_space_order();
    std::size_t count_live_edges() const;
    bool still_closest(const FarHit& hit) const;
    std::size_t short_edges_now(bool first_round);

    const ToleranceRefinementOptions& options_;
    // The work bound shared by the calls (set at the first: work_per_face times its faces),
    // the work done (splits, snaps, flips), and the splits refused below the floor.
    bool work_limit_set_ = false;
    std::size_t work_limit_ = 0, work_done_ = 0, floor_refusals_ = 0;
    bool work_limit_reached_ = false;
    // Per edge, where its ends were when this call's snap of one of them was refused: not
    // tried again (each try projects its star's samples) until an end moves.
    std::vector<std::array<Vec3d, 2>> refused_snaps_;
    // Per model point, by rank in space order: the output face that last proved it within the
    // tolerance, or was its closest (invalid: none yet). Faces are garbage-collected at the end
    // of the pipeline only: handles hold across the whole call.
    std::vector<FaceHandle> point_face_;
    // The refinement rounds, counted over all calls (0: none): the round in which point_face_
    // proved a point near (0: it does not), and the last in which a face's points changed; a
    // proof holds while its face has not changed since.
    std::uint32_t refine_round_ = 0;
    std::vector<std::uint32_t> point_proven_in_, face_changed_in_;
    std::vector<FaceHandle>
        faces_changed_now_;  // the faces changed in this round (after a call's first)
    // model_points_in_space_order(): rank -> index, index -> rank, rank -> point.
    std::vector<std::size_t> space_order_, rank_in_space_order_;
    std::vector<Vec3d> points_in_space_order_;
    // Per output face / edge: the centroid / midpoint last proven within the tolerance of the
    // model (kNoPoint: none).
    std::vector<Vec3d> near_centroid_, near_midpoint_;
    // While a refinement runs: the points of each output face (by handle index; stale for a
    // deleted one), and the vertices whose faces changed since they were last brought up.
    std::vector<std::array<Vec3d, 3>> face_points_;
    bool face_points_stale_ = true;  // all to be gathered again (each refinement's first round)
    ChangedVertices face_changes_;
    RefineScratch refine_scratch_;
    // The refinement's tree of the output (rebuild_output_tree), its triangles' faces, and the
    // storage its triangles are gathered in.
    ClosestPointTree output_tree_;
    std::vector<FaceHandle> output_tree_faces_;
    std::vector<std::array<Vec3d, 3>> output_tree_triangles_;
    // While a refinement runs: which edges were short for the reference size at the last count
    // (short_edges_now), how many, and the vertices changed since.
    std::vector<char> edge_is_short_;
    std::size_t short_edge_count_ = 0;
    ChangedVertices short_edge_changes_;  // (edges_deleted: the next count is a full one)
};

}  // namespace hdimesh::surface::detail
