#include "surface/detail/tolerance_refinement.h"

#include <algorithm>
#include <cassert>
#include <cstdio>
#include <limits>

#include "common/messages.h"
#include "surface/detail/local_ops_geometry.h"
#include "surface/surface_quality.h"

namespace hdimesh::surface::detail
{
namespace
{

// A refinement round splits only where the distance is at least this fraction of its worst.
constexpr double kRefineFocus = 0.75;
// A point equal to none (NaN coordinates): "not proven near" in the refinement's caches.
const Vec3d kNoPoint(std::numeric_limits<double>::quiet_NaN());

}  // namespace

ToleranceRefinement::ToleranceRefinement(RemeshRun& run, ToleranceKeeper& keeper, ChangeLog& log,
                                         const ToleranceOptions& tolerance,
                                         const ToleranceRefinementOptions& options)
    : ToleranceStage(run, keeper, tolerance), options_(options)
{
    log.add(face_changes_);
    log.add(short_edge_changes_);
}

std::size_t ToleranceRefinement::count_live_edges() const
{
    std::size_t n = 0;
    for (auto e : mesh_.edges())
        if (!mesh_.status(e).deleted()) ++n;
    return n;
}

// The edges short for the reference size (count_short_edges) while a refinement runs:
// counted in full at its first round, after that kept up to date at the edges of the
// vertices its changes noted (an edge's length and sizes change only with an end's).
std::size_t ToleranceRefinement::short_edges_now(bool first_round)
{
    auto is_short = [&](EdgeHandle e) {
        return !mesh_.status(e).deleted() &&
               size_quality(mesh_.calc_edge_length(e), keeper_.reference_size(e)) <
                   kSizeQualityThreshold;
    };
    if (first_round || short_edge_changes_.edges_deleted)
    {
        short_edge_changes_.edges_deleted = false;
        detail::reserve_with_room(edge_is_short_, mesh_.n_edges());
        edge_is_short_.assign(mesh_.n_edges(), 0);
        short_edge_count_ = 0;
        for (auto e : mesh_.edges())
            if (is_short(e)) edge_is_short_[e.idx()] = 1, ++short_edge_count_;
    }
    else
    {
        detail::resize_with_room(edge_is_short_, mesh_.n_edges(), char{0});
        for (const VertexHandle v : short_edge_changes_.vertices)
            if (!mesh_.status(v).deleted())
                for (auto e : mesh_.ve_range(v))
                {
                    const char now = is_short(e) ? 1 : 0;
                    short_edge_count_ += now;
                    short_edge_count_ -= edge_is_short_[e.idx()];
                    edge_is_short_[e.idx()] = now;
                }
    }
    short_edge_changes_.vertices.clear();
    assert(short_edge_count_ == keeper_.count_short_edges());
    return short_edge_count_;
}

// The tolerance, both ways (the two halves of the Hausdorff distance): triangles whose
// centroid or edge midpoints leave the model, and triangles closest to a model point they
// pass far from, get their longest edge split, farthest first, then the new vertices settle
// by flips. Splits make short edges: they stop when the edges shorter than 0.66 of the
// reference size reach refine_short_edge_budget of all edges (after the polish:
// refine_final_short_edge_budget). After the polish, a far point is first offered a snap of
// a vertex of its closest triangle, a chord far from the model a snap of an end.
std::size_t ToleranceRefinement::refine(bool after_polish)
{
    // After the polish only a repair of a few triangles follows: the splits may spend the
    // final budget, and a vertex may be snapped instead of a split (earlier, the polish
    // would move it back).
    RefineCall call;
    call.after_polish = after_polish;
    call.snap = after_polish && tolerance_.snap_min_angle_deg > 0.0;
    call.budget = after_polish && options_.final_short_edge_budget >= 0.0
                      ? options_.final_short_edge_budget
                      : options_.short_edge_budget;
    std::size_t total = 0;
    if (!(tolerance_.tolerance > 0.0)) return total;
    // The output's triangles are kept from round to round (face_points_), the changes noted.
    face_points_stale_ = true;
    face_changes_.vertices.clear();
    short_edge_changes_.vertices.clear();
    face_changes_.recording = short_edge_changes_.recording = true;
    // After the first round only the points still far get another look. Splits bring the
    // output nearer to the model points; a flip can take it away from a point it passed near
    // and that point is not looked at again in this call (the full call after the cleanup
    // does; after the last one, the final Hausdorff measurement is the check).
    // The first round looks at every model point, by rank in space order (the points, and
    // their faces in point_face_, are then read in memory order); a later round at the points
    // still far after the round before, whose hits it keeps in call.far_known.
    model_points_in_space_order();
    refused_snaps_.clear();
    if (!work_limit_set_)
    {
        // Proportional to the mesh the loop made, never a time: outputs stay deterministic.
        std::size_t faces = 0;
        for (auto f : mesh_.faces())
            if (!mesh_.status(f).deleted()) ++faces;
        work_limit_set_ = true;
        work_limit_ =
            options_.work_per_face < 0.0
                ? std::numeric_limits<std::size_t>::max()
                : static_cast<std::size_t>(options_.work_per_face * static_cast<double>(faces)) +
                      options_.min_work;
    }
    for (int round = 0; round < options_.rounds; ++round)
    {
        if (work_done_ >= work_limit_)
        {
            work_limit_reached_ = true;
            break;
        }
        const std::size_t done = refine_round(round, call);
        total += done;
        if (done == 0) break;
        settle_new_vertices(call);
    }
    face_changes_.recording = short_edge_changes_.recording = false;
    short_edge_changes_.vertices.clear();
    return total;
}

// One round of refine: the distances measured where the round before changed the output, the
// far places snapped or marked, the marked edges split farthest first. The number of changes.
std::size_t ToleranceRefinement::refine_round(int round, RefineCall& call)
{
    // The per-element scratch of a round: members, kept zero between rounds (the entries a
    // round set are reset from its lists), so a round pays for what it touches only (not for
    // vectors of all edges, faces and vertices, nor their page faults).
    RefineScratch& scratch = refine_scratch_;
    scratch.grow(mesh_.n_vertices(), mesh_.n_edges(), mesh_.n_faces());
    mark_near_changes(call);
    prepare_round_caches();
    check_chords(round == 0);
    call.split_vertices.clear();
    // A point within the tolerance of its face of last time (or of a face found from it)
    // is near without a search: the closest face can only be nearer. Most points stay near
    // from one call to the next; the others are searched. A far point whose hit of the
    // round before still holds (still_closest) needs neither.
    std::vector<FarHit> far_hits;
    const std::vector<std::size_t> unproven = unproven_points(round == 0, call.far_known, far_hits);
    search_far_points(unproven, far_hits);
    // Farthest first: a vertex of the closest triangle snapped onto the point costs no
    // short edge; the points no snap reaches ask for a split.
    std::sort(far_hits.begin(), far_hits.end(), [](const FarHit& a, const FarHit& b) {
        return a.distance != b.distance ? a.distance > b.distance : a.point < b.point;
    });
    std::size_t snaps = snap_or_mark_far_points(far_hits, call);
    const std::vector<EdgeCandidate> candidates = split_candidates();
    if (call.snap) snaps += snap_chord_ends(candidates, call);
    report_.refinement_snaps += snaps;
    work_done_ += snaps;
    RoundCounts counts;
    counts.short_edges = short_edges_now(round == 0);
    counts.edges = count_live_edges();
    const std::size_t next = split_farthest(candidates, call, counts);
    report_.splits += counts.splits;
    report_.refinement_splits += counts.splits;
    counts.done += snaps;
    scratch.clear_round();
    if (run_.options.verbosity > 0)
        hdimesh::emit(run_.options.messages, hdimesh::MessageKind::Trace,
                      "remesh: refinement round %d: %zu snaps, %zu edges marked, %zu split, %zu "
                      "short edges of %zu\n",
                      round + 1, snaps, candidates.size(), counts.splits, counts.short_edges,
                      counts.edges);
    // The candidates left for later rounds are looked at again there.
    for (std::size_t left = next; left < candidates.size(); ++left)
    {
        const EdgeHandle e = candidates[left].second;
        if (mesh_.status(e).deleted()) continue;
        const auto h = mesh_.halfedge_handle(e, 0);
        call.revisit.push_back(mesh_.from_vertex_handle(h));
        call.revisit.push_back(mesh_.to_vertex_handle(h));
    }
    return counts.done;
}

// After the first round only the neighbourhood of the last splits changed (and the places
// refused before stay refused): the projections there only. (Round 0 looks at everything:
// none is marked then.)
void ToleranceRefinement::mark_near_changes(RefineCall& call)
{
    for (const VertexHandle v : call.split_vertices)
    {
        mark_near_change(v);
        for (auto w : mesh_.vv_range(v)) mark_near_change(w);
    }
    for (const VertexHandle v : call.revisit)
        if (!mesh_.status(v).deleted()) mark_near_change(v);
    call.revisit.clear();
}

// v noted changed in this round (RefineScratch::changed), once.
void ToleranceRefinement::mark_near_change(VertexHandle v)
{
    RefineScratch& scratch = refine_scratch_;
    if (scratch.near_change[v.idx()]) return;
    scratch.near_change[v.idx()] = 1;
    scratch.changed.push_back(v);
}

// The caches a round reads brought up to the mesh: a new round counted, the output's
// triangles, and room for the proofs of every face and edge.
void ToleranceRefinement::prepare_round_caches()
{
    // Near enough is decided by the hint face alone, mostly; the distance of a far one
    // ranks it. (A maximum per edge: the order of the faces and edges does not matter.)
    // A point proven near before (the same point: whether it is near depends on it alone)
    // is near again: after a cleanup most of the output is as the last call left it.
    if (point_face_.size() != tolerance_.model_points.size())
    {
        point_face_.assign(tolerance_.model_points.size(), FaceHandle());
        point_proven_in_.assign(tolerance_.model_points.size(), 0);
    }
    ++refine_round_;
    update_face_points();
    if (near_centroid_.size() < mesh_.n_faces())
        detail::resize_with_room(near_centroid_, mesh_.n_faces(), kNoPoint);
    if (near_midpoint_.size() < mesh_.n_edges())
        detail::resize_with_room(near_midpoint_, mesh_.n_edges(), kNoPoint);
}

// The chords off the model marked (check_face, check_edge): in the first round of every face
// and edge, later of those at a vertex noted changed, each once.
void ToleranceRefinement::check_chords(bool first_round)
{
    if (first_round)
    {
        for (auto f : mesh_.faces())
            if (!mesh_.status(f).deleted()) check_face(f);
        for (auto e : mesh_.edges())
            if (!mesh_.status(e).deleted()) check_edge(e);
        return;
    }
    RefineScratch& scratch = refine_scratch_;
    // The faces and edges at a changed vertex, each once.
    std::vector<char>&face_seen = scratch.face_seen, &edge_seen = scratch.edge_seen;
    for (const VertexHandle v : scratch.changed)
    {
        for (auto f : mesh_.vf_range(v))
            if (!face_seen[f.idx()]) face_seen[f.idx()] = 1, check_face(f);
        for (auto e : mesh_.ve_range(v))
            if (!edge_seen[e.idx()]) edge_seen[e.idx()] = 1, check_edge(e);
    }
    // (A check changes no connectivity: the same faces and edges, unmarked.)
    for (const VertexHandle v : scratch.changed)
    {
        scratch.near_change[v.idx()] = 0;
        for (auto f : mesh_.vf_range(v)) face_seen[f.idx()] = 0;
        for (auto e : mesh_.ve_range(v)) edge_seen[e.idx()] = 0;
    }
    scratch.changed.clear();
}

// f's centroid, unless proven near before, measured: near, it is proven; far, f's longest edge
// is marked. (The centroid from the face's points kept in face_points_, in the order of
// face_vertices: the same sum; most faces are proven near by the cache, and walking the mesh
// to their points cost more than the test.)
void ToleranceRefinement::check_face(FaceHandle f)
{
    const auto& t = face_points_[f.idx()];
    const Vec3d centroid = (t[0] + t[1] + t[2]) / 3.0;
    if (near_centroid_[f.idx()] == centroid) return;
    const VertexHandle hint =
        mesh_.from_vertex_handle(mesh_.halfedge_handle(f));  // face_vertices' first
    if (ctx_.near_model(centroid, hint, tolerance_.tolerance))
        near_centroid_[f.idx()] = centroid;
    else
        mark_longest(f, ctx_.distance_to_model(centroid, hint), 0);
}

// e's midpoint, unless proven near before, measured: near, it is proven; far, e is marked.
void ToleranceRefinement::check_edge(EdgeHandle e)
{
    const auto h = mesh_.halfedge_handle(e, 0);
    const VertexHandle a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
    const Vec3d mid = 0.5 * (mesh_.point(a) + mesh_.point(b));
    if (near_midpoint_[e.idx()] == mid) return;
    if (ctx_.near_model(mid, a, tolerance_.tolerance))
        near_midpoint_[e.idx()] = mid;
    else
        raise_error(e, ctx_.distance_to_model(mid, a));
}

// e's worst distance that asks for a split raised to `distance` if larger (then true); the
// edges given an error > 0 are listed once each (RefineScratch::marked).
bool ToleranceRefinement::raise_error(EdgeHandle e, double distance)
{
    RefineScratch& scratch = refine_scratch_;
    if (!(distance > scratch.edge_error[e.idx()])) return false;
    if (!(scratch.edge_error[e.idx()] > 0.0)) scratch.marked.push_back(e);
    scratch.edge_error[e.idx()] = distance;
    return true;
}

// raise_error, and where it raised, the model point the new vertex goes onto (index + 1; 0:
// none).
void ToleranceRefinement::mark_edge(EdgeHandle e, double distance, std::size_t target)
{
    if (raise_error(e, distance)) refine_scratch_.edge_target[e.idx()] = target;
}

// mark_edge of f's longest edge (the first of the longest in f's order).
void ToleranceRefinement::mark_longest(FaceHandle f, double distance, std::size_t target)
{
    EdgeHandle longest;
    double best = -1.0;
    for (auto e : mesh_.fe_range(f))
        if (mesh_.calc_edge_length(e) > best) best = mesh_.calc_edge_length(e), longest = e;
    mark_edge(longest, distance, target);
}

// Whether an end of e was moved by a snap in this round. (A split later in the round adds
// vertices, and an edge it cut ends at one of them.)
bool ToleranceRefinement::snapped_end(EdgeHandle e) const
{
    return has_marked_end(mesh_, e, refine_scratch_.snapped_now);
}

// v noted moved by a snap in this round, its neighbourhood to be measured in the next.
void ToleranceRefinement::note_snap(VertexHandle v, RefineCall& call)
{
    refine_scratch_.snapped_now[v.idx()] = 1;
    refine_scratch_.snapped.push_back(v);
    call.split_vertices.push_back(v);
}

// The far hits, farthest first: after the polish a vertex of the closest triangle snapped onto
// the point, else an edge of it marked for a split. The hits of the points still far go to
// call.far_known. The number of snaps.
std::size_t ToleranceRefinement::snap_or_mark_far_points(const std::vector<FarHit>& far_hits,
                                                         RefineCall& call)
{
    const std::vector<char>& snapped_now = refine_scratch_.snapped_now;
    std::vector<FarHit> still_far;  // this round's hits of the points still far after it
    std::size_t snaps = 0;
    for (const FarHit& far : far_hits)
    {
        const bool smooth =
            tolerance_.model_point_smooth.empty() || tolerance_.model_point_smooth[far.point];
        if (!mesh_.status(far.face).deleted())
        {
            // A snap earlier in the round moved a vertex of this triangle: its distance is
            // stale; the next round measures it again.
            if (call.snap && std::any_of(mesh_.fv_begin(far.face), mesh_.fv_end(far.face),
                                         [&](VertexHandle v) { return snapped_now[v.idx()] != 0; }))
            {
                still_far.push_back(far);
                continue;
            }
            const VertexHandle snapped =
                call.snap ? snap_toward(far.point, far.face, smooth) : VertexHandle();
            if (snapped.is_valid())
            {
                ++snaps;
                note_snap(snapped, call);
                continue;
            }
            // A curve point (of the input's boundary or ridges) is reached by a split of
            // the face's curve edge nearest to it: the new vertex goes onto the curve
            // beside it. The longest edge may be an interior one, whose split leaves the
            // curve's chord where it was (a scan's staircase boundary: never reached).
            const EdgeHandle curve_edge =
                smooth ? EdgeHandle() : nearest_curve_edge(far.face, far.point);
            if (curve_edge.is_valid())
                mark_edge(curve_edge, far.distance, 0);
            else
                mark_longest(far.face, far.distance, smooth ? far.point + 1 : 0);
        }
        still_far.push_back(far);
    }
    call.far_known = std::move(still_far);
    return snaps;
}

// The marked edges long enough to split, farthest first (ties by index: deterministic).
std::vector<ToleranceRefinement::EdgeCandidate> ToleranceRefinement::split_candidates()
{
    RefineScratch& scratch = refine_scratch_;
    std::vector<EdgeCandidate> candidates;
    std::sort(scratch.marked.begin(), scratch.marked.end());  // (the verbose lines in index order)
    for (const EdgeHandle e : scratch.marked)
    {
        if (mesh_.status(e).deleted()) continue;
        // Marked before a snap moved an end: the next round looks at it again.
        if (snapped_end(e)) continue;
        if (mesh_.calc_edge_length(e) >= 2.0 * tolerance_.min_length_ratio * run_.edge_size(e))
            candidates.emplace_back(scratch.edge_error[e.idx()], e);
        else if (run_.options.verbosity > 1)
            hdimesh::emit(
                run_.options.messages, hdimesh::MessageKind::Trace,
                "remesh: refinement skips a short edge: distance %.3g, length/size %.3f\n",
                scratch.edge_error[e.idx()], mesh_.calc_edge_length(e) / run_.edge_size(e));
    }
    // Farthest first; ties by index keep it deterministic.
    std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
        return a.first != b.first ? a.first > b.first : a.second.idx() < b.second.idx();
    });
    return candidates;
}

