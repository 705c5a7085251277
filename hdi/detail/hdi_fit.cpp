// The HDI model's local fits: the admissible neighbours of a query (its side of the ridges),
// the diffuse plane and the quadratic Monge patch with Hermite rows, and the patch evaluated.

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>

#include "hdi/detail/hdi_model.h"
#include "hdi/weights.h"

namespace hdimesh::hdi::detail
{
namespace
{

constexpr int spare_candidates = 4;  // queried past n so later iterations can reuse the search
constexpr double min_hermite_cosine =
    0.2;  // a node normal this tilted from the plane gives no slope row

/// Squared distance from p to the triangle abc (Ericson, Real-Time Collision Detection 5.1.5).
double squared_distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return ap.squaredNorm();
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return bp.squaredNorm();
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).squaredNorm();
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return cp.squaredNorm();
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).squaredNorm();
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).squaredNorm();
    const double denominator = 1.0 / (va + vb + vc);
    const Vec3 closest = a + ab * (vb * denominator) + ac * (vc * denominator);
    return (p - closest).squaredNorm();
}

/// The normal of node v on smooth patch `patch`, or nullptr when v does not touch that patch.
const Vec3* side_normal_of(const Model& m, int v, int patch)
{
    const Model::NodeRecord& record = m.node_record[at(v)];
    if (record.sides == 0) return nullptr;
    if (record.patch == patch) return &record.normal;
    if (record.sides == 1) return nullptr;
    for (int s = m.side_begin[at(v)]; s < m.side_begin[at(v) + 1]; ++s)
        if (m.side_patch[at(s)] == patch) return &m.side_normal[at(s)];
    return nullptr;
}

/// The side a query belongs to: the patch of the input triangle nearest to it and that
/// triangle's normal as the local reference. Far from ridges (every candidate node on one side of
/// one patch) that patch and the nearest node's normal are used directly. Near a ridge the
/// triangles around every candidate node are searched: the nearest nodes alone can all lie on the
/// other side when that side is more finely meshed.
void choose_side(const Model& m, const Vec3& x, const Scratch& s, int& patch,
                 Vec3& reference_normal)
{
    const int first = s.candidate[0];
    const int candidate_count = static_cast<int>(s.candidate.size());
    bool ambiguous = false;
    if (m.several_patches && side_count(m, first) == 1)
    {
        const int first_patch = m.side_patch[at(m.side_begin[at(first)])];
        for (int i = 0; i < candidate_count && !ambiguous; ++i)
        {
            const int v = s.candidate[at(i)];
            ambiguous =
                side_count(m, v) != 1 || m.side_patch[at(m.side_begin[at(v)])] != first_patch;
        }
    }
    else
    {
        ambiguous = m.several_patches || side_count(m, first) != 1;
    }
    if (!ambiguous)
    {
        patch = m.side_patch[at(m.side_begin[at(first)])];
        reference_normal = m.side_normal[at(m.side_begin[at(first)])];
        return;
    }
    // Ties (x nearest to a ridge edge or node, as in the wedge outside a convex ridge) go to the
    // triangle x stands highest above: the one it was pushed off, whose side it projects into.
    double best = std::numeric_limits<double>::infinity();
    double best_height = 0;
    for (int i = 0; i < candidate_count; ++i)
    {
        const int v = s.candidate[at(i)];
        for (int k = m.incident_begin[at(v)]; k < m.incident_begin[at(v) + 1]; ++k)
        {
            const int t = m.incident_triangles[at(k)];
            if (m.face_normal[at(t)].squaredNorm() == 0) continue;
            const Triangle3& tri = m.triangles[at(t)];
            const double d2 = squared_distance_to_triangle(
                x, m.points[at(tri[0])], m.points[at(tri[1])], m.points[at(tri[2])]);
            const double height = std::abs((x - m.points[at(tri[0])]).dot(m.face_normal[at(t)]));
            const bool nearer =
                best == std::numeric_limits<double>::infinity() || d2 < best * (1 - 1e-9);
            const bool tied_and_higher = d2 <= best * (1 + 1e-9) && height > best_height;
            if (nearer || tied_and_higher)
            {
                best = std::min(best, d2);
                best_height = height;
                patch = m.triangle_patch[at(t)];
                reference_normal = m.face_normal[at(t)];
            }
        }
    }
    if (best == std::numeric_limits<double>::infinity())  // no triangle around: a point cloud
        for (int i = 0; i < candidate_count; ++i)
        {
            const int v = s.candidate[at(i)];
            if (side_count(m, v) == 0) continue;
            patch = m.side_patch[at(m.side_begin[at(v)])];
            reference_normal = m.side_normal[at(m.side_begin[at(v)])];
            break;
        }
}

