// Stage 2 of the cavity cascade: the cone from one new point inside the kernel.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "volume/fill/detail/cavity_stages.h"
#include "volume/fill/detail/kernel.h"
#include "volume/mesh/predicates.h"

namespace hdimesh::volume::detail
{

namespace
{

constexpr int kLpColumns = 4;

/// maximize c.x subject to A x <= b and x >= 0, where b >= 0 so that the origin is feasible:
/// a condensed (Tucker) simplex tableau, one row per constraint and one column per non-basic
/// variable, so that a pivot costs O(rows). Bland's rule: no cycling on the many degenerate
/// vertices a symmetric cavity gives.
class SmallLinearProgram
{
public:
    void clear()
    {
        rows_.clear();
        bounds_.clear();
        basic_.clear();
    }

    void add_row(const std::array<double, kLpColumns>& coefficients, double bound)
    {
        rows_.push_back(coefficients);
        bounds_.push_back(std::max(bound, 0.0));
        basic_.push_back(kLpColumns + static_cast<int>(basic_.size()));
    }

    /// false when unbounded or out of pivots; x gets the optimum otherwise.
    bool maximize(const std::array<double, kLpColumns>& objective,
                  std::array<double, kLpColumns>& x)
    {
        constexpr double kEps = 1e-12;
        std::array<double, kLpColumns> cost = objective;
        std::array<int, kLpColumns> nonbasic{};
        for (int k = 0; k < kLpColumns; ++k) nonbasic[k] = k;
        const int num_rows = static_cast<int>(rows_.size());
        const int max_pivots = 50 * (num_rows + kLpColumns);
        for (int pivots = 0;; ++pivots)
        {
            if (pivots > max_pivots) return false;
            int column = -1;
            for (int k = 0; k < kLpColumns; ++k)
                if (cost[k] > kEps && (column < 0 || nonbasic[k] < nonbasic[column])) column = k;
            if (column < 0) break;
            int row = -1;
            double best_ratio = 0;
            for (int r = 0; r < num_rows; ++r)
            {
                const double coefficient = rows_[r][column];
                if (coefficient <= kEps) continue;
                const double ratio = bounds_[r] / coefficient;
                if (row < 0 || ratio < best_ratio ||
                    (ratio == best_ratio && basic_[r] < basic_[row]))
                {
                    row = r;
                    best_ratio = ratio;
                }
            }
            if (row < 0) return false;
            pivot(row, column, cost);
            std::swap(basic_[row], nonbasic[column]);
        }
        x.fill(0.0);
        for (int r = 0; r < num_rows; ++r)
            if (basic_[r] < kLpColumns) x[basic_[r]] = bounds_[r];
        return true;
    }

private:
    void pivot(int row, int column, std::array<double, kLpColumns>& cost)
    {
        auto& pivot_row = rows_[row];
        const double inverse = 1.0 / pivot_row[column];
        for (int k = 0; k < kLpColumns; ++k) pivot_row[k] *= inverse;
        pivot_row[column] = inverse;
        bounds_[row] *= inverse;
        for (int r = 0; r < static_cast<int>(rows_.size()); ++r)
        {
            if (r == row) continue;
            auto& other = rows_[r];
            const double factor = other[column];
            if (factor == 0.0) continue;
            for (int k = 0; k < kLpColumns; ++k)
                if (k != column) other[k] -= factor * pivot_row[k];
            other[column] = -factor * inverse;
            bounds_[r] = std::max(bounds_[r] - factor * bounds_[row], 0.0);
        }
        const double factor = cost[column];
        for (int k = 0; k < kLpColumns; ++k)
            if (k != column) cost[k] -= factor * pivot_row[k];
        cost[column] = -factor * inverse;
    }