// Chords off the model (no far model point behind them): an end snapped toward the model
// point under the midpoint may bring the chord back, at no short edge. The number of snaps.
std::size_t ToleranceRefinement::snap_chord_ends(const std::vector<EdgeCandidate>& candidates,
                                                 RefineCall& call)
{
    std::size_t snaps = 0;
    for (const auto& [error, e] : candidates)
    {
        if (mesh_.status(e).deleted() || refine_scratch_.edge_target[e.idx()] > 0) continue;
        const auto he = mesh_.halfedge_handle(e, 0);
        const VertexHandle a = mesh_.from_vertex_handle(he), b = mesh_.to_vertex_handle(he);
        if (snapped_end(e)) continue;
        const std::array<Vec3d, 2> ends = {mesh_.point(a), mesh_.point(b)};
        const std::size_t i = static_cast<std::size_t>(e.idx());
        if (i < refused_snaps_.size() && refused_snaps_[i] == ends) continue;
        const Vec3d mid = 0.5 * (ends[0] + ends[1]);
        const ProjectedPoint on_model =
            ctx_.model.project_near(mid, VertexClass::Smooth, kNoCurve, ctx_.model_face(a));
        if (!on_model.ok) continue;
        const VertexHandle snapped = snap_vertex_of_edge(e, on_model.point);
        if (!snapped.is_valid())
        {
            if (refused_snaps_.size() <= i)
                refused_snaps_.resize(i + 1, {kNoPoint, kNoPoint});  // NaN: equal to nothing
            refused_snaps_[i] = ends;
            continue;
        }
        ++snaps;
        note_snap(snapped, call);
    }
    return snaps;
}

