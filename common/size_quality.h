#pragma once
// The one size-quality rule of the method (method.md §1), for both meshes: Qt = min(h/L, L/h)
// per edge, with h the size at the edge's midpoint; an edge is too long when Qt < 0.66 and
// L > h, too short when Qt < 0.66 and L < h.

#include <algorithm>

namespace hdimesh
{

/// Qt = min(h/L, L/h) of one edge of length L against the size h.
inline double size_quality(double length, double target)
{
    return std::min(target / length, length / target);
}

/// The paper's threshold: an edge whose Qt is below it is too long (L > h) or too short.
inline constexpr double kSizeQualityThreshold = 0.66;

inline bool is_too_long(double length, double target)
{
    return length > target && size_quality(length, target) < kSizeQualityThreshold;
}

inline bool is_too_short(double length, double target)
{
    return length < target && size_quality(length, target) < kSizeQualityThreshold;
}

/// The size an edge ab is measured against: size(p) at its midpoint. Any point type with
/// `0.5 * (a + b)` (Eigen, OpenMesh) and any callable size.
template <class SizeAt, class Point>
double size_at_midpoint(const SizeAt& size, const Point& a, const Point& b)
{
    return size(0.5 * (a + b));
}

}  // namespace hdimesh