    std::vector<std::array<double, kLpColumns>> rows_;
    std::vector<double> bounds_;
    std::vector<int> basic_;
};

/// Coordinates moved and scaled so that the cavity's box is [0,1] along its longest side: the
/// LP tolerances and the search steps are then relative to the cavity's size.
struct LocalFrame
{
    Vec3 origin = Vec3::Zero();
    double scale = 1;
    Vec3 to_local(const Vec3& p) const { return (p - origin) / scale; }
    Vec3 to_global(const Vec3& q) const { return origin + scale * q; }
};

LocalFrame frame_of(const std::vector<Vec3>& points, const std::vector<Triangle>& faces)
{
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max());
    Vec3 hi = -lo;
    for (const auto& face : faces)
        for (int v : face)
        {
            lo = lo.cwiseMin(points[v]);
            hi = hi.cwiseMax(points[v]);
        }
    LocalFrame frame;
    frame.origin = lo;
    frame.scale = std::max((hi - lo).maxCoeff(), std::numeric_limits<double>::min());
    return frame;
}

/// One cone tet, reduced to what depends on the apex: tet_quality of cone_tet(face, apex).
struct ConeFace
{
    Vec3 a, b, c;
    Vec3 outward;  // (b - a) x (c - a)
    double base_area = 0;
    double base_longest2 = 0;

    ConeFace(const Vec3& a_, const Vec3& b_, const Vec3& c_) : a(a_), b(b_), c(c_)
    {
        outward = (b - a).cross(c - a);
        base_area = 0.5 * outward.norm();
        base_longest2 =
            std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    }

    double quality(const Vec3& p) const
    {
        const double volume = -outward.dot(p - a) / 6.0;
        if (volume <= 0.0) return volume;
        const Vec3 pa = a - p, pb = b - p, pc = c - p;
        const double area =
            base_area + 0.5 * (pa.cross(pb).norm() + pb.cross(pc).norm() + pc.cross(pa).norm());
        const double longest2 =
            std::max({base_longest2, pa.squaredNorm(), pb.squaredNorm(), pc.squaredNorm()});
        return tet_quality_from_parts(volume, area, longest2);
    }

