#include "hdi/hdi_surface.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "common/errors.h"
#include "hdi/knn.h"

namespace hdimesh::hdi
{

struct HdiSurface::Model
{
    Model() : knn(std::vector<Vec3>{}), line_knn(std::vector<Vec3>{}) {}

    HdiOptions options;
    std::vector<Vec3> points;
    std::vector<Triangle3> triangles;
    FeatureSet features;               // as given, plus open boundaries and completed corners
    std::vector<FeatureChain> chains;  // feature lines cut at corners
    std::vector<char> corner;          // per point
    double scale = 0;
    KnnIndex knn;  // over every point

    // Smooth sides: a node has one (patch, normal) per smooth patch it touches.
    std::vector<int> triangle_patch;
    std::vector<Vec3> face_normal;
    std::vector<int> side_begin;  // CSR over points
    std::vector<int> side_patch;
    std::vector<Vec3> side_normal;
    // The hot data of each node in one cache line: its position and its first side, so that
    // sorting out the admissible neighbours of a query reads one record per candidate.
    struct NodeRecord
    {
        Vec3 point;
        Vec3 normal;  // of the first side
        int patch;    // of the first side
        int sides;    // 0: no triangle touches the node; > 1: a ridge node, see side_begin...
    };
    std::vector<NodeRecord> node_record;
    std::vector<int> incident_begin;  // CSR over points: triangles around each point
    std::vector<int> incident_triangles;
    bool several_patches = false;

    // Feature lines: a kd-tree over their nodes, and per node the segments (chain, j) touching it,
    // segment j of a chain joining its vertices j and j + 1 (mod size when closed).
    std::vector<int> line_node;  // point index of each line node
    KnnIndex line_knn;
    std::vector<int> segment_begin;  // CSR over line nodes
    std::vector<std::array<int, 2>> segments;
};

namespace
{

using Model = HdiSurface::Model;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

constexpr double relative_rank_threshold = 1e-10;
constexpr int spare_candidates = 4;  // queried past n so later iterations can reuse the search
constexpr double min_hermite_cosine =
    0.2;  // a node normal this tilted from the plane gives no slope row

/// Per-thread buffers of one query; they only grow, so a query allocates nothing once warm.
struct Scratch
{
    std::vector<int> candidate;  // the kd-tree's answer: nearest input nodes of the search point
    std::vector<double> candidate_d2;
    // The admissible candidates (on the query's side, normal agreeing), nearest to the current
    // point first; a fit uses the first n. Positions and normals are copied so the fit reads
    // contiguous memory.
    std::vector<int> node;
    std::vector<double> node_d2;
    std::vector<Vec3> node_point;
    std::vector<Vec3> node_normal;
};

Scratch& thread_scratch()
{
    static thread_local Scratch scratch;
    return scratch;
}

std::size_t at(int i) { return static_cast<std::size_t>(i); }

Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b)
{
    const Vec3 ab = b - a;
    const double length2 = ab.squaredNorm();
    if (!(length2 > 0)) return a;
    const double t = std::clamp((p - a).dot(ab) / length2, 0.0, 1.0);
    return a + t * ab;
}

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

int side_count(const Model& m, int v) { return m.side_begin[at(v) + 1] - m.side_begin[at(v)]; }

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

/// Finds the input nodes of one fit at x: the n nearest admissible ones, exactly. A search is
/// reused while it provably still contains them (x moved by less than half the gap between the
/// n-th admissible distance and the farthest candidate at the search point).
class NeighbourSearch
{
public:
    NeighbourSearch(const Model& m, Scratch& s) : m_(m), s_(s) {}

    /// Decides the side instead of the first gather(): a given smooth patch and reference normal.
    void fix_side(int patch, const Vec3& reference_normal)
    {
        side_fixed_ = true;
        patch_ = patch;
        reference_normal_ = reference_normal;
    }

