#include "surface/detail/keep_tolerance.h"

#include <algorithm>
#include <array>
#include <vector>

#include "surface/detail/local_ops_geometry.h"
#include "surface/surface_quality.h"

namespace hdimesh::surface::detail
{

// The size an edge is judged against for the short-edge budget of the refinement.
double ToleranceKeeper::reference_size(EdgeHandle e) const
{
    return options_.reference_size > 0.0 ? options_.reference_size : run_.edge_size(e);
}

std::size_t ToleranceKeeper::count_short_edges() const
{
    std::size_t n = 0;
    for (auto e : mesh_.edges())
        if (!mesh_.status(e).deleted() &&
            size_quality(mesh_.calc_edge_length(e), reference_size(e)) < kSizeQualityThreshold)
            ++n;
    return n;
}

// The model points in a grid of cells of about one size, built on first use (snaps, the
// tolerance-keeping flips and collapses ask it for the points around a star).
const PointGrid& ToleranceKeeper::model_point_grid()
{
    if (!model_point_grid_)
    {
        double cell = options_.reference_size;
        if (!(cell > 0.0))
        {
            double sum = 0.0;
            std::size_t n = 0;
            for (auto w : mesh_.vertices())
                if (!mesh_.status(w).deleted())
                    sum += mesh_.property(ctx_.props.vertex_size, w), ++n;
            cell = n > 0 ? sum / static_cast<double>(n) : 1.0;
        }
        model_point_grid_ = std::make_unique<PointGrid>(options_.model_points, cell);
    }
    return *model_point_grid_;
}

// The limits of a witnessed move of v (a snap, a curve fit): the star's edges in the Qt band
// of the reference size (or of v's size), an edge already short allowed down to the
// refinement's own shortest (a staircase boundary needs a vertex on each stair corner;
// docs/tuning.md), and as witnesses
// the model points within the star's reach (its longest edge plus `margin`) of v and of
// `target` if given, in index order.
void ToleranceKeeper::set_move_limits(VertexHandle v, const Vec3d* target, double margin,
                                      WitnessedMoveOptions& limits)
{
    const PointGrid& grid = model_point_grid();
    const double size = options_.reference_size > 0.0 ? options_.reference_size
                                                      : mesh_.property(ctx_.props.vertex_size, v);
    limits.tolerance = options_.tolerance;
    limits.min_angle_deg = options_.snap_min_angle_deg;
    limits.min_length = kSizeQualityThreshold * size;
    limits.max_length = size / kSizeQualityThreshold;
    limits.floor_length = options_.min_length_ratio * size;
    double reach = 0.0;
    for (auto h : mesh_.voh_range(v)) reach = std::max(reach, mesh_.calc_edge_length(h));
    reach += margin;
    std::vector<std::size_t> around = grid.within(mesh_.point(v), reach);
    if (target)
    {
        const std::vector<std::size_t> around_target = grid.within(*target, reach);
        around.insert(around.end(), around_target.begin(), around_target.end());
        std::sort(around.begin(), around.end());
        around.erase(std::unique(around.begin(), around.end()), around.end());
    }
    limits.witnesses.clear();
    for (const std::size_t i : around) limits.witnesses.push_back(options_.model_points[i]);
}

// try_snap_vertex within the limits of a witnessed move, with the witnesses around v and the
// target out to the tolerance beyond the star.
bool ToleranceKeeper::try_snap(VertexHandle v, const Vec3d& target, bool raise_min_angle)
{
    SnapOptions snap;
    set_move_limits(v, &target, options_.tolerance, snap);
    snap.raise_min_angle = raise_min_angle;
    return try_snap_vertex(ctx_, v, target, snap).done();
}

// A quality flip of e (try_flip) that keeps the tolerance: simulated first, refused when a
// model point around the pair ends farther from the output than max(tolerance, before) or
// the new pair's samples (edge midpoint, centroids) stray farther from the model than the
// old pair's did (when beyond the tolerance).
bool ToleranceKeeper::flip_keeping_tolerance(EdgeHandle e)
{
    if (mesh_.status(e).deleted() || ctx_.is_feature(e) || !flip_topology_ok(mesh_, e))
        return false;
    const HalfedgeHandle h0 = mesh_.halfedge_handle(e, 0), h1 = mesh_.halfedge_handle(e, 1);
    const VertexHandle a = mesh_.from_vertex_handle(h0), b = mesh_.to_vertex_handle(h0);
    const VertexHandle c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h0));
    const VertexHandle d = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h1));
    const Vec3d pa = mesh_.point(a), pb = mesh_.point(b), pc = mesh_.point(c), pd = mesh_.point(d);
    const std::array<Vec3d, 3> old0{pa, pb, pc}, old1{pb, pa, pd}, new0{pa, pd, pc},
        new1{pd, pb, pc};
    if (!(std::min(detail::qe(new0), detail::qe(new1)) >
          std::min(detail::qe(old0), detail::qe(old1)) + 1e-6))
        return false;
    // The faces around the four vertices, without the pair: the rest of the output nearby.
    std::vector<FaceHandle> around;
    for (const VertexHandle v : {a, b, c, d})
        for (auto f : mesh_.vf_range(v)) around.push_back(f);
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    // The output nearby before and after: the pair, and the rest of the faces around.
    std::vector<std::array<Vec3d, 3>> output_before{old0, old1}, output_after{new0, new1};
    for (const FaceHandle f : around)
        if (f != mesh_.face_handle(h0) && f != mesh_.face_handle(h1))
        {
            output_before.push_back(detail::face_points(mesh_, f));
            output_after.push_back(output_before.back());
        }
    auto worst_sample = [&](const Vec3d& mid, VertexHandle near, const std::array<Vec3d, 3>& t0,
                            const std::array<Vec3d, 3>& t1) {
        double worst = 0.0;
        for (const Vec3d& q : {mid, (t0[0] + t0[1] + t0[2]) / 3.0, (t1[0] + t1[1] + t1[2]) / 3.0})
            worst = std::max(worst, ctx_.distance_beyond(q, near, options_.tolerance));
        return worst;
    };
    const double bound = options_.tolerance;
    const double after = worst_sample(0.5 * (pc + pd), c, new0, new1);
    if (after > bound && after > worst_sample(0.5 * (pa + pb), a, old0, old1)) return false;
    const Vec3d centre = 0.25 * (pa + pb + pc + pd);
    double reach = 0.0;
    for (const Vec3d& q : {pa, pb, pc, pd}) reach = std::max(reach, (q - centre).norm());
    for (const std::size_t i : model_point_grid().within(centre, reach + options_.tolerance))
        if (!detail::keeps_witness(options_.model_points[i], output_before, output_after, bound,
                                   1e-12 * reach))
            return false;
    return try_flip(ctx_, e, FlipGoal::Quality).done();
}