    /// quality(p) and its gradient in p (for the vertex or edge that is longest there).
    double quality_and_gradient(const Vec3& p, Vec3& gradient) const
    {
        const double volume = -outward.dot(p - a) / 6.0;
        gradient.setZero();
        if (volume <= 0.0) return volume;
        const Vec3 pa = a - p, pb = b - p, pc = c - p;
        const Vec3 nab = pa.cross(pb), nbc = pb.cross(pc), nca = pc.cross(pa);
        const double lab = nab.norm(), lbc = nbc.norm(), lca = nca.norm();
        const double area = base_area + 0.5 * (lab + lbc + lca);
        // d|(x - p) x (y - p)| / dp = n^ x (y - x)
        Vec3 area_gradient = Vec3::Zero();
        if (lab > 0) area_gradient += nab.cross(b - a) / lab;
        if (lbc > 0) area_gradient += nbc.cross(c - b) / lbc;
        if (lca > 0) area_gradient += nca.cross(a - c) / lca;
        area_gradient *= 0.5;
        double longest2 = base_longest2;
        Vec3 longest_gradient = Vec3::Zero();  // of the longest edge's length squared
        for (const Vec3* edge : {&pa, &pb, &pc})
            if (edge->squaredNorm() > longest2)
            {
                longest2 = edge->squaredNorm();
                longest_gradient = -2.0 * *edge;
            }
        const double q = tet_quality_from_parts(volume, area, longest2);
        const Vec3 volume_gradient = -outward / 6.0;
        gradient = q * (volume_gradient / volume - area_gradient / area -
                        0.5 * longest_gradient / longest2);
        return q;
    }
};

/// The worst cone quality from p, cut short as soon as one tet is at or below `floor` (the
/// search only asks whether a point beats the current one). `first` is tried first and is set
/// to the face that decided.
double worst_cone_quality(const std::vector<ConeFace>& cone, const Vec3& p, double floor,
                          int& first)
{
    const int n = static_cast<int>(cone.size());
    double worst = std::numeric_limits<double>::max();
    int worst_face = first;
    for (int i = 0; i < n; ++i)
    {
        const int f = (first + i) % n;
        const double q = cone[f].quality(p);
        if (q < worst)
        {
            worst = q;
            worst_face = f;
            if (worst <= floor) break;
        }
    }
    first = worst_face;
    return worst;
}

/// Sequential linear programming for the max-min cone quality: the tets within a band of the
/// worst are linearized at p, a 4-variable LP finds the step (inside a trust box) that raises
/// the smallest linearized quality most, and the step is taken only when the true worst
/// quality rises; otherwise the box shrinks. Every point taken is in the kernel.
Vec3 raise_worst_quality(const std::vector<ConeFace>& cone, const Vec3& start, double radius,
                         double& worst)
{
    constexpr int kMaxIterations = 40;
    constexpr double kBand = 0.05;         // Qe above the worst still linearized
    constexpr double kSmallestBox = 1e-7;  // of the Chebyshev radius
    constexpr double kConverged = 1e-5;    // predicted gain of Qe that ends the search
    const int n = static_cast<int>(cone.size());
    Vec3 p = start;
    std::vector<double> quality(n);
    std::vector<Vec3> gradient(n);
    auto evaluate = [&](const Vec3& x) {
        double w = std::numeric_limits<double>::max();
        for (int i = 0; i < n; ++i)
        {
            quality[i] = cone[i].quality(x);
            w = std::min(w, quality[i]);
        }
        for (int i = 0; i < n; ++i)
            if (quality[i] <= w + kBand) cone[i].quality_and_gradient(x, gradient[i]);
        return w;
    };
    worst = evaluate(p);
    // a thin kernel can still be long: the first box is not below a tenth of the cavity
    double box = std::max(0.5 * radius, 0.1);
    int first = 0;
    SmallLinearProgram lp;
    for (int iteration = 0; iteration < kMaxIterations && box > kSmallestBox * radius; ++iteration)
    {
        // variables e = d + box (so e >= 0) and s - s_low >= 0; maximize s
        double s_low = std::numeric_limits<double>::max();
        for (int i = 0; i < n; ++i)
            if (quality[i] <= worst + kBand)
                s_low = std::min(s_low, quality[i] - box * gradient[i].cwiseAbs().sum());
        s_low -= 1.0;
        lp.clear();
        for (int i = 0; i < n; ++i)
        {
            if (quality[i] > worst + kBand) continue;
            const Vec3& g = gradient[i];
            // s <= q + g . d  <=>  (s - s_low) - g . e <= q - box * sum(g) - s_low
            lp.add_row({-g.x(), -g.y(), -g.z(), 1.0}, quality[i] - box * g.sum() - s_low);
        }
        for (int axis = 0; axis < 3; ++axis)
        {
            std::array<double, kLpColumns> row{};
            row[axis] = 1.0;
            lp.add_row(row, 2.0 * box);
        }
        std::array<double, kLpColumns> x{};
        if (!lp.maximize({0.0, 0.0, 0.0, 1.0}, x)) break;
        const Vec3 step(x[0] - box, x[1] - box, x[2] - box);
        const double predicted = x[3] + s_low - worst;
        if (predicted <= kConverged) break;
        const Vec3 q = p + step;
        if (worst_cone_quality(cone, q, worst, first) > worst)
        {
            p = q;
            const double before = worst;
            worst = evaluate(p);
            if (worst - before > 0.5 * predicted) box *= 2.0;
        }
        else
            box *= 0.25;
    }
    return p;
}

bool cone_is_positive(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                      const Vec3& apex)
{
    for (const auto& f : faces)
        if (orient3d(points[f[0]], points[f[2]], points[f[1]], apex) <= 0) return false;
    return true;
}

double cone_worst_quality(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                          const Vec3& apex)
{
    double worst = std::numeric_limits<double>::max();
    for (const auto& f : faces)
        worst = std::min(worst, tet_quality(points[f[0]], points[f[2]], points[f[1]], apex));
    return worst;
}

/// The LP in local coordinates: variables (x, y, z, t + kShift) >= 0 with x, y, z in the
/// cavity's box; maximize t subject to n_i . (p - a_i) >= t for each inward unit normal n_i.
bool local_chebyshev_centre(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                            const LocalFrame& frame, Vec3& centre, double& radius)
{
    // at least the box's diagonal (sqrt 3): every row's bound is then >= 0 at the origin
    constexpr double kShift = 2.0;
    constexpr double kMinRadius = 1e-9;
    SmallLinearProgram lp;
    for (const auto& f : faces)
    {
        const Vec3 a = frame.to_local(points[f[0]]);
        const Vec3 b = frame.to_local(points[f[1]]);
        const Vec3 c = frame.to_local(points[f[2]]);
        Vec3 inward = (c - a).cross(b - a);
        const double length = inward.norm();
        if (length > 0.0) inward /= length;
        // -n . x + s <= -n . a + kShift
        lp.add_row({-inward.x(), -inward.y(), -inward.z(), 1.0}, kShift - inward.dot(a));
    }
    for (int axis = 0; axis < 3; ++axis)
    {
        std::array<double, kLpColumns> row{};
        row[axis] = 1.0;
        lp.add_row(row, 1.0);
    }
    lp.add_row({0.0, 0.0, 0.0, 1.0}, kShift + 1.0);
    std::array<double, kLpColumns> x{};
    if (!lp.maximize({0.0, 0.0, 0.0, 1.0}, x)) return false;
    centre = Vec3(x[0], x[1], x[2]);
    radius = x[3] - kShift;
    return radius > kMinRadius;
}

}  // namespace

