#pragma once
// The size field: the target edge length h(p) anywhere in space. Every algorithm sees only
// this interface; the concrete fields (constant, the paper's benchmark cylinders, a background
// tet mesh with sizes at its vertices, a .sol) and the --hmin/--hmax/--hgrad treatment are
// declared in volume/size_fields.h.
//
// Edge size convention used everywhere (quality report, refinement, optimization):
// hth of edge ab is h((a+b)/2), the size at the edge's midpoint.

#include <algorithm>

#include "volume/geometry.h"

namespace hdimesh
{

class SizeField
{
public:
    virtual ~SizeField() = default;
    /// Target edge length at p (> 0).
    virtual double size(const Vec3& p) const = 0;
};

/// The size an edge is measured against: the field at its midpoint.
inline double edge_target_size(const SizeField& field, const Vec3& a, const Vec3& b)
{
    return field.size(0.5 * (a + b));
}

/// Qt = min(hth/L, L/hth) of one edge.
inline double size_quality(double length, double target)
{
    return std::min(target / length, length / target);
}

/// The paper's threshold: an edge whose Qt is below it is too long (L > hth) or too short.
inline constexpr double kSizeQualityThreshold = 0.66;

inline bool is_too_long(double length, double target)
{
    return length > target && size_quality(length, target) < kSizeQualityThreshold;
}

inline bool is_too_short(double length, double target)
{
    return length < target && size_quality(length, target) < kSizeQualityThreshold;
}

}  // namespace hdimesh
