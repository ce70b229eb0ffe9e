// A double-double value hi + lo with a rigorous bound e on its distance to the exact value it
// stands for: the correct solver's second rung (Bounded, one word further).
//
// The operations are the double-word algorithms of Joldes, Muller and Popescu ("Tight and
// rigorous error bounds for basic building blocks of double-word arithmetic", ACM TOMS 2017),
// whose relative errors are proven: AccurateDWPlusDW 3u^2/(1-4u), DWTimesDW3 (with fma) 4u^2
// (the bound they prove is 5u^2 for a variant; 5 is used), DWDivDW2 15u^2 + 56u^3, and the
// square root of Lefevre et al. (2022), 25/8 u^2; u = 2^-53. Each bound below uses a constant
// at least that large, adds the propagated errors, and is inflated by (1 + 2^-50) for its own
// rounding, plus the underflow floor for anything that may have underflowed.
//
// sign() is certain or `undecided`: never wrong. A zero is decided only when it is exact
// (e = 0), which only products and sums of two doubles keep; the solver's exact rung settles
// the rest. Overflow makes a bound infinite or NaN, which decides nothing.
#pragma once

#include "numeric/eft.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace linequad {

// What sign() returns when the bound cannot exclude zero (the exact form's `undecided`).
inline constexpr int undecided_sign = 2;

// T is double, or a lane type holding one value per lane (the batch correct solver's lanes).
template <class T>
struct BoundedDDT {
    T hi = T(0), lo = T(0); // |lo| <= ulp(hi) / 2
    T e = T(0);             // |hi + lo - exact| <= e

    BoundedDDT() = default;
    explicit BoundedDDT(T x) : hi(x) {}
    BoundedDDT(T h, T l, T err) : hi(h), lo(l), e(err) {}

    bool exact() const { return e == 0; }
};
using BoundedDD = BoundedDDT<double>;

// x in every lane of T (x itself for T = double).
template <class T>
LINEQUAD_INLINE BoundedDDT<T> lanes_of(const BoundedDD& x) {
    return {T(x.hi), T(x.lo), T(x.e)};
}

namespace dd_detail {
using F = detail::Binary64;
constexpr double u2 = F::u * F::u;
// |hi + lo| <= |hi| (1 + 2^-52)
inline double mag(const BoundedDD& x) {
    return std::fabs(x.hi) * F::cover(2);
}
inline double up(double e) {
    return e * F::cover(8) + F::underflow_floor;
}
// +-2^k with |k| < 1000 (std::frexp would be a library call on the hot path).
LINEQUAD_INLINE bool moderate_power_of_two(double x) {
    int biased = int((F::bits(x) & F::exponent_mask) >> 52); // 0 for zero: not a power of two
    return F::is_power_of_two(x) && biased > 1023 - F::moderate_exponent &&
           biased < 1023 + F::moderate_exponent;
}
// A product of doubles whose low part is exact: neither factor is tiny enough to underflow.
inline bool product_exact(double a, double b, double p) {
    return a == 0 || b == 0 || std::fabs(p) >= F::exact_product_min;
}
} // namespace dd_detail

LINEQUAD_INLINE int sign(const BoundedDD& x) {
    using dd_detail::mag;
    if (x.e == 0 && x.hi == 0) return 0; // normalized: lo = 0 too
    if (std::fabs(x.hi) * dd_detail::F::shrink(8) > x.e) return x.hi > 0 ? 1 : -1;
    return undecided_sign; // also for NaN and infinite bounds
}

LINEQUAD_INLINE BoundedDD operator-(BoundedDD a) {
    return {-a.hi, -a.lo, a.e};
}