/// Re-sorts the admissible nodes by their updated squared distances (they are nearly sorted).
void insertion_sort_nodes(Scratch& s)
{
    for (std::size_t i = 1; i < s.node.size(); ++i)
        for (std::size_t j = i; j > 0 && s.node_d2[j - 1] > s.node_d2[j]; --j)
        {
            std::swap(s.node_d2[j - 1], s.node_d2[j]);
            std::swap(s.node[j - 1], s.node[j]);
            std::swap(s.node_point[j - 1], s.node_point[j]);
            std::swap(s.node_normal[j - 1], s.node_normal[j]);
        }
}

/// Keeps, in order, the candidates on the query's side whose normal agrees with the reference.
void filter_admissible(const Model& m, int patch, const Vec3& reference_normal, Scratch& s)
{
    s.node.clear();
    s.node_d2.clear();
    s.node_point.clear();
    s.node_normal.clear();
    for (std::size_t i = 0; i < s.candidate.size(); ++i)
    {
        const int v = s.candidate[i];
        const Vec3* normal = side_normal_of(m, v, patch);
        if (!normal || normal->dot(reference_normal) < m.options.normal_agreement) continue;
        s.node.push_back(v);
        s.node_d2.push_back(s.candidate_d2[i]);
        s.node_point.push_back(m.node_record[at(v)].point);
        s.node_normal.push_back(*normal);
    }
}

