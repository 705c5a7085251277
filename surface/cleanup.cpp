#include "surface/detail/cleanup.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <functional>
#include <queue>

#include "common/messages.h"
#include "surface/detail/local_ops_geometry.h"
#include "surface/fit_curve_vertex.h"
#include "surface/surface_quality.h"

namespace hdimesh::surface::detail
{
namespace
{

// A curve vertex slid at a narrow corner keeps its edges within this band: up to 1.5 times the
// larger of the local and the reference size (Qt ≥ 0.66 against a uniform size), down to 0.3 of
// the local size: one long edge costs less than a needle at a corner (docs/tuning.md).
constexpr double kSlideMaxLength = 1.5;
constexpr double kSlideMinLength = 0.3;
// Slide rounds: a slide on one side of a narrow corner lets the other side slide further
// (docs/tuning.md).
constexpr int kSlideRounds = 8;
// Sweeps of the curve fit (each vertex's best place moves with its neighbours').
constexpr int kCurveFitSweeps = 4;

}  // namespace

Cleanup::Cleanup(RemeshRun& run, ToleranceKeeper& keeper, ChangeLog& log,
                 const ToleranceOptions& tolerance, const CleanupOptions& options)
    : ToleranceStage(run, keeper, tolerance), options_(options),
      cleanup_angle_margin_cos_(cos_deg(options.angle_deg + 1.0))
{
    log.add(angle_changes_);
}

void Cleanup::polish(const PolishOptions& options)
{
    for (int pass = 0; pass < options.passes; ++pass)
    {
        const std::vector<char> near_poor = vertices_of_poor_triangles(options.below_quality);
        flip_edges(run_, FlipGoal::Quality, &near_poor);
        shift_vertices(run_, true, &near_poor);
    }
}

// Edges still too short for the reference size (Qt < 0.66) were kept by the loop's bound on
// the new edges (4/3 of the local size, to converge); once no more splits follow, a new
// edge may be as long as Qt allows against the reference size.
void Cleanup::collapse_short_for_reference()
{
    if (!(tolerance_.reference_size > 0.0)) return;
    const double max_new_length = kReferenceCollapseLength * tolerance_.reference_size;
    for (int pass = 0; pass < 3; ++pass)
    {
        std::size_t done = 0;
        const int edge_count = static_cast<int>(mesh_.n_edges());  // (a collapse adds no edge)
        for (int index = 0; index < edge_count; ++index)
        {
            const EdgeHandle e(index);
            if (mesh_.status(e).deleted() ||
                size_quality(mesh_.calc_edge_length(e), tolerance_.reference_size) >=
                    kSizeQualityThreshold)
                continue;
            // Curve edges keep the loop's sizes: a longer chord of a curved ridge leaves it.
            if (ctx_.is_feature(e)) continue;
            HalfedgeHandle hs[2] = {mesh_.halfedge_handle(e, 0), mesh_.halfedge_handle(e, 1)};
            if (run_.removal_rank(mesh_.from_vertex_handle(hs[1])) <
                run_.removal_rank(mesh_.from_vertex_handle(hs[0])))
                std::swap(hs[0], hs[1]);
            for (const HalfedgeHandle hh : hs)
                if (try_collapse(ctx_, hh, max_new_length, false, kReferenceCollapseMinAngle)
                        .done())
                {
                    ++done;
                    break;
                }
        }
        report_.collapses += done;
        if (done == 0) return;
    }
}

// Per vertex (by handle index): whether it is a corner of a live triangle with Qe under
// `quality` (all of them when quality >= 1).
std::vector<char> Cleanup::vertices_of_poor_triangles(double quality) const
{
    std::vector<char> poor(mesh_.n_vertices(), quality >= 1.0 ? 1 : 0);
    if (quality >= 1.0) return poor;
    const int face_count = static_cast<int>(mesh_.n_faces());
    for (int index = 0; index < face_count; ++index)
    {
        const FaceHandle f(index);
        if (mesh_.status(f).deleted()) continue;
        const auto fv = detail::face_vertices(mesh_, f);
        if (triangle_qe(mesh_.point(fv[0]), mesh_.point(fv[1]), mesh_.point(fv[2])) < quality)
            for (const VertexHandle v : fv) poor[v.idx()] = 1;
    }
    return poor;
}

// Before the final refinement: edges short for the reference size (Qt < 0.66) that the
// polish and the cleanup made, collapsed where the tolerance is kept, as the reference
// collapses do (new edges up to 1.45 of it, no angle under 30°): the final refinement's
// short-edge budget then goes to the far places.
std::size_t Cleanup::collapse_short_keeping_tolerance()
{
    std::size_t total = 0;
    if (!(tolerance_.reference_size > 0.0) || !(tolerance_.tolerance > 0.0)) return total;
    std::vector<VertexHandle> collapsed_onto;
    for (int pass = 0; pass < 3; ++pass)
    {
        std::size_t done = 0;
        const int edge_count = static_cast<int>(mesh_.n_edges());  // (a collapse adds no edge)
        for (int index = 0; index < edge_count; ++index)
        {
            const EdgeHandle e(index);
            if (mesh_.status(e).deleted() || ctx_.is_feature(e) ||
                size_quality(mesh_.calc_edge_length(e), tolerance_.reference_size) >=
                    kSizeQualityThreshold)
                continue;
            for (int i = 0; i < 2; ++i)
            {
                const HalfedgeHandle h = mesh_.halfedge_handle(e, i);
                const VertexHandle kept = mesh_.to_vertex_handle(h);
                if (!keeper_.collapse_keeping_tolerance(h, CollapseFor::Budget)) continue;
                collapsed_onto.push_back(kept);
                ++done;
                break;
            }
        }
        total += done;
        if (run_.options.verbosity > 0)
            hdimesh::emit(run_.options.messages, hdimesh::MessageKind::Trace,
                          "remesh: budget collapse pass %d: %zu collapses\n", pass + 1, done);
        if (done == 0) break;
    }
    // The stars of the kept vertices settle: quality flips and smart shifts that keep the
    // tolerance and make no new short edge.
    ShiftOptions smart;
    smart.smart = true;
    for (int sweep = 0; sweep < 2; ++sweep)
        for (const VertexHandle v : collapsed_onto)
        {
            if (mesh_.status(v).deleted()) continue;
            const std::vector<EdgeHandle> around = run_.edges_of_faces_at(v);
            for (const EdgeHandle e : around)
                if (!mesh_.status(e).deleted() && keeper_.flip_keeping_tolerance(e))
                    ++report_.flips;
            std::vector<VertexHandle> ring{v};
            for (auto w : mesh_.vv_range(v)) ring.push_back(w);
            for (const VertexHandle w : ring)
                if (!mesh_.status(w).deleted() &&
                    keeper_.shift(w, smart, Keep::ToleranceAndLengths))
                    ++report_.shifts;
        }
    report_.collapses += total;
    return total;
}

// Ridge and boundary vertices whose chords stray from the input polyline beyond the
// tolerance (either way) slid along their curve to the position that follows it best
// (fit_curve_vertex), in sweeps over the curves while something moves: a vertex's best
// place depends on its curve neighbours'. A vertex is tried again in a later sweep only when
// a vertex within two rings of it moved since its last try: its fit reads nothing farther
// (its star, the 2-ring patch, its witnesses and hint), so it would end as before; the later
// sweeps, which move few vertices, then cost little.
std::size_t Cleanup::fit_curves()
{
    std::size_t moved = 0;
    if (!(tolerance_.tolerance > 0.0) || !(tolerance_.snap_min_angle_deg > 0.0)) return moved;
    std::vector<char> unsettled(mesh_.n_vertices(), 1);  // (a fit moves only: no new vertex)
    for (int sweep = 0; sweep < kCurveFitSweeps; ++sweep)
    {
        std::size_t done = 0;
        for (auto v : mesh_.vertices())
        {
            const VertexClass cls = ctx_.vertex_class(v);
            if (mesh_.status(v).deleted() ||
                (cls != VertexClass::Ridge && cls != VertexClass::Boundary))
                continue;
            if (!unsettled[v.idx()]) continue;
            unsettled[v.idx()] = 0;
            // The witnesses within the star's own reach: the curve around v is what it fits.
            CurveFitOptions fit;
            keeper_.set_move_limits(v, nullptr, 0.0, fit);
            if (!fit_curve_vertex(ctx_, v, fit).done()) continue;
            run_.set_size(v);
            ++done;
            unsettled[v.idx()] = 1;
            for (auto w : mesh_.vv_range(v))
            {
                unsettled[w.idx()] = 1;
                for (auto x : mesh_.vv_range(w)) unsettled[x.idx()] = 1;
            }
        }
        moved += done;
        if (run_.options.verbosity > 0)
            hdimesh::emit(run_.options.messages, hdimesh::MessageKind::Trace,
                          "remesh: curve fit sweep %d: %zu moves\n", sweep + 1, done);
        if (done == 0) break;
    }
    report_.shifts += moved;
    return moved;
}

// The live faces with an angle under the cleanup's (face_angle_below), in handle order: the
// scan of all faces the first time, after that the faces found last time and those at the
// vertices changed since (a face gets a new angle only when a vertex of it moves or it is
// made anew, and every such change is noted): the same faces, at a fraction of the cost of
// a full scan per round that finds a few triangles.
std::vector<FaceHandle> Cleanup::faces_under_cleanup_angle()
{
    std::vector<FaceHandle> bad;
    if (!angle_changes_.recording)
    {
        const int face_count = static_cast<int>(mesh_.n_faces());
        for (int index = 0; index < face_count; ++index)
        {
            const FaceHandle f(index);
            if (!mesh_.status(f).deleted() && face_angle_below(f, options_.angle_deg))
                bad.push_back(f);
        }
        angle_changes_.recording = true;
    }
    else
    {
        std::vector<FaceHandle> suspects = std::move(faces_under_angle_);
        for (const VertexHandle v : angle_changes_.vertices)
            if (!mesh_.status(v).deleted())
                for (auto f : mesh_.vf_range(v)) suspects.push_back(f);
        std::sort(suspects.begin(), suspects.end());
        suspects.erase(std::unique(suspects.begin(), suspects.end()), suspects.end());
        for (const FaceHandle f : suspects)
            if (!mesh_.status(f).deleted() && face_angle_below(f, options_.angle_deg))
                bad.push_back(f);
    }
    angle_changes_.vertices.clear();
#ifndef NDEBUG
    std::vector<FaceHandle> scanned;
    for (auto f : mesh_.faces())
        if (!mesh_.status(f).deleted() && face_angle_below(f, options_.angle_deg))
            scanned.push_back(f);
    assert(scanned == bad);
#endif
    faces_under_angle_ = bad;
    return bad;
}

std::vector<int> Cleanup::face_indices(const std::vector<FaceHandle>& faces)
{
    std::vector<int> indices;
    indices.reserve(faces.size());
    for (const FaceHandle f : faces) indices.push_back(f.idx());
    return indices;
}

// Whether f's smallest angle (triangle_min_angle_deg) is under `degrees`. A triangle whose
// smallest angle is clearly larger (law of cosines, a degree of margin for its rounding) is
// answered without the three atan2: every cleanup round asks it of every face.
bool Cleanup::face_angle_below(FaceHandle f, double degrees) const
{
    const auto p = detail::face_points(mesh_, f);
    double l2[3] = {(p[1] - p[2]).sqrnorm(), (p[2] - p[0]).sqrnorm(), (p[0] - p[1]).sqrnorm()};
    std::sort(l2, l2 + 3);  // the smallest angle is opposite the shortest side
    const double cosine = (l2[1] + l2[2] - l2[0]) / (2.0 * std::sqrt(l2[1] * l2[2]));
    // (The cleanup's bound computed once: the first scan asks it of every face.)
    const double clearly_above =
        degrees == options_.angle_deg ? cleanup_angle_margin_cos_ : detail::cos_deg(degrees + 1.0);
    if (l2[0] > 0.0 && cosine < clearly_above) return false;
    return triangle_min_angle_deg(p[0], p[1], p[2]) < degrees;
}

// The worst triangles: try, in order, a quality flip of each edge, a collapse of the
// shortest edge that raises the worst Qe around, removal of a vertex, a smart shift of each
// vertex; repeat while something changes. Keep::Tolerance: between refinements, a change
// keeps what the refinement reached (no model point around ends farther than
// max(tolerance, before), see the *_keeping_tolerance operators; no vertex removal, which
// has no such check), except on a triangle under the snap's angle bound, which gets the
// plain cure when the tolerance-keeping one fails (the refinement after the cleanup looks
// at the tolerance again; without it the worst angle falls, docs/tuning.md).
void Cleanup::cleanup_worst_triangles(Keep keep)
{
    ShiftOptions smart;
    smart.smart = true;
    for (int round = 0; round < options_.rounds; ++round)
    {
        const std::vector<FaceHandle> bad = faces_under_cleanup_angle();
        if (bad.empty()) break;
        std::size_t changed = 0;
        for (const FaceHandle f : bad)
        {
            if (mesh_.status(f).deleted() || !face_angle_below(f, options_.angle_deg)) continue;
            if (improve_face(f, smart, keep)) ++changed;
            // Under the refinement moves' own angle bound, the angle comes first (the
            // refinement after the cleanup looks at the tolerance again).
            else if (keep != Keep::Nothing && face_angle_below(f, tolerance_.snap_min_angle_deg) &&
                     improve_face(f, smart, Keep::Nothing))
                ++changed;
        }
        if (run_.options.verbosity > 0)
            hdimesh::emit(run_.options.messages, hdimesh::MessageKind::Trace,
                          "remesh: cleanup round %d: %zu bad triangles, %zu improved\n", round + 1,
                          bad.size(), changed);
        if (changed == 0) break;
        // Let the neighbourhood settle after the topological changes.
        for (const FaceHandle f : bad)
        {
            if (mesh_.status(f).deleted()) continue;
            for (auto v : mesh_.fv_range(f))
                if (keeper_.shift(v, smart, keep)) ++report_.shifts;
        }
    }
}

bool Cleanup::improve_face(FaceHandle f, const ShiftOptions& smart, Keep keep)
{
    const bool keep_tolerance = keep != Keep::Nothing;
    std::vector<EdgeHandle> edges;
    for (auto e : mesh_.fe_range(f)) edges.push_back(e);
    std::sort(edges.begin(), edges.end(), [&](EdgeHandle a, EdgeHandle b) {
        return mesh_.calc_edge_length(a) > mesh_.calc_edge_length(b);
    });
    // The longest edge is opposite the largest angle: flipping it is the usual cure.
    for (const EdgeHandle e : edges)
        if (keep_tolerance ? keeper_.flip_keeping_tolerance(e)
                           : try_flip(ctx_, e, FlipGoal::Quality).done())
        {
            ++report_.flips;
            return true;
        }
    // The shortest edge of a needle: collapse it if the neighbourhood gets better.
    const EdgeHandle shortest = edges.back();
    const double h = run_.edge_size(shortest);
    for (int i = 0; i < 2; ++i)
        if (keep_tolerance
                ? keeper_.collapse_keeping_tolerance(mesh_.halfedge_handle(shortest, i))
                : try_collapse(ctx_, mesh_.halfedge_handle(shortest, i), kTooLong * h, true).done())
        {
            ++report_.collapses;
            return true;
        }
    std::vector<VertexHandle> vertices;
    for (auto v : mesh_.fv_range(f)) vertices.push_back(v);
    for (const VertexHandle v : vertices)
        if (!keep_tolerance && try_remove_vertex(ctx_, v).done())
        {
            ++report_.removals;
            return true;
        }
    bool moved = false;
    for (const VertexHandle v : vertices)
        if (!mesh_.status(v).deleted() && keeper_.shift(v, smart, keep))
        {
            ++report_.shifts;
            moved = true;
        }
    return moved;
}

std::size_t Cleanup::raise_poor_triangles(double quality, Keep keep)
{
    std::size_t changes = 0;
    // After the first round, only where the round before changed something (a vertex moved or
    // a face made, and their neighbours): elsewhere every trial would be refused again.
    std::vector<char> near_change;
    auto note_change = [&](VertexHandle v) {  // (no stage here adds a vertex)
        near_change[v.idx()] = 1;
        for (auto w : mesh_.vv_range(v)) near_change[w.idx()] = 1;
    };
    for (int round = 0; round < options_.raise_rounds; ++round)
    {
        const std::vector<char> seen = std::move(near_change);
        near_change.assign(mesh_.n_vertices(), 0);
        auto wanted = [&](VertexHandle v) {
            return round == 0 || (v.idx() < static_cast<int>(seen.size()) && seen[v.idx()]);
        };
        const std::vector<char> poor = vertices_of_poor_triangles(quality);
        std::size_t done = 0;
        for (int index = 0; index < static_cast<int>(poor.size()); ++index)
        {
            const VertexHandle v(index);
            if (!poor[index] || mesh_.status(v).deleted() || !wanted(v)) continue;
            RelocateOptions relocate;
            const double h =
                std::max(mesh_.property(ctx_.props.vertex_size, v), tolerance_.reference_size);
            relocate.goal = quality;
            relocate.min_length = kSizeQualityThreshold * h;
            relocate.max_length = h / kSizeQualityThreshold;
            relocate.accept = [&](const Vec3d& after) {
                return keeper_.move_keeps(v, after, keep);
            };
            if (!relocate_vertex(ctx_, v, relocate).done()) continue;
            if (ctx_.vertex_class(v) != VertexClass::Smooth) run_.set_size(v);
            note_change(v);
            ++report_.shifts;
            ++done;
        }
        // Where no relocation lifts a triangle: a flip, or a collapse of its shortest edge
        // (a row of vertices squeezed between a ridge and its neighbour; a curve edge too, of
        // a triangle squeezed between two curves).
        const int face_count = static_cast<int>(mesh_.n_faces());
        for (int index = 0; index < face_count; ++index)
        {
            const FaceHandle f(index);
            if (mesh_.status(f).deleted() || detail::qe(detail::face_points(mesh_, f)) >= quality)
                continue;
            const auto fv = detail::face_vertices(mesh_, f);
            if (!wanted(fv[0]) && !wanted(fv[1]) && !wanted(fv[2])) continue;
            std::vector<EdgeHandle> edges;
            for (auto e : mesh_.fe_range(f)) edges.push_back(e);
            std::sort(edges.begin(), edges.end(), [&](EdgeHandle a, EdgeHandle b) {
                return mesh_.calc_edge_length(a) < mesh_.calc_edge_length(b);
            });
            bool changed = false;
            for (const EdgeHandle e : edges)
                if (!changed && keeper_.flip_keeping_tolerance(e))
                {
                    ++report_.flips;
                    // (the new edge's ends, with their neighbours the old edge's)
                    for (int side = 0; side < 2; ++side)
                        note_change(mesh_.to_vertex_handle(mesh_.halfedge_handle(e, side)));
                    changed = true;
                }
            std::vector<HalfedgeHandle> collapses = {mesh_.halfedge_handle(edges[0], 0),
                                                     mesh_.halfedge_handle(edges[0], 1)};
            // A vertex of valence 3 or 4 (no relocation balances so few triangles): removed,
            // onto whichever neighbour the collapse allows.
            for (const VertexHandle v : fv)
                if (mesh_.valence(v) <= 4 && ctx_.vertex_class(v) == VertexClass::Smooth)
                    for (auto h : mesh_.voh_range(v))
                        if (mesh_.edge_handle(h) != edges[0]) collapses.push_back(h);  // (tried)
            for (std::size_t i = 0; i < collapses.size() && !changed; ++i)
            {
                const HalfedgeHandle h = collapses[i];
                const VertexHandle kept = mesh_.to_vertex_handle(h);
                if (keeper_.collapse_keeping_tolerance(h, CollapseFor::Raise))
                {
                    ++report_.collapses;
                    note_change(kept);
                    changed = true;
                }
            }
            if (changed) ++done;
        }
        if (run_.options.verbosity > 0)
            hdimesh::emit(run_.options.messages, hdimesh::MessageKind::Trace,
                          "remesh: raise round %d: %zu changes\n", round + 1, done);
        changes += done;
        if (done == 0) break;
    }
    return changes;
}

// The triangles the last refinement left under the cleanup's angle: their vertices moved
// toward the balanced point of their ring (on the model) when that raises the smallest
// angle of the star and no model point around leaves the tolerance (the cleanup itself
// would undo what the refinement reached).
std::size_t Cleanup::repair_small_angles()
{
    std::size_t repaired = 0;
    if (!(tolerance_.tolerance > 0.0)) return repaired;
    // The moves are snaps (raise_min_angle): off with the snaps; the flips and collapses stay.
    const bool moves = tolerance_.snap_min_angle_deg > 0.0;
    for (int round = 0; round < 3; ++round)
    {
        const std::vector<FaceHandle> bad = faces_under_cleanup_angle();
        std::size_t moved = 0;
        for (const FaceHandle f : bad)
        {
            if (mesh_.status(f).deleted() || !face_angle_below(f, options_.angle_deg)) continue;
            std::vector<EdgeHandle> edges;
            for (auto e : mesh_.fe_range(f)) edges.push_back(e);
            std::sort(edges.begin(), edges.end(), [&](EdgeHandle x, EdgeHandle y) {
                const double lx = mesh_.calc_edge_length(x), ly = mesh_.calc_edge_length(y);
                return lx != ly ? lx > ly : x.idx() < y.idx();
            });
            bool flipped = false;
            for (const EdgeHandle e : edges)
                if (keeper_.flip_keeping_tolerance(e))
                {
                    ++report_.flips;
                    ++moved;
                    flipped = true;
                    break;
                }
            if (flipped) continue;
            // The shortest edge of a needle: collapsed, either way.
            const EdgeHandle shortest = edges.back();
            if (keeper_.collapse_keeping_tolerance(mesh_.halfedge_handle(shortest, 0)) ||
                keeper_.collapse_keeping_tolerance(mesh_.halfedge_handle(shortest, 1)))
            {
                ++report_.collapses;
                ++moved;
                continue;
            }
            for (auto v : mesh_.fv_range(f))
            {
                if (!moves) break;
                const VertexClass cls = ctx_.vertex_class(v);
                if (cls == VertexClass::Corner ||
                    (cls == VertexClass::Smooth && mesh_.is_boundary(v)))
                    continue;
                Vec3d sum(0, 0, 0);
                int n = 0;
                for (auto h : mesh_.voh_range(v))
                    if (cls == VertexClass::Smooth ||
                        ctx_.edge_curve(mesh_.edge_handle(h)) == ctx_.vertex_curve(v))
                        sum += mesh_.point(mesh_.to_vertex_handle(h)), ++n;
                if (n == 0) continue;
                const ProjectedPoint balanced =
                    ctx_.model.project_near(sum / n, cls, ctx_.vertex_curve(v), ctx_.model_face(v));
                if (!balanced.ok) continue;
                if (keeper_.try_snap(v, balanced.point, true))
                {
                    run_.set_size(v);
                    ++report_.shifts;
                    ++moved;
                }
            }
        }
        repaired += moved;
        if (run_.options.verbosity > 0)
            hdimesh::emit(run_.options.messages, hdimesh::MessageKind::Trace,
                          "remesh: angle repair round %d: %zu small-angle triangles, %zu moves\n",
                          round + 1, bad.size(), moved);
        if (moved == 0) break;
    }
    return repaired;
}

// The last word for needles with a curve vertex: that vertex slides along its curve
// (slide_curve_vertex), which every balancing step before would undo. The needle filling a
// narrow sector between two curves at a corner is cured only this way, and the slides in the
// neighbouring needles make room for it: all the small-angle faces slide, not the corner's
// own triangle alone (docs/tuning.md).
void Cleanup::slide_curve_vertices_of_needles()
{
    // Rounds: a slide on one side lets the other side slide further.
    for (int round = 0; round < kSlideRounds; ++round)
    {
        // The faces in handle order, each looked at as the slides before it in the round left
        // it: those under the angle at the round's start, and those a slide changes further
        // on (the others have no small angle when their turn comes).
        const std::vector<FaceHandle> bad = faces_under_cleanup_angle();
        std::priority_queue<int, std::vector<int>, std::greater<int>> queue(std::greater<int>(),
                                                                            face_indices(bad));
        int last = -1;
        std::size_t done = 0;
        while (!queue.empty())
        {
            const int index = queue.top();
            queue.pop();
            if (index == last) continue;
            last = index;
            const FaceHandle f(index);
            if (mesh_.status(f).deleted() || !face_angle_below(f, options_.angle_deg)) continue;
            for (auto v : mesh_.fv_range(f))
            {
                if (!try_slide(v)) continue;
                ++done;
                for (auto g : mesh_.vf_range(v))
                    if (g.idx() > index) queue.push(g.idx());
            }
        }
        if (run_.options.verbosity > 0)
            hdimesh::emit(run_.options.messages, hdimesh::MessageKind::Trace,
                          "remesh: slide round %d: %zu curve vertices slid\n", round + 1, done);
        if (done == 0) break;
    }
}

bool Cleanup::try_slide(VertexHandle v)
{
    SlideOptions slide;
    const double h = mesh_.property(ctx_.props.vertex_size, v);
    slide.max_length = kSlideMaxLength * std::max(h, tolerance_.reference_size);
    slide.min_length = kSlideMinLength * h;
    slide.tolerance = tolerance_.tolerance;
    if (!slide_curve_vertex(ctx_, v, slide).done()) return false;
    run_.set_size(v);
    ++report_.shifts;
    return true;
}

}  // namespace hdimesh::surface::detail
