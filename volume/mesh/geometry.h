#pragma once
// Geometric primitives shared by every volume algorithm: signed volume and the paper's
// shape measure Qe = alpha * inradius / longest edge (1 for a regular element, 0 when flat).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "common/point.h"
#include "volume/mesh/namespace.h"

namespace hdimesh::volume
{

using hdimesh::Vec3;

/// Six times the signed volume of (a,b,c,d): positive when d sees (a,b,c) counter-clockwise
/// from below, i.e. det(b-a, c-a, d-a).
inline double signed_volume6(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
    return (b - a).dot((c - a).cross(d - a));
}

inline double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
    return signed_volume6(a, b, c, d) / 6.0;
}

inline double triangle_area(const Vec3& a, const Vec3& b, const Vec3& c)
{
    return 0.5 * (b - a).cross(c - a).norm();
}

/// Qe from its parts: signed volume, sum of the four face areas, squared longest edge. Callers
/// that hoist the parts not depending on a moving point (smoothing) share the formula here.
inline double tet_quality_from_parts(double volume, double area, double longest2)
{
    if (area <= 0.0 || longest2 <= 0.0) return 0.0;
    constexpr double kAlpha = 4.898979485566356;  // 2*sqrt(6)
    return kAlpha * (3.0 * volume / area) / std::sqrt(longest2);
}

/// Tet shape quality Qe = 2*sqrt(6) * rho / h with rho = 3V / (sum of face areas) and h the
/// longest edge. Signed: a negative tet gets a negative quality, so "worst" stays the minimum.
inline double tet_quality(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
    const double volume = signed_volume(a, b, c, d);
    const double area = triangle_area(b, c, d) + triangle_area(a, d, c) + triangle_area(a, b, d) +
                        triangle_area(a, c, b);
    const double longest2 =
        std::max({(b - a).squaredNorm(), (c - a).squaredNorm(), (d - a).squaredNorm(),
                  (c - b).squaredNorm(), (d - b).squaredNorm(), (d - c).squaredNorm()});
    return tet_quality_from_parts(volume, area, longest2);
}

/// Triangle shape quality Qe = 2*sqrt(3) * rho / h with rho = 2A / perimeter.
inline double triangle_quality(const Vec3& a, const Vec3& b, const Vec3& c)
{
    const double ab = (b - a).norm(), bc = (c - b).norm(), ca = (a - c).norm();
    const double perimeter = ab + bc + ca;
    const double longest = std::max({ab, bc, ca});
    if (perimeter <= 0.0 || longest <= 0.0) return 0.0;
    constexpr double kAlpha = 3.4641016151377544;  // 2*sqrt(3)
    return kAlpha * (2.0 * triangle_area(a, b, c) / perimeter) / longest;
}

}  // namespace hdimesh::volume
