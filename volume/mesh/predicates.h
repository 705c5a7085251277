#pragma once
// Exact geometric predicates: the sign of orient3d and the intersection tests the cavity filler
// and the advancing front decide topology with. A floating-point filter answers almost every
// call; when the rounded result is too close to zero, the determinant is recomputed exactly
// with expansion arithmetic (after Shewchuk's adaptive predicates), so no answer depends on
// round-off. Tolerances are for quality and size only, never here.

#include <array>
#include <cmath>
#include <vector>

#include "volume/mesh/geometry.h"

namespace hdimesh::volume
{

namespace detail
{
/// The exact stages, out of line: called only when the filter below cannot decide.
int orient3d_exact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);
int orient2d_exact(const Vec3& a, const Vec3& b, const Vec3& c, int drop);

// Shewchuk's static relative error bounds for the rounded determinant (epsilon = 2^-53).
constexpr double kRoundoff = 1.1102230246251565e-16;
constexpr double kOrient3dBound = (7.0 + 56.0 * kRoundoff) * kRoundoff;
constexpr double kOrient2dBound = (3.0 + 16.0 * kRoundoff) * kRoundoff;
}  // namespace detail

/// Sign of det(b-a, c-a, d-a), exactly: +1 when d lies on the side of plane abc that makes
/// (a, b, c, d) a positive tet (volume/mesh/geometry.h signed_volume6), -1 on the other, 0
/// coplanar. Exact for finite coordinates whose products neither overflow nor underflow.
inline int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
    const double bax = b.x() - a.x(), bay = b.y() - a.y(), baz = b.z() - a.z();
    const double cax = c.x() - a.x(), cay = c.y() - a.y(), caz = c.z() - a.z();
    const double dax = d.x() - a.x(), day = d.y() - a.y(), daz = d.z() - a.z();
    const double cay_daz = cay * daz, caz_day = caz * day;
    const double caz_dax = caz * dax, cax_daz = cax * daz;
    const double cax_day = cax * day, cay_dax = cay * dax;
    const double det =
        bax * (cay_daz - caz_day) + bay * (caz_dax - cax_daz) + baz * (cax_day - cay_dax);
    // Semi-static filter: the bound scales with the permanent, so it holds at every scale.
    const double permanent = (std::abs(cay_daz) + std::abs(caz_day)) * std::abs(bax) +
                             (std::abs(caz_dax) + std::abs(cax_daz)) * std::abs(bay) +
                             (std::abs(cax_day) + std::abs(cay_dax)) * std::abs(baz);
    // One well-predicted branch; the sign itself without branching.
    if (std::abs(det) > detail::kOrient3dBound * permanent) return (det > 0.0) - (det < 0.0);
    return detail::orient3d_exact(a, b, c, d);
}

/// Sign of the 2-D orientation of (a, b, c) projected on the coordinate plane that drops axis
/// `drop` (0, 1 or 2), exactly: +1 counter-clockwise in the (axis+1, axis+2) frame, i.e. the
/// sign of component `drop` of (b-a) x (c-a).
inline int orient2d(const Vec3& a, const Vec3& b, const Vec3& c, int drop)
{
    const int u = drop == 2 ? 0 : drop + 1;
    const int v = drop == 0 ? 2 : drop - 1;
    const double left = (b[u] - a[u]) * (c[v] - a[v]);
    const double right = (b[v] - a[v]) * (c[u] - a[u]);
    const double det = left - right;
    // Rounding keeps signs, so products of opposite signs (or a zero) already decide.
    if (left > 0.0)
    {
        if (right <= 0.0) return 1;
    }
    else if (left < 0.0)
    {
        if (right >= 0.0) return -1;
    }
    else
    {
        return right > 0.0 ? -1 : (right < 0.0 ? 1 : 0);
    }
    if (std::abs(det) > detail::kOrient2dBound * (std::abs(left) + std::abs(right)))
        return (det > 0.0) - (det < 0.0);
    return detail::orient2d_exact(a, b, c, drop);
}

/// The intersection tests below take vertex ids into `points`, so that shared vertices are
/// known exactly. Two simplices sharing vertices "intersect" when they have a common point
/// outside the simplex spanned by their shared vertices: two triangles sharing an edge and
/// otherwise apart do not intersect; two triangles sharing a vertex intersect only if they
/// also meet elsewhere. Closed simplices: touching counts. Degenerate input simplices (a flat
/// triangle, a zero segment) are allowed and handled exactly: a simplex is the convex hull of
/// its points. Distinct ids at the same coordinates are distinct vertices, so such a point is
/// a common point outside the shared simplex. Every answer is exact (orient3d / orient2d
/// signs and coordinate comparisons only).

/// Closed segment s and closed triangle t meet outside their shared vertices.
/// - no shared id: any common point, an end on the triangle's boundary included;
/// - s is an edge of t: false;
/// - one shared vertex k: true exactly when s leaves k into t, i.e. s's direction lies in the
///   closed angle of t at k (in t's plane; along one of t's edges counts).
bool segment_triangle_intersect(const std::vector<Vec3>& points, const std::array<int, 2>& s,
                                const std::array<int, 3>& t);

/// Closed triangles t1 and t2 meet outside the simplex of their shared vertices (coplanar
/// overlaps included).
/// - no shared id: any common point (a vertex on the other, edges crossing, coplanar overlap);
/// - the same three ids: false;
/// - shared edge ab: true only when coplanar with the third vertices on the same side of ab
///   (overlap); folded or unfolded (opposite sides) is false;
/// - shared vertex a: true when they meet at any other point: the edge opposite a in one meets
///   the other triangle (this covers coplanar overlapping angles at a, and angles sharing a
///   ray).
bool triangles_intersect(const std::vector<Vec3>& points, const std::array<int, 3>& t1,
                         const std::array<int, 3>& t2);

/// Point p lies in the closed tet (a, b, c, d): its faces, edges and vertices count (a
/// different id at a vertex's coordinates is inside). p being one of the tet's ids gives false
/// (a shared vertex is no common point).
bool point_in_tet(const std::vector<Vec3>& points, int p, const std::array<int, 4>& tet);

/// Closed tet and closed triangle t meet outside the simplex of their shared vertices (a
/// triangle on a face of the tet, or sharing an edge and lying outside, does not).
/// - no shared id: any common point (a vertex of t on the tet's boundary counts);
/// - t is a face of the tet: false;
/// - shared edge k1k2: true exactly when t's third vertex lies in the closed dihedral wedge
///   of the tet at k1k2, so t lying in the plane of an adjacent face over that face counts,
///   and beyond the edge in that plane does not;
/// - shared vertex k: true when t meets the tet at any other point (t along a tet edge or
///   over a face counts).
/// The tet must not be flat; it is used positive (negative input is reordered).
bool tet_triangle_intersect(const std::vector<Vec3>& points, const std::array<int, 4>& tet,
                            const std::array<int, 3>& t);

}  // namespace hdimesh::volume
