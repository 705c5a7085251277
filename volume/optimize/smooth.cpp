#include "volume/optimize/smooth.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "common/metric.h"
#include "volume/check/quality_report.h"
#include "volume/mesh/tet_tables.h"
#include "volume/optimize/collapse.h"
#include "volume/optimize/vertex_marks.h"

namespace hdimesh::volume
{

namespace
{

/// What a move found: the point and the ball's worst quality there and at the start.
struct Placement
{
    Vec3 point;
    double worst_start = 0, worst = 0;
};

/// One tet of the moving ball: its face opposite the vertex, ordered so that (f0, f1, f2, P) is
/// positive for P on the tet's side, with what tet_quality computes from the face alone done
/// once. quality(p) is bitwise tet_quality(f0, f1, f2, p): the same operations in the same order,
/// only the terms that do not depend on p are hoisted (a move tries many points per ball).
struct BallFace
{
    std::array<Vec3, 3> f;
    double perimeter = 0;  // |f1 - f0| + |f2 - f1| + |f0 - f2|
    // in an anisotropic field: the metric at the tet's centroid when the move began (held
    // while the vertex moves, so every candidate is judged by the same measure) as its square
    // root, which maps to the space where the metric is the identity, and back
    bool in_metric = false;
    Metric root, root_inverse;
    // the face where shapes are judged: f, or f mapped by root; and its hoisted parts
    std::array<Vec3, 3> g;
    Vec3 e1, e2;               // g1 - g0, g2 - g0
    double fixed_area = 0;     // triangle_area(g0, g2, g1), the last term of tet_quality's sum
    double face_longest2 = 0;  // longest squared edge of g

    explicit BallFace(const std::array<Vec3, 3>& face) : f(face)
    {
        perimeter = (f[1] - f[0]).norm() + (f[2] - f[1]).norm() + (f[0] - f[2]).norm();
        hoist(f);
    }

    void hoist(const std::array<Vec3, 3>& face)
    {
        g = face;
        e1 = g[1] - g[0];
        e2 = g[2] - g[0];
        fixed_area = triangle_area(g[0], g[2], g[1]);
        face_longest2 = std::max({e1.squaredNorm(), e2.squaredNorm(), (g[2] - g[1]).squaredNorm()});
    }

    void set_metric(const Metric& metric)
    {
        in_metric = true;
        Eigen::SelfAdjointEigenSolver<Metric> eigen;
        eigen.computeDirect(metric);  // closed form: fast, and a root needs no more accuracy
        const Eigen::Matrix3d& q = eigen.eigenvectors();
        root = q * eigen.eigenvalues().cwiseSqrt().asDiagonal() * q.transpose();
        root_inverse =
            q * eigen.eigenvalues().cwiseSqrt().cwiseInverse().asDiagonal() * q.transpose();
        hoist({root * f[0], root * f[1], root * f[2]});
    }

    /// p where shapes are judged.
    Vec3 judged(const Vec3& p) const { return in_metric ? Vec3(root * p) : p; }

    double quality(const Vec3& p) const
    {
        // tet_quality(a, b, c, d) with a, b, c = g0, g1, g2 and d = p (mapped)
        const Vec3& a = g[0];
        const Vec3& b = g[1];
        const Vec3& c = g[2];
        const Vec3 d = judged(p);
        const double volume = e1.dot(e2.cross(d - a)) / 6.0;
        const double area =
            triangle_area(b, c, d) + triangle_area(a, d, c) + triangle_area(a, b, d) + fixed_area;
        const double longest2 = std::max(
            {face_longest2, (d - a).squaredNorm(), (d - b).squaredNorm(), (d - c).squaredNorm()});
        return tet_quality_from_parts(volume, area, longest2);
    }
};

/// The ball of the moving vertex, reduced to what a move changes: each tet is its face
/// opposite the vertex.
struct MovingBall
{
    int vertex = -1;
    std::vector<int> tets;
    std::vector<BallFace> faces;
    std::vector<Vec3> neighbours;  // the other vertices of the ball, each once
    double mean_edge = 0;          // of the opposite faces: the scale of the steps

