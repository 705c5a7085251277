// Exact stages of orient3d and orient2d by floating-point expansion arithmetic (after
// Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
// Predicates", 1997), and the intersection tests built on their signs.
//
// An expansion is a sum of doubles stored by increasing magnitude, nonoverlapping, zeros
// removed; its sign is the sign of its last (largest) component. The arithmetic below is only
// exact under round-to-nearest-even without fused multiply-adds the algorithm did not ask for
// (CMakeLists.txt compiles this file with -ffp-contract=off).

#include "volume/mesh/predicates.h"

#include <cassert>
#include <cmath>
#include <utility>

#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#endif

namespace hdimesh::volume
{

namespace
{

// ---------------------------------------------------------------------------------------------
// Error-free transformations: a op b = x + y exactly, x the rounded result.

inline void two_sum(double a, double b, double& x, double& y)
{
    x = a + b;
    const double b_virtual = x - a;
    const double a_virtual = x - b_virtual;
    y = (a - a_virtual) + (b - b_virtual);
}

inline void two_diff(double a, double b, double& x, double& y)
{
    x = a - b;
    const double b_virtual = a - x;
    const double a_virtual = x + b_virtual;
    y = (a - a_virtual) + (b_virtual - b);
}

/// Requires |a| >= |b| (or a == 0).
inline void fast_two_sum(double a, double b, double& x, double& y)
{
    x = a + b;
    y = b - (x - a);
}

#if !defined(__FMA__)
/// Dekker's split of a into two 26-bit halves, hi + lo == a exactly.
inline void split(double a, double& hi, double& lo)
{
    constexpr double kSplitter = 134217729.0;  // 2^27 + 1
    const double c = kSplitter * a;
    const double big = c - a;
    hi = c - big;
    lo = a - hi;
}
#endif

inline void two_product(double a, double b, double& x, double& y)
{
    x = a * b;
#if defined(__FMA__)
    y = std::fma(a, b, -x);
#else
    double a_hi, a_lo, b_hi, b_lo;
    split(a, a_hi, a_lo);
    split(b, b_hi, b_lo);
    const double err1 = x - a_hi * b_hi;
    const double err2 = err1 - a_lo * b_hi;
    const double err3 = err2 - a_hi * b_lo;
    y = a_lo * b_lo - err3;
#endif
}

// ---------------------------------------------------------------------------------------------
// Expansions as arrays on the stack with their lengths; each function writes its result to an
// output array (never aliasing an input) and returns the result's length.

/// a - b exactly, in at most two terms.
inline int difference(double a, double b, double* h)
{
    double head, tail;
    two_diff(a, b, head, tail);
    int n = 0;
    if (tail != 0.0) h[n++] = tail;
    if (head != 0.0) h[n++] = head;
    return n;
}

/// e + f: the components merged by magnitude and accumulated with two_sum (Shewchuk's
/// fast expansion sum, with zero elimination).
int add(const double* e, int e_size, const double* f, int f_size, double* h)
{
    const int total = e_size + f_size;
    if (total == 0) return 0;
    int i = 0, j = 0, n = 0;
    auto next_smallest = [&]() {
        if (j == f_size || (i < e_size && std::abs(e[i]) < std::abs(f[j]))) return e[i++];
        return f[j++];
    };
    double q = next_smallest();
    for (int k = 1; k < total; ++k)
    {
        double sum, error;
        two_sum(q, next_smallest(), sum, error);
        if (error != 0.0) h[n++] = error;
        q = sum;
    }
    if (q != 0.0) h[n++] = q;
    return n;
}

/// e * b for one double b.
int scale(const double* e, int e_size, double b, double* h)
{
    if (e_size == 0 || b == 0.0) return 0;
    int n = 0;
    double q, low;
    two_product(e[0], b, q, low);
    if (low != 0.0) h[n++] = low;
    for (int i = 1; i < e_size; ++i)
    {
        double product_high, product_low, sum, error;
        two_product(e[i], b, product_high, product_low);
        two_sum(q, product_low, sum, error);
        if (error != 0.0) h[n++] = error;
        fast_two_sum(product_high, sum, q, error);
        if (error != 0.0) h[n++] = error;
    }
    if (q != 0.0) h[n++] = q;
    return n;
}

/// e * f for f of at most two terms (a coordinate difference); h needs 4 * e_size entries.
int multiply(const double* e, int e_size, const double* f, int f_size, double* h)
{
    if (f_size == 0) return 0;
    if (f_size == 1) return scale(e, e_size, f[0], h);
    double low[64], high[64];
    assert(e_size <= 32);
    const int low_size = scale(e, e_size, f[0], low);
    const int high_size = scale(e, e_size, f[1], high);
    return add(low, low_size, high, high_size, h);
}

struct Difference
{
    double terms[2];
    int size;
    Difference(double a, double b) : size(difference(a, b, terms)) {}
};

/// x1 * y1 - x2 * y2 exactly, at most 16 terms.
int cross_term(const Difference& x1, const Difference& y1, const Difference& x2,
               const Difference& y2, double* h)
{
    double first[8], second[8];
    const int first_size = multiply(x1.terms, x1.size, y1.terms, y1.size, first);
    const int second_size = multiply(x2.terms, x2.size, y2.terms, y2.size, second);
    for (int i = 0; i < second_size; ++i) second[i] = -second[i];
    return add(first, first_size, second, second_size, h);
}

int sign_of_expansion(const double* e, int size)
{
    return size == 0 ? 0 : (e[size - 1] > 0.0 ? 1 : -1);
}

}  // namespace

namespace detail
{

int orient3d_exact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
    // The differences to a are exact as two-term expansions, so the determinant of
    // differences is the exact one; exact differences (one term) keep expansions short.
    const Difference bax(b.x(), a.x()), bay(b.y(), a.y()), baz(b.z(), a.z());
    const Difference cax(c.x(), a.x()), cay(c.y(), a.y()), caz(c.z(), a.z());
    const Difference dax(d.x(), a.x()), day(d.y(), a.y()), daz(d.z(), a.z());
    double minor[16], term_x[64], term_y[64], term_z[64], partial[128], total[192];
    int minor_size = cross_term(cay, daz, caz, day, minor);
    const int x_size = multiply(minor, minor_size, bax.terms, bax.size, term_x);
    minor_size = cross_term(caz, dax, cax, daz, minor);
    const int y_size = multiply(minor, minor_size, bay.terms, bay.size, term_y);
    minor_size = cross_term(cax, day, cay, dax, minor);
    const int z_size = multiply(minor, minor_size, baz.terms, baz.size, term_z);
    const int partial_size = add(term_x, x_size, term_y, y_size, partial);
    const int total_size = add(partial, partial_size, term_z, z_size, total);
    return sign_of_expansion(total, total_size);
}

int orient2d_exact(const Vec3& a, const Vec3& b, const Vec3& c, int drop)
{
    const int u = drop == 2 ? 0 : drop + 1;
    const int v = drop == 0 ? 2 : drop - 1;
    double det[16];
    const int size = cross_term(Difference(b[u], a[u]), Difference(c[v], a[v]),
                                Difference(b[v], a[v]), Difference(c[u], a[u]), det);
    return sign_of_expansion(det, size);
}

}  // namespace detail

