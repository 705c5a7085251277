#include "common/metric.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>

namespace hdimesh
{

namespace
{

Metric from_eigen(const Eigen::Matrix3d& vectors, const Vec3& values)
{
    return vectors * values.asDiagonal() * vectors.transpose();
}

// Eigen's iterative solver: accurate for nearly equal eigenvalues, where the closed form is not.
Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen_of(const Metric& m)
{
    return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m);
}

}  // namespace

Metric isotropic_metric(double h) { return Metric::Identity() / (h * h); }

Metric metric_from_medit(const double* m6)
{
    Metric m;
    m << m6[0], m6[1], m6[3], m6[1], m6[2], m6[4], m6[3], m6[4], m6[5];
    return m;
}

std::array<double, 6> metric_to_medit(const Metric& m)
{
    return {m(0, 0), m(1, 0), m(1, 1), m(2, 0), m(2, 1), m(2, 2)};
}

std::string metric_problem(const Metric& m)
{
    if (!m.allFinite()) return "not finite";
    const Vec3 values = eigen_of(m).eigenvalues();
    if (!(values.minCoeff() > 0.0))
    {
        std::ostringstream out;
        out << "not positive definite (eigenvalues " << values[0] << ", " << values[1] << ", "
            << values[2] << ")";
        return out.str();
    }
    return {};
}

Metric metric_from_row_major(const double* m9, std::string* problem)
{
    Metric m;
    m << m9[0], m9[1], m9[2], m9[3], m9[4], m9[5], m9[6], m9[7], m9[8];
    const double scale = m.cwiseAbs().maxCoeff();
    if (problem && (m - m.transpose()).cwiseAbs().maxCoeff() > 1e-10 * scale)
        *problem = "not symmetric";
    return 0.5 * (m + m.transpose());
}

Metric metric_log(const Metric& m)
{
    const auto eigen = eigen_of(m);
    return from_eigen(eigen.eigenvectors(), eigen.eigenvalues().array().log().matrix());
}

Metric metric_exp(const Metric& log_m)
{
    const auto eigen = eigen_of(log_m);
    return from_eigen(eigen.eigenvectors(), eigen.eigenvalues().array().exp().matrix());
}

Metric bound_metric(const Metric& m, double hmin, double hmax)
{
    const auto eigen = eigen_of(m);
    const double largest = hmin > 0.0 ? 1.0 / (hmin * hmin) : HUGE_VAL;
    const double smallest = std::isfinite(hmax) && hmax > 0.0 ? 1.0 / (hmax * hmax) : 0.0;
    Vec3 values = eigen.eigenvalues();
    for (int k = 0; k < 3; ++k) values[k] = std::clamp(values[k], smallest, largest);
    return from_eigen(eigen.eigenvectors(), values);
}

Metric intersect_metrics(const Metric& a, const Metric& b)
{
    // in the frame where a is the identity, b is c = L⁻¹ b L⁻ᵀ; there the two balls' common
    // ball is c's eigenbasis with each eigenvalue at least 1
    const Eigen::LLT<Metric> chol(a);
    const Eigen::Matrix3d l = chol.matrixL();
    const Eigen::Matrix3d l_inv = l.inverse();
    const Metric c = l_inv * b * l_inv.transpose();
    const auto eigen = eigen_of(0.5 * (c + c.transpose()));
    const Vec3 values = eigen.eigenvalues().cwiseMax(1.0);
    const Eigen::Matrix3d q = l * eigen.eigenvectors();
    return q * values.asDiagonal() * q.transpose();
}

Vec3 metric_sizes(const Metric& m)
{
    const Vec3 values = eigen_of(m).eigenvalues();
    return Vec3(1.0 / std::sqrt(values[2]), 1.0 / std::sqrt(values[1]), 1.0 / std::sqrt(values[0]));
}

double metric_mean_size(const Metric& m) { return std::pow(m.determinant(), -1.0 / 6.0); }

double metric_tet_quality(const Metric& m, const Vec3& a, const Vec3& b, const Vec3& c,
                          const Vec3& d)
{
    // cof(m): |m^½ u × m^½ v|² = (u×v)ᵀ cof(m) (u×v) for symmetric m
    Metric cof;
    cof(0, 0) = m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1);
    cof(0, 1) = m(1, 2) * m(2, 0) - m(1, 0) * m(2, 2);
    cof(0, 2) = m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0);
    cof(1, 1) = m(0, 0) * m(2, 2) - m(0, 2) * m(2, 0);
    cof(1, 2) = m(0, 1) * m(2, 0) - m(0, 0) * m(2, 1);
    cof(2, 2) = m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0);
    cof(1, 0) = cof(0, 1);
    cof(2, 0) = cof(0, 2);
    cof(2, 1) = cof(1, 2);
    const double det = m(0, 0) * cof(0, 0) + m(0, 1) * cof(0, 1) + m(0, 2) * cof(0, 2);
    const auto area = [&](const Vec3& p, const Vec3& q, const Vec3& r) {
        const Vec3 n = (q - p).cross(r - p);
        return 0.5 * std::sqrt(std::max(0.0, n.dot(cof * n)));
    };
    const double volume = (b - a).dot((c - a).cross(d - a)) / 6.0 * std::sqrt(det);
    const double faces = area(b, c, d) + area(a, d, c) + area(a, b, d) + area(a, c, b);
    double longest2 = 0.0;
    for (const Vec3& e :
         {Vec3(b - a), Vec3(c - a), Vec3(d - a), Vec3(c - b), Vec3(d - b), Vec3(d - c)})
        longest2 = std::max(longest2, e.dot(m * e));
    if (faces <= 0.0 || longest2 <= 0.0) return 0.0;
    constexpr double kAlpha = 4.898979485566356;  // 2*sqrt(6), as volume/mesh/geometry.h
    return kAlpha * (3.0 * volume / faces) / std::sqrt(longest2);
}

double mmg_tet_quality(const Metric& mean, const Vec3& a, const Vec3& b, const Vec3& c,
                       const Vec3& d)
{
    double sum = 0.0;
    for (const Vec3& e :
         {Vec3(b - a), Vec3(c - a), Vec3(d - a), Vec3(c - b), Vec3(d - b), Vec3(d - c)})
        sum += e.dot(mean * e);
    if (sum <= 0.0) return 0.0;
    const double volume = (b - a).dot((c - a).cross(d - a)) / 6.0 * std::sqrt(mean.determinant());
    return 72.0 * std::sqrt(3.0) * volume / (sum * std::sqrt(sum));
}

}  // namespace hdimesh
