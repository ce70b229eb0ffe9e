// A double together with a rigorous bound on its distance to the exact value it stands for
// (running error analysis, as pbrt-v3's EFloat): the certified solver's numbers. Every operation
// adds its own rounding error, u |result|, to the propagated bounds; the bound's own computation
// rounds too, so each new bound is inflated by (1 + 16u), far more than the few u that computing
// it can lose, plus the underflow floor for anything that may have underflowed. Callers keep
// magnitudes far from overflow and underflow (the solvers prescale by powers of two and refuse
// fragile scenes).
#pragma once

#include "numeric/eft.hpp"
#include "numeric/format.hpp"

#include <cmath>
#include <cstdlib>

namespace linequad {

struct Bounded {
    double v = 0; // the computed value
    double e = 0; // |v - exact| <= e

    static Bounded exact(double x) { return {x, 0}; }
    // The sign of the exact value when it is certain, else 0.
    int certain_sign() const { return v > e ? 1 : v < -e ? -1 : 0; }
    // A bound on |v - exact| (e itself: every operation has inflated it already).
    double bound() const { return e; }
};

namespace bounded_detail {
using F = detail::Binary64;
// The new bound, inflated to cover its own rounding. The underflow floor is left out when the
// operation was exact (a zero error on an exact zero), so that exact zeros stay exact and can
// decide parallel, tangent and on-surface cases.
inline double up(double e, bool may_have_rounded) {
    return e * F::cover(16) + (e != 0 || may_have_rounded ? F::underflow_floor : 0.0);
}
inline bool exact_zero(Bounded x) {
    return x.v == 0 && x.e == 0;
}
} // namespace bounded_detail

// For exact operands the rounding error itself is known exactly (two_sum, fma): exact results
// keep a zero bound, which lets exact zeros decide the degenerate cases.
inline Bounded operator+(Bounded a, Bounded b) {
    using bounded_detail::F;
    double s = a.v + b.v; // a sum that rounds to zero is exactly zero
    if (a.e == 0 && b.e == 0) {
        double bb = s - a.v, err = (a.v - (s - bb)) + (b.v - bb);
        return {s, std::fabs(err)};
    }
    return {s, bounded_detail::up(a.e + b.e + F::u * std::fabs(s), s != 0)};
}
inline Bounded operator-(Bounded a, Bounded b) {
    return a + Bounded{-b.v, b.e};
}
inline Bounded operator-(Bounded a) {
    return {-a.v, a.e};
}
inline Bounded operator*(Bounded a, Bounded b) {
    using bounded_detail::F;
    double p = a.v * b.v;
    if (a.e == 0 && b.e == 0) { // fma gives the exact error unless the product underflowed
        bool tiny = std::fabs(p) < F::exact_product_min && a.v != 0 && b.v != 0;
        return {p, std::fabs(std::fma(a.v, b.v, -p)) + (tiny ? F::underflow_floor : 0.0)};
    }
    double e = std::fabs(a.v) * b.e + std::fabs(b.v) * a.e + a.e * b.e + F::u * std::fabs(p);
    // Only an exact zero factor makes the product exact. Otherwise the bound's own products may
    // underflow to zero (2^-392 times an error of 2^-881), and the floor must stay.
    bool exact = bounded_detail::exact_zero(a) || bounded_detail::exact_zero(b);
    return {p, bounded_detail::up(e, !exact)};
}
// |b| > b.e is required (the divisor's sign is certain); otherwise the bound is infinite.
inline Bounded operator/(Bounded a, Bounded b) {
    using bounded_detail::F;
    double q = a.v / b.v;
    double gap = std::fabs(b.v) - b.e;
    if (!(gap > 0)) return {q, F::inf};
    if (a.e == 0 && b.e == 0 && std::fabs(q) > F::exact_product_min) {
        double r = std::fma(q, b.v, -a.v); // the remainder is exact: |q - a/b| = |r/b|
        return {q, r == 0 ? 0.0 : bounded_detail::up(std::fabs(r) / std::fabs(b.v), true)};
    }
    double e = (a.e + std::fabs(q) * b.e) / gap + F::u * std::fabs(q);
    return {q, bounded_detail::up(e, !bounded_detail::exact_zero(a))};
}
// For an argument whose exact value is known to be >= 0.
inline Bounded sqrt(Bounded a) {
    using bounded_detail::F;
    double r = std::sqrt(std::fmax(a.v, 0.0));
    if (a.e == 0 && std::fma(r, r, -a.v) == 0) return {r, 0}; // a perfect square
    double low = std::sqrt(std::fmax(a.v - a.e, 0.0));
    double denom = r + low;
    double e = denom > 0 ? a.e / denom : std::sqrt(a.e); // |sqrt(x) - sqrt(y)| <= sqrt(|x - y|)
    return {r, bounded_detail::up(e + F::u * r, !bounded_detail::exact_zero(a))};
}

// Bounded without its two costs: no exact-zero tracking (so no branches) and no inflation per
// operation. Each operation adds the same propagated terms and its own rounding, u |result|,
// plus the underflow floor always. The bound's own arithmetic rounds too, by at most a relative
// u per step, since it only adds and multiplies non-negative terms: a chain of fewer than 2^12
// steps is covered by inflating once, by (1 + 2^13 u), wherever a bound is used (bound(): a
// sign, a divisor's gap, a root's lower end, the final bound).
//
// Every bound is at least the underflow floor, so no zero is ever certain in it: the degenerate
// cases that exact zeros decide (parallel, tangent, on the surface) come out uncertain. The
// certified solvers try it first and solve again in Bounded whenever it leaves anything
// uncertain; the values are the same in both (the same operations on v), only the bounds differ.
// T: double, or a lane type (the batch hit test's quick line form).
template <class T>
struct QuickBoundedT {
    T v = T(0);
    T e = T(0); // |v - exact| <= bound()

