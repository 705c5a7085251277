#include "surface/fit_curve_vertex.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "surface/detail/closest_point_tree.h"
#include "surface/detail/local_ops_geometry.h"
#include "surface/surface_quality.h"

namespace hdimesh::surface
{
namespace
{

// A fit must lower the worst (or, with it kept, the summed) excess by this fraction of the
// tolerance: not a move of rounding noise.
constexpr double kMinGain = 0.01;

struct Excess
{
    double worst = 0.0, sum = 0.0;
    void add(double distance, double tolerance)
    {
        const double over = distance - tolerance;
        if (over <= 0.0) return;
        worst = std::max(worst, over);
        sum += over;
    }
};

// v's star as a fit sees it, for trial positions q of v: the excess both ways, and whether the
// star stays legal.
class CurveFitStar
{
public:
    CurveFitStar(OperatorContext& ctx, VertexHandle v, const CurveFitOptions& options,
                 const std::vector<Vec3d>& neighbours, const std::vector<char>& on_curve)
        : ctx_(ctx), mesh_(ctx.mesh), v_(v), options_(options), neighbours_(neighbours),
          on_curve_(on_curve), p_(ctx.mesh.point(v)), patch_(ctx.mesh, v)
    {
        using namespace detail;
        for (auto f : mesh_.vf_range(v_)) star_.push_back(f);
        double old_min_angle = 180.0;
        for (const FaceHandle f : star_)
        {
            const auto t = face_points(mesh_, f);
            old_min_angle = std::min(old_min_angle, triangle_min_angle_deg(t[0], t[1], t[2]));
        }
        min_angle_ = std::min(options_.min_angle_deg, old_min_angle);
        max_turn_cos_ = cos_deg(ctx_.limits.max_normal_turn_deg);
    }

    // The excess both ways with v at q: witnesses to the 2-ring; the star's edge midpoints (and
    // the quarter points of its curve chords, which cut the zigs), centroids to the model.
    Excess excess(const Vec3d& q)
    {
        using namespace detail;
        Excess e;
        // (Only an excess counts: a witness within the tolerance of some triangle adds nothing.)
        patch_.triangles_at(&q, patch_at_);
        for (const Vec3d& w : options_.witnesses)
            if (!detail::within_triangles(w, patch_at_, options_.tolerance))
                e.add(patch_.distance(w, &q), options_.tolerance);
        for (std::size_t i = 0; i < neighbours_.size(); ++i)
        {
            sample(e, 0.5 * (q + neighbours_[i]));
            if (on_curve_[i])
            {
                sample(e, 0.75 * q + 0.25 * neighbours_[i]);
                sample(e, 0.25 * q + 0.75 * neighbours_[i]);
            }
        }
        for (const FaceHandle f : star_)
        {
            const auto t = face_points_with(mesh_, f, v_, q);
            sample(e, (t[0] + t[1] + t[2]) / 3.0);
        }
        return e;
    }

    // Geometry and quality of the star with v at q.
    bool legal(const Vec3d& q) const
    {
        using namespace detail;
        for (const FaceHandle f : star_)
        {
            const auto before = face_points(mesh_, f), after = face_points_with(mesh_, f, v_, q);
            if (!turn_ok_cos(normal(before), normal(after), max_turn_cos_) ||
                qe(after) < ctx_.limits.min_new_quality ||
                triangle_min_angle_deg(after[0], after[1], after[2]) < min_angle_)
                return false;
        }
        int out_before = 0, out_after = 0;
        for (const Vec3d& w : neighbours_)
        {
            const double length = (w - q).norm();
            const double before =
                out_of_band((w - p_).norm(), options_.min_length, options_.max_length);
            const double after = out_of_band(length, options_.min_length, options_.max_length);
            out_before += before > 0.0;
            out_after += after > 0.0;
            const bool shorter_above_floor = options_.floor_length > 0.0 &&
                                             length < options_.min_length &&
                                             length >= options_.floor_length;
            if (after > before && !shorter_above_floor) return false;
        }
        return out_after <= out_before;
    }

private:
    void sample(Excess& e, const Vec3d& s) const
    {
        e.add(ctx_.distance_beyond(s, v_, options_.tolerance), options_.tolerance);
    }