// A collapse of h (try_collapse with the limits of `purpose`) that keeps the tolerance:
// simulated first, refused when a model point around ends farther from the output than
// max(tolerance, before) or the new triangles' samples stray farther.
bool ToleranceKeeper::collapse_keeping_tolerance(HalfedgeHandle h, CollapseFor purpose)
{
    const double bound = options_.tolerance;
    const VertexHandle a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
    const bool curve_too = purpose == CollapseFor::Raise;
    if (!curve_too && (ctx_.vertex_class(a) != VertexClass::Smooth || mesh_.is_boundary(a)))
        return false;
    // The collapse's own layers first: the tolerance checks below are the expensive part,
    // and most candidates fail the layers.
    const double size = options_.reference_size > 0.0 ? options_.reference_size
                                                      : run_.edge_size(mesh_.edge_handle(h));
    const bool for_budget = purpose == CollapseFor::Budget;
    const double max_length =
        for_budget ? kReferenceCollapseLength * size : size / kSizeQualityThreshold;
    const bool require_gain = !for_budget;
    const double min_angle = for_budget ? kReferenceCollapseMinAngle : 0.0;
    if (collapse_shape_status(ctx_, h, max_length, require_gain, min_angle) != OpStatus::Done)
        return false;
    const Vec3d pa = mesh_.point(a), pb = mesh_.point(b);
    std::vector<std::array<Vec3d, 3>> before, after;
    std::vector<FaceHandle> faces;
    for (auto f : mesh_.vf_range(a)) faces.push_back(f);
    for (auto f : mesh_.vf_range(b)) faces.push_back(f);
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    double worst_before = 0.0, worst_after = 0.0;
    auto sample = [&](const Vec3d& q, VertexHandle near) {
        return ctx_.distance_beyond(q, near, options_.tolerance);
    };
    for (const FaceHandle f : faces)
    {
        const auto fv = detail::face_vertices(mesh_, f);
        const bool has_a = fv[0] == a || fv[1] == a || fv[2] == a,
                   has_b = fv[0] == b || fv[1] == b || fv[2] == b;
        const auto t = detail::face_points(mesh_, f);
        before.push_back(t);
        if (has_a) worst_before = std::max(worst_before, sample((t[0] + t[1] + t[2]) / 3.0, a));
        if (has_a && has_b) continue;
        if (!has_a)
        {
            after.push_back(t);
            continue;
        }
        const auto moved = detail::face_points_with(mesh_, f, a, pb);
        after.push_back(moved);
        worst_after = std::max(worst_after, sample((moved[0] + moved[1] + moved[2]) / 3.0, b));
    }
    for (auto w : mesh_.vv_range(a))
    {
        worst_before = std::max(worst_before, sample(0.5 * (pa + mesh_.point(w)), a));
        if (w != b) worst_after = std::max(worst_after, sample(0.5 * (pb + mesh_.point(w)), b));
    }
    if (worst_after > bound && worst_after > worst_before) return false;
    double reach = 0.0;
    for (auto w : mesh_.vv_range(a)) reach = std::max(reach, (mesh_.point(w) - pb).norm());
    for (const std::size_t i : model_point_grid().within(pb, reach + bound))
        if (!detail::keeps_witness(options_.model_points[i], before, after, bound, 1e-12 * reach))
            return false;
    return try_collapse(ctx_, h, max_length, require_gain, min_angle).done();
}