// ---------------------------------------------------------------------------------------------
// Intersection tests. Closed simplices throughout; every decision is a sign of orient3d or
// orient2d or a comparison of coordinates, so none depends on round-off.

namespace
{

bool same_point(const Vec3& a, const Vec3& b)
{
    return a.x() == b.x() && a.y() == b.y() && a.z() == b.z();
}

/// The axis whose dropping projects triangle abc without flattening it (exactly), tried in
/// order of the rounded normal's components; -1 when a, b, c are collinear. `sign` receives
/// orient2d(a, b, c) on that projection.
int injective_drop(const Vec3& a, const Vec3& b, const Vec3& c, int& sign)
{
    const Vec3 normal = (b - a).cross(c - a).cwiseAbs();
    int first = 0;
    if (normal[1] > normal[first]) first = 1;
    if (normal[2] > normal[first]) first = 2;
    for (int step = 0; step < 3; ++step)
    {
        const int drop = (first + step) % 3;
        sign = orient2d(a, b, c, drop);
        if (sign != 0) return drop;
    }
    return -1;
}

bool collinear(const Vec3& a, const Vec3& b, const Vec3& c)
{
    int sign;
    return injective_drop(a, b, c, sign) < 0;
}

bool between(double x, double y, double z) { return y <= z ? y <= x && x <= z : z <= x && x <= y; }

/// x in the bounding box of y, z on the axes kept by `drop`; for collinear projections this
/// is x on the projected segment yz.
bool in_box_2d(const Vec3& x, const Vec3& y, const Vec3& z, int drop)
{
    const int u = (drop + 1) % 3, v = (drop + 2) % 3;
    return between(x[u], y[u], z[u]) && between(x[v], y[v], z[v]);
}

/// x on segment yz, for x, y, z known collinear.
bool on_collinear_segment(const Vec3& x, const Vec3& y, const Vec3& z)
{
    return between(x.x(), y.x(), z.x()) && between(x.y(), y.y(), z.y()) &&
           between(x.z(), y.z(), z.z());
}

/// Closed segments pq and rs of the projection dropping `drop` meet (either may be a point).
bool segments_meet_2d(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s, int drop)
{
    const int o1 = orient2d(p, q, r, drop), o2 = orient2d(p, q, s, drop);
    const int o3 = orient2d(r, s, p, drop), o4 = orient2d(r, s, q, drop);
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    return (o1 == 0 && in_box_2d(r, p, q, drop)) || (o2 == 0 && in_box_2d(s, p, q, drop)) ||
           (o3 == 0 && in_box_2d(p, r, s, drop)) || (o4 == 0 && in_box_2d(q, r, s, drop));
}

/// Closed segments pq and rs meet in 3-D. Coplanar points lie in a plane that some
/// coordinate projection maps one to one, and projections only add meetings, so the segments
/// meet exactly when they meet in all three projections.
bool segments_meet(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s)
{
    if (orient3d(p, q, r, s) != 0) return false;
    for (int drop = 0; drop < 3; ++drop)
        if (!segments_meet_2d(p, q, r, s, drop)) return false;
    return true;
}

/// x in closed triangle abc of the projection dropping `drop`, whose orientation `sign` != 0.
bool point_in_triangle_2d(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c, int drop,
                          int sign)
{
    return orient2d(a, b, x, drop) * sign >= 0 && orient2d(b, c, x, drop) * sign >= 0 &&
           orient2d(c, a, x, drop) * sign >= 0;
}

/// Closed segment pq and closed triangle abc meet, given side_p = orient3d(a, b, c, p) and
/// side_q = orient3d(a, b, c, q) (or both with one opposite sign convention).
bool segment_meets_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                            const Vec3& c, int side_p, int side_q)
{
    if (side_p * side_q > 0) return false;
    if (side_p == 0 && side_q == 0)
    {
        int sign;
        const int drop = injective_drop(a, b, c, sign);
        if (drop < 0)  // a flat triangle is covered by any two of its edges
            return segments_meet(p, q, a, b) || segments_meet(p, q, b, c);
        return point_in_triangle_2d(p, a, b, c, drop, sign) ||
               point_in_triangle_2d(q, a, b, c, drop, sign) || segments_meet_2d(p, q, a, b, drop) ||
               segments_meet_2d(p, q, b, c, drop) || segments_meet_2d(p, q, c, a, drop);
    }
    // pq crosses the plane at one point (an endpoint when one side is 0): it is in the
    // triangle exactly when the line pq turns the same way around the three edges.
    const int s1 = orient3d(p, q, a, b), s2 = orient3d(p, q, b, c), s3 = orient3d(p, q, c, a);
    return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

bool segment_meets_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                            const Vec3& c)
{
    return segment_meets_triangle(p, q, a, b, c, orient3d(a, b, c, p), orient3d(a, b, c, q));
}

