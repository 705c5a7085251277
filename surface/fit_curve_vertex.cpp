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
    const detail::TwoRingPatch patch(mesh, v);
    std::vector<FaceHandle> star;
    for (auto f : mesh.vf_range(v)) star.push_back(f);

    // The excess both ways with v at q: witnesses to the 2-ring; the star's edge midpoints (and
    // the quarter points of its curve chords, which cut the zigs), centroids to the model.
    std::vector<std::array<Vec3d, 3>> patch_at;  // the patch with v at q (excess)
    auto excess = [&](const Vec3d& q) {
        Excess e;
        // (Only an excess counts: a witness within the tolerance of some triangle adds nothing.)
        patch.triangles_at(&q, patch_at);
        for (const Vec3d& w : options.witnesses)
            if (!detail::within_triangles(w, patch_at, options.tolerance))
                e.add(patch.distance(w, &q), options.tolerance);
        auto sample = [&](const Vec3d& s) {
            e.add(ctx.distance_beyond(s, v, options.tolerance), options.tolerance);
        };
        for (std::size_t i = 0; i < neighbours.size(); ++i)
        {
            sample(0.5 * (q + neighbours[i]));
            if (on_curve[i])
            {
                sample(0.75 * q + 0.25 * neighbours[i]);
                sample(0.25 * q + 0.75 * neighbours[i]);
            }
        }
        for (const FaceHandle f : star)
        {
            const auto t = face_points_with(mesh, f, v, q);
            sample((t[0] + t[1] + t[2]) / 3.0);
        }
        return e;
    };
    // Geometry and quality of the star with v at q.
    double old_min_angle = 180.0;
    for (const FaceHandle f : star)
    {
        const auto t = face_points(mesh, f);
        old_min_angle = std::min(old_min_angle, triangle_min_angle_deg(t[0], t[1], t[2]));
    }
    const double min_angle = std::min(options.min_angle_deg, old_min_angle);
    const double max_turn_cos = cos_deg(ctx.limits.max_normal_turn_deg);
    auto legal = [&](const Vec3d& q) {
        for (const FaceHandle f : star)
        {
            const auto before = face_points(mesh, f), after = face_points_with(mesh, f, v, q);
            if (!turn_ok_cos(normal(before), normal(after), max_turn_cos) ||
                qe(after) < ctx.limits.min_new_quality ||
                triangle_min_angle_deg(after[0], after[1], after[2]) < min_angle)
                return false;
        }
        int out_before = 0, out_after = 0;
        for (const Vec3d& w : neighbours)
        {
            const double length = (w - q).norm();
            const double before =
                out_of_band((w - p).norm(), options.min_length, options.max_length);
            const double after = out_of_band(length, options.min_length, options.max_length);
            out_before += before > 0.0;
            out_after += after > 0.0;
            const bool shorter_above_floor = options.floor_length > 0.0 &&
                                             length < options.min_length &&
                                             length >= options.floor_length;
            if (after > before && !shorter_above_floor) return false;
        }
        return out_after <= out_before;
    };

    // Nothing to fit where the star is within the tolerance already (most curve vertices): no
    // candidates are projected then.
    const Excess before = excess(p);
    if (!(before.worst > 0.0))
    {
        result.status = OpStatus::Quality;
        return result;
    }

    // Candidates: on the curve strictly between the curve neighbours (no fold along it).
    const double span = (curve_neighbours[1] - curve_neighbours[0]).norm();
    auto between = [&](const Vec3d& q) {
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

    Excess best = before;
    ProjectedPoint best_point;
    const double gain = kMinGain * options.tolerance;
    for (const ProjectedPoint& c : candidates)
    {
        if (!legal(c.point)) continue;  // the cheaper test first: the star alone
        const Excess e = excess(c.point);
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
