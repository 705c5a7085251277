#include "hdi/hdi_surface.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>

#include "hdi/detail/hdi_model.h"

namespace hdimesh::hdi
{
namespace
{

using detail::at;
using detail::Model;
using detail::relative_rank_threshold;
using detail::segment_count;

Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b)
{
    const Vec3 ab = b - a;
    const double length2 = ab.squaredNorm();
    if (!(length2 > 0)) return a;
    const double t = std::clamp((p - a).dot(ab) / length2, 0.0, 1.0);
    return a + t * ab;
}

/// The nearest feature segment to x: (chain, j).
std::array<int, 2> nearest_segment(const Model& m, const Vec3& x)
{
    int indices[4];
    double d2[4];
    const int found = m.line_knn.nearest(x, 4, indices, d2);
    std::array<int, 2> best{-1, -1};
    double best_d2 = std::numeric_limits<double>::infinity();
    for (int i = 0; i < found; ++i)
        for (int k = m.segment_begin[at(indices[i])]; k < m.segment_begin[at(indices[i]) + 1]; ++k)
        {
            const auto [chain, j] = m.segments[at(k)];
            const std::vector<int>& line = m.chains[at(chain)].vertices;
            const Vec3& a = m.points[at(line[at(j)])];
            const Vec3& b = m.points[at(line[(at(j) + 1) % line.size()])];
            const double distance2 = (x - closest_point_on_segment(x, a, b)).squaredNorm();
            if (distance2 < best_d2)
            {
                best_d2 = distance2;
                best = {chain, j};
            }
        }
    return best;
}

double distance2_to_segment(const Model& m, const FeatureChain& chain, int j, const Vec3& x)
{
    const Vec3& a = m.points[at(chain.vertices[at(j)])];
    const Vec3& b = m.points[at(chain.vertices[(at(j) + 1) % chain.vertices.size()])];
    return (x - closest_point_on_segment(x, a, b)).squaredNorm();
}

/// The chain's segment nearest to `current`, slid to from segment j along the chain.
int slide_to_nearest_segment(const Model& m, const FeatureChain& chain, int j, const Vec3& current)
{
    const int segments = segment_count(chain);
    while (true)
    {
        const double here = distance2_to_segment(m, chain, j, current);
        const int before = chain.closed ? (j - 1 + segments) % segments : j - 1;
        const int after = chain.closed ? (j + 1) % segments : j + 1;
        if (before >= 0 && before != j && distance2_to_segment(m, chain, before, current) < here)
            j = before;
        else if (after < segments && after != j &&
                 distance2_to_segment(m, chain, after, current) < here)
            j = after;
        else
            break;
    }
    return j;
}

/// A ridge fit's window: its nodes' weights, the diffuse origin and radius, and the tangent.
struct RidgeFrame
{
    double rho = 0;
    double weights[64];
    Vec3 origin = Vec3::Zero();
    Vec3 tangent;
};

/// The frame of the window's `count` nodes around `current`; false when the radius or the
/// weights vanish.
bool fit_ridge_frame(const Model& m, const int* node, int count, const Vec3& current,
                     RidgeFrame& frame)
{
    const HdiOptions& o = m.options;
    double farthest = 0;
    for (int i = 0; i < count; ++i)
        farthest = std::max(farthest, (m.points[at(node[i])] - current).norm());
    const double rho = o.window_factor * farthest;
    frame.rho = rho;
    if (!(rho > 0)) return false;
    double* weights = frame.weights;
    double weight_sum = 0;
    Vec3 origin = Vec3::Zero();
    for (int i = 0; i < count; ++i)
    {
        weights[i] = diffuse_weight(o.weight, (m.points[at(node[i])] - current).norm() / rho);
        weight_sum += weights[i];
        origin += weights[i] * m.points[at(node[i])];
    }
    if (!(weight_sum > 0)) return false;
    origin /= weight_sum;
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (int i = 0; i < count; ++i)
    {
        const Vec3 d = (m.points[at(node[i])] - origin) / rho;
        scatter.noalias() += weights[i] * d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
    eigen.computeDirect(scatter);
    Vec3 tangent = eigen.eigenvectors().col(2).normalized();  // largest eigenvalue: along the line
    const Vec3 chain_direction = m.points[at(node[count - 1])] - m.points[at(node[0])];
    if (tangent.dot(chain_direction) < 0) tangent = -tangent;
    frame.origin = origin;
    frame.tangent = tangent;
    return true;
}

/// Offsets from a frame's tangent line as quadratics in the scaled parameter s.
struct RidgeCurve
{
    Eigen::Matrix3d coefficients = Eigen::Matrix3d::Zero();  // rows: c0, c1, c2 (3-vectors)
    double s_first = 0, s_last = 0;  // the parameters of the window's first and last nodes
    bool linear = false;
};

RidgeCurve fit_ridge_curve(const Model& m, const int* node, int count, const RidgeFrame& frame)
{
    const double rho = frame.rho;
    const double* weights = frame.weights;
    const Vec3& origin = frame.origin;
    const Vec3& tangent = frame.tangent;
    RidgeCurve curve;
    Eigen::Matrix3d normal_matrix = Eigen::Matrix3d::Zero();
    Eigen::Matrix3d right_side = Eigen::Matrix3d::Zero();  // column k: the k-th offset coordinate
    for (int i = 0; i < count; ++i)
    {
        const Vec3 d = (m.points[at(node[i])] - origin) / rho;
        const double s = d.dot(tangent);
        const Vec3 offset = d - s * tangent;
        const Vec3 row(1, s, s * s);
        normal_matrix.noalias() += weights[i] * row * row.transpose();
        right_side.noalias() += weights[i] * row * offset.transpose();
        if (i == 0) curve.s_first = s;
        if (i == count - 1) curve.s_last = s;
    }
    Eigen::ColPivHouseholderQR<Eigen::Matrix3d> qr(normal_matrix);
    qr.setThreshold(relative_rank_threshold);
    curve.linear = qr.rank() < 3;
    if (!curve.linear)
    {
        curve.coefficients = qr.solve(right_side);
    }
    else
    {
        const Eigen::Matrix2d small = normal_matrix.topLeftCorner<2, 2>();
        Eigen::ColPivHouseholderQR<Eigen::Matrix2d> small_qr(small);
        small_qr.setThreshold(relative_rank_threshold);
        if (small_qr.rank() == 2)
            curve.coefficients.topRows<2>() = small_qr.solve(right_side.topRows<2>());
    }
    return curve;
}

/// Orientation only: the sides' mean normal at the line node of segment j nearest to `point`.
Vec3 ridge_normal(const Model& m, const FeatureChain& chain, int j, const Vec3& point)
{
    int nearest_node = chain.vertices[at(j)];
    const int other = chain.vertices[(at(j) + 1) % chain.vertices.size()];
    if ((m.points[at(other)] - point).squaredNorm() <
        (m.points[at(nearest_node)] - point).squaredNorm())
        nearest_node = other;
    Vec3 normal = Vec3::Zero();
    for (int s = m.side_begin[at(nearest_node)]; s < m.side_begin[at(nearest_node) + 1]; ++s)
        normal += m.side_normal[at(s)];
    return normal.squaredNorm() > 0 ? Vec3(normal.normalized()) : Vec3::Zero();
}

}  // namespace

HdiSurface::HdiSurface(std::vector<Vec3> points, std::vector<Triangle3> triangles,
                       const FeatureSet& features, const HdiOptions& options)
    : model_(
          detail::build_model(std::move(points), nullptr, std::move(triangles), features, options))
{
}

HdiSurface::HdiSurface(std::vector<Vec3> points, std::vector<Vec3> normals,
                       std::vector<Triangle3> triangles, const FeatureSet& features,
                       const HdiOptions& options)
    : model_(
          detail::build_model(std::move(points), &normals, std::move(triangles), features, options))
{
}

Projection HdiSurface::project(const Vec3& x) const
{
    const Model& m = *model_;
    detail::Scratch& scratch = detail::thread_scratch();
    detail::NeighbourSearch search(m, scratch);
    Projection result;
    result.point = x;
    result.status = ProjectionStatus::Failed;
    Vec3 current = x;
    double previous_move = 0;
    for (int iteration = 0; iteration < m.options.max_iterations; ++iteration)
    {
        const int count = search.gather(current);
        detail::MongePatch patch;
        if (count < 3 || !detail::fit_monge_patch(m, scratch, count, patch))
        {
            if (iteration == 0) return result;
            break;  // keep the last good point
        }
        Projection next;
        detail::evaluate_monge_patch(patch, current, next);
        const double move = (next.point - current).norm();
        result = next;
        result.status = ProjectionStatus::NotConverged;
        current = next.point;
        // Converged when the move is below tolerance * rho, or when the next one is predicted to
        // be: the fit moves with the point at the contraction rate r = move / previous move
        // (r << 1: the weights change slowly), so the point is within r / (1 - r) * move of the
        // fixed point. This saves the third fit of most projections.
        const double tolerance = m.options.tolerance * patch.rho;
        const double rate = iteration > 0 && previous_move > 0 ? move / previous_move : 1.0;
        if (move < tolerance || (rate < 0.5 && rate / (1 - rate) * move < tolerance))
        {
            result.status = patch.linear ? ProjectionStatus::LinearFallback : ProjectionStatus::Ok;
            break;
        }
        previous_move = move;
    }
    return result;
}

DiffusePlane HdiSurface::diffuse_plane(const Vec3& x) const
{
    const Model& m = *model_;
    detail::Scratch& scratch = detail::thread_scratch();
    detail::NeighbourSearch search(m, scratch);
    DiffusePlane plane;
    const int count = search.gather(x);
    detail::MongePatch patch;
    if (count < 3 || !detail::fit_monge_patch(m, scratch, count, patch)) return plane;
    plane.origin = patch.origin;
    plane.normal = patch.n;
    plane.e1 = patch.e1;
    plane.e2 = patch.e2;
    plane.window_radius = patch.rho;
    plane.ok = true;
    return plane;
}

Projection HdiSurface::project_to_ridge(const Vec3& x) const
{
    const Model& m = *model_;
    Projection result;
    result.point = x;
    result.status = ProjectionStatus::Failed;
    if (m.line_node.empty()) return result;
    auto [chain_index, j] = nearest_segment(m, x);
    if (chain_index < 0) return result;
    const FeatureChain& chain = m.chains[at(chain_index)];
    const int size = static_cast<int>(chain.vertices.size());
    const int window = std::min(m.options.ridge_neighbours, size);
    const HdiOptions& o = m.options;

    Vec3 current = x;
    for (int iteration = 0; iteration < o.max_iterations; ++iteration)
    {
        // Slide to the chain's nearest segment to the current point.
        j = slide_to_nearest_segment(m, chain, j, current);
        // The window: `window` consecutive line nodes centred on segment j, shifted inside an open
        // chain.
        int first = j + 1 - window / 2;
        if (!chain.closed) first = std::clamp(first, 0, size - window);
        int node[64];
        const int count = std::min(window, 64);
        for (int i = 0; i < count; ++i)
            node[i] = chain.vertices[at(((first + i) % size + size) % size)];

        if (count == 2)
        {  // a single segment: the line itself
            const Vec3& a = m.points[at(node[0])];
            const Vec3& b = m.points[at(node[1])];
            result.point = closest_point_on_segment(current, a, b);
            result.tangent = (b - a).normalized();
            result.k1 = result.k2 = 0;
            result.status = ProjectionStatus::Ok;
            break;
        }
        RidgeFrame frame;
        if (!fit_ridge_frame(m, node, count, current, frame)) break;
        const double rho = frame.rho;
        const Vec3& origin = frame.origin;
        const Vec3& tangent = frame.tangent;
        const RidgeCurve curve = fit_ridge_curve(m, node, count, frame);
        const Eigen::Matrix3d& coefficients = curve.coefficients;
        const double s_first = curve.s_first, s_last = curve.s_last;
        double s = (current - origin).dot(tangent) / rho;
        // Past the end of an open line: stop at its end node (a corner or a dangling end).
        const bool at_start = !chain.closed && first == 0 && s < std::min(s_first, s_last);
        const bool at_end = !chain.closed && first + count == size && s > std::max(s_first, s_last);
        Vec3 next;
        if (at_start || at_end)
        {
            const bool start_is_low = s_first < s_last;
            const int end_node = (at_start == start_is_low) ? node[0] : node[count - 1];
            next = m.points[at(end_node)];
            s = (next - origin).dot(tangent) / rho;
        }
        else
        {
            const Vec3 c0 = coefficients.row(0).transpose(), c1 = coefficients.row(1).transpose(),
                       c2 = coefficients.row(2).transpose();
            next = origin + rho * (s * tangent + c0 + s * c1 + s * s * c2);
        }
        const Vec3 derivative =
            tangent + coefficients.row(1).transpose() + 2 * s * coefficients.row(2).transpose();
        const Vec3 second = 2 * coefficients.row(2).transpose() / rho;
        result.tangent = derivative.normalized();
        result.k1 = derivative.cross(second).norm() / std::pow(derivative.norm(), 3);
        result.k2 = 0;
        const double move = (next - current).norm();
        result.point = next;
        current = next;
        result.status = ProjectionStatus::NotConverged;
        if (move < o.tolerance * rho || at_start || at_end)
        {
            result.status = curve.linear ? ProjectionStatus::LinearFallback : ProjectionStatus::Ok;
            break;
        }
    }
    result.normal = ridge_normal(m, chain, j, result.point);
    return result;
}

bool HdiSurface::is_corner(int input_vertex) const
{
    return input_vertex >= 0 && input_vertex < static_cast<int>(model_->corner.size()) &&
           model_->corner[at(input_vertex)] != 0;
}

const FeatureSet& HdiSurface::features() const { return model_->features; }
const std::vector<FeatureChain>& HdiSurface::feature_lines() const { return model_->chains; }
const std::vector<Vec3>& HdiSurface::points() const { return model_->points; }
const std::vector<Triangle3>& HdiSurface::triangles() const { return model_->triangles; }
const HdiOptions& HdiSurface::options() const { return model_->options; }
double HdiSurface::scale() const { return model_->scale; }

}  // namespace hdimesh::hdi