/// The vertex of a triangle alone on its side of the other triangle's plane: strictly off it,
/// with the two others on the closed opposite side; -1 when there is none (all three on one
/// closed side).
int lone_vertex(const std::array<int, 3>& sides)
{
    for (int i = 0; i < 3; ++i)
        if (sides[i] != 0 && sides[i] * sides[(i + 1) % 3] <= 0 &&
            sides[i] * sides[(i + 2) % 3] <= 0)
            return i;
    return -1;
}

/// Closed triangles t1 = abc and t2 = def meet, given the exact signs side2[j] =
/// orient3d(a, b, c, t2[j]) and side1[i] = orient3d(d, e, f, t1[i]).
bool triangles_meet(std::array<const Vec3*, 3> t1, std::array<const Vec3*, 3> t2,
                    std::array<int, 3> side1, std::array<int, 3> side2)
{
    auto all_strictly_one_side = [](const std::array<int, 3>& s) {
        return s[0] * s[1] > 0 && s[0] * s[2] > 0;
    };
    if (all_strictly_one_side(side2) || all_strictly_one_side(side1)) return false;
    const bool flat_or_coplanar = (side1[0] == 0 && side1[1] == 0 && side1[2] == 0) ||
                                  (side2[0] == 0 && side2[1] == 0 && side2[2] == 0);
    if (!flat_or_coplanar)
    {
        // Both cross the other's plane: each meets the line L of the two planes in an
        // interval, and they meet exactly when the intervals overlap (after Devillers and
        // Guigue). A triangle touching the other plane at one vertex only gives a point.
        const int lone1 = lone_vertex(side1), lone2 = lone_vertex(side2);
        if (lone1 < 0 || lone2 < 0)
        {
            const bool first = lone1 < 0;
            const auto& touching = first ? t1 : t2;
            const auto& other = first ? t2 : t1;
            const auto& sides = first ? side1 : side2;
            const Vec3& point = *touching[sides[0] == 0 ? 0 : (sides[1] == 0 ? 1 : 2)];
            int sign;
            const int drop = injective_drop(*other[0], *other[1], *other[2], sign);
            return point_in_triangle_2d(point, *other[0], *other[1], *other[2], drop, sign);
        }
        // Rotate so a and d are alone, then make a lie above plane def and d above plane abc
        // (swapping the two others flips a plane's orientation).
        auto rotate = [](auto& t, std::array<int, 3>& s, int first) {
            t = {t[first], t[(first + 1) % 3], t[(first + 2) % 3]};
            s = {s[first], s[(first + 1) % 3], s[(first + 2) % 3]};
        };
        rotate(t1, side1, lone1);
        rotate(t2, side2, lone2);
        if (side1[0] < 0)
        {
            std::swap(t2[1], t2[2]);
            std::swap(side2[1], side2[2]);
            for (int& x : side1) x = -x;
        }
        if (side2[0] < 0)
        {
            std::swap(t1[1], t1[2]);
            std::swap(side1[1], side1[2]);
            for (int& x : side2) x = -x;
        }
        // Along L oriented by n1 x n2, t1's interval runs from its point on ac to its point on
        // ab, and t2's from de to df; orient3d(a, b, d, e) and orient3d(a, c, d, f) compare
        // the ends that must not pass each other.
        const Vec3 &a = *t1[0], &b = *t1[1], &c = *t1[2], &d = *t2[0], &e = *t2[1], &f = *t2[2];
        return orient3d(a, b, d, e) <= 0 && orient3d(a, c, d, f) >= 0;
    }
    // Coplanar, or one is flat: the meeting set, if any, contains a point of an edge of one
    // triangle (its relative boundary; a flat triangle is all edges) lying in the other.
    const Vec3 &a = *t1[0], &b = *t1[1], &c = *t1[2], &d = *t2[0], &e = *t2[1], &f = *t2[2];
    return segment_meets_triangle(a, b, d, e, f, side1[0], side1[1]) ||
           segment_meets_triangle(b, c, d, e, f, side1[1], side1[2]) ||
           segment_meets_triangle(c, a, d, e, f, side1[2], side1[0]) ||
           segment_meets_triangle(d, e, a, b, c, side2[0], side2[1]) ||
           segment_meets_triangle(e, f, a, b, c, side2[1], side2[2]) ||
           segment_meets_triangle(f, d, a, b, c, side2[2], side2[0]);
}