// A shift of v (shift_vertex), refused before it is committed when it would break what
// `keep` asks: a model point around the star ending farther from it than max(tolerance,
// before), the star's samples (edge midpoints, centroids) straying farther from the model
// than before beyond the tolerance, and (ToleranceAndLengths) an edge of the star getting
// short for the reference size.
// The state before the move is gathered here, when a move is asked (the mesh is still as
// before it).
bool ToleranceKeeper::move_keeps(VertexHandle v, const Vec3d& after, Keep keep)
{
    if (keep == Keep::Nothing || !(options_.tolerance > 0.0)) return true;
    const double bound = options_.tolerance;
    // The star's edges short for the reference size with v at `at`.
    auto short_star_edges = [&](const Vec3d& at) {
        int n = 0;
        for (auto h : mesh_.voh_range(v))
            if (size_quality((mesh_.point(mesh_.to_vertex_handle(h)) - at).norm(),
                             reference_size(mesh_.edge_handle(h))) < kSizeQualityThreshold)
                ++n;
        return n;
    };
    const Vec3d before = mesh_.point(v);
    if (keep == Keep::ToleranceAndLengths && short_star_edges(after) > short_star_edges(before))
        return false;
    const double samples_after = detail::star_samples_beyond(ctx_, v, after, bound);
    if (samples_after > bound &&
        samples_after > detail::star_samples_beyond(ctx_, v, before, bound))
        return false;
    // The 2-ring before and after (keeps_witness).
    const detail::TwoRingPatch patch(mesh_, v);
    std::vector<std::array<Vec3d, 3>> patch_after;
    patch.triangles_at(&after, patch_after);
    double reach = 0.0;
    for (auto h : mesh_.voh_range(v)) reach = std::max(reach, mesh_.calc_edge_length(h));
    for (const std::size_t k : model_point_grid().within(before, reach + bound))
        if (!detail::keeps_witness(options_.model_points[k], patch.triangles, patch_after, bound,
                                   1e-12 * reach))
            return false;
    return true;
}

bool ToleranceKeeper::shift(VertexHandle v, const ShiftOptions& options, Keep keep)
{
    if (keep == Keep::Nothing || !(options_.tolerance > 0.0))
        return shift_vertex(ctx_, v, options).done();
    ShiftOptions keeping = options;
    // Most smart shifts stop at their quality test and never ask, and a shift that does not
    // move needs no patch, witnesses or samples.
    keeping.accept = [&](const Vec3d& after) {
        return move_keeps(v, after, keep) && (!options.accept || options.accept(after));
    };
    return shift_vertex(ctx_, v, keeping).done();
}

}  // namespace hdimesh::surface::detail
