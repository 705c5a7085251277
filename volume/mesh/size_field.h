#pragma once
// The size field: the target edge length h(p) anywhere in space. Every algorithm sees only
// this interface; the concrete fields (constant, the paper's benchmark cylinders, a background
// tet mesh with sizes at its vertices, a .sol) and the --hmin/--hmax/--hgrad treatment are
// declared in volume/size/size_fields.h.
//
// Edge size convention used everywhere (quality report, refinement, optimization):
// hth of edge ab is h((a+b)/2), the size at the edge's midpoint.

#include "common/size_quality.h"
#include "volume/mesh/geometry.h"

namespace hdimesh::volume
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
    return size_at_midpoint([&field](const Vec3& p) { return field.size(p); }, a, b);
}

}  // namespace hdimesh::volume
