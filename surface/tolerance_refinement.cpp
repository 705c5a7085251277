#include "surface/detail/tolerance_refinement.h"

#include <algorithm>
#include <cassert>
#include <cstdio>
#include <limits>

#include "common/morton.h"
#include "surface/detail/local_ops_geometry.h"
#include "surface/surface_quality.h"

namespace hdimesh::surface::detail
{
namespace
{

// A refinement round splits only where the distance is at least this fraction of its worst.
constexpr double kRefineFocus = 0.75;
// The refinement's walk toward a model point from the face of the point before stops after
// this many vertices (a walk mostly takes a few: a longer one is the tree's job).
constexpr int kWalkSteps = 16;
// A far point's closest face is alone when no other face is within its distance times
// sqrt(1 + this): far above the rounding by which the tree's search may prefer a face as close.
constexpr double kAloneMargin = 1e-6;
// A far point's hit of the round before is looked at again only when the round changed at most
// this many faces (each is measured against it): after a round of many changes the tree's
// search costs less.
constexpr std::size_t kMaxChangedFacesForReuse = 1024;
// A refinement snap moves a vertex at most this fraction of the size (farther: a split's job).
constexpr double kMaxSnapDistance = 0.6;
// A split refused onto its far model point is tried these fractions of the way from the edge's
// midpoint (the snap's steps, try_snap_vertex).
constexpr double kSplitTowardSteps[] = {0.75, 0.5, 0.35};
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

// A split of e with its new vertex onto model point `target` (far from the output near e).
// Refused there (at a rim sharper than the size the new triangles turn past the split's 60°),
// part of the way from the edge's midpoint, projected onto the model, keeping the
// angles as a snap does: the midpoint split alone leaves the point almost as far and still
// spends the budget. Only after the polish, as the snaps: earlier the polish moves the vertex
// anyway (docs/tuning.md).
OpResult ToleranceRefinement::split_toward(EdgeHandle e, const Vec3d& target, bool part_of_the_way)
{
    OpResult r = try_split(ctx_, e, &target);
    // (A curve edge's split stays on its curve: the target is not its to reach.)
    if (r.done() || !part_of_the_way || ctx_.is_feature(e)) return r;
    const auto h = mesh_.halfedge_handle(e, 0);
    const VertexHandle a = mesh_.from_vertex_handle(h);
    const Vec3d pa = mesh_.point(a), pb = mesh_.point(mesh_.to_vertex_handle(h));
    const Vec3d mid = 0.5 * (pa + pb);
    // The new triangles keep no angle under the snap's bound or under the worst of the two
    // triangles before (else the worst angle falls, docs/tuning.md).
    std::vector<Vec3d> opposite;
    double old_min_angle = 180.0;
    for (const auto side : {h, mesh_.opposite_halfedge_handle(h)})
    {
        if (mesh_.is_boundary(side)) continue;
        const Vec3d c = mesh_.point(mesh_.to_vertex_handle(mesh_.next_halfedge_handle(side)));
        opposite.push_back(c);
        old_min_angle = std::min(old_min_angle, triangle_min_angle_deg(pa, pb, c));
    }
    const double min_angle = std::min(tolerance_.snap_min_angle_deg, old_min_angle);
    for (const double step : kSplitTowardSteps)
    {
        const ProjectedPoint on_model = ctx_.model.project_near(
            mid + step * (target - mid), VertexClass::Smooth, kNoCurve, ctx_.model_face(a));
        if (!on_model.ok) continue;
        const Vec3d& p = on_model.point;
        if (std::any_of(opposite.begin(), opposite.end(), [&](const Vec3d& c) {
                return triangle_min_angle_deg(pa, p, c) < min_angle ||
                       triangle_min_angle_deg(p, pb, c) < min_angle;
            }))
            continue;
        const OpResult partial = try_split(ctx_, e, &p);
        if (partial.done()) return partial;
    }
    return r;
}

// The curve edge (boundary or ridge) of f nearest to model point `point` (invalid: none).
EdgeHandle ToleranceRefinement::nearest_curve_edge(FaceHandle f, std::size_t point) const
{
    const Vec3d& q = tolerance_.model_points[point];
    EdgeHandle nearest;
    double best = 1e300;
    for (auto e : mesh_.fe_range(f))
    {
        if (!ctx_.is_feature(e)) continue;
        const auto h = mesh_.halfedge_handle(e, 0);
        const double d = (closest_point_on_segment(q, mesh_.point(mesh_.from_vertex_handle(h)),
                                                   mesh_.point(mesh_.to_vertex_handle(h))) -
                          q)
                             .sqrnorm();
        if (d < best) best = d, nearest = e;
    }
    return nearest;
}

// A vertex of `face` (the output triangle closest to model point `point`, far from it) moved
// onto the point: the nearest vertex that may go there (a smooth one onto a smooth point, a
// curve vertex onto a point of its curve) and whose move keeps the star's shape and sizes
// and brings no other model point around it out of the tolerance. Invalid handle: none.
VertexHandle ToleranceRefinement::snap_toward(std::size_t point, FaceHandle face, bool smooth_point)
{
    const Vec3d& target = tolerance_.model_points[point];
    std::vector<VertexHandle> vertices;
    for (auto v : mesh_.fv_range(face)) vertices.push_back(v);
    return snap_one_of(vertices, target, smooth_point);
}

// An end of chord e (far from the model) moved toward `target`, the model point under its midpoint.
VertexHandle ToleranceRefinement::snap_vertex_of_edge(EdgeHandle e, const Vec3d& target)
{
    const auto h = mesh_.halfedge_handle(e, 0);
    return snap_one_of({mesh_.from_vertex_handle(h), mesh_.to_vertex_handle(h)}, target, true);
}

// The first of `vertices`, nearest first, that try_snap_vertex moves toward `target`, with
// the star's edges kept in the Qt band of the reference size and the model points around
// the star and the target as witnesses.
VertexHandle ToleranceRefinement::snap_one_of(std::vector<VertexHandle> vertices,
                                              const Vec3d& target, bool smooth_point)
{
    std::sort(vertices.begin(), vertices.end(), [&](VertexHandle a, VertexHandle b) {
        const double da = (mesh_.point(a) - target).sqrnorm(),
                     db = (mesh_.point(b) - target).sqrnorm();
        return da != db ? da < db : a.idx() < b.idx();  // ties by index: deterministic
    });
    for (const VertexHandle v : vertices)
    {
        const VertexClass cls = ctx_.vertex_class(v);
        if (cls == VertexClass::Corner || (cls == VertexClass::Smooth) != smooth_point) continue;
        const double size = tolerance_.reference_size > 0.0
                                ? tolerance_.reference_size
                                : mesh_.property(ctx_.props.vertex_size, v);
        const Vec3d p = mesh_.point(v);
        if ((p - target).norm() > kMaxSnapDistance * size) continue;
        if (keeper_.try_snap(v, target, false))
        {
            run_.set_size(v);
            return v;
        }
    }
    return VertexHandle();
}

// visit(h) for the outgoing halfedges h of v in turn, until one returns true (then true).
// (By the halfedges themselves: OpenMesh's circulators cost a third more in the
// refinement's walks.)
template <class Visit>
bool ToleranceRefinement::any_outgoing(VertexHandle v, Visit visit) const
{
    const HalfedgeHandle first = mesh_.halfedge_handle(v);
    HalfedgeHandle h = first;
    do
    {
        if (visit(h)) return true;
        h = mesh_.next_halfedge_handle(mesh_.opposite_halfedge_handle(h));
    } while (h != first);
    return false;
}

// Output face f (if live), or else a face found from it, within the tolerance of p (invalid:
// none is), by the arithmetic of the tree's search, on the triangles kept up to date
// (update_face_points, face_points_: cheaper than walking the mesh to each face's points).
// Which face proves p near decides nothing else: a point not proven
// near here is measured by the tree, whose answer depends on the point alone.
FaceHandle ToleranceRefinement::near_face_around(const Vec3d& p, FaceHandle f) const
{
    if (!f.is_valid() || mesh_.status(f).deleted()) return FaceHandle();
    // (detail::within_triangle: a triangle whose box is clearly beyond the tolerance gets
    // no closest point: most triangles asked are around a face that is not near.)
    auto within_tolerance = [&](FaceHandle g) {
        return detail::within_triangle(p, face_points_[g.idx()], tolerance_.tolerance);
    };
    if (within_tolerance(f)) return f;
    // The faces around the vertex a walk from f toward p ends at: the first refinement's
    // points in space order are mostly a few faces from the one before, where f's own
    // vertices do not reach and the tree's search costs more than a few faces' tests.
    // (Which of the faces proves p near is no matter, their order neither.)
    const VertexHandle end = vertex_toward(p, f);
    FaceHandle found;
    any_outgoing(end, [&](HalfedgeHandle h) {
        const FaceHandle g = mesh_.face_handle(h);
        if (g.is_valid() && within_tolerance(g)) found = g;
        return found.is_valid();
    });
    if (found.is_valid()) return found;
    for (auto v : mesh_.fv_range(f))
    {
        if (v == end) continue;  // (its faces were just tried)
        for (auto g : mesh_.vf_range(v))
            if (g != f && within_tolerance(g)) return g;
    }
    return FaceHandle();
}

// From the corner of f nearest to p, the neighbour nearest to p while it is nearer than the
// vertex before, at most kWalkSteps times (a walk across the model costs more than the
// tree's search).
VertexHandle ToleranceRefinement::vertex_toward(const Vec3d& p, FaceHandle f) const
{
    VertexHandle v;
    double v_d2 = std::numeric_limits<double>::max();
    for (const VertexHandle w : detail::face_vertices(mesh_, f))
    {
        const double d2 = (mesh_.point(w) - p).sqrnorm();
        if (d2 < v_d2) v_d2 = d2, v = w;
    }
    for (int step = 0; step < kWalkSteps; ++step)
    {
        VertexHandle next;
        any_outgoing(v, [&](HalfedgeHandle h) {
            const VertexHandle w = mesh_.to_vertex_handle(h);
            const double d2 = (mesh_.point(w) - p).sqrnorm();
            if (d2 < v_d2) v_d2 = d2, next = w;
            return false;
        });
        if (!next.is_valid()) break;
        v = next;
    }
    return v;
}

// Model point of rank i (model_points_in_space_order) proven within the tolerance of the
// output: by its proof of an earlier round if that face has not changed since, else by its
// face of last time or a face near_face_around finds from it (which becomes its face).
bool ToleranceRefinement::near_by_face_of(std::size_t i)
{
    // Proven by a face unchanged since: near_face_around would find that face again at once.
    const FaceHandle f = point_face_[i];
    if (point_proven_in_[i] > 0 && f.is_valid() &&
        face_changed_in_[f.idx()] <= point_proven_in_[i] && !mesh_.status(f).deleted())
        return true;
    const FaceHandle near = near_face_around(points_in_space_order_[i], f);
    if (near.is_valid()) set_point_face(i, near, true);
    return near.is_valid();
}

// Model point of rank i's face: the one that proves it near this round, or the one nearest.
void ToleranceRefinement::set_point_face(std::size_t i, FaceHandle f, bool proves_near)
{
    point_face_[i] = f;
    point_proven_in_[i] = proves_near ? refine_round_ : 0;
}

// output_tree_ made a (lazy) tree over the live output faces in handle order, and
// output_tree_faces_ the face of each of its triangles, in the memory of the last round's.
// face_points_ up to date.
void ToleranceRefinement::rebuild_output_tree()
{
    output_tree_triangles_.clear();
    output_tree_faces_.clear();
    // (With room: the buffers the tree hands back were made exactly as long as the last
    // round's output, which grew since.)
    detail::reserve_with_room(output_tree_triangles_, mesh_.n_faces());
    detail::reserve_with_room(output_tree_faces_, mesh_.n_faces());
    for (auto f : mesh_.faces())
    {
        if (mesh_.status(f).deleted()) continue;
        output_tree_triangles_.push_back(face_points_[f.idx()]);
        output_tree_faces_.push_back(f);
    }
    output_tree_.rebuild_lazy(output_tree_triangles_);
}

// face_points_ brought up to the mesh: all faces at the first call of a refinement (its
// points gathered once: the mesh's connectivity is slow to walk), after that the faces at
// the vertices noted since.
void ToleranceRefinement::update_face_points()
{
    // A face whose points change (or that is new) is noted changed in this round.
    // (faces_changed_now_: those of a round after the first, each once.)
    const std::size_t known_faces = face_points_.size();
    detail::resize_with_room(face_changed_in_, mesh_.n_faces(), std::uint32_t{0});
    faces_changed_now_.clear();
    auto refresh = [&](FaceHandle f) {
        const std::array<Vec3d, 3> points = detail::face_points(mesh_, f);
        if (static_cast<std::size_t>(f.idx()) < known_faces && points == face_points_[f.idx()])
            return;
        face_points_[f.idx()] = points;
        if (face_changed_in_[f.idx()] != refine_round_ && !face_points_stale_)
            faces_changed_now_.push_back(f);
        face_changed_in_[f.idx()] = refine_round_;
    };
    if (face_points_stale_)
    {
        // (Stale, not cleared: a cleared vector is zero-filled again by the resize. Compared:
        // the faces the stages since the last refinement left as they were keep their proofs.)
        detail::resize_with_room(face_points_, mesh_.n_faces());
        for (auto f : mesh_.faces())
            if (!mesh_.status(f).deleted()) refresh(f);
        face_points_stale_ = false;
    }
    else
    {
        detail::resize_with_room(face_points_, mesh_.n_faces());
        for (const VertexHandle v : face_changes_.vertices)
            if (!mesh_.status(v).deleted())
                for (auto f : mesh_.vf_range(v)) refresh(f);
    }
    face_changes_.vertices.clear();
#ifndef NDEBUG
    for (auto f : mesh_.faces())
        assert(mesh_.status(f).deleted() || face_points_[f.idx()] == detail::face_points(mesh_, f));
#endif
}

// The model points' indices along a Z-order curve over their box (computed once): in that
// order a point is mostly next to the one before, whose face then proves it near without a
// search (the input's own order jumps at every row of its vertices and edges).
const std::vector<std::size_t>& ToleranceRefinement::model_points_in_space_order()
{
    if (space_order_.size() == tolerance_.model_points.size()) return space_order_;
    Vec3d lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const Vec3d& p : tolerance_.model_points)
    {
        lo.minimize(p);
        hi.maximize(p);
    }
    const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-300});
    std::vector<std::pair<std::uint64_t, std::size_t>> keyed(tolerance_.model_points.size());
    for (std::size_t i = 0; i < keyed.size(); ++i)
    {
        // Each axis over the box's largest extent, in cells 0..kMortonCellMax.
        std::uint64_t cell[3];
        for (int axis = 0; axis < 3; ++axis)
        {
            const double t = (tolerance_.model_points[i][axis] - lo[axis]) / extent;
            cell[axis] = static_cast<std::uint64_t>(std::clamp(t, 0.0, 1.0) * kMortonCellMax);
        }
        keyed[i] = {morton_key(cell[0], cell[1], cell[2]), i};
    }
    // Sorted by (key, index): a stable radix sort of the keys (the indices come in
    // increasing order), 11 bits a pass (faster than std::sort of the pairs).
    std::vector<std::pair<std::uint64_t, std::size_t>> sorted(keyed.size());
    constexpr int kDigitBits = 11;
    for (int shift = 0; shift < 3 * kMortonBitsPerAxis && !keyed.empty(); shift += kDigitBits)
    {
        std::vector<std::size_t> start((std::size_t(1) << kDigitBits) + 1, 0);
        auto digit = [&](std::uint64_t key) {
            return static_cast<std::size_t>((key >> shift) & ((1u << kDigitBits) - 1));
        };
        for (const auto& k : keyed) ++start[digit(k.first) + 1];
        if (start[digit(keyed.front().first) + 1] == keyed.size())
            continue;  // one digit: in order already
        for (std::size_t d = 1; d < start.size(); ++d) start[d] += start[d - 1];
        for (const auto& k : keyed) sorted[start[digit(k.first)]++] = k;
        keyed.swap(sorted);
    }
    assert(std::is_sorted(keyed.begin(), keyed.end()));
    space_order_.resize(keyed.size());
    rank_in_space_order_.resize(keyed.size());
    points_in_space_order_.resize(keyed.size());
    for (std::size_t i = 0; i < keyed.size(); ++i)
    {
        space_order_[i] = keyed[i].second;
        rank_in_space_order_[keyed[i].second] = i;
        points_in_space_order_[i] = tolerance_.model_points[keyed[i].second];
    }
    return space_order_;
}

