// The exact predicates: orient3d and orient2d against an exact big-integer determinant on
// inputs where rounded arithmetic fails (near-coplanar points, coplanar integer grids), their
// symmetries (permutations, translations and scalings by powers of two); then every
// configuration of the intersection tests, each drawn.

#include "volume/mesh/predicates.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

using namespace hdimesh;
using hdimesh::volume::Vec3;

namespace
{

// ---------------------------------------------------------------------------------------------
// An exact reference independent of expansions: signed big integers on dyadic coordinates.

struct BigInt
{
    bool negative = false;
    std::vector<std::uint32_t> limbs;  // magnitude, least significant first, no leading zeros

    static BigInt from_uint(std::uint64_t value)
    {
        BigInt result;
        while (value != 0)
        {
            result.limbs.push_back(static_cast<std::uint32_t>(value));
            value >>= 32;
        }
        return result;
    }
    bool is_zero() const { return limbs.empty(); }
    int sign() const { return is_zero() ? 0 : (negative ? -1 : 1); }
};

void trim(std::vector<std::uint32_t>& limbs)
{
    while (!limbs.empty() && limbs.back() == 0) limbs.pop_back();
}

int compare_magnitude(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b)
{
    if (a.size() != b.size()) return a.size() < b.size() ? -1 : 1;
    for (std::size_t i = a.size(); i-- > 0;)
        if (a[i] != b[i]) return a[i] < b[i] ? -1 : 1;
    return 0;
}

std::vector<std::uint32_t> add_magnitude(const std::vector<std::uint32_t>& a,
                                         const std::vector<std::uint32_t>& b)
{
    std::vector<std::uint32_t> result(std::max(a.size(), b.size()) + 1, 0);
    std::uint64_t carry = 0;
    for (std::size_t i = 0; i + 1 < result.size(); ++i)
    {
        const std::uint64_t sum = carry + (i < a.size() ? a[i] : 0) + (i < b.size() ? b[i] : 0);
        result[i] = static_cast<std::uint32_t>(sum);
        carry = sum >> 32;
    }
    result.back() = static_cast<std::uint32_t>(carry);
    trim(result);
    return result;
}

/// a - b for |a| >= |b|.
std::vector<std::uint32_t> subtract_magnitude(const std::vector<std::uint32_t>& a,
                                              const std::vector<std::uint32_t>& b)
{
    std::vector<std::uint32_t> result(a.size(), 0);
    std::int64_t borrow = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
    {
        std::int64_t diff = static_cast<std::int64_t>(a[i]) - (i < b.size() ? b[i] : 0) - borrow;
        borrow = diff < 0 ? 1 : 0;
        if (diff < 0) diff += (std::int64_t{1} << 32);
        result[i] = static_cast<std::uint32_t>(diff);
    }
    trim(result);
    return result;
}

BigInt operator+(const BigInt& a, const BigInt& b)
{
    BigInt result;
    if (a.negative == b.negative)
    {
        result.limbs = add_magnitude(a.limbs, b.limbs);
        result.negative = a.negative;
    }
    else if (compare_magnitude(a.limbs, b.limbs) >= 0)
    {
        result.limbs = subtract_magnitude(a.limbs, b.limbs);
        result.negative = a.negative;
    }
    else
    {
        result.limbs = subtract_magnitude(b.limbs, a.limbs);
        result.negative = b.negative;
    }
    if (result.is_zero()) result.negative = false;
    return result;
}

BigInt operator-(const BigInt& a)
{
    BigInt result = a;
    if (!result.is_zero()) result.negative = !result.negative;
    return result;
}

BigInt operator-(const BigInt& a, const BigInt& b) { return a + (-b); }

BigInt operator*(const BigInt& a, const BigInt& b)
{
    BigInt result;
    if (a.is_zero() || b.is_zero()) return result;
    std::vector<std::uint64_t> wide(a.limbs.size() + b.limbs.size() + 1, 0);
    for (std::size_t i = 0; i < a.limbs.size(); ++i)
    {
        std::uint64_t carry = 0;
        for (std::size_t j = 0; j < b.limbs.size(); ++j)
        {
            const std::uint64_t current =
                wide[i + j] + static_cast<std::uint64_t>(a.limbs[i]) * b.limbs[j] + carry;
            wide[i + j] = current & 0xffffffffu;
            carry = current >> 32;
        }
        wide[i + b.limbs.size()] += carry;
    }
    result.limbs.assign(wide.size(), 0);
    for (std::size_t i = 0; i < wide.size(); ++i)
        result.limbs[i] = static_cast<std::uint32_t>(wide[i]);
    trim(result.limbs);
    result.negative = a.negative != b.negative;
    return result;
}

BigInt shifted_left(BigInt value, int bits)
{
    const int whole = bits / 32, rest = bits % 32;
    std::vector<std::uint32_t> limbs(whole, 0);
    std::uint32_t carry = 0;
    for (std::uint32_t limb : value.limbs)
    {
        limbs.push_back(rest == 0 ? limb : ((limb << rest) | carry));
        carry = rest == 0 ? 0 : (limb >> (32 - rest));
    }
    limbs.push_back(carry);
    trim(limbs);
    value.limbs = limbs;
    return value;
}

/// x as an integer multiple of 2^lowest_exponent (every finite double is one, for a low
/// enough exponent).
BigInt exact_integer(double x, int lowest_exponent)
{
    if (x == 0.0) return BigInt();
    int exponent = 0;
    const double mantissa = std::frexp(std::abs(x), &exponent);
    const auto integer = static_cast<std::uint64_t>(std::ldexp(mantissa, 53));
    BigInt result = shifted_left(BigInt::from_uint(integer), exponent - 53 - lowest_exponent);
    result.negative = x < 0.0;
    return result;
}

int lowest_exponent(const std::vector<double>& values)
{
    int lowest = 0;
    for (double x : values)
        if (x != 0.0)
        {
            int exponent = 0;
            std::frexp(x, &exponent);
            lowest = std::min(lowest, exponent - 53);
        }
    return lowest;
}

int reference_orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
    const int low = lowest_exponent(
        {a.x(), a.y(), a.z(), b.x(), b.y(), b.z(), c.x(), c.y(), c.z(), d.x(), d.y(), d.z()});
    auto diff = [low, &a](const Vec3& p, int k) {
        return exact_integer(p[k], low) - exact_integer(a[k], low);
    };
    const BigInt bx = diff(b, 0), by = diff(b, 1), bz = diff(b, 2);
    const BigInt cx = diff(c, 0), cy = diff(c, 1), cz = diff(c, 2);
    const BigInt dx = diff(d, 0), dy = diff(d, 1), dz = diff(d, 2);
    return (bx * (cy * dz - cz * dy) + by * (cz * dx - cx * dz) + bz * (cx * dy - cy * dx)).sign();
}