bool triangles_meet(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e,
                    const Vec3& f)
{
    const std::array<int, 3> side2 = {orient3d(a, b, c, d), orient3d(a, b, c, e),
                                      orient3d(a, b, c, f)};
    if (side2[0] * side2[1] > 0 && side2[0] * side2[2] > 0) return false;
    const std::array<int, 3> side1 = {orient3d(d, e, f, a), orient3d(d, e, f, b),
                                      orient3d(d, e, f, c)};
    return triangles_meet({&a, &b, &c}, {&d, &e, &f}, side1, side2);
}

/// x - k and t - k are nonzero and point the same way (for any x, k, t).
bool same_ray(const Vec3& k, const Vec3& x, const Vec3& t)
{
    if (same_point(k, x) || same_point(k, t) || !collinear(k, x, t)) return false;
    for (int axis = 0; axis < 3; ++axis)
        if (t[axis] != k[axis]) return (t[axis] > k[axis]) == (x[axis] > k[axis]);
    return false;
}

/// Segment kx meets triangle (k, t1, t2) beyond k: by convexity, exactly when x - k is a
/// nonzero direction of the cone spanned by t1 - k and t2 - k (any triangle, flat included).
bool beyond_vertex_in_triangle(const Vec3& k, const Vec3& x, const Vec3& t1, const Vec3& t2)
{
    if (same_point(k, x) || orient3d(k, t1, t2, x) != 0) return false;
    int sign;
    const int drop = injective_drop(k, t1, t2, sign);
    if (drop < 0) return same_ray(k, x, t1) || same_ray(k, x, t2);
    return orient2d(k, t1, x, drop) * sign >= 0 && orient2d(k, x, t2, drop) * sign >= 0;
}