std::size_t ToleranceRefinement::count_live_edges() const
{
    std::size_t n = 0;
    for (auto e : mesh_.edges())
        if (!mesh_.status(e).deleted()) ++n;
    return n;
}

// Whether `hit` of the round before holds in this one: its face alone close to the point,
// and unchanged since, and no face changed since within the distance and the margin: its
// face is then the only one that close and the output tree's search would find it again
// (whatever the tree's order among ties: there is none). Most far points stay far from one
// round to the next, away from the round's few splits. (faces_changed_now_ holds the faces
// changed in this round only: a hit of an earlier round is searched again.)
bool ToleranceRefinement::still_closest(const FarHit& hit) const
{
    const FaceHandle f = hit.face;
    if (!hit.alone || hit.measured_in + 1 != refine_round_ ||
        faces_changed_now_.size() > kMaxChangedFacesForReuse || mesh_.status(f).deleted() ||
        face_changed_in_[f.idx()] > hit.measured_in)
        return false;
    const Vec3d& p = tolerance_.model_points[hit.point];
    const double bound_d2 = hit.distance * hit.distance * (1.0 + kAloneMargin);
    for (const FaceHandle g : faces_changed_now_)
    {
        if (mesh_.status(g).deleted()) continue;
        const auto& t = face_points_[g.idx()];
        if (!detail::clearly_beyond(p, t, bound_d2) &&
            (closest_point_on_triangle(p, t[0], t[1], t[2]) - p).sqrnorm() <= bound_d2)
            return false;
    }
    return true;
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

// A split beside a chord whose own split the triangles refuse: the longest other edge of
// either face at it, when not too short to split.
OpResult ToleranceRefinement::split_beside(EdgeHandle e)
{
    OpResult result = refused(OpStatus::Geometry);
    for (int side = 0; side < 2 && !result.done(); ++side)
    {
        const FaceHandle f = mesh_.face_handle(mesh_.halfedge_handle(e, side));
        if (!f.is_valid()) continue;
        EdgeHandle longest;
        double best = 0.0;
        for (auto other : mesh_.fe_range(f))
            if (other != e && mesh_.calc_edge_length(other) > best)
                best = mesh_.calc_edge_length(other), longest = other;
        if (longest.is_valid() &&
            best >= 2.0 * tolerance_.min_length_ratio * run_.edge_size(longest))
            result = try_split(ctx_, longest);
    }
    return result;
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
    const bool snap = after_polish && tolerance_.snap_min_angle_deg > 0.0;
    const double budget = after_polish && options_.final_short_edge_budget >= 0.0
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
    std::vector<VertexHandle> split_vertices;  // of the last round (and ends of its distance flips)
    std::vector<VertexHandle> revisit;         // ends of the last round's candidates not tried
    // The first round looks at every model point, by rank in space order (the points, and
    // their faces in point_face_, are then read in memory order); a later round at the points
    // still far after the round before, whose hits it keeps in far_known.
    const std::size_t point_count = model_points_in_space_order().size();
    std::vector<FarHit> far_known;
    // The per-element scratch of a round: members, kept zero between rounds (the entries a
    // round set are reset from its lists), so a round pays for what it touches only (not for
    // vectors of all edges, faces and vertices, nor their page faults).
    RefineScratch& scratch = refine_scratch_;
    for (int round = 0; round < options_.rounds; ++round)
    {
        scratch.grow(mesh_.n_vertices(), mesh_.n_edges(), mesh_.n_faces());
        std::vector<double>& edge_error =
            scratch.edge_error;  // worst distance that asks for a split
        // A model point far from the output: the new vertex goes onto it (index + 1; 0: none).
        std::vector<std::size_t>& edge_target = scratch.edge_target;
        std::vector<EdgeHandle>& marked =
            scratch.marked;  // the edges given an error > 0, once each
        auto raise_error = [&](EdgeHandle e, double distance) {
            if (!(distance > edge_error[e.idx()])) return false;
            if (!(edge_error[e.idx()] > 0.0)) marked.push_back(e);
            edge_error[e.idx()] = distance;
            return true;
        };
        auto mark_edge = [&](EdgeHandle e, double distance, std::size_t target) {
            if (raise_error(e, distance)) edge_target[e.idx()] = target;
        };
        auto mark_longest = [&](FaceHandle f, double distance, std::size_t target) {
            EdgeHandle longest;
            double best = -1.0;
            for (auto e : mesh_.fe_range(f))
                if (mesh_.calc_edge_length(e) > best) best = mesh_.calc_edge_length(e), longest = e;
            mark_edge(longest, distance, target);
        };
        // After the first round only the neighbourhood of the last splits changed (and the
        // places refused before stay refused): the projections there only.
        // (Round 0 looks at everything: none is marked then.)
        std::vector<VertexHandle>& changed = scratch.changed;  // (after round 0)
        std::vector<char>& near_change = scratch.near_change;
        auto mark_changed = [&](VertexHandle v) {
            if (near_change[v.idx()]) return;
            near_change[v.idx()] = 1;
            changed.push_back(v);
        };
        for (const VertexHandle v : split_vertices)
        {
            mark_changed(v);
            for (auto w : mesh_.vv_range(v)) mark_changed(w);
        }
        for (const VertexHandle v : revisit)
            if (!mesh_.status(v).deleted()) mark_changed(v);
        revisit.clear();
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
        // (The centroid from the face's points kept in face_points_, in the order of
        // face_vertices: the same sum; most faces are proven near by the cache, and walking
        // the mesh to their points cost more than the test.)
        auto check_face = [&](FaceHandle f) {
            const auto& t = face_points_[f.idx()];
            const Vec3d centroid = (t[0] + t[1] + t[2]) / 3.0;
            if (near_centroid_[f.idx()] == centroid) return;
            const VertexHandle hint =
                mesh_.from_vertex_handle(mesh_.halfedge_handle(f));  // face_vertices' first
            if (ctx_.near_model(centroid, hint, tolerance_.tolerance))
                near_centroid_[f.idx()] = centroid;
            else
                mark_longest(f, ctx_.distance_to_model(centroid, hint), 0);
        };
        auto check_edge = [&](EdgeHandle e) {
            const auto h = mesh_.halfedge_handle(e, 0);
            const VertexHandle a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
            const Vec3d mid = 0.5 * (mesh_.point(a) + mesh_.point(b));
            if (near_midpoint_[e.idx()] == mid) return;
            if (ctx_.near_model(mid, a, tolerance_.tolerance))
                near_midpoint_[e.idx()] = mid;
            else
                raise_error(e, ctx_.distance_to_model(mid, a));
        };
        if (round == 0)
        {
            for (auto f : mesh_.faces())
                if (!mesh_.status(f).deleted()) check_face(f);
            for (auto e : mesh_.edges())
                if (!mesh_.status(e).deleted()) check_edge(e);
        }
        else
        {
            // The faces and edges at a changed vertex, each once.
            std::vector<char>&face_seen = scratch.face_seen, &edge_seen = scratch.edge_seen;
            for (const VertexHandle v : changed)
            {
                for (auto f : mesh_.vf_range(v))
                    if (!face_seen[f.idx()]) face_seen[f.idx()] = 1, check_face(f);
                for (auto e : mesh_.ve_range(v))
                    if (!edge_seen[e.idx()]) edge_seen[e.idx()] = 1, check_edge(e);
            }
            // (A check changes no connectivity: the same faces and edges, unmarked.)
            for (const VertexHandle v : changed)
            {
                near_change[v.idx()] = 0;
                for (auto f : mesh_.vf_range(v)) face_seen[f.idx()] = 0;
                for (auto e : mesh_.ve_range(v)) edge_seen[e.idx()] = 0;
            }
            changed.clear();
        }
        split_vertices.clear();
        std::vector<FarHit> still_far;  // this round's hits of the points still far after it
        std::vector<FarHit> far_hits;
        std::vector<char>& snapped_now = scratch.snapped_now;  // moved by a snap in this round
        // (A split later in the round adds vertices, and an edge it cut ends at one of them.)
        auto snapped_end = [&](EdgeHandle e) { return has_marked_end(mesh_, e, snapped_now); };
        // A point within the tolerance of its face of last time (or of a face found from it)
        // is near without a search: the closest face can only be nearer. Most points stay near
        // from one call to the next; the others are searched. A far point whose hit of the
        // round before still holds (still_closest) needs neither.
        std::vector<std::size_t> unproven;  // ranks
        // (Reserved: the first call's first round has all of them, not grown by doubling.)
        unproven.reserve(round == 0 ? point_count : far_known.size());
        if (round == 0)
        {
            for (std::size_t r = 0; r < point_count; ++r)
                if (!near_by_face_of(r)) unproven.push_back(r);
        }
        else
        {
            for (const FarHit& known : far_known)
            {
                const std::size_t r = rank_in_space_order_[known.point];
                if (still_closest(known))
                {
                    FarHit again = known;
                    again.measured_in = refine_round_;  // as good as a search of this round
                    far_hits.push_back(again);
                    set_point_face(r, again.face, false);
                    continue;
                }
                if (!near_by_face_of(r)) unproven.push_back(r);
            }
        }
        // Consecutive model points are mostly neighbours: the last hit is the hint of the
        // next search, and a point within the tolerance of it is near without a search.
        if (!unproven.empty()) rebuild_output_tree();
        const ClosestPointTree& output = output_tree_;
        const std::vector<FaceHandle>& face_of = output_tree_faces_;  // per triangle of `output`
        std::vector<int>& triangle_of = scratch.triangle_of;  // (only read when the tree is built)
        if (!unproven.empty())
        {
            detail::reserve_with_room(triangle_of, mesh_.n_faces());
            triangle_of.assign(mesh_.n_faces(), -1);
            for (std::size_t t = 0; t < face_of.size(); ++t)
                triangle_of[face_of[t].idx()] = static_cast<int>(t);
        }
        FaceHandle previous;
        for (const std::size_t r : unproven)
        {
            const std::size_t i = space_order_[r];
            const Vec3d& point = points_in_space_order_[r];
            const FaceHandle near = near_face_around(point, previous);
            if (near.is_valid())
            {
                set_point_face(r, previous = near, true);
                continue;
            }
            const auto hit =
                output.closest(point, previous.is_valid() ? triangle_of[previous.idx()] : -1);
            if (hit.primitive < 0) continue;
            const bool near_now = !(hit.distance > tolerance_.tolerance);
            set_point_face(r, previous = face_of[hit.primitive], near_now);
            if (near_now) continue;
            const bool alone = output.alone_within(
                point, hit.primitive, hit.distance * hit.distance * (1.0 + kAloneMargin));
            far_hits.push_back({hit.distance, i, face_of[hit.primitive], alone, refine_round_});
        }
        // Farthest first: a vertex of the closest triangle snapped onto the point costs no
        // short edge; the points no snap reaches ask for a split.
        std::sort(far_hits.begin(), far_hits.end(), [](const FarHit& a, const FarHit& b) {
            return a.distance != b.distance ? a.distance > b.distance : a.point < b.point;
        });
        std::size_t snaps = 0;
        for (const FarHit& far : far_hits)
        {
            const bool smooth =
                tolerance_.model_point_smooth.empty() || tolerance_.model_point_smooth[far.point];
            if (!mesh_.status(far.face).deleted())
            {
                // A snap earlier in the round moved a vertex of this triangle: its distance is
                // stale; the next round measures it again.
                if (snap && std::any_of(mesh_.fv_begin(far.face), mesh_.fv_end(far.face),
                                        [&](VertexHandle v) { return snapped_now[v.idx()] != 0; }))
                {
                    still_far.push_back(far);
                    continue;
                }
                const VertexHandle snapped =
                    snap ? snap_toward(far.point, far.face, smooth) : VertexHandle();
                if (snapped.is_valid())
                {
                    ++snaps;
                    snapped_now[snapped.idx()] = 1;
                    scratch.snapped.push_back(snapped);
                    split_vertices.push_back(snapped);
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
        far_known = std::move(still_far);
        std::vector<std::pair<double, EdgeHandle>> candidates;
        std::sort(marked.begin(), marked.end());  // (the verbose lines in index order)
        for (const EdgeHandle e : marked)
        {
            if (mesh_.status(e).deleted()) continue;
            // Marked before a snap moved an end: the next round looks at it again.
            if (snapped_end(e)) continue;
            if (mesh_.calc_edge_length(e) >= 2.0 * tolerance_.min_length_ratio * run_.edge_size(e))
                candidates.emplace_back(edge_error[e.idx()], e);
            else if (run_.options.verbosity > 1)
                std::fprintf(
                    stderr,
                    "remesh: refinement skips a short edge: distance %.3g, length/size %.3f\n",
                    edge_error[e.idx()], mesh_.calc_edge_length(e) / run_.edge_size(e));
        }
        // Farthest first; ties by index keep it deterministic.
        std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
            return a.first != b.first ? a.first > b.first : a.second.idx() < b.second.idx();
        });
        // Chords off the model (no far model point behind them): an end snapped toward the
        // model point under the midpoint may bring the chord back, at no short edge.
        for (const auto& [error, e] : candidates)
        {
            if (!snap) break;
            if (mesh_.status(e).deleted() || edge_target[e.idx()] > 0) continue;
            const auto he = mesh_.halfedge_handle(e, 0);
            const VertexHandle a = mesh_.from_vertex_handle(he), b = mesh_.to_vertex_handle(he);
            if (snapped_end(e)) continue;
            const Vec3d mid = 0.5 * (mesh_.point(a) + mesh_.point(b));
            const ProjectedPoint on_model =
                ctx_.model.project_near(mid, VertexClass::Smooth, kNoCurve, ctx_.model_face(a));
            if (!on_model.ok) continue;
            const VertexHandle snapped = snap_vertex_of_edge(e, on_model.point);
            if (!snapped.is_valid()) continue;
            ++snaps;
            snapped_now[snapped.idx()] = 1;
            scratch.snapped.push_back(snapped);
            split_vertices.push_back(snapped);
        }
        report_.refinement_snaps += snaps;
        std::size_t short_edges = short_edges_now(round == 0), edges = count_live_edges();
        std::size_t done = 0,
                    splits = 0;  // changes of the round (splits and distance flips), splits
        // The budget goes to the worst places first: a round splits only near the worst
        // distance it could change (a refused split ahead of it does not hold the others
        // back, round after round); the next round sees the result.
        double worst = 0.0;
        std::size_t next = 0;
        for (; next < candidates.size(); ++next)
        {
            const auto& [error, e] = candidates[next];
            if (done > 0 && error < kRefineFocus * worst) break;
            if (budget < 1.0 &&
                static_cast<double>(short_edges) >= budget * static_cast<double>(edges))
                break;
            if (mesh_.status(e).deleted()) continue;
            if (snapped_end(e)) continue;
            const bool boundary = mesh_.is_boundary(e);
            const bool was_short = size_quality(mesh_.calc_edge_length(e),
                                                keeper_.reference_size(e)) < kSizeQualityThreshold;
            // Onto the far model point if the triangles allow it, else at the projected midpoint.
            // Where splits are rationed (a size to keep), a chord across a crease first:
            // turned along it, it comes nearer at no short edge. Not when the tolerance is the
            // contract: a flip judged on its own samples may take the output away from model
            // points it passed near (the adaptive default would miss hausd).
            if (options_.short_edge_budget < 1.0 && !ctx_.is_feature(e))
            {
                const auto h = mesh_.halfedge_handle(e, 0);
                const VertexHandle c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
                const VertexHandle d = mesh_.to_vertex_handle(
                    mesh_.next_halfedge_handle(mesh_.opposite_halfedge_handle(h)));
                if (try_flip(ctx_, e, FlipGoal::Distance).done())
                {
                    if (done == 0) worst = error;
                    ++report_.flips;
                    split_vertices.push_back(c);
                    split_vertices.push_back(d);
                    ++done;
                    continue;
                }
            }
            OpResult r;
            if (edge_target[e.idx()] > 0)
                r = split_toward(e, tolerance_.model_points[edge_target[e.idx()] - 1], snap);
            if (!r.done()) r = try_split(ctx_, e);
            // A chord whose split the triangles refuse (its midpoint far off them, across a
            // bend): the longest other edge of a face beside it, so that the next round finds
            // the chord's neighbourhood finer.
            if (!r.done() && r.status == OpStatus::Geometry) r = split_beside(e);
            if (!r.done())
            {
                if (run_.options.verbosity > 1)
                    std::fprintf(stderr,
                                 "remesh: refinement split refused (layer %d), distance %.3g, "
                                 "length/size %.3f\n",
                                 static_cast<int>(r.status), error,
                                 mesh_.calc_edge_length(e) / run_.edge_size(e));
                continue;
            }
            run_.set_size(r.vertex);
            split_vertices.push_back(r.vertex);
            if (done == 0) worst = error;
            ++done;
            ++splits;
            // The two halves and the new edges across: the budget's count follows the split.
            edges += boundary ? 2 : 3;
            if (was_short) --short_edges;  // replaced by its halves, counted below
            for (auto oh : mesh_.voh_range(r.vertex))
                if (size_quality(mesh_.calc_edge_length(mesh_.edge_handle(oh)),
                                 keeper_.reference_size(mesh_.edge_handle(oh))) <
                    kSizeQualityThreshold)
                    ++short_edges;
        }
        report_.splits += splits;
        report_.refinement_splits += splits;
        done += snaps;
        scratch.clear_round();
        total += done;
        if (run_.options.verbosity > 0)
            std::fprintf(stderr,
                         "remesh: refinement round %d: %zu snaps, %zu edges marked, %zu split, %zu "
                         "short edges of %zu\n",
                         round + 1, snaps, candidates.size(), splits, short_edges, edges);
        // The candidates left for later rounds are looked at again there.
        for (; next < candidates.size(); ++next)
        {
            const EdgeHandle e = candidates[next].second;
            if (mesh_.status(e).deleted()) continue;
            const auto h = mesh_.halfedge_handle(e, 0);
            revisit.push_back(mesh_.from_vertex_handle(h));
            revisit.push_back(mesh_.to_vertex_handle(h));
        }
        if (done == 0) break;
        // The new vertices settle: quality flips of the edges around them. Known: this may
        // turn a distance-flipped edge back (a distance flip accepts half the old quality).
        // Protecting those edges is worse (docs/tuning.md): the refinement's outcome is
        // fragile there.
        // After the polish nothing checks the tolerance again: the settle flips keep it.
        for (const VertexHandle v : split_vertices)
        {
            const std::vector<EdgeHandle> around = run_.edges_of_faces_at(v);
            for (const EdgeHandle e : around)
            {
                if (mesh_.status(e).deleted()) continue;
                const bool flipped = after_polish ? keeper_.flip_keeping_tolerance(e)
                                                  : try_flip(ctx_, e, FlipGoal::Quality).done();
                if (flipped) ++report_.flips;
            }
        }
    }
    face_changes_.recording = short_edge_changes_.recording = false;
    short_edge_changes_.vertices.clear();
    return total;
}

}  // namespace hdimesh::surface::detail
