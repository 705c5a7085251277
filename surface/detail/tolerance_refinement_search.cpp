// Which model points are far from the output: the proofs that a point is near (its face of last
// time, a short walk from it), the output's tree for the others, and the caches both read (the
// output's triangles, the model points in space order).

#include <algorithm>
#include <cassert>
#include <limits>
#include <vector>

#include "common/morton.h"
#include "surface/detail/local_ops_geometry.h"
#include "surface/detail/tolerance_refinement.h"

namespace hdimesh::surface::detail
{
namespace
{

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

}  // namespace

// visit(h) for the outgoing halfedges h of v in turn, until one returns true (then true).
// (By the halfedges themselves: cheaper than OpenMesh's circulators in the refinement's walks,
// docs/tuning.md.)
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

// The ranks of the model points a round searches: in the first round those its face of last
// time does not prove near; later, of the points still far after the round before, those
// whose hit no longer holds (a hit that still holds goes into far_hits as it was, see
// still_closest) and that are not proven near now.
std::vector<std::size_t> ToleranceRefinement::unproven_points(bool first_round,
                                                              const std::vector<FarHit>& far_known,
                                                              std::vector<FarHit>& far_hits)
{
    const std::size_t point_count = space_order_.size();
    std::vector<std::size_t> unproven;  // ranks
    // (Reserved: the first call's first round has all of them, not grown by doubling.)
    unproven.reserve(first_round ? point_count : far_known.size());
    if (first_round)
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
    return unproven;
}

// The unproven points (by rank) searched in the output's tree; a far one's hit goes into
// far_hits. Consecutive model points are mostly neighbours: the last hit is the hint of the
// next search, and a point within the tolerance of it is near without a search.
void ToleranceRefinement::search_far_points(const std::vector<std::size_t>& unproven,
                                            std::vector<FarHit>& far_hits)
{
    if (unproven.empty()) return;
    rebuild_output_tree();
    const ClosestPointTree& output = output_tree_;
    const std::vector<FaceHandle>& face_of = output_tree_faces_;  // per triangle of `output`
    std::vector<int>& triangle_of = refine_scratch_.triangle_of;
    detail::reserve_with_room(triangle_of, mesh_.n_faces());
    triangle_of.assign(mesh_.n_faces(), -1);
    for (std::size_t t = 0; t < face_of.size(); ++t)
        triangle_of[face_of[t].idx()] = static_cast<int>(t);
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
        const bool alone = output.alone_within(point, hit.primitive,
                                               hit.distance * hit.distance * (1.0 + kAloneMargin));
        far_hits.push_back({hit.distance, i, face_of[hit.primitive], alone, refine_round_});
    }
}

}  // namespace hdimesh::surface::detail
