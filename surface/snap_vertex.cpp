#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "surface/detail/closest_point_tree.h"
#include "surface/detail/local_ops_geometry.h"
#include "surface/local_ops.h"
#include "surface/surface_quality.h"

namespace hdimesh::surface
{
namespace
{

// As a split onto the model (split_edge.cpp): a snap exists to bend the star over a crest the
// chords cut, so its triangles may turn more than a smoothing move's, but not fold.
constexpr double kMaxSnapTurnDeg = 60.0;
// No triangle of the star turns farther than this from the model under it (its centroid's
// projection): a fold. Not from the model at the target: on the rounded rim of a flange thinner
// than the size, a triangle down a flank from a vertex on the crest is at ~90° to the crest's
// normal, and the snap the rim needs would be refused (docs/tuning.md).
constexpr double kMaxTurnFromModelDeg = 85.0;
// A repair must raise the star's smallest angle by this much (not a move of rounding noise).
constexpr double kMinAngleGainDeg = 0.1;
// The fractions of the way to the target tried, the whole way first.
constexpr double kSnapSteps[] = {1.0, 0.75, 0.5, 0.35};

// A snap's trial positions q of v judged: geometry, quality, distance both ways (a status, Done
// when legal). The 2-ring and the witnesses' distances before: computed once, when a position
// gets that far.
class SnapCheck
{
public:
    SnapCheck(OperatorContext& ctx, VertexHandle v, const Vec3d& target, const SnapOptions& options,
              double star_length)
        : ctx_(ctx), mesh_(ctx.mesh), v_(v), cls_(ctx.vertex_class(v)), p_(ctx.mesh.point(v)),
          target_(target), options_(options), star_length_(star_length), patch_(ctx.mesh, v)
    {
    }

    OpStatus operator()(const Vec3d& q, const ProjectedPoint& q_on_model)
    {
        // The target must come within the tolerance: the point of the move (not of a repair).
        if (!options_.raise_min_angle && patch_.distance(target_, &q) > options_.tolerance)
            return OpStatus::Geometry;
        const OpStatus shape = shape_status(q, q_on_model);
        if (shape != OpStatus::Done) return shape;
        const OpStatus sizes = size_status(q);
        if (sizes != OpStatus::Done) return sizes;
        return distance_status(q);
    }

private:
    // The star's triangles: no fold, turn or poor shape, and the smallest angle kept (a repair:
    // raised).
    OpStatus shape_status(const Vec3d& q, const ProjectedPoint& q_on_model) const
    {
        using namespace detail;
        double old_min_angle = 180.0, new_min_angle = 180.0;
        // Bending over a crest needs the larger turn; a repair move is an ordinary smoothing
        // move and keeps the operators' limit.
        const double turn_limit = options_.raise_min_angle
                                      ? ctx_.limits.max_normal_turn_deg
                                      : std::max(ctx_.limits.max_normal_turn_deg, kMaxSnapTurnDeg);
        const double turn_limit_cos = cos_deg(turn_limit),
                     from_model_cos = cos_deg(kMaxTurnFromModelDeg);
        for (auto f : mesh_.vf_range(v_))
        {
            const auto before = face_points(mesh_, f), after = face_points_with(mesh_, f, v_, q);
            const Vec3d n_after = normal(after);
            old_min_angle =
                std::min(old_min_angle, triangle_min_angle_deg(before[0], before[1], before[2]));
            new_min_angle =
                std::min(new_min_angle, triangle_min_angle_deg(after[0], after[1], after[2]));
            if (!turn_ok_cos(normal(before), n_after, turn_limit_cos) ||
                qe(after) < ctx_.limits.min_new_quality)
                return OpStatus::Geometry;
            if (cls_ == VertexClass::Smooth && q_on_model.ok)
            {
                const ProjectedPoint under = ctx_.model.project_near(
                    (after[0] + after[1] + after[2]) / 3.0, VertexClass::Smooth, kNoCurve,
                    q_on_model.face >= 0 ? q_on_model.face : ctx_.model_face(v_));
                if (!turn_ok_cos(under.ok ? under.normal : q_on_model.normal, n_after,
                                 from_model_cos))
                    return OpStatus::Geometry;
            }
        }
        if (options_.raise_min_angle
                ? !(new_min_angle > old_min_angle + kMinAngleGainDeg)
                : new_min_angle < std::min(options_.min_angle_deg, old_min_angle))
            return OpStatus::Quality;
        return OpStatus::Done;
    }

    // Sizes: no edge of the star leaves the band or gets farther out of it; a repair may
    // trade (a needle's short edge is what it repairs) but not add an edge out of the band.
    OpStatus size_status(const Vec3d& q) const
    {
        using namespace detail;
        int out_before = 0, out_after = 0;
        for (auto w : mesh_.vv_range(v_))
        {
            const Vec3d r = mesh_.point(w);
            const double before =
                out_of_band((r - p_).norm(), options_.min_length, options_.max_length);
            const double after =
                out_of_band((r - q).norm(), options_.min_length, options_.max_length);
            out_before += before > 0.0;
            out_after += after > 0.0;
            const double length = (r - q).norm();
            const bool shorter_above_floor = options_.floor_length > 0.0 &&
                                             length < options_.min_length &&
                                             length >= options_.floor_length;
            if (!options_.raise_min_angle && after > 0.0 && after > before && !shorter_above_floor)
                return OpStatus::Quality;
        }
        if (out_after > out_before) return OpStatus::Quality;
        return OpStatus::Done;
    }