    OperatorContext& ctx_;
    const SurfaceMesh& mesh_;
    const VertexHandle v_;
    const CurveFitOptions& options_;
    const std::vector<Vec3d>& neighbours_;
    const std::vector<char>& on_curve_;
    const Vec3d p_;  // v's point before
    const detail::TwoRingPatch patch_;
    std::vector<FaceHandle> star_;
    double min_angle_ = 0.0, max_turn_cos_ = 0.0;
    std::vector<std::array<Vec3d, 3>> patch_at_;  // the patch with v at q (excess)
};

// Candidates: on the curve strictly between the curve neighbours (no fold along it): the
// witnesses on it, and samples toward each curve neighbour.
std::vector<ProjectedPoint> curve_fit_candidates(const OperatorContext& ctx, VertexHandle v,
                                                 const CurveFitOptions& options,
                                                 const std::vector<Vec3d>& curve_neighbours)
{
    const VertexClass cls = ctx.vertex_class(v);
    const int curve = ctx.vertex_curve(v);
    const Vec3d p = ctx.mesh.point(v);
    const double span = (curve_neighbours[1] - curve_neighbours[0]).norm();
    auto between = [&curve_neighbours, span](const Vec3d& q) {
        return (q - curve_neighbours[0]).norm() < span && (q - curve_neighbours[1]).norm() < span;
    };
    std::vector<ProjectedPoint> candidates;
    for (const Vec3d& w : options.witnesses)
    {
        if (!between(w)) continue;
        const ProjectedPoint on = ctx.model.project_near(w, cls, curve, ctx.model_face(v));
        if (on.ok && (on.point - w).norm() <= 1e-9 * span) candidates.push_back(on);
    }
    for (const Vec3d& end : curve_neighbours)
        for (int i = 1; i <= options.samples; ++i)
        {
            const double t = 0.8 * static_cast<double>(i) / static_cast<double>(options.samples);
            const ProjectedPoint on =
                ctx.model.project_near(p + t * (end - p), cls, curve, ctx.model_face(v));
            if (on.ok && between(on.point)) candidates.push_back(on);
        }
    return candidates;
}

}  // namespace

OpResult fit_curve_vertex(OperatorContext& ctx, VertexHandle v, const CurveFitOptions& options)
{
    using namespace detail;
    SurfaceMesh& mesh = ctx.mesh;
    OpResult result;
    const VertexClass cls = ctx.vertex_class(v);
    const int curve = ctx.vertex_curve(v);
    if (mesh.status(v).deleted() || (cls != VertexClass::Ridge && cls != VertexClass::Boundary))
    {
        result.status = OpStatus::Class;
        return result;
    }
    std::vector<Vec3d> curve_neighbours, neighbours;
    std::vector<char> on_curve;
    for (auto h : mesh.voh_range(v))
    {
        const bool along = ctx.edge_curve(mesh.edge_handle(h)) == curve;
        neighbours.push_back(mesh.point(mesh.to_vertex_handle(h)));
        on_curve.push_back(along);
        if (along) curve_neighbours.push_back(neighbours.back());
    }
    if (curve_neighbours.size() != 2)
    {
        result.status = OpStatus::Class;
        return result;
    }
    const Vec3d p = mesh.point(v);
    CurveFitStar fit(ctx, v, options, neighbours, on_curve);

    // Nothing to fit where the star is within the tolerance already (most curve vertices): no
    // candidates are projected then.
    const Excess before = fit.excess(p);
    if (!(before.worst > 0.0))
    {
        result.status = OpStatus::Quality;
        return result;
    }
    const std::vector<ProjectedPoint> candidates =
        curve_fit_candidates(ctx, v, options, curve_neighbours);

    Excess best = before;
    ProjectedPoint best_point;
    const double gain = kMinGain * options.tolerance;
    for (const ProjectedPoint& c : candidates)
    {
        if (!fit.legal(c.point)) continue;  // the cheaper test first: the star alone
        const Excess e = fit.excess(c.point);
        const bool better =
            e.worst < best.worst - gain || (e.worst <= best.worst && e.sum < best.sum - gain);
        if (!better) continue;
        best = e;
        best_point = c;
    }
    if (!best_point.ok)
    {
        result.status = OpStatus::Quality;
        return result;
    }
    return commit_move(ctx, v, best_point.point, best_point.face);
}

}  // namespace hdimesh::surface