    /// Returns n' = min(n, admissible nodes found): the fit's nodes are the first n' of s.node...
    /// The first call fixes the side.
    int gather(const Vec3& x)
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

private:
    const Model& m_;
    Scratch& s_;
    bool searched_ = false;
    bool side_fixed_ = false;
    bool complete_ = false;  // the last search returned every node
    int patch_ = -1;
    Vec3 reference_normal_ = Vec3::Zero();
    Vec3 search_point_ = Vec3::Zero();
    double nth_distance_ = 0;
    double farthest_distance_ = 0;
};

/// A quadratic Monge patch z = <1, u, v, u², uv, v²>·a over the diffuse plane, in coordinates
/// scaled by the window radius (so the normal equations are well conditioned at any model size).
struct MongePatch
{
    Vec3 origin, e1, e2, n;
    double rho = 0;
    Vector6d a = Vector6d::Zero();
    bool linear = false;
};

bool fit_monge_patch(const Model& m, const Scratch& s, int count, MongePatch& patch,
                     bool hermite = true)
{
    const HdiOptions& o = m.options;
    patch.rho = o.window_factor * std::sqrt(s.node_d2[at(count - 1)]);
    if (!(patch.rho > 0)) return false;
    const double inverse_rho = 1.0 / patch.rho;
    double weights[256];
    const int used = std::min(count, 256);
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
    Vec3 offsets[256];                                  // (x_i - xd) / rho
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

    // Weighted least squares with Hermite rows. In scaled coordinates the paper's rho² weight on
    // the slope rows is the same weight as the height rows'. The normal equations are assembled
    // from moment sums: a height row r = <1, u, v, u², uv, v²> contributes r rᵀ, whose entries
    // are the monomials u^a v^b (a + b <= 4); the slope rows r_u = <0, 1, 0, 2u, v, 0> and
    // r_v = <0, 0, 1, 0, u, 2v> need moments up to degree 2 only.
    double height[5][5] = {};  // height[a][b] = sum w u^a v^b, a + b <= 4
    double slope[3][3] = {};  // slope[a][b] = sum w u^a v^b over nodes with a slope row, a + b <= 2
    Vector6d right_side = Vector6d::Zero();
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
        return true;
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

int segment_count(const FeatureChain& chain)
{
    const int n = static_cast<int>(chain.vertices.size());
    return chain.closed ? n : n - 1;
}

double distance2_to_segment(const Model& m, const FeatureChain& chain, int j, const Vec3& x)
{
    const Vec3& a = m.points[at(chain.vertices[at(j)])];
    const Vec3& b = m.points[at(chain.vertices[(at(j) + 1) % chain.vertices.size()])];
    return (x - closest_point_on_segment(x, a, b)).squaredNorm();
}

void fill_node_records(Model& m)
{
    m.node_record.resize(m.points.size());
    for (std::size_t v = 0; v < m.points.size(); ++v)
    {
        Model::NodeRecord& record = m.node_record[v];
        record.point = m.points[v];
        record.sides = m.side_begin[v + 1] - m.side_begin[v];
        record.patch = record.sides > 0 ? m.side_patch[at(m.side_begin[v])] : -1;
        record.normal = record.sides > 0 ? m.side_normal[at(m.side_begin[v])] : Vec3::Zero();
    }
}

/// Face-averaged node normals are only first-order accurate on irregular meshes, and the Hermite
/// rows pass their error on to the patch (the observed order drops from 3 toward 2). A quadratic
/// fit of the node's admissible neighbours' positions alone, evaluated at the node, gives its
/// normal to second order; that becomes the side's normal.
void refine_side_normals(Model& m)
{
    Scratch& scratch = thread_scratch();
    std::vector<Vec3> refined = m.side_normal;
    for (int v = 0; v < static_cast<int>(m.points.size()); ++v)
        for (int side = m.side_begin[at(v)]; side < m.side_begin[at(v) + 1]; ++side)
        {
            NeighbourSearch search(m, scratch);
            search.fix_side(m.side_patch[at(side)], m.side_normal[at(side)]);
            const Vec3& x = m.points[at(v)];
            const int count = search.gather(x);
            MongePatch patch;
            if (count < 6 || !fit_monge_patch(m, scratch, count, patch, false) || patch.linear)
                continue;
            Projection at_node;
            evaluate_monge_patch(patch, x, at_node);
            if (at_node.normal.dot(m.side_normal[at(side)]) > 0.5)
                refined[at(side)] = at_node.normal;
        }
    m.side_normal = std::move(refined);
}

}  // namespace

namespace
{

std::shared_ptr<Model> build_model(std::vector<Vec3> points, const std::vector<Vec3>* given_normals,
                                   std::vector<Triangle3> triangles, const FeatureSet& features,
                                   const HdiOptions& options)
{
    const int n = static_cast<int>(points.size());
    if (options.neighbours < 3 || options.neighbours > 256)
        throw InputError("hdi: HdiOptions::neighbours must be in [3, 256]");
    if (!(options.window_factor >= 1.0))
        throw InputError("hdi: HdiOptions::window_factor must be at least 1");
    if (options.max_iterations < 1)
        throw InputError("hdi: HdiOptions::max_iterations must be at least 1");
    if (!(options.tolerance > 0)) throw InputError("hdi: HdiOptions::tolerance must be positive");
    if (options.ridge_neighbours < 2 || options.ridge_neighbours > 64)
        throw InputError("hdi: HdiOptions::ridge_neighbours must be in [2, 64]");
    if (given_normals && given_normals->size() != points.size())
        throw InputError("hdi: " + std::to_string(given_normals->size()) + " normals given for " +
                         std::to_string(points.size()) + " points");
    check_triangle_indices(triangles, n);
    auto check_vertex = [n](int v, const char* what) {
        if (v < 0 || v >= n)
            throw InputError(std::string("hdi: feature ") + what + " names vertex " +
                             std::to_string(v) + " but there are " + std::to_string(n) + " points");
    };
    for (const auto& e : features.ridge_edges)
    {
        check_vertex(e[0], "ridge edge");
        check_vertex(e[1], "ridge edge");
    }
    for (const auto& e : features.boundary_edges)
    {
        check_vertex(e[0], "boundary edge");
        check_vertex(e[1], "boundary edge");
    }
    for (int c : features.corners) check_vertex(c, "corner");

    auto m = std::make_shared<Model>();
    m->options = options;
    m->points = std::move(points);
    m->triangles = std::move(triangles);
    m->scale = bounding_box(m->points).diagonal();

    // Features, normalized: sorted (min, max) edges, open boundaries added, corners completed.
    auto normalized = [](std::vector<std::array<int, 2>> edges) {
        for (auto& e : edges)
            if (e[0] > e[1]) std::swap(e[0], e[1]);
        std::sort(edges.begin(), edges.end());
        edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
        return edges;
    };
    m->features.ridge_edges = normalized(features.ridge_edges);
    std::vector<std::array<int, 2>> boundary = features.boundary_edges;
    const std::vector<std::array<int, 2>> open = open_boundary_edges(m->triangles);
    boundary.insert(boundary.end(), open.begin(), open.end());
    m->features.boundary_edges = normalized(boundary);
    std::vector<int> degree(at(n), 0);
    {
        std::vector<std::array<int, 2>> all = m->features.ridge_edges;
        all.insert(all.end(), m->features.boundary_edges.begin(), m->features.boundary_edges.end());
        for (const auto& e : normalized(all))
        {
            ++degree[at(e[0])];
            ++degree[at(e[1])];
        }
    }
    m->features.corners = features.corners;
    for (int v = 0; v < n; ++v)
        if (degree[at(v)] > 0 && degree[at(v)] != 2) m->features.corners.push_back(v);
    std::sort(m->features.corners.begin(), m->features.corners.end());
    m->features.corners.erase(std::unique(m->features.corners.begin(), m->features.corners.end()),
                              m->features.corners.end());
    m->corner.assign(at(n), 0);
    for (int c : m->features.corners) m->corner[at(c)] = 1;
    m->chains = feature_chains(m->features, n);

    // Smooth patches and the per-side node normals.
    const std::size_t triangle_count = m->triangles.size();
    m->triangle_patch = smooth_patches(m->triangles, m->features);
    m->face_normal.resize(triangle_count);
    for (std::size_t t = 0; t < triangle_count; ++t)
    {
        const Triangle3& tri = m->triangles[t];
        m->face_normal[t] =
            triangle_normal(m->points[at(tri[0])], m->points[at(tri[1])], m->points[at(tri[2])]);
    }
    struct Contribution
    {
        int vertex, patch;
        Vec3 normal;
    };
    std::vector<Contribution> contributions;
    contributions.reserve(3 * triangle_count);
    for (std::size_t t = 0; t < triangle_count; ++t)
    {
        const Triangle3& tri = m->triangles[t];
        const Vec3& fn = m->face_normal[t];
        if (fn.squaredNorm() == 0) continue;
        for (std::size_t c = 0; c < 3; ++c)
        {
            const Vec3& p = m->points[at(tri[c])];
            const Vec3& q = m->points[at(tri[(c + 1) % 3])];
            const Vec3& r = m->points[at(tri[(c + 2) % 3])];
            double weight;
            if (options.normal_weighting == NormalWeighting::Area)
            {
                weight = 0.5 * (q - p).cross(r - p).norm();
            }
            else
            {
                const Vec3 u = q - p, v = r - p;
                weight = std::atan2(u.cross(v).norm(), u.dot(v));
            }
            contributions.push_back({tri[c], m->triangle_patch[t], weight * fn});
        }
    }
    if (m->triangles.empty() && given_normals)  // a pure point cloud: one patch
        for (int v = 0; v < n; ++v) contributions.push_back({v, 0, (*given_normals)[at(v)]});
    std::sort(contributions.begin(), contributions.end(),
              [](const Contribution& a, const Contribution& b) {
                  return a.vertex < b.vertex || (a.vertex == b.vertex && a.patch < b.patch);
              });
    m->side_begin.assign(at(n) + 1, 0);
    for (std::size_t i = 0; i < contributions.size();)
    {
        std::size_t j = i;
        Vec3 sum = Vec3::Zero();
        while (j < contributions.size() && contributions[j].vertex == contributions[i].vertex &&
               contributions[j].patch == contributions[i].patch)
            sum += contributions[j++].normal;
        if (sum.squaredNorm() > 0)
        {
            m->side_patch.push_back(contributions[i].patch);
            m->side_normal.push_back(sum.normalized());
            ++m->side_begin[at(contributions[i].vertex) + 1];
        }
        i = j;
    }
    std::partial_sum(m->side_begin.begin(), m->side_begin.end(), m->side_begin.begin());
    if (given_normals && !m->triangles.empty())  // the given normal wins where it is unambiguous
        for (int v = 0; v < n; ++v)
            if (side_count(*m, v) == 1 && (*given_normals)[at(v)].squaredNorm() > 0)
                m->side_normal[at(m->side_begin[at(v)])] = (*given_normals)[at(v)].normalized();
    const int patch_count =
        m->triangle_patch.empty()
            ? 1
            : *std::max_element(m->triangle_patch.begin(), m->triangle_patch.end()) + 1;
    m->several_patches = patch_count > 1;

    m->incident_begin.assign(at(n) + 1, 0);
    for (const Triangle3& tri : m->triangles)
        for (int v : tri) ++m->incident_begin[at(v) + 1];
    std::partial_sum(m->incident_begin.begin(), m->incident_begin.end(), m->incident_begin.begin());
    m->incident_triangles.resize(at(m->incident_begin.back()));
    {
        std::vector<int> fill(m->incident_begin.begin(), m->incident_begin.end() - 1);
        for (std::size_t t = 0; t < triangle_count; ++t)
            for (int v : m->triangles[t])
                m->incident_triangles[at(fill[at(v)]++)] = static_cast<int>(t);
    }

    m->knn = KnnIndex(m->points);
    fill_node_records(*m);
    if (options.refine_normals && !given_normals)
    {
        refine_side_normals(*m);
        fill_node_records(*m);
    }

    // Feature lines.
    std::vector<int> line_index(at(n), -1);
    std::vector<std::vector<std::array<int, 2>>> node_segments;
    for (std::size_t c = 0; c < m->chains.size(); ++c)
    {
        const FeatureChain& chain = m->chains[c];
        for (int v : chain.vertices)
            if (line_index[at(v)] < 0)
            {
                line_index[at(v)] = static_cast<int>(m->line_node.size());
                m->line_node.push_back(v);
                node_segments.emplace_back();
            }
        const int segments = segment_count(chain);
        for (int j = 0; j < segments; ++j)
        {
            const int a = chain.vertices[at(j)];
            const int b = chain.vertices[(at(j) + 1) % chain.vertices.size()];
            node_segments[at(line_index[at(a)])].push_back({static_cast<int>(c), j});
            node_segments[at(line_index[at(b)])].push_back({static_cast<int>(c), j});
        }
    }
    m->segment_begin.assign(m->line_node.size() + 1, 0);
    for (std::size_t i = 0; i < node_segments.size(); ++i)
    {
        m->segment_begin[i + 1] = m->segment_begin[i] + static_cast<int>(node_segments[i].size());
        m->segments.insert(m->segments.end(), node_segments[i].begin(), node_segments[i].end());
    }
    std::vector<Vec3> line_points;
    line_points.reserve(m->line_node.size());
    for (int v : m->line_node) line_points.push_back(m->points[at(v)]);
    m->line_knn = KnnIndex(line_points);
    return m;
}

}  // namespace

HdiSurface::HdiSurface(std::vector<Vec3> points, std::vector<Triangle3> triangles,
                       const FeatureSet& features, const HdiOptions& options)
    : model_(build_model(std::move(points), nullptr, std::move(triangles), features, options))
{
}

HdiSurface::HdiSurface(std::vector<Vec3> points, std::vector<Vec3> normals,
                       std::vector<Triangle3> triangles, const FeatureSet& features,
                       const HdiOptions& options)
    : model_(build_model(std::move(points), &normals, std::move(triangles), features, options))
{
}

Projection HdiSurface::project(const Vec3& x) const
{
    const Model& m = *model_;
    Scratch& scratch = thread_scratch();
    NeighbourSearch search(m, scratch);
    Projection result;
    result.point = x;
    result.status = ProjectionStatus::Failed;
    Vec3 current = x;
    double previous_move = 0;
    for (int iteration = 0; iteration < m.options.max_iterations; ++iteration)
    {
        const int count = search.gather(current);
        MongePatch patch;
        if (count < 3 || !fit_monge_patch(m, scratch, count, patch))
        {
            if (iteration == 0) return result;
            break;  // keep the last good point
        }
        Projection next;
        evaluate_monge_patch(patch, current, next);
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
    Scratch& scratch = thread_scratch();
    NeighbourSearch search(m, scratch);
    DiffusePlane plane;
    const int count = search.gather(x);
    MongePatch patch;
    if (count < 3 || !fit_monge_patch(m, scratch, count, patch)) return plane;
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
    const int segments = segment_count(chain);
    const int window = std::min(m.options.ridge_neighbours, size);
    const HdiOptions& o = m.options;

    Vec3 current = x;
    for (int iteration = 0; iteration < o.max_iterations; ++iteration)
    {
        // Slide to the chain's nearest segment to the current point.
        while (true)
        {
            const double here = distance2_to_segment(m, chain, j, current);
            const int before = chain.closed ? (j - 1 + segments) % segments : j - 1;
            const int after = chain.closed ? (j + 1) % segments : j + 1;
            if (before >= 0 && before != j &&
                distance2_to_segment(m, chain, before, current) < here)
                j = before;
            else if (after < segments && after != j &&
                     distance2_to_segment(m, chain, after, current) < here)
                j = after;
            else
                break;
        }
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
        double farthest = 0;
        for (int i = 0; i < count; ++i)
            farthest = std::max(farthest, (m.points[at(node[i])] - current).norm());
        const double rho = o.window_factor * farthest;
        if (!(rho > 0)) break;
        double weights[64];
        double weight_sum = 0;
        Vec3 origin = Vec3::Zero();
        for (int i = 0; i < count; ++i)
        {
            weights[i] = diffuse_weight(o.weight, (m.points[at(node[i])] - current).norm() / rho);
            weight_sum += weights[i];
            origin += weights[i] * m.points[at(node[i])];
        }
        if (!(weight_sum > 0)) break;
        origin /= weight_sum;
        Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
        for (int i = 0; i < count; ++i)
        {
            const Vec3 d = (m.points[at(node[i])] - origin) / rho;
            scatter.noalias() += weights[i] * d * d.transpose();
        }
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
        eigen.computeDirect(scatter);
        Vec3 tangent =
            eigen.eigenvectors().col(2).normalized();  // largest eigenvalue: along the line
        const Vec3 chain_direction = m.points[at(node[count - 1])] - m.points[at(node[0])];
        if (tangent.dot(chain_direction) < 0) tangent = -tangent;

        // Offsets from the tangent line as quadratics in the scaled parameter s.
        Eigen::Matrix3d normal_matrix = Eigen::Matrix3d::Zero();
        Eigen::Matrix3d right_side =
            Eigen::Matrix3d::Zero();  // column k: the k-th offset coordinate
        double s_first = 0, s_last = 0;
        for (int i = 0; i < count; ++i)
        {
            const Vec3 d = (m.points[at(node[i])] - origin) / rho;
            const double s = d.dot(tangent);
            const Vec3 offset = d - s * tangent;
            const Vec3 row(1, s, s * s);
            normal_matrix.noalias() += weights[i] * row * row.transpose();
            right_side.noalias() += weights[i] * row * offset.transpose();
            if (i == 0) s_first = s;
            if (i == count - 1) s_last = s;
        }
        Eigen::Matrix3d coefficients = Eigen::Matrix3d::Zero();  // rows: c0, c1, c2 (3-vectors)
        Eigen::ColPivHouseholderQR<Eigen::Matrix3d> qr(normal_matrix);
        qr.setThreshold(relative_rank_threshold);
        const bool linear = qr.rank() < 3;
        if (!linear)
        {
            coefficients = qr.solve(right_side);
        }
        else
        {
            const Eigen::Matrix2d small = normal_matrix.topLeftCorner<2, 2>();
            Eigen::ColPivHouseholderQR<Eigen::Matrix2d> small_qr(small);
            small_qr.setThreshold(relative_rank_threshold);
            if (small_qr.rank() == 2)
                coefficients.topRows<2>() = small_qr.solve(right_side.topRows<2>());
        }
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
            result.status = linear ? ProjectionStatus::LinearFallback : ProjectionStatus::Ok;
            break;
        }
    }
    // Orientation only: the sides' mean normal at the nearest line node.
    int nearest_node = chain.vertices[at(j)];
    const int other = chain.vertices[(at(j) + 1) % chain.vertices.size()];
    if ((m.points[at(other)] - result.point).squaredNorm() <
        (m.points[at(nearest_node)] - result.point).squaredNorm())
        nearest_node = other;
    Vec3 normal = Vec3::Zero();
    for (int s = m.side_begin[at(nearest_node)]; s < m.side_begin[at(nearest_node) + 1]; ++s)
        normal += m.side_normal[at(s)];
    result.normal = normal.squaredNorm() > 0 ? Vec3(normal.normalized()) : Vec3::Zero();
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