int reference_orient2d(const Vec3& a, const Vec3& b, const Vec3& c, int drop)
{
    const int u = (drop + 1) % 3, v = (drop + 2) % 3;
    const int low = lowest_exponent({a[u], a[v], b[u], b[v], c[u], c[v]});
    auto diff = [low, &a](const Vec3& p, int k) {
        return exact_integer(p[k], low) - exact_integer(a[k], low);
    };
    return (diff(b, u) * diff(c, v) - diff(b, v) * diff(c, u)).sign();
}

int sign_of(double x) { return x > 0.0 ? 1 : (x < 0.0 ? -1 : 0); }

/// splitmix64: the same sequence on every platform, unlike std distributions.
struct Random
{
    std::uint64_t state;
    std::uint64_t next()
    {
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    int integer(int below) { return static_cast<int>(next() % static_cast<std::uint64_t>(below)); }
    double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    Vec3 unit_point() { return Vec3(unit(), unit(), unit()); }
};

std::int64_t integer_orient3d(const std::array<int, 3>& a, const std::array<int, 3>& b,
                              const std::array<int, 3>& c, const std::array<int, 3>& d)
{
    std::int64_t m[3][3];
    for (int k = 0; k < 3; ++k)
    {
        m[0][k] = b[k] - a[k];
        m[1][k] = c[k] - a[k];
        m[2][k] = d[k] - a[k];
    }
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) +
           m[0][1] * (m[1][2] * m[2][0] - m[1][0] * m[2][2]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

}  // namespace

TEST_CASE("the big-integer reference agrees with integer determinants")
{
    const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
    CHECK(reference_orient3d(a, b, c, d) == 1);
    CHECK(reference_orient3d(a, c, b, d) == -1);
    CHECK(reference_orient3d(a, b, c, Vec3(0.25, 0.5, 0)) == 0);
    CHECK(reference_orient2d(a, b, c, 2) == 1);
    CHECK(reference_orient2d(a, b, Vec3(2, 0, 5), 2) == 0);
}

TEST_CASE("orient3d: the positive reference tet and the sign convention of signed_volume6")
{
    const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
    CHECK(volume::orient3d(a, b, c, d) == 1);
    CHECK(volume::orient3d(a, c, b, d) == -1);
    CHECK(volume::orient3d(a, b, c, Vec3(0.3, 0.3, 0)) == 0);
    CHECK(volume::orient3d(a, b, c, a) == 0);
    CHECK(sign_of(volume::signed_volume6(a, b, c, d)) == 1);
}

TEST_CASE("orient3d equals the exact integer determinant on a small grid (many coplanar)")
{
    // Coordinates in {0..3}, optionally as 1 + i * 2^-30 (exact doubles, same signs): a
    // quarter of the quadruples or so are exactly coplanar.
    Random random{15};
    int zeros = 0, count = 0;
    for (double scale : {1.0, 0x1.0p-30})
    {
        for (int trial = 0; trial < 100000; ++trial)
        {
            std::array<std::array<int, 3>, 4> grid;
            std::array<Vec3, 4> points;
            for (int p = 0; p < 4; ++p)
                for (int k = 0; k < 3; ++k)
                {
                    grid[p][k] = random.integer(4);
                    points[p][k] = (scale == 1.0 ? 0.0 : 1.0) + scale * grid[p][k];
                }
            const int expected =
                sign_of(static_cast<double>(integer_orient3d(grid[0], grid[1], grid[2], grid[3])));
            const int got = volume::orient3d(points[0], points[1], points[2], points[3]);
            REQUIRE(got == expected);
            zeros += expected == 0;
            ++count;
        }
    }
    CHECK(zeros > count / 10);
}

TEST_CASE("orient3d is exact near a plane where the rounded determinant fails")
{
    // Shewchuk's near-degenerate grid, in 3-D: a sweeps a 2^-53-spaced grid around
    // (0.5, 0.5, 0.5), which lies on the plane through b, c, d (the line x=y=z is in it).
    //
    //      d ·
    //         \        a ∈ {0.5 + i·2^-53}^3, 16^3 points straddling the plane b c d
    //   (.5,.5,.5)*---b(12,12,12)-----c(24,24,24)
    const Vec3 b(12, 12, 12), c(24, 24, 24), d(3.5, -1.25, 7.0);
    const double ulp = 0x1.0p-53;
    int rounded_wrong = 0, zeros = 0, positives = 0, negatives = 0;
    for (int i = -8; i < 8; ++i)
        for (int j = -8; j < 8; ++j)
            for (int k = -8; k < 8; ++k)
            {
                const Vec3 a(0.5 + i * ulp, 0.5 + j * ulp, 0.5 + k * ulp);
                const int expected = reference_orient3d(a, b, c, d);
                REQUIRE(volume::orient3d(a, b, c, d) == expected);
                REQUIRE(volume::orient3d(b, c, d, a) == -expected);
                rounded_wrong += sign_of(volume::signed_volume6(a, b, c, d)) != expected;
                zeros += expected == 0;
                positives += expected > 0;
                negatives += expected < 0;
            }
    // The grid is a real test only if plain doubles get it wrong and all signs occur.
    CHECK(rounded_wrong > 0);
    CHECK(zeros > 0);
    CHECK(positives > 0);
    CHECK(negatives > 0);
    MESSAGE("rounded determinant wrong on ", rounded_wrong, " of 4096 grid points");
}

TEST_CASE("orient3d is exact on rounded points of random planes, at several offsets")
{
    // d = a + s(b-a) + t(c-a) rounded: within a few ulps of the plane, on either side or on it.
    Random random{7};
    int zeros = 0;
    for (double offset : {0.0, 1.0, 1000.0, -3.0e6})
        for (int trial = 0; trial < 20000; ++trial)
        {
            const Vec3 shift(offset, offset * 0.5, -offset);
            const Vec3 a = random.unit_point() + shift, b = random.unit_point() + shift,
                       c = random.unit_point() + shift;
            const double s = random.unit() * 2 - 0.5, t = random.unit() * 2 - 0.5;
            const Vec3 d = a + s * (b - a) + t * (c - a);
            const int expected = reference_orient3d(a, b, c, d);
            REQUIRE(volume::orient3d(a, b, c, d) == expected);
            zeros += expected == 0;
        }
    MESSAGE(zeros, " of 80000 rounded points exactly coplanar");
}

TEST_CASE("orient3d flips with the parity of a permutation")
{
    Random random{3};
    std::array<int, 4> order = {0, 1, 2, 3};
    for (int trial = 0; trial < 2000; ++trial)
    {
        std::array<Vec3, 4> p = {random.unit_point(), random.unit_point(), random.unit_point(),
                                 Vec3()};
        // half the trials near-coplanar, where only the exact stage can keep the symmetry
        const double s = random.unit(), t = random.unit();
        p[3] = trial % 2 ? random.unit_point() : p[0] + s * (p[1] - p[0]) + t * (p[2] - p[0]);
        const int base = volume::orient3d(p[0], p[1], p[2], p[3]);
        std::sort(order.begin(), order.end());
        do
        {
            int inversions = 0;
            for (int i = 0; i < 4; ++i)
                for (int j = i + 1; j < 4; ++j) inversions += order[i] > order[j];
            const int parity = inversions % 2 ? -1 : 1;
            REQUIRE(volume::orient3d(p[order[0]], p[order[1]], p[order[2]], p[order[3]]) ==
                    parity * base);
        } while (std::next_permutation(order.begin(), order.end()));
    }
}

TEST_CASE("orient3d is invariant under exact translations and scalings by powers of two")
{
    // Points on a 2^-20 grid of [0,1]^3, translated by 2^k (exact up to k = 30), scaled by 2^k.
    Random random{11};
    for (int trial = 0; trial < 5000; ++trial)
    {
        std::array<Vec3, 4> p;
        for (auto& point : p)
            for (int k = 0; k < 3; ++k) point[k] = random.integer(1 << 20) * 0x1.0p-20;
        if (trial % 2)  // near-coplanar: snap the last point to the grid near the plane
        {
            const Vec3 q = p[0] + 0.3 * (p[1] - p[0]) + 0.6 * (p[2] - p[0]);
            for (int k = 0; k < 3; ++k) p[3][k] = std::round(q[k] * 0x1.0p20) * 0x1.0p-20;
        }
        const int base = volume::orient3d(p[0], p[1], p[2], p[3]);
        REQUIRE(base == reference_orient3d(p[0], p[1], p[2], p[3]));
        for (int power : {1, 7, 30})
        {
            const Vec3 shift(std::ldexp(1.0, power), -std::ldexp(1.0, power - 1), 0.0);
            REQUIRE(volume::orient3d(p[0] + shift, p[1] + shift, p[2] + shift, p[3] + shift) ==
                    base);
        }
        for (int power : {-200, -5, 9, 200})
        {
            const double f = std::ldexp(1.0, power);
            REQUIRE(volume::orient3d(f * p[0], f * p[1], f * p[2], f * p[3]) == base);
        }
    }
}

TEST_CASE("orient2d is exact on every dropped axis and agrees with orient3d")
{
    // Near-degenerate 2-D grid (Shewchuk's example): a around (0.5, 0.5) on a 2^-53 grid,
    // b (12, 12), c (24, 24); the third coordinate is arbitrary.
    const double ulp = 0x1.0p-53;
    int rounded_wrong = 0;
    for (int drop = 0; drop < 3; ++drop)
    {
        const int u = (drop + 1) % 3, v = (drop + 2) % 3;
        for (int i = -16; i < 16; ++i)
            for (int j = -16; j < 16; ++j)
            {
                Vec3 a(7, 7, 7), b(-2, -2, -2), c(5, 5, 5);
                a[u] = 0.5 + i * ulp;
                a[v] = 0.5 + j * ulp;
                b[u] = b[v] = 12;
                c[u] = c[v] = 24;
                const int expected = reference_orient2d(a, b, c, drop);
                REQUIRE(volume::orient2d(a, b, c, drop) == expected);
                REQUIRE(volume::orient2d(b, a, c, drop) == -expected);
                REQUIRE(volume::orient2d(b, c, a, drop) == expected);
                const double rounded =
                    (b[u] - a[u]) * (c[v] - a[v]) - (b[v] - a[v]) * (c[u] - a[u]);
                rounded_wrong += sign_of(rounded) != expected;
            }
    }
    CHECK(rounded_wrong > 0);

    // On integer points orient3d(a, b, c, a + e_drop) is the sign of normal[drop], exactly.
    Random random{5};
    for (int trial = 0; trial < 30000; ++trial)
    {
        Vec3 a, b, c;
        for (int k = 0; k < 3; ++k)
        {
            a[k] = random.integer(4);
            b[k] = random.integer(4);
            c[k] = random.integer(4);
        }
        for (int drop = 0; drop < 3; ++drop)
        {
            const int got = volume::orient2d(a, b, c, drop);
            REQUIRE(got == volume::orient3d(a, b, c, a + Vec3::Unit(drop)));
            REQUIRE(got == sign_of((b - a).cross(c - a)[drop]));
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Intersection tests.

namespace
{

using volume::point_in_tet;
using volume::segment_triangle_intersect;
using volume::tet_triangle_intersect;
using volume::triangles_intersect;

/// An independent exact reference on integer points: closed convex hulls A and B are disjoint
/// exactly when some axis separates them strictly, and one always can be found among the
/// differences of their points, the cross products of two such, and the cross products of
/// such a cross product with a difference (facet normals of A - B, in-plane normals, and
/// the perpendicular to a line).
using IVec = std::array<__int128, 3>;

IVec minus(const IVec& a, const IVec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
IVec cross(const IVec& a, const IVec& b)
{
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
__int128 dot(const IVec& a, const IVec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

bool separated_along(const IVec& axis, const std::vector<IVec>& a, const std::vector<IVec>& b)
{
    if (axis[0] == 0 && axis[1] == 0 && axis[2] == 0) return false;
    __int128 min_a = dot(axis, a[0]), max_a = min_a, min_b = dot(axis, b[0]), max_b = min_b;
    for (const IVec& p : a)
        min_a = std::min(min_a, dot(axis, p)), max_a = std::max(max_a, dot(axis, p));
    for (const IVec& p : b)
        min_b = std::min(min_b, dot(axis, p)), max_b = std::max(max_b, dot(axis, p));
    return max_a < min_b || max_b < min_a;
}

bool hulls_meet(const std::vector<IVec>& a, const std::vector<IVec>& b)
{
    std::vector<IVec> all = a;
    all.insert(all.end(), b.begin(), b.end());
    std::vector<IVec> differences;
    for (std::size_t i = 0; i < all.size(); ++i)
        for (std::size_t j = i + 1; j < all.size(); ++j)
        {
            const IVec d = minus(all[i], all[j]);
            if (d[0] != 0 || d[1] != 0 || d[2] != 0) differences.push_back(d);
        }
    for (const IVec& d : differences)
        if (separated_along(d, a, b)) return false;
    for (std::size_t i = 0; i < differences.size(); ++i)
        for (std::size_t j = i + 1; j < differences.size(); ++j)
        {
            const IVec n = cross(differences[i], differences[j]);
            if (n[0] == 0 && n[1] == 0 && n[2] == 0) continue;
            if (separated_along(n, a, b)) return false;
            for (const IVec& d : differences)
                if (separated_along(cross(n, d), a, b)) return false;
        }
    return true;
}

bool affinely_independent(const std::vector<Vec3>& points, const std::vector<int>& ids)
{
    const Vec3& o = points[ids[0]];
    if (ids.size() == 2) return !(points[ids[1]] == o);
    const Vec3 n = (points[ids[1]] - o).cross(points[ids[2]] - o);  // exact on small integers
    if (ids.size() == 3) return !n.isZero(0.0);
    return n.dot(points[ids[3]] - o) != 0.0;
}

/// Simplices s and t (ids into integer points) meet outside the hull K of their shared ids.
/// With K empty that is hulls_meet. Otherwise the points of s beyond K are those with weight
/// w > 0 on its other vertices; by convexity they meet t exactly when the slice of s at a
/// small w does, and w = 2^-20 is below every positive optimum of that linear program on
/// coordinates in {0..3}. The slice needs s non-flat; the relation is symmetric, so either
/// simplex may be sliced. Returns -1 when both are flat and share vertices.
int reference_intersect(const std::vector<Vec3>& points, std::vector<int> s, std::vector<int> t)
{
    const __int128 scale = 1 << 20;
    auto scaled = [&](int id, __int128 factor) {
        return IVec{static_cast<__int128>(points[id].x()) * factor,
                    static_cast<__int128>(points[id].y()) * factor,
                    static_cast<__int128>(points[id].z()) * factor};
    };
    std::vector<int> shared;
    for (int id : s)
        if (std::find(t.begin(), t.end(), id) != t.end()) shared.push_back(id);
    if (shared.empty())
    {
        std::vector<IVec> a, b;
        for (int id : s) a.push_back(scaled(id, 1));
        for (int id : t) b.push_back(scaled(id, 1));
        return hulls_meet(a, b);
    }
    if (!affinely_independent(points, s)) std::swap(s, t);
    if (!affinely_independent(points, s)) return -1;
    std::vector<IVec> slice, other;
    for (int k : shared)
        for (int v : s)
            if (std::find(shared.begin(), shared.end(), v) == shared.end())
            {
                const IVec kk = scaled(k, scale - 1), vv = scaled(v, 1);
                slice.push_back({kk[0] + vv[0], kk[1] + vv[1], kk[2] + vv[2]});
            }
    if (slice.empty()) return 0;  // s is the shared simplex itself
    for (int id : t) other.push_back(scaled(id, scale));
    return hulls_meet(slice, other);
}

std::vector<Vec3> points_of(std::initializer_list<Vec3> list) { return std::vector<Vec3>(list); }

}  // namespace

TEST_CASE("segment_triangle_intersect: every configuration")
{
    // Triangle 0 1 2 in the plane z = 0; segment ends are added per case.
    //
    //   y
    //   2
    //   |\          .
    //   | \         .
    //   0--1  x
    std::vector<Vec3> p = points_of({{0, 0, 0}, {4, 0, 0}, {0, 4, 0}});
    auto with = [&p](Vec3 a, Vec3 b) {
        p.resize(3);
        p.push_back(a);
        p.push_back(b);
        return std::array<int, 2>{3, 4};
    };
    const std::array<int, 3> tri = {0, 1, 2};
    SUBCASE("disjoint: above the plane")
    {
        CHECK_FALSE(segment_triangle_intersect(p, with({1, 1, 1}, {2, 1, 3}), tri));
    }
    SUBCASE("disjoint: crosses the plane outside the triangle")
    {
        CHECK_FALSE(segment_triangle_intersect(p, with({3, 3, -1}, {3, 3, 1}), tri));
    }
    SUBCASE("crossing the interior")
    {
        CHECK(segment_triangle_intersect(p, with({1, 1, -1}, {1, 1, 1}), tri));
    }
    SUBCASE("touching: an end on the interior, on an edge, at a vertex")
    {
        CHECK(segment_triangle_intersect(p, with({1, 1, 0}, {1, 1, 2}), tri));
        CHECK(segment_triangle_intersect(p, with({2, 0, 0}, {2, 1, 2}), tri));
        CHECK(segment_triangle_intersect(p, with({-1, 0, -1}, {1, 0, 1}), tri));  // through 0
        CHECK(segment_triangle_intersect(p, with({4, 0, 0}, {5, 5, 5}), tri));    // at vertex 1
    }
    SUBCASE("touching: crossing an edge's line just at the edge")
    {
        CHECK(segment_triangle_intersect(p, with({2, 2, -1}, {2, 2, 1}), tri));  // on edge 12
        CHECK_FALSE(segment_triangle_intersect(
            p, with({2, 2.0000000000000004, -1}, {2, 2.0000000000000004, 1}),
            tri));  // one ulp outside
    }
    SUBCASE("coplanar: crossing, inside, touching a vertex, apart")
    {
        CHECK(segment_triangle_intersect(p, with({-1, 1, 0}, {5, 1, 0}), tri));
        CHECK(segment_triangle_intersect(p, with({1, 1, 0}, {1, 2, 0}), tri));
        CHECK(segment_triangle_intersect(p, with({4, 0, 0}, {6, 1, 0}), tri));
        CHECK(segment_triangle_intersect(p, with({-2, 2, 0}, {2, -2, 0}), tri));  // through 0
        CHECK_FALSE(segment_triangle_intersect(p, with({3, 3, 0}, {5, 1, 0}), tri));
        CHECK_FALSE(segment_triangle_intersect(p, with({-1, -1, 0}, {-1, 5, 0}), tri));
    }
    SUBCASE("coplanar and collinear with an edge: overlapping, touching, apart")
    {
        CHECK(segment_triangle_intersect(p, with({-1, 0, 0}, {1, 0, 0}), tri));
        CHECK(segment_triangle_intersect(p, with({4, 0, 0}, {6, 0, 0}), tri));
        CHECK_FALSE(segment_triangle_intersect(p, with({5, 0, 0}, {6, 0, 0}), tri));
    }
    SUBCASE("a zero-length segment is a point")
    {
        CHECK(segment_triangle_intersect(p, with({1, 1, 0}, {1, 1, 0}), tri));
        CHECK_FALSE(segment_triangle_intersect(p, with({1, 1, 1}, {1, 1, 1}), tri));
        CHECK_FALSE(segment_triangle_intersect(p, with({3, 3, 0}, {3, 3, 0}), tri));
    }
    SUBCASE("an edge of the triangle itself does not intersect it")
    {
        CHECK_FALSE(segment_triangle_intersect(p, {0, 1}, tri));
        CHECK_FALSE(segment_triangle_intersect(p, {2, 1}, tri));
    }
    SUBCASE("shared vertex 0: only a direction into the triangle's wedge intersects")
    {
        //   2
        //   |\   3 = (1,1,0) in the wedge; (1,1,1) off the plane; (-1,1,0) outside it;
        //   0--1     (2,0,0) along edge 01; (-1,0,0) along it backwards
        auto from0 = [&p](Vec3 x) {
            p.resize(3);
            p.push_back(x);
            return std::array<int, 2>{0, 3};
        };
        CHECK(segment_triangle_intersect(p, from0({1, 1, 0}), tri));
        CHECK(segment_triangle_intersect(p, from0({9, 9, 0}), tri));  // leaves it, still meets
        CHECK(segment_triangle_intersect(p, from0({2, 0, 0}), tri));
        CHECK(segment_triangle_intersect(p, from0({0, 7, 0}), tri));
        CHECK_FALSE(segment_triangle_intersect(p, from0({1, 1, 1}), tri));
        CHECK_FALSE(segment_triangle_intersect(p, from0({-1, 1, 0}), tri));
        CHECK_FALSE(segment_triangle_intersect(p, from0({-1, 0, 0}), tri));
        CHECK_FALSE(segment_triangle_intersect(p, from0({0, 0, 0}), tri));  // zero length at 0
        const std::array<int, 2> forward = from0({1, 2, 0}), backward = {3, 0};
        CHECK(segment_triangle_intersect(p, backward, tri));
        CHECK(segment_triangle_intersect(p, forward, {2, 0, 1}));
    }
    SUBCASE("a flat triangle is its longest edge")
    {
        //   0----3----1   triangle (0, 1, 3) collinear, crossed at (3,0,0) or missed
        p = points_of({{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {2, 0, 0}, {3, -1, 0}, {3, 1, 0}});
        CHECK(segment_triangle_intersect(p, {4, 5}, {0, 1, 3}));
        CHECK(segment_triangle_intersect(p, {4, 5}, {0, 3, 1}));
        p[4] = {5, -1, 0};
        p[5] = {5, 1, 0};
        CHECK_FALSE(segment_triangle_intersect(p, {4, 5}, {0, 1, 3}));
        p[4] = {3, 0, -1};
        p[5] = {3, 0, 1};
        CHECK(segment_triangle_intersect(p, {4, 5}, {0, 1, 3}));
        // Sharing the middle vertex 3: a segment from 3 along the line overlaps the flat
        // triangle beyond 3 whichever way it goes; off the line it only touches at 3.
        CHECK_FALSE(segment_triangle_intersect(p, {3, 1}, {0, 1, 3}));  // an edge (2 shared)
        p[4] = {9, 0, 0};
        p[5] = {-9, 0, 0};
        CHECK(segment_triangle_intersect(p, {3, 4}, {0, 1, 3}));
        CHECK(segment_triangle_intersect(p, {3, 5}, {0, 1, 3}));
        p[5] = {3, 0, 1};
        CHECK_FALSE(segment_triangle_intersect(p, {3, 5}, {0, 1, 3}));
    }
}

TEST_CASE("triangles_intersect: every configuration")
{
    // Base triangle A = 0 1 2 in z = 0; B's vertices are 3 4 5 unless it shares some.
    //   2
    //   |\        .
    //   0--1
    std::vector<Vec3> p;
    auto setup = [&p](std::initializer_list<Vec3> extra) {
        p = points_of({{0, 0, 0}, {4, 0, 0}, {0, 4, 0}});
        p.insert(p.end(), extra.begin(), extra.end());
    };
    const std::array<int, 3> a = {0, 1, 2}, b = {3, 4, 5};
    auto both_ways = [&p](const std::array<int, 3>& s, const std::array<int, 3>& t) {
        const bool result = triangles_intersect(p, s, t);
        CHECK(triangles_intersect(p, t, s) == result);
        CHECK(triangles_intersect(p, {s[1], s[2], s[0]}, {t[2], t[1], t[0]}) == result);
        return result;
    };
    SUBCASE("disjoint: parallel planes, or crossing the plane outside")
    {
        setup({{0, 0, 1}, {4, 0, 1}, {0, 4, 1}});
        CHECK_FALSE(both_ways(a, b));
        setup({{3, 3, -1}, {5, 3, 1}, {3, 5, 1}});
        CHECK_FALSE(both_ways(a, b));
    }
    SUBCASE("crossing: B pierces A's interior")
    {
        setup({{1, 1, -1}, {1, 1, 1}, {3, 3, 0.5}});
        CHECK(both_ways(a, b));
    }
    SUBCASE("touching: a vertex of B on A's interior, on an edge; an edge of B across A's edge")
    {
        setup({{1, 1, 0}, {1, 1, 2}, {2, 1, 2}});
        CHECK(both_ways(a, b));
        setup({{2, 0, 0}, {2, 1, 2}, {3, 1, 2}});
        CHECK(both_ways(a, b));
        setup({{2, -1, 0}, {2, 1, 0}, {2, 0, 3}});  // B's edge crosses edge 01 in the plane
        CHECK(both_ways(a, b));
        setup({{2, -1, 0.5}, {2, 1, -0.5}, {2, -1, 3}});  // B's edge passes through (2,0,0)
        CHECK(both_ways(a, b));
    }
    SUBCASE("coplanar: overlapping, one inside the other, apart, touching at a vertex")
    {
        setup({{1, 1, 0}, {5, 1, 0}, {1, 5, 0}});
        CHECK(both_ways(a, b));
        setup({{0.5, 0.5, 0}, {1, 0.5, 0}, {0.5, 1, 0}});
        CHECK(both_ways(a, b));
        setup({{3, 3, 0}, {5, 3, 0}, {3, 5, 0}});
        CHECK_FALSE(both_ways(a, b));
        setup({{4, 0, 0}, {6, 0, 0}, {6, 2, 0}});  // distinct ids at the same point
        CHECK(both_ways(a, b));
    }
    SUBCASE("shared edge 01: folded, unfolded, coplanar on one side")
    {
        //   folded: 3 above the plane     unfolded: 3 = (2,-3,0)    same side: 3 = (1,1,0)
        //
        //     2                              2                         2
        //     |\      3                      |\                        |\       .
        //     0--1   (up)                    0--1                      0-3-1
        //                                     \/                         overlap
        //                                     3
        setup({{2, 1, 3}});
        CHECK_FALSE(both_ways(a, {0, 1, 3}));
        setup({{2, -3, 0}});
        CHECK_FALSE(both_ways(a, {0, 1, 3}));
        setup({{1, 1, 0}});
        CHECK(both_ways(a, {0, 1, 3}));
        CHECK(both_ways(a, {1, 0, 3}));
        setup({{9, 9, 0}});  // same side and larger than A
        CHECK(both_ways(a, {0, 1, 3}));
    }
    SUBCASE("shared vertex 0: apart, the opposite edge piercing, coplanar wedges")
    {
        //   B = (0, 3, 4)
        setup({{0, 0, 4}, {-4, 0, 4}});  // B stands on 0 outside A
        CHECK_FALSE(both_ways(a, {0, 3, 4}));
        setup({{1, 1, -3}, {1, 1, 3}});  // B's edge 34 pierces A
        CHECK(both_ways(a, {0, 3, 4}));
        setup({{4, 4, -3}, {4, 4, 3}});  // B contains the ray (1,1,0), which runs through A
        CHECK(both_ways(a, {0, 3, 4}));
        setup({{-1, 1, 0}, {-1, -1, 0}});  // coplanar, wedges apart
        CHECK_FALSE(both_ways(a, {0, 3, 4}));
        setup({{1, 3, 0}, {-4, 1, 0}});  // coplanar, wedges overlap
        CHECK(both_ways(a, {0, 3, 4}));
        setup({{0, 9, 0}, {-4, 1, 0}});  // coplanar, B's edge 03 along A's edge 02
        CHECK(both_ways(a, {0, 3, 4}));
        setup({{0, -9, 0}, {-4, 1, 0}});  // coplanar, wedges meet only at 0
        CHECK_FALSE(both_ways(a, {0, 3, 4}));
        setup({{0, 0, 3}, {0, 0, -3}});  // flat B through 0, perpendicular to A
        CHECK_FALSE(both_ways(a, {0, 3, 4}));
        setup({{1, 1, 0}, {-1, -1, 0}});  // flat B through 0, along A's interior
        CHECK(both_ways(a, {0, 3, 4}));
    }
    SUBCASE("the same triangle, and a flat triangle on the shared edge")
    {
        setup({});
        CHECK_FALSE(both_ways(a, {2, 1, 0}));
        //   0--3--1 with 3 = (2,0,0): the flat (0,1,3) lies on A's edge 01
        setup({{2, 0, 0}, {6, 0, 0}});
        CHECK_FALSE(both_ways(a, {0, 1, 3}));
        CHECK(both_ways(a, {0, 1, 4}) == false);  // flat, beyond 1 along the line: outside A
        CHECK(both_ways({0, 1, 4}, {1, 0, 3}) == false);
        p.push_back({8, 0, 0});
        CHECK(both_ways({0, 1, 4}, {0, 1, 5}));  // two flat ones overlapping beyond 1
    }
    SUBCASE("a flat triangle crossing, touching or missing a triangle")
    {
        setup({{1, 1, -1}, {1, 1, 1}, {1, 1, 3}});
        CHECK(both_ways(a, b));
        setup({{1, 1, 1}, {1, 1, 2}, {1, 1, 3}});
        CHECK_FALSE(both_ways(a, b));
        setup({{1, 1, 0}, {1, 1, 2}, {1, 1, 3}});
        CHECK(both_ways(a, b));
        setup({{5, 5, 5}, {5, 5, 5}, {5, 5, 5}});  // a triangle collapsed to a point
        CHECK_FALSE(both_ways(a, b));
    }
}

TEST_CASE("point_in_tet: inside, outside, on a face, an edge, a vertex")
{
    //   3
    //   |\     tet 0 1 2 3, positive; p = point 4
    //   0-2
    //    \|
    //     1
    std::vector<Vec3> p = points_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}});
    const std::array<int, 4> tet = {0, 1, 2, 3}, negative = {0, 2, 1, 3};
    auto at = [&p, &tet](Vec3 x) {
        p[4] = x;
        return point_in_tet(p, 4, tet);
    };
    CHECK(at({0.1, 0.1, 0.1}));
    CHECK_FALSE(at({1, 1, 1}));
    CHECK_FALSE(at({-0.1, 0.1, 0.1}));
    CHECK(at({0.25, 0.25, 0.5}));  // on the far face
    CHECK(at({0.5, 0, 0.5}));      // on an edge
    CHECK(at({0, 0, 1}));          // at a vertex, as another id
    CHECK_FALSE(at({0.5, 0.5, 0.0000000000000001}));
    CHECK(point_in_tet(p, 4, negative) == point_in_tet(p, 4, tet));
    CHECK_FALSE(point_in_tet(p, 3, tet));  // a vertex of the tet shares, it does not meet
}

TEST_CASE("tet_triangle_intersect: every configuration")
{
    //   3
    //   |\     tet T = 0 1 2 3 (the unit corner), triangle vertices 4 5 6 unless shared
    //   0-2
    //    \|
    //     1
    std::vector<Vec3> p;
    auto setup = [&p](std::initializer_list<Vec3> extra) {
        p = points_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
        p.insert(p.end(), extra.begin(), extra.end());
    };
    const std::array<int, 4> tet = {0, 1, 2, 3};
    auto meets = [&p, &tet](const std::array<int, 3>& t) {
        const bool result = tet_triangle_intersect(p, tet, t);
        CHECK(tet_triangle_intersect(p, {1, 0, 3, 2}, {t[1], t[2], t[0]}) == result);
        CHECK(tet_triangle_intersect(p, {0, 2, 1, 3}, t) == result);  // given negative
        return result;
    };
    const std::array<int, 3> free = {4, 5, 6};
    SUBCASE("no shared vertex: apart, inside, piercing, slicing a corner, touching")
    {
        setup({{2, 2, 2}, {3, 2, 2}, {2, 3, 2}});
        CHECK_FALSE(meets(free));
        setup({{0.1, 0.1, 0.1}, {0.2, 0.1, 0.1}, {0.1, 0.2, 0.1}});  // inside
        CHECK(meets(free));
        setup({{0.2, 0.2, -1}, {0.2, 0.2, 2}, {5, 5, 0.2}});  // an edge pierces two faces
        CHECK(meets(free));
        setup({{-1, -1, 0.5}, {3, -1, 0.5}, {-1, 3, 0.5}});  // cuts every tet edge up to 3
        CHECK(meets(free));
        setup({{-1, -1, 0}, {3, -1, 0}, {-1, 3, 0}});  // contains the face 0 1 2
        CHECK(meets(free));
        setup({{-1, -1, -1}, {3, -1, -1}, {-1, 3, -1}});  // parallel below
        CHECK_FALSE(meets(free));
        setup({{0.5, 0.5, 0}, {2, 2, -1}, {2, 0, -1}});  // a vertex on the edge 12
        CHECK(meets(free));
        setup({{0.6, 0.6, 0}, {2, 2, -1}, {2, 0, -1}});  // just past it
        CHECK_FALSE(meets(free));
        setup({{0.5, 0.5, 0.5}, {2, 2, 2}, {2, 0, 2}});  // a vertex beyond the far face
        CHECK_FALSE(meets(free));
        setup({{1, 1, 1}, {-1, -1, -1}, {1, -1, 0}});  // through vertex 0 with other ids
        CHECK(meets(free));
    }
    SUBCASE("a face of the tet does not intersect it; a triangle sharing an edge")
    {
        //   sharing edge 12 (the front's neighbour face): outside, folded into the tet,
        //   coplanar with face 1 2 3 outside / overlapping it, coplanar with 0 1 2 outside
        setup({});
        CHECK_FALSE(meets({1, 2, 3}));
        CHECK_FALSE(meets({3, 0, 2}));
        setup({{1, 1, 1}});
        CHECK_FALSE(meets({1, 2, 4}));
        setup({{0.1, 0.1, 0.1}});
        CHECK(meets({1, 2, 4}));
        setup({{1, 1, -1}});  // on plane 1 2 3, beyond the edge
        CHECK_FALSE(meets({1, 2, 4}));
        setup({{0.2, 0.2, 0.6}});  // on plane 1 2 3, over the face
        CHECK(meets({1, 2, 4}));
        setup({{1, 1, 0}});  // on plane 0 1 2, beyond the edge
        CHECK_FALSE(meets({1, 2, 4}));
        setup({{0.2, 0.2, 0}});  // on face 0 1 2 (the triangle 1 2 4 is inside the face)
        CHECK(meets({1, 2, 4}));
        setup({{2, -1, 0}});  // flat: on the line of edge 12, beyond 1
        CHECK_FALSE(meets({1, 2, 4}));
    }
    SUBCASE("sharing vertex 0: outside, the opposite edge through the tet, on a face plane")
    {
        setup({{-1, 0, 0}, {0, -1, 0}});
        CHECK_FALSE(meets({0, 4, 5}));
        setup({{0.2, 0.2, -1}, {0.2, 0.2, 2}});  // edge 45 pierces the tet
        CHECK(meets({0, 4, 5}));
        setup({{5, 5, -1}, {5, 5, 5}});  // big: edge 45 passes outside, face 1 2 3 cuts it
        CHECK(meets({0, 4, 5}));
        setup({{1, -1, 0}, {2, -1, 0}});  // in plane z = 0, outside the face
        CHECK_FALSE(meets({0, 4, 5}));
        setup({{1, 0.5, 0}, {-1, 2, 0}});  // in plane z = 0, over face 0 1 2
        CHECK(meets({0, 4, 5}));
        setup({{2, 0, 0}, {-1, -1, 0}});  // along edge 01 and outside: overlap on the edge
        CHECK(meets({0, 4, 5}));
        setup({{0.1, 0.1, 0.1}, {-1, -1, -1}});  // flat through 0, into the tet
        CHECK(meets({0, 4, 5}));
        setup({{-0.1, 0.1, 0.1}, {-1, 1, 1}});  // flat from 0, outside
        CHECK_FALSE(meets({0, 4, 5}));
    }
}

TEST_CASE("the intersection tests agree with an exact separating-axis reference")
{
    // Points on {0,1,2}^3 plus three repeated points under new ids: random simplices hit
    // every coplanar, collinear, touching and shared-vertex case many times.
    std::vector<Vec3> p;
    for (int x = 0; x < 3; ++x)
        for (int y = 0; y < 3; ++y)
            for (int z = 0; z < 3; ++z) p.emplace_back(x, y, z);
    p.push_back(p[13]);
    p.push_back(p[0]);
    p.push_back(p[5]);
    const int n = static_cast<int>(p.size());
    Random random{21};
    auto distinct = [&](int count) {
        std::vector<int> ids;
        while (static_cast<int>(ids.size()) < count)
        {
            const int id = random.integer(n);
            if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
        }
        return ids;
    };
    // Draw the second simplex mostly from the first one's vertices, so sharing is common.
    auto near = [&](const std::vector<int>& base, int count) {
        std::vector<int> ids;
        while (static_cast<int>(ids.size()) < count)
        {
            const int id = random.integer(3) == 0
                               ? random.integer(n)
                               : base[random.integer(static_cast<int>(base.size()))];
            if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
        }
        return ids;
    };
    std::array<int, 2> seen_true{}, seen_false{};
    auto record = [&](int kind, bool value) { (value ? seen_true : seen_false)[kind]++; };
    for (int trial = 0; trial < 4000; ++trial)
    {
        const std::vector<int> t = distinct(3);
        const std::vector<int> s = near(t, 2), u = near(t, 3);
        const int expected_s = reference_intersect(p, s, t);
        if (expected_s >= 0)
            REQUIRE(segment_triangle_intersect(p, {s[0], s[1]}, {t[0], t[1], t[2]}) ==
                    (expected_s == 1));
        const int expected_u = reference_intersect(p, u, t);
        if (expected_u >= 0)
        {
            INFO("t1 ", u[0], " ", u[1], " ", u[2], " t2 ", t[0], " ", t[1], " ", t[2]);
            REQUIRE(triangles_intersect(p, {u[0], u[1], u[2]}, {t[0], t[1], t[2]}) ==
                    (expected_u == 1));
            record(0, expected_u == 1);
        }
        std::vector<int> tet = near(t, 4);
        if (!affinely_independent(p, tet)) continue;
        const int expected_tet = reference_intersect(p, tet, t);
        INFO("tet ", tet[0], " ", tet[1], " ", tet[2], " ", tet[3], " t ", t[0], " ", t[1], " ",
             t[2]);
        REQUIRE(expected_tet >= 0);
        REQUIRE(tet_triangle_intersect(p, {tet[0], tet[1], tet[2], tet[3]}, {t[0], t[1], t[2]}) ==
                (expected_tet == 1));
        record(1, expected_tet == 1);
        const int q = random.integer(n);
        if (std::find(tet.begin(), tet.end(), q) == tet.end())
            REQUIRE(point_in_tet(p, q, {tet[0], tet[1], tet[2], tet[3]}) ==
                    (reference_intersect(p, {q}, tet) == 1));
    }
    CHECK(seen_true[0] > 100);
    CHECK(seen_false[0] > 100);
    CHECK(seen_true[1] > 100);
    CHECK(seen_false[1] > 100);
}
