#include "hdi/point_cloud.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.h"

namespace hdimesh::hdi
{

namespace
{

/// Angle at corner p of the triangle (p, q, r); atan2 stays accurate for thin triangles.
double corner_angle(const Vec3& p, const Vec3& q, const Vec3& r)
{
    const Vec3 u = q - p;
    const Vec3 v = r - p;
    return std::atan2(u.cross(v).norm(), u.dot(v));
}

}  // namespace

Vec3 triangle_normal(const Vec3& a, const Vec3& b, const Vec3& c)
{
    const Vec3 n = (b - a).cross(c - a);
    const double length = n.norm();
    return length > 0 ? Vec3(n / length) : Vec3::Zero();
}

void check_triangle_indices(const std::vector<Triangle3>& triangles, int point_count)
{
    for (std::size_t t = 0; t < triangles.size(); ++t)
        for (int corner = 0; corner < 3; ++corner)
        {
            const int v = triangles[t][static_cast<std::size_t>(corner)];
            if (v < 0 || v >= point_count)
                throw InputError("hdi: triangle " + std::to_string(t) + " names vertex " +
                                 std::to_string(v) + " but there are " +
                                 std::to_string(point_count) + " points");
        }
}

std::vector<Vec3> vertex_normals(const std::vector<Vec3>& points,
                                 const std::vector<Triangle3>& triangles, NormalWeighting weighting)
{
    check_triangle_indices(triangles, static_cast<int>(points.size()));
    std::vector<Vec3> normals(points.size(), Vec3::Zero());
    for (const Triangle3& t : triangles)
    {
        const Vec3& a = points[static_cast<std::size_t>(t[0])];
        const Vec3& b = points[static_cast<std::size_t>(t[1])];
        const Vec3& c = points[static_cast<std::size_t>(t[2])];
        const Vec3 doubled_area_normal = (b - a).cross(c - a);
        const double doubled_area = doubled_area_normal.norm();
        if (!(doubled_area > 0)) continue;
        const Vec3 unit = doubled_area_normal / doubled_area;
        if (weighting == NormalWeighting::Area)
        {
            for (int v : t) normals[static_cast<std::size_t>(v)] += 0.5 * doubled_area * unit;
        }
        else
        {
            normals[static_cast<std::size_t>(t[0])] += corner_angle(a, b, c) * unit;
            normals[static_cast<std::size_t>(t[1])] += corner_angle(b, c, a) * unit;
            normals[static_cast<std::size_t>(t[2])] += corner_angle(c, a, b) * unit;
        }
    }
    for (Vec3& n : normals)
    {
        const double length = n.norm();
        n = length > 0 ? Vec3(n / length) : Vec3::Zero();
    }
    return normals;
}

BoundingBox bounding_box(const std::vector<Vec3>& points)
{
    BoundingBox box;
    if (points.empty()) return box;
    box.min = box.max = points.front();
    for (const Vec3& p : points)
    {
        box.min = box.min.cwiseMin(p);
        box.max = box.max.cwiseMax(p);
    }
    return box;
}

}  // namespace hdimesh::hdi
