#pragma once
// The HDI model's input data: surface nodes, triangles, node normals, and the cloud's scale.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "common/point.h"

namespace hdimesh::hdi
{

using hdimesh::Vec3;
using Triangle3 = std::array<int, 3>;  ///< vertex indices, counter-clockwise seen from outside

/// How the face normals around a node are averaged into the node's normal.
enum class NormalWeighting
{
    Angle,  ///< by the corner angle at the node (independent of how the fan is split)
    Area    ///< by the triangle area
};

/// Unit normal of the triangle (a, b, c), or zero when it is degenerate.
Vec3 triangle_normal(const Vec3& a, const Vec3& b, const Vec3& c);

/// One unit normal per point from the triangles around it (zero for a point no usable
/// triangle touches). Throws InputError naming the triangle if an index is out of range.
std::vector<Vec3> vertex_normals(const std::vector<Vec3>& points,
                                 const std::vector<Triangle3>& triangles,
                                 NormalWeighting weighting = NormalWeighting::Angle);

struct BoundingBox
{
    Vec3 min = Vec3::Zero();
    Vec3 max = Vec3::Zero();
    double diagonal() const { return (max - min).norm(); }
};

BoundingBox bounding_box(const std::vector<Vec3>& points);

/// Throws InputError naming the first triangle whose index is outside [0, point_count).
void check_triangle_indices(const std::vector<Triangle3>& triangles, int point_count);

}  // namespace hdimesh::hdi