// The candidates split (or flipped) farthest first while the budget lasts, the counts kept up
// to date. The index of the first candidate not tried.
std::size_t ToleranceRefinement::split_farthest(const std::vector<EdgeCandidate>& candidates,
                                                RefineCall& call, RoundCounts& counts)
{
    // The budget goes to the worst places first: a round splits only near the worst
    // distance it could change (a refused split ahead of it does not hold the others
    // back, round after round); the next round sees the result.
    double worst = 0.0;
    std::size_t next = 0;
    for (; next < candidates.size(); ++next)
    {
        const auto& [error, e] = candidates[next];
        if (counts.done > 0 && error < kRefineFocus * worst) break;
        if (call.budget < 1.0 && static_cast<double>(counts.short_edges) >=
                                     call.budget * static_cast<double>(counts.edges))
            break;
        if (mesh_.status(e).deleted()) continue;
        if (snapped_end(e)) continue;
        if (work_done_ >= work_limit_)
        {
            work_limit_reached_ = true;
            break;
        }
        // Halves below the floor: the tolerance is out of reach there (the model is off its
        // own input, or the point is one of a spike's), not a reason to split without end.
        if (mesh_.calc_edge_length(e) < 2.0 * tolerance_.min_split_length)
        {
            ++floor_refusals_;
            continue;
        }
        const bool boundary = mesh_.is_boundary(e);
        const bool was_short = size_quality(mesh_.calc_edge_length(e), keeper_.reference_size(e)) <
                               kSizeQualityThreshold;
        // Onto the far model point if the triangles allow it, else at the projected midpoint.
        // Where splits are rationed (a size to keep), a chord across a crease first:
        // turned along it, it comes nearer at no short edge. Not when the tolerance is the
        // contract: a flip judged on its own samples may take the output away from model
        // points it passed near (the adaptive default would miss hausd).
        if (options_.short_edge_budget < 1.0 && !ctx_.is_feature(e) && flip_toward_model(e, call))
        {
            if (counts.done == 0) worst = error;
            ++counts.done;
            ++work_done_;
            continue;
        }
        const OpResult r = split_candidate(e, error, call.snap);
        if (!r.done()) continue;
        run_.set_size(r.vertex);
        call.split_vertices.push_back(r.vertex);
        if (counts.done == 0) worst = error;
        ++counts.done;
        ++counts.splits;
        ++work_done_;
        // The two halves and the new edges across: the budget's count follows the split.
        counts.edges += boundary ? 2 : 3;
        if (was_short) --counts.short_edges;  // replaced by its halves, counted below
        for (auto oh : mesh_.voh_range(r.vertex))
            if (size_quality(mesh_.calc_edge_length(mesh_.edge_handle(oh)),
                             keeper_.reference_size(mesh_.edge_handle(oh))) < kSizeQualityThreshold)
                ++counts.short_edges;
    }
    return next;
}