bool kernel_chebyshev_centre(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                             Vec3& centre, double& radius)
{
    if (faces.empty()) return false;
    const LocalFrame frame = frame_of(points, faces);
    Vec3 local_centre;
    double local_radius = 0;
    if (!local_chebyshev_centre(points, faces, frame, local_centre, local_radius)) return false;
    centre = frame.to_global(local_centre);
    radius = local_radius * frame.scale;
    return true;
}

bool best_kernel_point(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                       Vec3& point, double& worst_quality)
{
    if (faces.empty()) return false;
    const LocalFrame frame = frame_of(points, faces);
    Vec3 centre;
    double radius = 0;
    if (!local_chebyshev_centre(points, faces, frame, centre, radius)) return false;
    std::vector<ConeFace> cone;
    cone.reserve(faces.size());
    for (const auto& f : faces)
        cone.emplace_back(frame.to_local(points[f[0]]), frame.to_local(points[f[1]]),
                          frame.to_local(points[f[2]]));
    double local_worst = 0;
    const Vec3 best = raise_worst_quality(cone, centre, radius, local_worst);
    // the search's point first; the centre when rounding to global coordinates broke it
    for (const Vec3& candidate : {frame.to_global(best), frame.to_global(centre)})
    {
        if (!cone_is_positive(points, faces, candidate)) continue;
        point = candidate;
        worst_quality = cone_worst_quality(points, faces, candidate);
        return true;
    }
    return false;
}

bool fill_by_kernel_fan(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                        CavityFill& fill)
{
    Vec3 apex;
    double worst = 0;
    if (faces.size() < 4 || !best_kernel_point(points, faces, apex, worst)) return false;
    const int apex_id = static_cast<int>(points.size());
    fill.tets.clear();
    fill.tets.reserve(faces.size());
    for (const auto& f : faces) fill.tets.push_back(cone_tet(f, apex_id));
    fill.new_points.assign(1, apex);
    fill.faces = faces;
    fill.filled = true;
    fill.stage = FillStage::KernelFan;
    fill.worst_quality = worst;
    fill.failure.clear();
    return true;
}

}  // namespace hdimesh::volume::detail
