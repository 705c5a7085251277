// A vertex moved to the trial point where its star's triangles fall least short of a Qe goal.
//
// George's weighted point balances the ball: beside a ridge, a row of vertices standing over
// the ridge vertices (right triangles on the ridge edges) is such a balance, each right
// triangle's pull toward its equilateral apex cancelled by the faces on the other side. A
// trial at that apex itself, or part of the way, breaks the tie wherever the star's worst
// triangle rises.

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "surface/detail/local_ops_geometry.h"
#include "surface/local_ops.h"

namespace hdimesh::surface
{
namespace
{

struct Score
{
    double worst = 1.0;
    double shortfall = 0.0;
};

struct Trial
{
    Score score;
    ProjectedPoint point;
};

// The star of v with the relocation's measure.
struct RelocateStar : detail::TrialStar
{
    using TrialStar::TrialStar;

    // Worst Qe and the faces' summed shortfall from `goal` with v at p; worst -1 when a face
    // turns past the limit or degenerates.
    Score score(const Vec3d& p, double min_cos, double goal) const
    {
        Score s;
        for (const detail::StarFace& face : faces)
        {
            const std::array<Vec3d, 3> after = face.with_moved_at(p);
            if (!detail::turn_ok_cos(face.normal, detail::normal(after), min_cos))
                return {-1.0, 0.0};
            const double q = detail::qe(after);
            s.worst = std::min(s.worst, q);
            s.shortfall += std::max(0.0, goal - q);
        }
        return s;
    }
};

// The smooth trials' targets: each face's equilateral apex on its outer edge, on v's side in
// the plane of normal n, and their mean weighted by 1/Qe² (George's point).
std::vector<Vec3d> smooth_targets(const RelocateStar& star, const Vec3d& n)
{
    std::vector<Vec3d> targets;
    Vec3d sum(0, 0, 0);
    double weight_sum = 0.0;
    for (const detail::StarFace& face : star.faces)
    {
        // (v, a, b) in the face's turning order.
        const Vec3d& pa = face.points[(face.moved + 1) % 3];
        const Vec3d& pb = face.points[(face.moved + 2) % 3];
        Vec3d apex;
        if (!detail::equilateral_apex(pa, pb, (pb - pa).norm(), n, apex)) continue;
        targets.push_back(apex);
        const double q = std::max(detail::qe(face.points), 0.05);
        sum += apex / (q * q);
        weight_sum += 1.0 / (q * q);
    }
    if (weight_sum > 0.0) targets.push_back(sum / weight_sum);
    return targets;
}

}  // namespace

OpResult relocate_vertex(OperatorContext& ctx, VertexHandle v, const RelocateOptions& options)
{
    SurfaceMesh& mesh = ctx.mesh;
    const VertexClass cls = ctx.vertex_class(v);
    if (cls == VertexClass::Corner || mesh.is_isolated(v)) return refused(OpStatus::Class);
    if (cls == VertexClass::Smooth && mesh.is_boundary(v)) return refused(OpStatus::Class);
    const Vec3d p = mesh.point(v);
    const RelocateStar star(mesh, v);
    const double min_cos = detail::cos_deg(ctx.limits.max_normal_turn_deg);
    const Score before = star.score(p, -1.0, options.goal);
    // The worst may fall a little for a smaller shortfall, never under this.
    const double floor = std::max(ctx.limits.min_new_quality,
                                  std::min(before.worst, options.goal) - options.worst_slack);

    // The trial points, before projection.
    std::vector<Vec3d> trials;
    Vec3d n(0, 0, 0);  // a smooth vertex's tangent plane
    if (cls == VertexClass::Smooth)
    {
        for (const detail::StarFace& face : star.faces)
            n += OpenMesh::cross(face.points[1] - face.points[0], face.points[2] - face.points[0]);
        if (!(n.norm() > 0.0)) return refused(OpStatus::Geometry);
        n = detail::tangent_normal(ctx, v, n.normalized());
        for (const Vec3d& target : smooth_targets(star, n))
            for (const double step : {1.0, 0.6, 0.3})
            {
                Vec3d q = p + step * (target - p);
                trials.push_back(q - OpenMesh::dot(q - p, n) * n);
            }
    }
    else
    {
        const std::vector<Vec3d> curve_ends = detail::curve_neighbour_points(ctx, v);
        if (curve_ends.size() != 2) return refused(OpStatus::Class);
        // Up to half the way: the neighbour's other edges are not looked at here.
        for (const Vec3d& end : curve_ends)
            for (int i = 1; i <= 8; ++i) trials.push_back(p + (0.0625 * i) * (end - p));
    }

    // In a zone the tolerance refined below the size, every edge is short: one may shorten
    // down to the star's shortest (no new shortest edge), which the band alone would forbid.
    double shortest = 0.0;
    for (const Vec3d& w : star.neighbours)
        shortest = shortest > 0.0 ? std::min(shortest, (w - p).norm()) : (w - p).norm();
    const double min_length = std::min(options.min_length, shortest);

    // Better than v where it is: less shortfall, or (none short of the goal) a higher worst.
    auto better_than_before = [&](const Score& s) {
        return before.shortfall > 0.0 ? s.shortfall < before.shortfall - options.min_gain
                                      : s.worst > before.worst + options.min_gain;
    };

    // Through the layers (band, turn, quality), the legal ones best first.
    std::vector<Trial> legal;
    for (const Vec3d& t : trials)
    {
        const ProjectedPoint q =
            ctx.model.project_near(t, cls, ctx.vertex_curve(v), ctx.model_face(v));
        if (!q.ok || !star.lengths_ok(q.point, min_length, options.max_length)) continue;
        const Score after = star.score(q.point, min_cos, options.goal);
        if (after.worst < floor) continue;
        if (better_than_before(after)) legal.push_back({after, q});
    }
    auto ahead = [](const Score& a, const Score& b) {
        return a.shortfall != b.shortfall ? a.shortfall < b.shortfall : a.worst > b.worst;
    };
    std::sort(legal.begin(), legal.end(),
              [&](const Trial& a, const Trial& b) { return ahead(a.score, b.score); });
    // The discrete trials land near an optimum, rarely on it: a compass search in the tangent
    // plane from the best of them (or from v) takes the last part of the way.
    if (cls == VertexClass::Smooth && options.search_steps > 0)
    {
        auto improves = [](const Score& a, const Score& b) {
            return a.shortfall < b.shortfall - 1e-6 ||
                   (a.shortfall <= b.shortfall && a.worst > b.worst + 1e-6);
        };
        Trial centre{before, {}};
        centre.point.point = p;
        centre.point.face = ctx.model_face(v);
        if (!legal.empty()) centre = legal.front();
        Vec3d u = OpenMesh::cross(n, Vec3d(1, 0, 0));
        if (u.norm() < 0.5) u = OpenMesh::cross(n, Vec3d(0, 1, 0));
        u.normalize();
        const Vec3d w = OpenMesh::cross(n, u);
        double step = 0.125 * shortest;
        bool moved = false;
        for (int level = 0, evaluations = 0; level < options.search_steps && evaluations < 64;)
        {
            bool improved = false;
            for (int k = 0; k < 8 && !improved; ++k, ++evaluations)
            {
                const double angle = k * (M_PI / 4.0);
                const Vec3d t =
                    centre.point.point + step * (std::cos(angle) * u + std::sin(angle) * w);
                const ProjectedPoint q =
                    ctx.model.project_near(t, cls, ctx.vertex_curve(v), centre.point.face);
                if (!q.ok || !star.lengths_ok(q.point, min_length, options.max_length)) continue;
                const Score after = star.score(q.point, min_cos, options.goal);
                if (after.worst < floor || !improves(after, centre.score)) continue;
                centre = {after, q};
                improved = moved = true;
            }
            if (!improved)
            {
                step *= 0.5;
                ++level;
            }
        }
        if (moved && better_than_before(centre.score)) legal.insert(legal.begin(), centre);
    }
    if (legal.empty()) return refused(OpStatus::Quality);
    const std::size_t asked = std::min<std::size_t>(legal.size(), 3);
    for (std::size_t i = 0; i < asked; ++i)
        if (!options.accept || options.accept(legal[i].point.point))
            return commit_move(ctx, v, legal[i].point.point, legal[i].point.face);
    return refused(OpStatus::Geometry);
}

}  // namespace hdimesh::surface