/// A positive tet by its points, with the orientations of a point x replacing each vertex:
/// x's barycentric coordinates' signs, all >= 0 exactly when x is in the closed tet.
struct PositiveTet
{
    std::array<const Vec3*, 4> v;

    std::array<int, 4> barycentric_signs(const Vec3& x) const
    {
        return {orient3d(x, *v[1], *v[2], *v[3]), orient3d(*v[0], x, *v[2], *v[3]),
                orient3d(*v[0], *v[1], x, *v[3]), orient3d(*v[0], *v[1], *v[2], x)};
    }
    /// The face opposite vertex i, ordered so that orient3d(face, x) is barycentric_signs(x)[i].
    std::array<const Vec3*, 3> face(int i) const
    {
        switch (i)
        {
            case 0: return {v[2], v[1], v[3]};
            case 1: return {v[0], v[2], v[3]};
            case 2: return {v[1], v[0], v[3]};
            default: return {v[0], v[1], v[2]};
        }
    }
    /// The indices of face(i)'s vertices.
    static std::array<int, 3> face_indices(int i)
    {
        switch (i)
        {
            case 0: return {2, 1, 3};
            case 1: return {0, 2, 3};
            case 2: return {1, 0, 3};
            default: return {0, 1, 2};
        }
    }
};

