// The exact predicates: orient3d and orient2d against an exact big-integer determinant on
// inputs where rounded arithmetic fails (near-coplanar points, coplanar integer grids), their
// symmetries (permutations, translations and scalings by powers of two); then every
// configuration of the intersection tests, each drawn.

#include "volume/predicates.h"

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