LINEQUAD_INLINE BoundedDD operator+(const BoundedDD& a, const BoundedDD& b) {
    TwoTerm s = two_sum(a.hi, b.hi);
    if (a.lo == 0 && b.lo == 0 && a.e == 0 && b.e == 0) return {s.hi, s.lo, 0}; // exact
    TwoTerm t = two_sum(a.lo, b.lo);
    TwoTerm v = fast_two_sum(s.hi, s.lo + t.hi);
    TwoTerm z = fast_two_sum(v.hi, t.lo + v.lo);
    return {z.hi, z.lo, dd_detail::up(a.e + b.e + 4 * dd_detail::u2 * std::fabs(z.hi))};
}

LINEQUAD_INLINE BoundedDD operator-(const BoundedDD& a, const BoundedDD& b) {
    return a + (-b);
}

LINEQUAD_INLINE BoundedDD operator*(const BoundedDD& a, const BoundedDD& b) {
    using dd_detail::mag;
    TwoTerm c = two_prod(a.hi, b.hi);
    if (a.lo == 0 && b.lo == 0 && a.e == 0 && b.e == 0 &&
        dd_detail::product_exact(a.hi, b.hi, c.hi))
        return {c.hi, c.lo, 0};
    double tl = std::fma(a.hi, b.lo, a.lo * b.lo);
    double cl = c.lo + std::fma(a.lo, b.hi, tl);
    TwoTerm z = fast_two_sum(c.hi, cl);
    double e = mag(a) * b.e + mag(b) * a.e + a.e * b.e + 5 * dd_detail::u2 * std::fabs(z.hi);
    return {z.hi, z.lo, dd_detail::up(e)};
}

// Infinite bound unless the divisor's sign is certain.
LINEQUAD_INLINE BoundedDD operator/(const BoundedDD& a, const BoundedDD& b) {
    using dd_detail::mag;
    if (a.e == 0 && b.e == 0 && b.lo == 0 && dd_detail::moderate_power_of_two(b.hi)) {
        // by a power of two: exact, far from underflow
        double inv = 1 / b.hi;
        if ((a.hi == 0 || std::fabs(a.hi * inv) >= 0x1p-900) &&
            (a.lo == 0 || std::fabs(a.lo * inv) >= 0x1p-1000)) // far from the subnormals
            return {a.hi * inv, a.lo * inv, 0};
    }
    double th = a.hi / b.hi;
    TwoTerm r = two_prod(b.hi, th);
    double rl = std::fma(b.lo, th, r.lo);
    TwoTerm rr = fast_two_sum(r.hi, rl);
    double d = (a.hi - rr.hi) + (a.lo - rr.lo);
    TwoTerm z = fast_two_sum(th, d / b.hi);
    double gap = std::fabs(b.hi) * dd_detail::F::shrink(8) - b.e;
    if (!(gap > 0)) return {z.hi, z.lo, dd_detail::F::inf};
    double q = std::fabs(z.hi) * dd_detail::F::cover(8);
    double e = (a.e + q * b.e) / gap + 16 * dd_detail::u2 * q;
    return {z.hi, z.lo, dd_detail::up(e * dd_detail::F::cover(8))};
}

// For an argument whose exact value is known to be >= 0.
LINEQUAD_INLINE BoundedDD sqrt(const BoundedDD& a) {
    double h = std::sqrt(std::fmax(a.hi, 0.0));
    if (h == 0) return {0, 0, a.e == 0 ? 0 : dd_detail::up(std::sqrt(a.e + dd_detail::mag(a)))};
    double rho = std::fma(-h, h, a.hi) + a.lo;
    TwoTerm z = fast_two_sum(h, rho / (2 * h));
    // |sqrt(x) - sqrt(y)| <= |x - y| / (sqrt(x) + sqrt(y)), and <= sqrt(|x - y|) always.
    using dd_detail::F;
    double low = std::sqrt(std::fmax(a.hi - a.e * F::cover(8) - std::fabs(a.lo), 0.0));
    double prop = low > 0 ? a.e / (h * F::shrink(8) + low) : std::sqrt(a.e) * F::cover(8);
    return {z.hi, z.lo, dd_detail::up(prop + 4 * dd_detail::u2 * std::fabs(z.hi))};
}

} // namespace linequad