bool all_nonnegative(const std::array<int, 4>& signs)
{
    return signs[0] >= 0 && signs[1] >= 0 && signs[2] >= 0 && signs[3] >= 0;
}

/// Closed segment pq and the closed tet meet, given both endpoints' barycentric signs: an
/// endpoint is inside, or the segment crosses the boundary, i.e. meets a face.
bool segment_meets_tet(const Vec3& p, const Vec3& q, const PositiveTet& tet,
                       const std::array<int, 4>& signs_p, const std::array<int, 4>& signs_q)
{
    if (all_nonnegative(signs_p) || all_nonnegative(signs_q)) return true;
    for (int i = 0; i < 4; ++i)
        if (signs_p[i] < 0 && signs_q[i] < 0) return false;  // both beyond one face plane
    for (int i = 0; i < 4; ++i)
    {
        const auto f = tet.face(i);
        if (segment_meets_triangle(p, q, *f[0], *f[1], *f[2], signs_p[i], signs_q[i])) return true;
    }
    return false;
}

int count_shared(const int* ids, int n, const int* others, int m)
{
    int shared = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j) shared += ids[i] == others[j];
    return shared;
}

bool contains(const int* ids, int n, int id)
{
    for (int i = 0; i < n; ++i)
        if (ids[i] == id) return true;
    return false;
}

/// The tet's ids reordered positive (two swapped if it was given negative).
std::array<int, 4> positive_tet(const std::vector<Vec3>& points, std::array<int, 4> tet)
{
    const int orientation =
        orient3d(points[tet[0]], points[tet[1]], points[tet[2]], points[tet[3]]);
    assert(orientation != 0 && "tet must not be flat");
    if (orientation < 0) std::swap(tet[2], tet[3]);
    return tet;
}

}  // namespace

