#pragma once
// Riemannian metrics: a symmetric positive definite 3x3 matrix M per point, edge e of length
// sqrt(eᵀ M e) in it. The isotropic size h is the metric h⁻² I. Files and arrays hold the six
// distinct entries in Medit's order (m11 m12 m22 m13 m23 m33: the lower triangle row by row),
// Gmsh's NodeData all nine, row-major.

#include <Eigen/Core>
#include <array>
#include <string>

#include "common/point.h"

namespace hdimesh
{

using Metric = Eigen::Matrix3d;

/// The isotropic metric of size h: h⁻² I.
Metric isotropic_metric(double h);

/// The metric from six values in Medit's order (m11 m12 m22 m13 m23 m33).
Metric metric_from_medit(const double* m6);
/// The six values of m in Medit's order.
std::array<double, 6> metric_to_medit(const Metric& m);

/// Why m is not a metric, to follow "is" ("not finite", "not positive definite (...)"); empty
/// when it is one.
std::string metric_problem(const Metric& m);
/// The metric from Gmsh's nine row-major values; *problem says so when they are not symmetric
/// (to a relative 1e-10).
Metric metric_from_row_major(const double* m9, std::string* problem);

/// Length of e in m: sqrt(eᵀ m e).
inline double metric_length(const Metric& m, const Vec3& e) { return std::sqrt(e.dot(m * e)); }

/// The matrix logarithm and exponential of a symmetric matrix (log of an SPD one): the
/// log-Euclidean frame (Arsigny et al. 2006) in which metrics are interpolated linearly.
Metric metric_log(const Metric& m);
Metric metric_exp(const Metric& log_m);

/// m with its sizes (eigenvalues λ as 1/√λ) bounded to [hmin, hmax]; hmax may be +infinity.
Metric bound_metric(const Metric& m, double hmin, double hmax);

/// The largest metric whose unit ball lies in both unit balls (simultaneous reduction, Alauzet
/// & Frey): the sizes in each direction the smaller of the two.
Metric intersect_metrics(const Metric& a, const Metric& b);

/// The sizes of m (1/√λ), smallest first.
Vec3 metric_sizes(const Metric& m);

/// The isotropic size with the same volume as m's unit ball: det(m)^(-1/6).
double metric_mean_size(const Metric& m);

/// Shape quality of tet (a,b,c,d) in metric m: Qe of the tet mapped by m^½ (1 for a tet that is
/// regular in m), computed from m without its square root: volumes scale by √det m, face
/// areas by √(nᵀ cof(m) n).
double metric_tet_quality(const Metric& m, const Vec3& a, const Vec3& b, const Vec3& c,
                          const Vec3& d);

/// Mmg's quality in a metric (MMG5_caltet_ani), with `mean` the mean of the four vertex
/// metrics: Q = 72√3 · V_M / (Σ ℓ_M²)^{3/2}, 1 for a regular tet.
double mmg_tet_quality(const Metric& mean, const Vec3& a, const Vec3& b, const Vec3& c,
                       const Vec3& d);

}  // namespace hdimesh