    static QuickBoundedT exact(T x) { return {x, T(0)}; }
    T bound() const { return e * T(detail::Binary64::cover(8192)); }
    int certain_sign() const {
        double b = bound();
        return v > b ? 1 : v < -b ? -1 : 0;
    }
};
using QuickBounded = QuickBoundedT<double>;

template <class T>
inline QuickBoundedT<T> operator+(QuickBoundedT<T> a, QuickBoundedT<T> b) {
    using bounded_detail::F;
    using std::fabs;
    T s = a.v + b.v;
    return {s, a.e + b.e + T(F::u) * fabs(s) + T(F::underflow_floor)};
}
template <class T>
inline QuickBoundedT<T> operator-(QuickBoundedT<T> a) {
    return {-a.v, a.e};
}
template <class T>
inline QuickBoundedT<T> operator-(QuickBoundedT<T> a, QuickBoundedT<T> b) {
    return a + QuickBoundedT<T>{-b.v, b.e};
}
template <class T>
inline QuickBoundedT<T> operator*(QuickBoundedT<T> a, QuickBoundedT<T> b) {
    using bounded_detail::F;
    using std::fabs;
    T p = a.v * b.v;
    T e = fabs(a.v) * b.e + fabs(b.v) * a.e + a.e * b.e;
    return {p, e + T(F::u) * fabs(p) + T(F::underflow_floor)};
}
// |b| > bound(b) is required; otherwise the bound is infinite.
inline QuickBounded operator/(QuickBounded a, QuickBounded b) {
    using bounded_detail::F;
    double q = a.v / b.v;
    double gap = std::fabs(b.v) - b.bound();
    if (!(gap > 0)) return {q, F::inf};
    double e = (a.e + std::fabs(q) * b.e) / gap;
    return {q, e + F::u * std::fabs(q) + F::underflow_floor};
}
// For an argument whose exact value is known to be >= 0.
inline QuickBounded sqrt(QuickBounded a) {
    using bounded_detail::F;
    double r = std::sqrt(std::fmax(a.v, 0.0));
    double ea = a.bound();
    double denom = r + std::sqrt(std::fmax(a.v - ea, 0.0));
    double e = denom > 0 ? ea / denom : std::sqrt(ea); // |sqrt(x) - sqrt(y)| <= sqrt(|x - y|)
    return {r, e + F::u * r + F::underflow_floor};
}

namespace detail {

// Vectors of either bounded type: exact doubles, and an exact two-term value (hi + lo) as its
// rounded part hi with the bound |lo|.
template <class BT>
Vec3T<BT> exact(Vec3 a) {
    return {BT::exact(a.x), BT::exact(a.y), BT::exact(a.z)};
}
// R: the components' number type (double, or a lane type for QuickBoundedT of it).
template <class BT, class R>
Vec3T<BT> within_low_part(const Vec3TwoTermT<R>& d) {
    using std::fabs;
    return {{d.hi.x, fabs(d.lo.x)}, {d.hi.y, fabs(d.lo.y)}, {d.hi.z, fabs(d.lo.z)}};
}
// p - q, computed exactly (difference_exact), as its rounded value with the bound |lo|.
template <class BT, class R>
Vec3T<BT> difference_bounded(Vec3T<R> p, Vec3T<R> q) {
    return within_low_part<BT>(difference_exact(p, q));
}

} // namespace detail

} // namespace linequad