/// The diffuse plane of the first `used` nodes: each node's weight and its offset from the
/// diffuse origin over rho (arrays of `used`), and the patch's origin and frame. False when the
/// weights vanish.
bool fit_diffuse_frame(const Model& m, const Scratch& s, int used, MongePatch& patch,
                       double* weights, Vec3* offsets)
{
    const HdiOptions& o = m.options;
    const double inverse_rho = 1.0 / patch.rho;
    double weight_sum = 0;
    Vec3 weighted_sum = Vec3::Zero();
    Vec3 normal_sum = Vec3::Zero();
    for (int i = 0; i < used; ++i)
    {
        const double w = diffuse_weight(o.weight, std::sqrt(s.node_d2[at(i)]) * inverse_rho);
        weights[i] = w;
        weight_sum += w;
        weighted_sum += w * s.node_point[at(i)];
        normal_sum += w * s.node_normal[at(i)];
    }
    if (!(weight_sum > 0)) return false;
    patch.origin = weighted_sum / weight_sum;  // eq. 5, normalized

    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();  // P^T W P, eq. 7
    for (int i = 0; i < used; ++i)
    {
        offsets[i] = (s.node_point[at(i)] - patch.origin) * inverse_rho;
        scatter.noalias() += weights[i] * offsets[i] * offsets[i].transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
    eigen.computeDirect(scatter);
    patch.n = eigen.eigenvectors().col(0).normalized();  // smallest eigenvalue first
    if (patch.n.dot(normal_sum) < 0) patch.n = -patch.n;
    patch.e1 = patch.n.unitOrthogonal();
    patch.e2 = patch.n.cross(patch.e1);
    return true;
}

/// The moment sums the patch's normal equations are assembled from (accumulate_moments).
struct MomentSums
{
    double height[5][5] = {};  // height[a][b] = sum w u^a v^b, a + b <= 4
    double slope[3][3] = {};  // slope[a][b] = sum w u^a v^b over nodes with a slope row, a + b <= 2
    Vector6d right_side = Vector6d::Zero();
};

/// Weighted least squares with Hermite rows. In scaled coordinates the paper's rho² weight on
/// the slope rows is the same weight as the height rows'. The normal equations are assembled
/// from moment sums: a height row r = <1, u, v, u², uv, v²> contributes r rᵀ, whose entries
/// are the monomials u^a v^b (a + b <= 4); the slope rows r_u = <0, 1, 0, 2u, v, 0> and
/// r_v = <0, 0, 1, 0, u, 2v> need moments up to degree 2 only.
void accumulate_moments(const Scratch& s, const MongePatch& patch, int used, const double* weights,
                        const Vec3* offsets, bool hermite, MomentSums& sums)
{
    auto& height = sums.height;
    auto& slope = sums.slope;
    Vector6d& right_side = sums.right_side;
    for (int i = 0; i < used; ++i)
    {
        const double w = weights[i];
        const Vec3& d = offsets[i];
        const double u = d.dot(patch.e1), v = d.dot(patch.e2), z = d.dot(patch.n);
        double u_power[5] = {1, u, u * u, 0, 0}, v_power[5] = {1, v, v * v, 0, 0};
        u_power[3] = u_power[2] * u;
        u_power[4] = u_power[2] * u_power[2];
        v_power[3] = v_power[2] * v;
        v_power[4] = v_power[2] * v_power[2];
        for (int a = 0; a <= 4; ++a)
            for (int b = 0; a + b <= 4; ++b) height[a][b] += w * u_power[a] * v_power[b];
        const double wz = w * z;
        right_side[0] += wz;
        right_side[1] += wz * u;
        right_side[2] += wz * v;
        right_side[3] += wz * u_power[2];
        right_side[4] += wz * u * v;
        right_side[5] += wz * v_power[2];
        const Vec3& normal = s.node_normal[at(i)];
        const double c = normal.dot(patch.n);
        if (!hermite || c < min_hermite_cosine) continue;
        const double slope_u = -normal.dot(patch.e1) / c;
        const double slope_v = -normal.dot(patch.e2) / c;
        for (int a = 0; a <= 2; ++a)
            for (int b = 0; a + b <= 2; ++b) slope[a][b] += w * u_power[a] * v_power[b];
        // + slope_u r_u + slope_v r_v
        const double wu = w * slope_u, wv = w * slope_v;
        right_side[1] += wu;
        right_side[2] += wv;
        right_side[3] += 2 * wu * u;
        right_side[4] += wu * v + wv * u;
        right_side[5] += 2 * wv * v;
    }
}

/// The patch's coefficients from the moment sums: the quadratic, or the plane when the 6 x 6
/// system is ill-conditioned.
void solve_monge_system(const MomentSums& sums, MongePatch& patch)
{
    const auto& height = sums.height;
    const auto& slope = sums.slope;
    const Vector6d& right_side = sums.right_side;
    // Monomial exponents of the basis <1, u, v, u², uv, v²>.
    static constexpr int exponent_u[6] = {0, 1, 0, 2, 1, 0};
    static constexpr int exponent_v[6] = {0, 0, 1, 0, 1, 2};
    Matrix6d normal_matrix;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j <= i; ++j)
            normal_matrix(i, j) =
                height[exponent_u[i] + exponent_u[j]][exponent_v[i] + exponent_v[j]];
    // sum w (r_u r_uᵀ + r_v r_vᵀ), lower triangle, written out.
    normal_matrix(1, 1) += slope[0][0];
    normal_matrix(2, 2) += slope[0][0];
    normal_matrix(3, 1) += 2 * slope[1][0];
    normal_matrix(4, 1) += slope[0][1];
    normal_matrix(4, 2) += slope[1][0];
    normal_matrix(5, 2) += 2 * slope[0][1];
    normal_matrix(3, 3) += 4 * slope[2][0];
    normal_matrix(4, 3) += 2 * slope[1][1];
    normal_matrix(4, 4) += slope[0][2] + slope[2][0];
    normal_matrix(5, 4) += 2 * slope[1][1];
    normal_matrix(5, 5) += 4 * slope[0][2];
    normal_matrix.triangularView<Eigen::StrictlyUpper>() = normal_matrix.transpose();

    // Pivoted LDLᵀ of the (symmetric, positive semi-definite) 6 x 6 system; ill-conditioned when
    // the pivots span more than 1 / relative_rank_threshold.
    const Eigen::LDLT<Matrix6d, Eigen::Lower> ldlt(normal_matrix);
    const auto pivots = ldlt.vectorD().cwiseAbs();
    if (ldlt.info() == Eigen::Success &&
        pivots.minCoeff() > relative_rank_threshold * pivots.maxCoeff())
    {
        patch.a = ldlt.solve(right_side);
        patch.linear = false;
        return;
    }
    // Linear fallback: the plane <1, u, v> from the same moments.
    patch.linear = true;
    patch.a.setZero();
    Eigen::Matrix3d linear_matrix;
    linear_matrix << height[0][0], height[1][0], height[0][1], height[1][0],
        height[2][0] + slope[0][0], height[1][1], height[0][1], height[1][1],
        height[0][2] + slope[0][0];
    const Vec3 linear_right_side =
        right_side.head<3>();  // the slope rows add to entries 1 and 2 only
    Eigen::ColPivHouseholderQR<Eigen::Matrix3d> linear_qr(linear_matrix);
    linear_qr.setThreshold(relative_rank_threshold);
    if (linear_qr.rank() == 3) patch.a.head<3>() = linear_qr.solve(linear_right_side);
    // else: the plane through the diffuse origin (a = 0)
}

}  // namespace