    double quality_at(std::size_t i, const Vec3& p) const { return faces[i].quality(p); }

    /// The smallest dihedral angle of the ball's tets with the vertex at p, in degrees.
    double smallest_dihedral(const Vec3& p) const
    {
        // acos falls as its argument rises: the smallest angle is the acos of the largest cosine
        double largest = -1.0;
        for (const BallFace& face : faces)
            largest = std::max(
                largest, smallest_dihedral_cosine(face.g[0], face.g[1], face.g[2], face.judged(p)));
        return std::min(180.0, dihedral_cosine_to_deg(largest));
    }

    /// The worst quality with the vertex at p, stopping early once it is <= floor. When it
    /// does not stop early, *worst_index gets the first tet of least quality.
    double worst_at(const Vec3& p, double floor = -std::numeric_limits<double>::infinity(),
                    std::size_t* worst_index = nullptr) const
    {
        double worst = std::numeric_limits<double>::infinity();
        std::size_t index = 0;
        for (std::size_t i = 0; i < faces.size(); ++i)
        {
            const double q = quality_at(i, p);
            if (q < worst)
            {
                worst = q;
                index = i;
            }
            if (worst <= floor) break;
        }
        if (worst_index != nullptr) *worst_index = index;
        return worst;
    }

    /// Whether the worst quality at p is above floor, deciding exactly as worst_at(p, floor)
    /// > floor but testing first the tet that refused the previous point: a rejected
    /// candidate usually fails on the same tet, so most rejections cost one evaluation. When
    /// it returns true, *worst and *worst_index are worst_at's full results.
    bool worst_above(const Vec3& p, double floor, double* worst, std::size_t* worst_index) const
    {
        const std::size_t hint = refused_last;
        double hint_quality = 0;
        if (hint < faces.size())
        {
            hint_quality = quality_at(hint, p);
            if (hint_quality <= floor) return false;
        }
        double running = std::numeric_limits<double>::infinity();
        std::size_t index = 0;
        for (std::size_t i = 0; i < faces.size(); ++i)
        {
            const double q = i == hint ? hint_quality : quality_at(i, p);
            if (q < running)
            {
                running = q;
                index = i;
            }
            if (running <= floor)
            {
                refused_last = i;
                return false;
            }
        }
        *worst = running;
        *worst_index = index;
        return true;
    }

