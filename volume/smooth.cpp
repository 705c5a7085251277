#include "volume/smooth.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "volume/tet_tables.h"

namespace hdimesh
{

namespace
{

/// The ball of the moving vertex, reduced to what a move changes: each tet is its face
/// opposite the vertex, ordered so that (f0, f1, f2, P) is positive for P on the tet's side.
struct MovingBall
{
    int vertex = -1;
    std::vector<int> tets;
    std::vector<std::array<Vec3, 3>> faces;
    std::vector<int> neighbours;  // the other vertices of the ball, sorted, unique
    double mean_edge = 0;         // of the opposite faces: the scale of the steps

    double quality_at(std::size_t i, const Vec3& p) const
    {
        return tet_quality(faces[i][0], faces[i][1], faces[i][2], p);
    }

    /// The worst quality with the vertex at p, stopping early once it is <= floor.
    double worst_at(const Vec3& p, double floor = -std::numeric_limits<double>::infinity()) const
    {
        double worst = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < faces.size(); ++i)
        {
            worst = std::min(worst, quality_at(i, p));
            if (worst <= floor) break;
        }
        return worst;
    }

    std::size_t worst_index(const Vec3& p) const
    {
        std::size_t index = 0;
        double worst = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < faces.size(); ++i)
        {
            const double q = quality_at(i, p);
            if (q < worst)
            {
                worst = q;
                index = i;
            }
        }
        return index;
    }
};

MovingBall collect_ball(const TetMesh& mesh, const OperatorContext& context, int v)
{
    MovingBall ball;
    ball.vertex = v;
    vertex_ball(mesh, context.vertex_tet[v], v, ball.tets);
    double edge_sum = 0;
    for (int t : ball.tets)
    {
        const int lv = local_index(mesh, t, v);
        const auto& fv = tet::kFaceVertices[lv];
        const auto& tv = mesh.tets[t];
        // the face is outward for t, so the vertex sees it clockwise: swap two for (f, P) > 0
        const Vec3& f0 = mesh.points[tv[fv[0]]];
        const Vec3& f1 = mesh.points[tv[fv[2]]];
        const Vec3& f2 = mesh.points[tv[fv[1]]];
        ball.faces.push_back({f0, f1, f2});
        edge_sum += (f1 - f0).norm() + (f2 - f1).norm() + (f0 - f2).norm();
        for (int k : fv) ball.neighbours.push_back(tv[k]);
    }
    std::sort(ball.neighbours.begin(), ball.neighbours.end());
    ball.neighbours.erase(std::unique(ball.neighbours.begin(), ball.neighbours.end()),
                          ball.neighbours.end());
    ball.mean_edge = edge_sum / (3.0 * static_cast<double>(ball.faces.size()));
    return ball;
}

/// George's target: the 1/Q^2-weighted mean of the points that make each tet regular.
Vec3 nodal_shifting_target(const MovingBall& ball, const Vec3& current)
{
    Vec3 sum = Vec3::Zero();
    double weight_sum = 0;
    for (std::size_t i = 0; i < ball.faces.size(); ++i)
    {
        const auto& f = ball.faces[i];
        // (f0, f1, f2, P) positive: P lies on the side of (f1 - f0) x (f2 - f0)
        const Vec3 normal = (f[1] - f[0]).cross(f[2] - f[0]);
        const double norm = normal.norm();
        if (norm <= 0) continue;
        const double edge = ((f[1] - f[0]).norm() + (f[2] - f[1]).norm() + (f[0] - f[2]).norm()) / 3;
        const Vec3 ideal = (f[0] + f[1] + f[2]) / 3 + (std::sqrt(2.0 / 3.0) * edge / norm) * normal;
        const double q = std::max(ball.quality_at(i, current), 1e-3);
        const double weight = 1.0 / (q * q);
        sum += weight * ideal;
        weight_sum += weight;
    }
    return weight_sum > 0 ? Vec3(sum / weight_sum) : current;
}

/// No edge of the vertex may become too long or too short at p (edges already so may stay).
bool sizes_allow(const TetMesh& mesh, const OperatorContext& context, const MovingBall& ball,
                 const Vec3& from, const Vec3& to)
{
    if (context.field == nullptr) return true;
    for (int n : ball.neighbours)
    {
        const Vec3& q = mesh.points[n];
        if (context.too_long(to, q) && !context.too_long(from, q)) return false;
        if (context.too_short(to, q) && !context.too_short(from, q)) return false;
    }
    return true;
}