    // Distance both ways: the star's samples no farther out than before, nor the witnesses.
    OpStatus distance_status(const Vec3d& q)
    {
        const double bound = options_.tolerance;
        const double star_after = worst_sample(q);
        if (star_after > bound)
        {
            if (star_before_ < 0.0) star_before_ = worst_sample(p_);
            if (star_after > star_before_) return OpStatus::Geometry;
        }
        if (witness_before_.size() != options_.witnesses.size())
        {
            witness_before_.clear();
            for (const Vec3d& w : options_.witnesses)
                witness_before_.push_back(patch_.distance(w, nullptr));
        }
        for (std::size_t i = 0; i < options_.witnesses.size(); ++i)
        {
            const double after = patch_.distance(options_.witnesses[i], &q);
            if (after > bound && after > witness_before_[i] + 1e-12 * star_length_)
                return OpStatus::Geometry;
        }
        return OpStatus::Done;
    }

    double worst_sample(const Vec3d& at) const
    {
        return detail::star_samples_beyond(ctx_, v_, at, options_.tolerance);
    }

    OperatorContext& ctx_;
    const SurfaceMesh& mesh_;
    const VertexHandle v_;
    const VertexClass cls_;
    const Vec3d p_;  // v's point before
    const Vec3d& target_;
    const SnapOptions& options_;
    const double star_length_;
    const detail::TwoRingPatch patch_;
    std::vector<double> witness_before_;
    double star_before_ = -1.0;  // the worst sample of the star before, computed when needed
};

}  // namespace

OpResult try_snap_vertex(OperatorContext& ctx, VertexHandle v, const Vec3d& target,
                         const SnapOptions& options)
{
    using namespace detail;
    SurfaceMesh& mesh = ctx.mesh;
    OpResult result;
    if (mesh.status(v).deleted() || mesh.is_isolated(v)) return result;

    // Class layer: corners stay; a smooth vertex on an open boundary is unclassified (left alone);
    // a curve vertex only onto its own curve, between its curve neighbours (no fold along it).
    const VertexClass cls = ctx.vertex_class(v);
    const int curve = ctx.vertex_curve(v);
    if (cls == VertexClass::Corner || (cls == VertexClass::Smooth && mesh.is_boundary(v)))
    {
        result.status = OpStatus::Class;
        return result;
    }
    const Vec3d p = mesh.point(v);
    double star_length = 0.0;
    std::vector<Vec3d> curve_neighbours;
    for (auto h : mesh.voh_range(v))
    {
        star_length = std::max(star_length, mesh.calc_edge_length(h));
        if (cls != VertexClass::Smooth && ctx.edge_curve(mesh.edge_handle(h)) == curve)
            curve_neighbours.push_back(mesh.point(mesh.to_vertex_handle(h)));
    }
    const ProjectedPoint on_model = ctx.model.project_near(target, cls, curve, ctx.model_face(v));
    if (cls != VertexClass::Smooth)
    {
        const bool on_own_curve =
            on_model.ok && (on_model.point - target).norm() <= 1e-9 * star_length;
        bool between = curve_neighbours.size() == 2;
        if (between)
        {
            const double span = (curve_neighbours[1] - curve_neighbours[0]).norm();
            between = (target - curve_neighbours[0]).norm() < span &&
                      (target - curve_neighbours[1]).norm() < span;
        }
        if (!on_own_curve || !between)
        {
            result.status = OpStatus::Class;
            return result;
        }
    }

    // The star with v at q: geometry, quality, distance both ways (a status, Done when legal).
    SnapCheck check(ctx, v, target, options, star_length);

    // All the way onto the target, else part of the way (back onto the model): the target only
    // has to come within the tolerance, and a shorter move keeps the star's shape.
    // A refusal reports why the whole move was refused.
    Vec3d q = target;
    ProjectedPoint q_on_model = on_model;
    OpStatus status = OpStatus::Geometry;
    for (const double step : kSnapSteps)
    {
        if (step < 1.0)
        {
            q_on_model =
                ctx.model.project_near(p + step * (target - p), cls, curve, ctx.model_face(v));
            if (!q_on_model.ok) continue;
            q = q_on_model.point;
        }
        const OpStatus at_q = check(q, q_on_model);
        if (step == 1.0 || at_q == OpStatus::Done) status = at_q;
        if (status == OpStatus::Done) break;
    }
    if (status != OpStatus::Done)
    {
        result.status = status;
        return result;
    }

    return commit_move(ctx, v, q, q_on_model.ok ? q_on_model.face : -1);
}

}  // namespace hdimesh::surface
