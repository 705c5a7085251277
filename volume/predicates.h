#pragma once
// Exact geometric predicates: the sign of orient3d and the intersection tests the cavity filler
// and the advancing front decide topology with. A floating-point filter answers almost every
// call; when the rounded result is too close to zero, the determinant is recomputed exactly
// with expansion arithmetic (after Shewchuk's adaptive predicates), so no answer depends on
// round-off. Tolerances are for quality and size only, never here.

#include <array>
#include <vector>

#include "volume/geometry.h"

namespace hdimesh::volume
{

/// Sign of det(b-a, c-a, d-a), exactly: +1 when d lies on the side of plane abc that makes
/// (a, b, c, d) a positive tet (volume/geometry.h signed_volume6), -1 on the other, 0 coplanar.
int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Sign of the 2-D orientation of (a, b, c) projected on the coordinate plane that drops axis
/// `drop` (0, 1 or 2), exactly: +1 counter-clockwise in the (axis+1, axis+2) frame.
int orient2d(const Vec3& a, const Vec3& b, const Vec3& c, int drop);

/// The intersection tests below take vertex ids into `points`, so that shared vertices are
/// known exactly. Two simplices sharing vertices "intersect" when they have a common point
/// outside the simplex spanned by their shared vertices: two triangles sharing an edge and
/// otherwise apart do not intersect; two triangles sharing a vertex intersect only if they
/// also meet elsewhere. Closed simplices: touching counts. Degenerate input simplices (a flat
/// triangle, a zero segment) are allowed and handled exactly.

/// Closed segment s and closed triangle t meet outside their shared vertices.
bool segment_triangle_intersect(const std::vector<Vec3>& points, const std::array<int, 2>& s,
                                const std::array<int, 3>& t);

/// Closed triangles t1 and t2 meet outside the simplex of their shared vertices (coplanar
/// overlaps included).
bool triangles_intersect(const std::vector<Vec3>& points, const std::array<int, 3>& t1,
                         const std::array<int, 3>& t2);

/// Point p (an id, not a vertex of tet) lies in the closed tet (a, b, c, d), given positive.
bool point_in_tet(const std::vector<Vec3>& points, int p, const std::array<int, 4>& tet);

/// Closed positive tet and closed triangle t meet outside the simplex of their shared vertices
/// (a triangle on a face of the tet, or sharing an edge and lying outside, does not).
bool tet_triangle_intersect(const std::vector<Vec3>& points, const std::array<int, 4>& tet,
                            const std::array<int, 3>& t);

}  // namespace hdimesh::volume