bool segment_triangle_intersect(const std::vector<Vec3>& points, const std::array<int, 2>& s,
                                const std::array<int, 3>& t)
{
    assert(s[0] != s[1] && t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
    const int shared = count_shared(s.data(), 2, t.data(), 3);
    if (shared == 2) return false;  // the segment is an edge of the triangle
    if (shared == 0)
        return segment_meets_triangle(points[s[0]], points[s[1]], points[t[0]], points[t[1]],
                                      points[t[2]]);
    const int k = contains(t.data(), 3, s[0]) ? s[0] : s[1];
    const int x = k == s[0] ? s[1] : s[0];
    const int at = k == t[0] ? 0 : (k == t[1] ? 1 : 2);
    return beyond_vertex_in_triangle(points[k], points[x], points[t[(at + 1) % 3]],
                                     points[t[(at + 2) % 3]]);
}

bool triangles_intersect(const std::vector<Vec3>& points, const std::array<int, 3>& t1,
                         const std::array<int, 3>& t2)
{
    assert(t1[0] != t1[1] && t1[1] != t1[2] && t1[0] != t1[2]);
    assert(t2[0] != t2[1] && t2[1] != t2[2] && t2[0] != t2[2]);
    const int shared = count_shared(t1.data(), 3, t2.data(), 3);
    if (shared == 3) return false;
    if (shared == 0)
        return triangles_meet(points[t1[0]], points[t1[1]], points[t1[2]], points[t2[0]],
                              points[t2[1]], points[t2[2]]);

    // Rotate both so the shared ids come first: t1 = (a, b, c), t2 = (a, d, e) or (a, b, d).
    auto rotate_shared_first = [&](std::array<int, 3> t, const std::array<int, 3>& other) {
        for (int turn = 0; turn < 3; ++turn)
        {
            const bool first = contains(other.data(), 3, t[0]);
            const bool second = contains(other.data(), 3, t[1]);
            if (shared == 1 ? first : (first && second)) break;
            t = {t[1], t[2], t[0]};
        }
        return t;
    };
    const std::array<int, 3> r1 = rotate_shared_first(t1, t2);
    std::array<int, 3> r2 = rotate_shared_first(t2, t1);
    if (shared == 2 && r2[0] != r1[0]) r2 = {r2[1], r2[0], r2[2]};
    const Vec3 &a = points[r1[0]], &b = points[r1[1]], &c = points[r1[2]];
    const Vec3 &d = points[r2[1]], &e = points[r2[2]];

    if (shared == 1)
    {
        // t1 = (a, b, c), t2 = (a, d, e). Non-flat: the ray from a through a common point
        // leaves each triangle through its opposite edge, and the nearer exit lies in both.
        const int side_d = orient3d(a, b, c, d), side_e = orient3d(a, b, c, e);
        const int side_b = orient3d(a, d, e, b), side_c = orient3d(a, d, e, c);
        const bool flat1 = side_d == 0 && side_e == 0 && collinear(a, b, c);
        const bool flat2 = side_b == 0 && side_c == 0 && collinear(a, d, e);
        if (flat1)  // t1 is the union of ab and ac
            return beyond_vertex_in_triangle(a, b, d, e) || beyond_vertex_in_triangle(a, c, d, e);
        if (flat2)
            return beyond_vertex_in_triangle(a, d, b, c) || beyond_vertex_in_triangle(a, e, b, c);
        if (side_d * side_e > 0 || side_b * side_c > 0) return false;
        return segment_meets_triangle(b, c, a, d, e, side_b, side_c) ||
               segment_meets_triangle(d, e, a, b, c, side_d, side_e);
    }

    // shared == 2: t1 = (a, b, c), t2 = (a, b, e) sharing edge ab.
    if (orient3d(a, b, c, e) != 0) return false;  // two planes meet on line ab only
    int sign1, sign2;
    const int drop1 = injective_drop(a, b, c, sign1);
    const int drop2 = injective_drop(a, b, e, sign2);
    if (drop1 >= 0 && drop2 >= 0)  // coplanar: overlap exactly when on one side of ab
        return orient2d(a, b, e, drop1) == sign1;
    // A flat triangle reaches beyond ab only past a or past b, from where the question is
    // whether that piece enters the other triangle.
    auto flat_part_enters = [](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& other) {
        if (on_collinear_segment(c, a, b)) return false;
        if (on_collinear_segment(b, a, c)) return beyond_vertex_in_triangle(b, c, a, other);
        return beyond_vertex_in_triangle(a, c, b, other);
    };
    if (drop1 < 0) return flat_part_enters(a, b, c, e);
    return flat_part_enters(a, b, e, c);
}

bool point_in_tet(const std::vector<Vec3>& points, int p, const std::array<int, 4>& tet)
{
    if (contains(tet.data(), 4, p)) return false;  // a shared vertex is no common point
    const std::array<int, 4> positive = positive_tet(points, tet);
    const PositiveTet t{
        {&points[positive[0]], &points[positive[1]], &points[positive[2]], &points[positive[3]]}};
    return all_nonnegative(t.barycentric_signs(points[p]));
}

bool tet_triangle_intersect(const std::vector<Vec3>& points, const std::array<int, 4>& tet,
                            const std::array<int, 3>& t)
{
    assert(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
    const int shared = count_shared(tet.data(), 4, t.data(), 3);
    if (shared == 3) return false;  // t is a face of the tet
    const std::array<int, 4> ids = positive_tet(points, tet);
    const PositiveTet solid{{&points[ids[0]], &points[ids[1]], &points[ids[2]], &points[ids[3]]}};

    if (shared == 0)
    {
        // Either a vertex of t is inside, or t (connected) crosses the boundary: meets a face.
        const Vec3 &a = points[t[0]], &b = points[t[1]], &c = points[t[2]];
        const std::array<int, 4> signs_a = solid.barycentric_signs(a),
                                 signs_b = solid.barycentric_signs(b),
                                 signs_c = solid.barycentric_signs(c);
        for (int i = 0; i < 4; ++i)
            if (signs_a[i] < 0 && signs_b[i] < 0 && signs_c[i] < 0) return false;
        if (all_nonnegative(signs_a) || all_nonnegative(signs_b) || all_nonnegative(signs_c))
            return true;
        std::array<int, 4> sides;
        for (int i = 0; i < 4; ++i) sides[i] = orient3d(a, b, c, *solid.v[i]);
        if (sides[0] * sides[1] > 0 && sides[0] * sides[2] > 0 && sides[0] * sides[3] > 0)
            return false;
        for (int i = 0; i < 4; ++i)
        {
            const auto face = PositiveTet::face_indices(i);
            if (triangles_meet(solid.face(i), {&a, &b, &c},
                               {sides[face[0]], sides[face[1]], sides[face[2]]},
                               {signs_a[i], signs_b[i], signs_c[i]}))
                return true;
        }
        return false;
    }

    // Rotate t so its shared ids come first.
    std::array<int, 3> r = t;
    for (int turn = 0; turn < 3; ++turn)
    {
        const bool first = contains(ids.data(), 4, r[0]);
        const bool second = contains(ids.data(), 4, r[1]);
        if (shared == 1 ? first : (first && second)) break;
        r = {r[1], r[2], r[0]};
    }
    auto index_in_tet = [&ids](int id) {
        for (int i = 0; i < 4; ++i)
            if (ids[i] == id) return i;
        return -1;
    };

    if (shared == 1)
    {
        // t = (k, x, y). A point of t beyond k lies on a ray from k that leaves t through xy
        // and the tet through the face opposite k; the nearer exit lies in both.
        const int at = index_in_tet(r[0]);
        const Vec3 &k = points[r[0]], &x = points[r[1]], &y = points[r[2]];
        const std::array<int, 4> signs_x = solid.barycentric_signs(x),
                                 signs_y = solid.barycentric_signs(y);
        auto beyond_k_inside = [&](const Vec3& q, const std::array<int, 4>& signs) {
            if (same_point(q, k)) return false;
            for (int i = 0; i < 4; ++i)
                if (i != at && signs[i] < 0) return false;
            return true;
        };
        if (collinear(k, x, y))  // t is the union of kx and ky
            return beyond_k_inside(x, signs_x) || beyond_k_inside(y, signs_y);
        for (int i = 0; i < 4; ++i)
            if (i != at && signs_x[i] < 0 && signs_y[i] < 0) return false;
        if (segment_meets_tet(x, y, solid, signs_x, signs_y)) return true;
        // k replacing itself gives the tet's own orientation, +1.
        const auto face = solid.face(at);
        const auto face_ids = PositiveTet::face_indices(at);
        std::array<int, 3> face_sides;
        for (int j = 0; j < 3; ++j) face_sides[j] = orient3d(k, x, y, *solid.v[face_ids[j]]);
        return triangles_meet(face, {&k, &x, &y}, face_sides, {1, signs_x[at], signs_y[at]});
    }

    // shared == 2: t = (k1, k2, x) on tet edge k1k2 whose other vertices are p1, p2. Near the
    // edge the tet is the dihedral wedge between half-planes k1k2p1 and k1k2p2, and t is the
    // half-plane towards x: they overlap beyond the edge exactly when x is in the wedge. A flat
    // t stays on the edge's line, which meets the tet in the edge alone.
    const Vec3 &k1 = points[r[0]], &k2 = points[r[1]], &x = points[r[2]];
    if (collinear(k1, k2, x)) return false;
    std::array<const Vec3*, 2> others{};
    for (int i = 0, n = 0; i < 4; ++i)
        if (ids[i] != r[0] && ids[i] != r[1]) others[n++] = solid.v[i];
    const Vec3 &p1 = *others[0], &p2 = *others[1];
    const int wedge = orient3d(k1, k2, p1, p2);
    return orient3d(k1, k2, p1, x) * wedge >= 0 && orient3d(k1, k2, p2, x) * wedge <= 0;
}

}  // namespace hdimesh::volume