    mutable std::size_t refused_last = static_cast<std::size_t>(-1);  // the hint above
};

MovingBall collect_ball(const TetMesh& mesh, const OperatorContext& context, int v)
{
    MovingBall ball;
    ball.vertex = v;
    context.ball(mesh, v, ball.tets);
    std::vector<int> neighbour_ids;
    VertexMarks& marks = vertex_marks();
    marks.next_round(mesh.num_vertices());
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
        ball.faces.emplace_back(std::array<Vec3, 3>{f0, f1, f2});
        if (context.field != nullptr && context.field->anisotropic())
            ball.faces.back().set_metric(
                context.field->metric(0.25 * (f0 + f1 + f2 + mesh.points[v])));
        edge_sum += ball.faces.back().perimeter;
        for (int k : fv)
            if (marks.mark(tv[k])) neighbour_ids.push_back(tv[k]);
    }
    std::sort(neighbour_ids.begin(), neighbour_ids.end());
    for (int n : neighbour_ids) ball.neighbours.push_back(mesh.points[n]);
    ball.mean_edge = edge_sum / (3.0 * static_cast<double>(ball.faces.size()));
    return ball;
}

/// The apex over face f that makes a regular tet of the face's mean edge, on the positive side;
/// false for a flat face.
bool regular_apex(const std::array<Vec3, 3>& f, Vec3& apex)
{
    // (f0, f1, f2, P) positive: P lies on the side of (f1 - f0) x (f2 - f0)
    const Vec3 normal = (f[1] - f[0]).cross(f[2] - f[0]);
    const double norm = normal.norm();
    if (norm <= 0) return false;
    const double edge = ((f[1] - f[0]).norm() + (f[2] - f[1]).norm() + (f[0] - f[2]).norm()) / 3;
    apex = (f[0] + f[1] + f[2]) / 3 + (std::sqrt(2.0 / 3.0) * edge / norm) * normal;
    return true;
}

/// George's target: the 1/Q^2-weighted mean of the points that make each tet regular (in the
/// metric, for a metric).
Vec3 nodal_shifting_target(const MovingBall& ball, const Vec3& current)
{
    Vec3 sum = Vec3::Zero();
    double weight_sum = 0;
    for (std::size_t i = 0; i < ball.faces.size(); ++i)
    {
        const BallFace& face = ball.faces[i];
        Vec3 ideal;
        if (!regular_apex(face.g, ideal)) continue;
        if (face.in_metric) ideal = face.root_inverse * ideal;
        const double q = std::max(ball.quality_at(i, current), 1e-3);
        const double weight = 1.0 / (q * q);
        sum += weight * ideal;
        weight_sum += weight;
    }
    return weight_sum > 0 ? Vec3(sum / weight_sum) : current;
}

/// The ball's edges at the start of a move: every candidate compares with the same old edges,
/// so each old target is asked of the field once, when first needed.
class OldEdges
{
public:
    OldEdges(const OperatorContext& context, const MovingBall& ball, const Vec3& from)
        : context_(context), ball_(ball), from_(from),
          targets_(ball.neighbours.size(), std::numeric_limits<double>::quiet_NaN())
    {
    }
    /// As OperatorContext::too_long(from, neighbour i) and too_short measure them.
    bool too_long(std::size_t i) const { return edge(i).too_long(); }
    bool too_short(std::size_t i) const { return edge(i).too_short(); }

private:
    EdgeInField edge(std::size_t i) const
    {
        double& t = targets_[i];
        if (std::isnan(t)) t = edge_target_size(*context_.field, from_, ball_.neighbours[i]);
        return {(ball_.neighbours[i] - from_).norm(), t};
    }

