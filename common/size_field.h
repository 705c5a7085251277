#pragma once
// The sizing layer under both meshes: the size field, h(p) anywhere, and the one way an edge
// is measured by it. Operators ask measure_edge whether an edge is too long or too short and
// for its length in the field, never the field itself, so that a metric changes the answers
// here and nowhere else. The concrete fields live in volume/size/size_fields.h.
//
// The paper's convention (method.md §1, common/size_quality.h): the size of edge ab is the
// field at its midpoint, h((a+b)/2). An anisotropic field is a metric M (common/metric.h): edge
// e's length in it is sqrt(eᵀ M e) with M at the midpoint, so the size it is measured against
// is |e| over that; for a size field M = h⁻² I and the two rules are one.

#include "common/metric.h"
#include "common/point.h"
#include "common/size_quality.h"

namespace hdimesh
{

class SizeField
{
public:
    virtual ~SizeField() = default;
    /// Target edge length at p (> 0); for a metric, the size of the same volume (the parts that
    /// place points by a size alone: the front, the surface pass, the tet-count guard).
    virtual double size(const Vec3& p) const = 0;
    /// True when metric() has directions: edges are measured and tets shaped in it.
    virtual bool anisotropic() const { return false; }
    /// The metric at p: h(p)⁻² I for a size field.
    virtual Metric metric(const Vec3& p) const { return isotropic_metric(size(p)); }
};

/// The size an edge is measured against: the field at its midpoint; in a metric, the edge's
/// length over its length in the metric there (the size in the edge's direction).
inline double edge_target_size(const SizeField& field, const Vec3& a, const Vec3& b)
{
    if (!field.anisotropic())
        return size_at_midpoint([&field](const Vec3& p) { return field.size(p); }, a, b);
    const Vec3 mid = 0.5 * (a + b);
    const Metric m = field.metric(mid);
    const double length = (b - a).norm();
    return length > 0.0 ? length / metric_length(m, b - a) : metric_mean_size(m);
}

/// An edge as the field measures it: its length and the size it is measured against.
struct EdgeInField
{
    double length = 0;  ///< Euclidean
    double size = 0;    ///< the field at the midpoint

    /// L/h: 1 on target, above 1 longer than the field asks.
    double in_field() const { return length / size; }
    /// Qt = min(h/L, L/h).
    double quality() const { return size_quality(length, size); }
    bool too_long() const { return is_too_long(length, size); }
    bool too_short() const { return is_too_short(length, size); }
};

/// Edge ab measured by `field`.
inline EdgeInField measure_edge(const SizeField& field, const Vec3& a, const Vec3& b)
{
    return {(b - a).norm(), edge_target_size(field, a, b)};
}

}  // namespace hdimesh