Scratch& thread_scratch()
{
    static thread_local Scratch scratch;
    return scratch;
}

int NeighbourSearch::gather(const Vec3& x)
{
    const int total = m_.knn.size();
    const int wanted = m_.options.neighbours;
    if (searched_)
    {
        const double moved = (x - search_point_).norm();
        if (complete_ || nth_distance_ + 2 * moved <= farthest_distance_)
        {
            for (std::size_t i = 0; i < s_.node.size(); ++i)
                s_.node_d2[i] = (s_.node_point[i] - x).squaredNorm();
            insertion_sort_nodes(s_);
            return std::min(wanted, static_cast<int>(s_.node.size()));
        }
    }
    int count = std::min(total, wanted + spare_candidates);
    while (true)
    {
        s_.candidate.resize(at(count));
        s_.candidate_d2.resize(at(count));
        const int found = m_.knn.nearest(x, count, s_.candidate.data(), s_.candidate_d2.data());
        s_.candidate.resize(at(found));
        s_.candidate_d2.resize(at(found));
        if (!searched_)
        {
            if (found == 0) return 0;
            if (!side_fixed_) choose_side(m_, x, s_, patch_, reference_normal_);
            searched_ = true;
        }
        filter_admissible(m_, patch_, reference_normal_, s_);
        // Too many nodes dropped (ridge sides, thin parts): widen the search.
        if (static_cast<int>(s_.node.size()) >= wanted || found == total) break;
        count = std::min(total, 2 * count);
    }
    const int used = std::min(wanted, static_cast<int>(s_.node.size()));
    search_point_ = x;
    complete_ = static_cast<int>(s_.candidate.size()) == total;
    nth_distance_ = used == 0 ? 0.0 : std::sqrt(s_.node_d2[at(used - 1)]);
    farthest_distance_ = s_.candidate.empty() ? 0.0 : std::sqrt(s_.candidate_d2.back());
    return used;
}

bool fit_monge_patch(const Model& m, const Scratch& s, int count, MongePatch& patch, bool hermite)
{
    const HdiOptions& o = m.options;
    patch.rho = o.window_factor * std::sqrt(s.node_d2[at(count - 1)]);
    if (!(patch.rho > 0)) return false;
    double weights[256];
    Vec3 offsets[256];  // (x_i - xd) / rho
    const int used = std::min(count, 256);
    if (!fit_diffuse_frame(m, s, used, patch, weights, offsets)) return false;
    MomentSums sums;
    accumulate_moments(s, patch, used, weights, offsets, hermite, sums);
    solve_monge_system(sums, patch);
    return true;
}

/// Moves x onto the patch along its plane normal; fills point, normal and curvatures.
void evaluate_monge_patch(const MongePatch& patch, const Vec3& x, Projection& result)
{
    const Vec3 d = (x - patch.origin) / patch.rho;
    const double u = d.dot(patch.e1), v = d.dot(patch.e2);
    const Vector6d& a = patch.a;
    const double f = a[0] + a[1] * u + a[2] * v + a[3] * u * u + a[4] * u * v + a[5] * v * v;
    const double fu = a[1] + 2 * a[3] * u + a[4] * v;
    const double fv = a[2] + a[4] * u + 2 * a[5] * v;
    result.point = patch.origin + patch.rho * (u * patch.e1 + v * patch.e2 + f * patch.n);
    result.normal = (patch.n - fu * patch.e1 - fv * patch.e2).normalized();
    // Fundamental forms of the graph; second derivatives back in real units.
    const double fuu = 2 * a[3] / patch.rho, fuv = a[4] / patch.rho, fvv = 2 * a[5] / patch.rho;
    const double e = 1 + fu * fu, g = 1 + fv * fv, f_cross = fu * fv;
    const double w = std::sqrt(1 + fu * fu + fv * fv);
    const double l = fuu / w, mm = fuv / w, nn = fvv / w;
    const double metric = e * g - f_cross * f_cross;
    const double mean = (e * nn - 2 * f_cross * mm + g * l) / (2 * metric);
    const double gauss = (l * nn - mm * mm) / metric;
    const double root = std::sqrt(std::max(0.0, mean * mean - gauss));
    // Curvature toward the normal is -(bending away from it): flip the sign of the mean.
    result.k1 = -mean + root;
    result.k2 = -mean - root;
}

}  // namespace hdimesh::hdi::detail