    const OperatorContext& context_;
    const MovingBall& ball_;
    const Vec3 from_;
    mutable std::vector<double> targets_;  // NaN: not asked yet
};

/// No edge of the vertex may become too long or too short at p (edges already so may stay).
/// The candidate's length and target are computed once per edge (the field is the costly part);
/// the old edge is measured only when the new one fails.
bool sizes_allow(const OperatorContext& context, const MovingBall& ball, const OldEdges& old,
                 const Vec3& to)
{
    if (context.field == nullptr) return true;
    for (std::size_t i = 0; i < ball.neighbours.size(); ++i)
    {
        const Vec3& q = ball.neighbours[i];
        const EdgeInField edge = measure_edge(*context.field, to, q);
        if (edge.too_long() && !old.too_long(i)) return false;
        if (edge.too_short() && !old.too_short(i)) return false;
    }
    return true;
}

/// Whether sizes_allow accepts p; when it does not, p is first moved radially from each
/// neighbour whose edge it refuses to just inside the size band (the displacements added, one
/// pass: the field is the costly part) and checked again.
bool fit_size_band(const OperatorContext& context, const MovingBall& ball, const OldEdges& old,
                   Vec3& p)
{
    if (context.field == nullptr) return true;
    // a hair inside the band, so that the check after the move does not refuse it again
    constexpr double kInside = 1e-3;
    Vec3 shift = Vec3::Zero();
    bool refused = false;
    for (std::size_t i = 0; i < ball.neighbours.size(); ++i)
    {
        const Vec3& q = ball.neighbours[i];
        const Vec3 d = p - q;
        const double length = d.norm();
        const EdgeInField edge{length, edge_target_size(*context.field, p, q)};
        double wanted = length;
        if (edge.too_short() && !old.too_short(i))
            wanted = kSizeQualityThreshold * edge.size * (1 + kInside);
        else if (edge.too_long() && !old.too_long(i))
            wanted = edge.size / kSizeQualityThreshold * (1 - kInside);
        if (wanted == length) continue;
        if (!(length > 0)) return false;
        refused = true;
        shift += (wanted / length - 1) * d;
    }
    if (!refused) return true;
    p += shift;
    return sizes_allow(context, ball, old, p);
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

/// The point of the convex hull of `vectors` nearest the origin (Frank-Wolfe with exact line
/// search; a handful of vectors): every vector has a positive dot product with it unless it is
/// zero, so it raises all their functions at once.
Vec3 min_norm_in_hull(const std::vector<Vec3>& vectors)
{
    Vec3 x = vectors.front();
    for (int iteration = 0; iteration < 64 && vectors.size() > 1; ++iteration)
    {
        const Vec3* vertex = &vectors.front();
        for (const Vec3& v : vectors)
            if (v.dot(x) < vertex->dot(x)) vertex = &v;
        const Vec3 d = *vertex - x;
        const double gap = -x.dot(d);  // the duality gap: zero at the optimum
        const double d2 = d.squaredNorm();
        if (gap <= 1e-12 * x.squaredNorm() || d2 <= 0) break;
        x += std::min(1.0, gap / d2) * d;
    }
    return x;
}

/// Where the vertex of `ball` should go from `start`: smooth_vertex's two moves (see the
/// header). Returns the start itself when nothing beats it by options.min_gain.
Placement best_position(const MovingBall& ball, const OperatorContext& context, const Vec3& start,
                        const SmoothOptions& options, const Vec3* plane_normal = nullptr)
{
    // a vertex of a flat boundary moves within its plane
    const auto onto_plane = [&](Vec3& p) {
        if (plane_normal) p -= (p - start).dot(*plane_normal) * *plane_normal;
    };
    // the index of the current worst tet comes with every full evaluation at the current point
    std::size_t current_worst_index = 0;
    const double worst_start =
        ball.worst_at(start, -std::numeric_limits<double>::infinity(), &current_worst_index);

    Vec3 current = start;
    double worst = worst_start;
    const OldEdges old(context, ball, start);
    auto try_point = [&](Vec3 candidate) {
        onto_plane(candidate);
        const double floor = worst + options.min_gain;
        std::size_t index = 0;
        double w = 0;
        if (!ball.worst_above(candidate, floor, &w, &index)) return false;
        if (options.size_projection)
        {
            // the best shapes often lie just past a too-short edge: the point pulled back into
            // the size band is still better than staying
            const Vec3 unfitted = candidate;
            if (!fit_size_band(context, ball, old, candidate)) return false;
            onto_plane(candidate);
            if (candidate != unfitted && !ball.worst_above(candidate, floor, &w, &index))
                return false;
        }
        else if (!sizes_allow(context, ball, old, candidate))
        {
            return false;
        }
        current = candidate;
        worst = w;
        current_worst_index = index;  // w > floor: the evaluation went through every tet
        return true;
    };

    // 1. nodal shifting: full, half, quarter step toward the weighted target
    if (options.nodal_shifting)
    {
        const Vec3 target = nodal_shifting_target(ball, current);
        for (double alpha : {1.0, 0.5, 0.25})
            if (try_point(current + alpha * (target - current))) break;
    }

    // 2. max-min ascent: the direction that raises every nearly worst tet at once (the
    //    minimum-norm point of their gradients' hull), backtracking on the ball's true minimum
    if (options.optimization_based && worst < options.good_enough)
    {
        const double fd_step = 1e-6 * ball.mean_edge;
        std::vector<Vec3> gradients;
        for (int iteration = 0; iteration < options.max_ascent_steps; ++iteration)
        {
            gradients.clear();
            gradients.push_back(quality_gradient(ball, current_worst_index, current, fd_step));
            for (std::size_t i = 0; i < ball.faces.size(); ++i)
                if (i != current_worst_index &&
                    ball.quality_at(i, current) <= worst + options.active_band)
                    gradients.push_back(quality_gradient(ball, i, current, fd_step));
            const Vec3 g = min_norm_in_hull(gradients);
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

    Placement placement;
    placement.worst_start = worst_start;
    // Qe can rise while a dihedral angle falls: a move must not trade one for the other
    const bool keeps_angles = !(worst > worst_start + options.min_gain) ||
                              ball.smallest_dihedral(current) >=
                                  std::min(ball.smallest_dihedral(start), options.min_dihedral_deg);
    const bool moved = worst > worst_start + options.min_gain && keeps_angles;
    placement.point = moved ? current : start;
    placement.worst = moved ? worst : worst_start;
    return placement;
}

}  // namespace

SmoothResult smooth_vertex(TetMesh& mesh, OperatorContext& context, int v,
                           const SmoothOptions& options)
{
    SmoothResult result;
    if (context.vertex_tet[v] < 0) return result;
    std::optional<Vec3> plane;
    if (!context.constraints.is_free_vertex(v))
    {
        if (!options.in_flat_boundary || !context.constraints.is_surface_vertex(v)) return result;
        plane = flat_boundary_normal(mesh, context, v);
        if (!plane) return result;
    }
    const MovingBall ball = collect_ball(mesh, context, v);
    const Placement placement =
        best_position(ball, context, mesh.points[v], options, plane ? &*plane : nullptr);
    result.worst_before = placement.worst_start;
    result.worst_after = placement.worst;
    if (placement.worst > placement.worst_start)
    {
        mesh.points[v] = placement.point;
        context.tets_changed(ball.tets);
        result.moved = true;
    }
    return result;
}

PointPlacement place_vertex(const OperatorContext& context,
                            const std::vector<std::array<Vec3, 3>>& faces, const Vec3& start,
                            const SmoothOptions& options)
{
    MovingBall ball;
    double edge_sum = 0;
    for (const auto& f : faces)
    {
        ball.faces.emplace_back(f);
        if (context.field != nullptr && context.field->anisotropic())
            ball.faces.back().set_metric(
                context.field->metric(0.25 * (f[0] + f[1] + f[2] + start)));
        edge_sum += ball.faces.back().perimeter;
        for (const Vec3& q : f) ball.neighbours.push_back(q);
    }
    std::sort(ball.neighbours.begin(), ball.neighbours.end(), [](const Vec3& x, const Vec3& y) {
        return std::lexicographical_compare(x.data(), x.data() + 3, y.data(), y.data() + 3);
    });
    ball.neighbours.erase(std::unique(ball.neighbours.begin(), ball.neighbours.end()),
                          ball.neighbours.end());
    ball.mean_edge = faces.empty() ? 0 : edge_sum / (3.0 * static_cast<double>(faces.size()));
    PointPlacement result;
    result.point = start;
    if (faces.empty()) return result;
    const Placement placement = best_position(ball, context, start, options);
    result.point = placement.point;
    result.worst_at_start = placement.worst_start;
    result.worst = placement.worst;
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
        for (const Vec3& q : ball.neighbours) worst = std::min(worst, context.size_quality(p, q));
        return worst;
    };
    const double size_before = worst_size(start);
    result.worst_before = result.worst_after = ball.worst_at(start);
    if (size_before >= kSizeQualityThreshold) return result;  // nothing to fix here

    // each neighbour proposes the point at its edge's target length, toward the vertex
    Vec3 target = Vec3::Zero();
    for (const Vec3& q : ball.neighbours)
    {
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
        for (const Vec3& q : ball.neighbours)
            creates_long =
                creates_long || (context.too_long(candidate, q) && !context.too_long(start, q));
        if (creates_long) continue;
        mesh.points[v] = candidate;
        context.tets_changed(ball.tets);
        result.moved = true;
        result.worst_after = shape;
        return result;
    }
    return result;
}

}  // namespace hdimesh::volume