void ToleranceRefinement::note_bounds_reached()
{
    char text[200];
    if (work_limit_reached_)
    {
        std::snprintf(text, sizeof text,
                      "tolerance refinement: stopped at its work bound (%zu changes); the "
                      "surface may stray farther than the tolerance",
                      work_limit_);
        report_.notes.emplace_back(text);
    }
    if (floor_refusals_ > 0)
    {
        std::snprintf(text, sizeof text,
                      "tolerance refinement: %zu splits refused below the shortest edge it "
                      "makes (%.3g); the tolerance is out of reach there",
                      floor_refusals_, tolerance_.min_split_length);
        report_.notes.emplace_back(text);
    }
}

// A distance flip of interior edge e (its opposite vertices then noted changed); whether done.
bool ToleranceRefinement::flip_toward_model(EdgeHandle e, RefineCall& call)
{
    const auto h = mesh_.halfedge_handle(e, 0);
    const VertexHandle c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
    const VertexHandle d =
        mesh_.to_vertex_handle(mesh_.next_halfedge_handle(mesh_.opposite_halfedge_handle(h)));
    if (!try_flip(ctx_, e, FlipGoal::Distance).done()) return false;
    ++report_.flips;
    call.split_vertices.push_back(c);
    call.split_vertices.push_back(d);
    return true;
}

