// Exact stages of orient3d and orient2d by floating-point expansion arithmetic (after
// Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
// Predicates", 1997), and the intersection tests built on their signs.
//
// An expansion is a sum of doubles stored by increasing magnitude, nonoverlapping, zeros
// removed; its sign is the sign of its last (largest) component. The arithmetic below is only
// exact under round-to-nearest-even without fused multiply-adds the algorithm did not ask for
// (CMakeLists.txt compiles this file with -ffp-contract=off).

#include "volume/predicates.h"

#include <cassert>
#include <cmath>

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
// Expansions of bounded length on the stack.

template <int Capacity>
struct Expansion
{
    double terms[Capacity];
    int size = 0;

    int sign() const { return size == 0 ? 0 : (terms[size - 1] > 0.0 ? 1 : -1); }
    void push_nonzero(double value)
    {
        if (value != 0.0)
        {
            assert(size < Capacity);
            terms[size++] = value;
        }
    }
};

/// a - b exactly, as an expansion of at most two terms.
Expansion<2> difference(double a, double b)
{
    Expansion<2> result;
    double head, tail;
    two_diff(a, b, head, tail);
    result.push_nonzero(tail);
    result.push_nonzero(head);
    return result;
}

/// e + f by merging the components by magnitude and accumulating with two_sum.
template <int C, int E, int F>
Expansion<C> add(const Expansion<E>& e, const Expansion<F>& f)
{
    static_assert(C >= E + F, "sum capacity");
    Expansion<C> h;
    int i = 0, j = 0;
    auto next_smallest = [&]() {
        if (j == f.size || (i < e.size && std::abs(e.terms[i]) < std::abs(f.terms[j])))
            return e.terms[i++];
        return f.terms[j++];
    };
    const int total = e.size + f.size;
    if (total == 0) return h;
    double q = next_smallest();
    for (int k = 1; k < total; ++k)
    {
        double sum, error;
        two_sum(q, next_smallest(), sum, error);
        h.push_nonzero(error);
        q = sum;
    }
    h.push_nonzero(q);
    return h;
}

template <int E>
Expansion<E> negate(Expansion<E> e)
{
    for (int i = 0; i < e.size; ++i) e.terms[i] = -e.terms[i];
    return e;
}

/// e * b for one double b.
template <int C, int E>
Expansion<C> scale(const Expansion<E>& e, double b)
{
    static_assert(C >= 2 * E, "scale capacity");
    Expansion<C> h;
    if (e.size == 0 || b == 0.0) return h;
    double q, low;
    two_product(e.terms[0], b, q, low);
    h.push_nonzero(low);
    for (int i = 1; i < e.size; ++i)
    {
        double product_high, product_low, sum, error;
        two_product(e.terms[i], b, product_high, product_low);
        two_sum(q, product_low, sum, error);
        h.push_nonzero(error);
        fast_two_sum(product_high, sum, q, error);
        h.push_nonzero(error);
    }
    h.push_nonzero(q);
    return h;
}

/// e * f for a factor f of at most two terms (a coordinate difference).
template <int C, int E>
Expansion<C> multiply(const Expansion<E>& e, const Expansion<2>& f)
{
    static_assert(C >= 4 * E, "product capacity");
    if (f.size == 0) return Expansion<C>();
    if (f.size == 1) return scale<C>(e, f.terms[0]);
    return add<C>(scale<2 * E>(e, f.terms[0]), scale<2 * E>(e, f.terms[1]));
}

/// x1 * y1 - x2 * y2 exactly.
Expansion<16> cross_term(const Expansion<2>& x1, const Expansion<2>& y1, const Expansion<2>& x2,
                         const Expansion<2>& y2)
{
    return add<16>(multiply<8>(x1, y1), negate(multiply<8>(x2, y2)));
}

}  // namespace

namespace detail
{

int orient3d_exact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
    // The differences to a are exact as two-term expansions, so the determinant of
    // differences is the exact one; short expansions keep the common cases cheap.
    const Expansion<2> bax = difference(b.x(), a.x()), bay = difference(b.y(), a.y()),
                       baz = difference(b.z(), a.z());
    const Expansion<2> cax = difference(c.x(), a.x()), cay = difference(c.y(), a.y()),
                       caz = difference(c.z(), a.z());
    const Expansion<2> dax = difference(d.x(), a.x()), day = difference(d.y(), a.y()),
                       daz = difference(d.z(), a.z());
    const Expansion<64> term_x = multiply<64>(cross_term(cay, daz, caz, day), bax);
    const Expansion<64> term_y = multiply<64>(cross_term(caz, dax, cax, daz), bay);
    const Expansion<64> term_z = multiply<64>(cross_term(cax, day, cay, dax), baz);
    return add<192>(add<128>(term_x, term_y), term_z).sign();
}

int orient2d_exact(const Vec3& a, const Vec3& b, const Vec3& c, int drop)
{
    const int u = drop == 2 ? 0 : drop + 1;
    const int v = drop == 0 ? 2 : drop - 1;
    return cross_term(difference(b[u], a[u]), difference(c[v], a[v]), difference(b[v], a[v]),
                      difference(c[u], a[u]))
        .sign();
}

}  // namespace detail

}  // namespace hdimesh::volume