/// Central-difference gradient of one tet's quality with respect to the moving point.
Vec3 quality_gradient(const MovingBall& ball, std::size_t i, const Vec3& p, double step)
{
    Vec3 g;
    for (int axis = 0; axis < 3; ++axis)
    {
        Vec3 plus = p, minus = p;
        plus[axis] += step;
        minus[axis] -= step;
        g[axis] = (ball.quality_at(i, plus) - ball.quality_at(i, minus)) / (2 * step);
    }
    return g;
}

}  // namespace

SmoothResult smooth_vertex(TetMesh& mesh, OperatorContext& context, int v,
                           const SmoothOptions& options)
{
    SmoothResult result;
    if (!context.constraints.is_free_vertex(v) || context.vertex_tet[v] < 0) return result;
    const MovingBall ball = collect_ball(mesh, context, v);
    const Vec3 start = mesh.points[v];
    const double worst_start = ball.worst_at(start);
    result.worst_before = result.worst_after = worst_start;

    Vec3 current = start;
    double worst = worst_start;
    auto try_point = [&](const Vec3& candidate) {
        const double floor = worst + options.min_gain;
        const double w = ball.worst_at(candidate, floor);
        if (w <= floor || !sizes_allow(mesh, context, ball, start, candidate)) return false;
        current = candidate;
        worst = w;
        return true;
    };

    // 1. nodal shifting: full, half, quarter step toward the weighted target
    if (options.nodal_shifting)
    {
        const Vec3 target = nodal_shifting_target(ball, current);
        for (double alpha : {1.0, 0.5, 0.25})
            if (try_point(current + alpha * (target - current))) break;
    }

    // 2. max-min ascent on the worst tet, backtracking on the ball's true minimum
    if (options.optimization_based && worst < options.good_enough)
    {
        const double fd_step = 1e-6 * ball.mean_edge;
        for (int iteration = 0; iteration < options.max_ascent_steps; ++iteration)
        {
            const std::size_t w = ball.worst_index(current);
            const Vec3 g = quality_gradient(ball, w, current, fd_step);
            const double gnorm = g.norm();
            if (!(gnorm > 0)) break;
            const Vec3 direction = g / gnorm;
            bool improved = false;
            const double worst_before_step = worst;
            for (double step = 0.2 * ball.mean_edge; step > 0.004 * ball.mean_edge; step *= 0.5)
                if (try_point(current + step * direction))
                {
                    improved = true;
                    break;
                }
            // stop when blocked or when the gain no longer pays for the evaluations
            if (!improved || worst - worst_before_step < 1e-3) break;
        }
    }

    if (worst > worst_start + options.min_gain)
    {
        mesh.points[v] = current;
        context.touched.insert(context.touched.end(), ball.tets.begin(), ball.tets.end());
        result.moved = true;
        result.worst_after = worst;
    }
    return result;
}

SmoothResult equalize_edge_sizes(TetMesh& mesh, OperatorContext& context, int v,
                                 const SizeSmoothOptions& options)
{
    SmoothResult result;
    if (context.field == nullptr || !context.constraints.is_free_vertex(v) ||
        context.vertex_tet[v] < 0)
        return result;
    const MovingBall ball = collect_ball(mesh, context, v);
    const Vec3 start = mesh.points[v];
    auto worst_size = [&](const Vec3& p) {
        double worst = 1.0;
        for (int n : ball.neighbours) worst = std::min(worst, context.size_quality(p, mesh.points[n]));
        return worst;
    };
    const double size_before = worst_size(start);
    result.worst_before = result.worst_after = ball.worst_at(start);
    if (size_before >= kSizeQualityThreshold) return result;  // nothing to fix here

    // each neighbour proposes the point at its edge's target length, toward the vertex
    Vec3 target = Vec3::Zero();
    for (int n : ball.neighbours)
    {
        const Vec3& q = mesh.points[n];
        const Vec3 d = start - q;
        const double length = d.norm();
        if (length <= 0) return result;
        target += q + (edge_target_size(*context.field, q, start) / length) * d;
    }
    target /= static_cast<double>(ball.neighbours.size());

    const double floor = std::min(result.worst_before, options.min_quality);
    for (double alpha : {1.0, 0.5, 0.25})
    {
        const Vec3 candidate = start + alpha * (target - start);
        const double shape = ball.worst_at(candidate, floor);
        if (shape <= 0 || shape < floor) continue;
        if (worst_size(candidate) <= size_before + options.min_gain) continue;
        bool creates_long = false;
        for (int n : ball.neighbours)
            creates_long = creates_long || (context.too_long(candidate, mesh.points[n]) &&
                                            !context.too_long(start, mesh.points[n]));
        if (creates_long) continue;
        mesh.points[v] = candidate;
        context.touched.insert(context.touched.end(), ball.tets.begin(), ball.tets.end());
        result.moved = true;
        result.worst_after = shape;
        return result;
    }
    return result;
}

}  // namespace hdimesh