// A split of candidate e at `error` from the model: onto its far model point (part of the way
// after the polish), else at the projected midpoint, else beside it.
OpResult ToleranceRefinement::split_candidate(EdgeHandle e, double error, bool snap)
{
    const std::vector<std::size_t>& edge_target = refine_scratch_.edge_target;
    OpResult r;
    if (edge_target[e.idx()] > 0)
        r = split_toward(e, tolerance_.model_points[edge_target[e.idx()] - 1], snap);
    if (!r.done())
    {
        const auto h = mesh_.halfedge_handle(e, 0);
        const Vec3d mid = 0.5 * (mesh_.point(mesh_.from_vertex_handle(h)) +
                                 mesh_.point(mesh_.to_vertex_handle(h)));
        r = clear_of_floor(e, mid) ? try_split(ctx_, e) : refused(OpStatus::Geometry);
    }
    // A chord whose split the triangles refuse (its midpoint far off them, across a
    // bend): the longest other edge of a face beside it, so that the next round finds
    // the chord's neighbourhood finer.
    if (!r.done() && r.status == OpStatus::Geometry) r = split_beside(e);
    if (!r.done() && run_.options.verbosity > 1)
        hdimesh::emit(run_.options.messages, hdimesh::MessageKind::Trace,
                      "remesh: refinement split refused (layer %d), distance %.3g, "
                      "length/size %.3f\n",
                      static_cast<int>(r.status), error,
                      mesh_.calc_edge_length(e) / run_.edge_size(e));
    return r;
}

// The new vertices settle: quality flips of the edges around them. Known: this may turn a
// distance-flipped edge back (a distance flip accepts half the old quality). Protecting those
// edges is worse (docs/tuning.md): the refinement's outcome is fragile there. After the polish
// nothing checks the tolerance again: the settle flips keep it.
void ToleranceRefinement::settle_new_vertices(const RefineCall& call)
{
    for (const VertexHandle v : call.split_vertices)
    {
        const std::vector<EdgeHandle> around = run_.edges_of_faces_at(v);
        for (const EdgeHandle e : around)
        {
            if (mesh_.status(e).deleted()) continue;
            const bool flipped = call.after_polish ? keeper_.flip_keeping_tolerance(e)
                                                   : try_flip(ctx_, e, FlipGoal::Quality).done();
            if (flipped) ++report_.flips;
        }
    }
}

}  // namespace hdimesh::surface::detail
