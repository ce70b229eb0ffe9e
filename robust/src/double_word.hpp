// Double-word numbers (hi + lo, two doubles) of positive values, with a proven relative error
// per operation: the oracle's quick way to a correctly rounded answer. The rounding filter
// (exact.cpp) encloses each exact part of (X + Y sqrt(D)) / Den in a double-word, evaluates the
// value's cancellation-free form in these operations, and keeps the answer only where the error
// bound proves which double (or float) is nearest; the rest go to MPFR (rounding.hpp).
//
// The oracle keeps its own arithmetic, apart from fast/'s: it grades fast/'s solvers, so a flaw
// in shared arithmetic could hide in both.
//
// Every operand here is positive (the forms add only terms of one sign, or subtract one at most
// half the other), normalized (|lo| <= u |hi|, u = 2^-53) and, as the caller checks, far from
// underflow and overflow (|hi| in [2^-900, 2^900]): then each error-free transformation is
// exact, and each operation's result is within the stated multiple of u^2 of the exact result of
// its operands. Each bound is derived in its comment (first order in u, the rest absorbed by
// rounding the constants up), for algorithms that follow, or simplify for positive operands,
// those of Joldes, Muller and Popescu, "Tight and rigorous error bounds for basic building blocks
// of double-word arithmetic" (ACM TOMS 44, 2017); the caller budgets far more than their sum.
//
// robust/ compiles with -ffp-contract=off (a fused a + b * c would break two_sum's exactness and
// the bounds), and these run in round-to-nearest.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

namespace linequad::exact::dw {

struct DoubleWord {
    double hi = 0, lo = 0;
};

// a + b = s + e exactly, for |a| >= |b|.
inline DoubleWord fast_two_sum(double a, double b) {
    double s = a + b;
    return {s, b - (s - a)};
}

// a + b = s + e exactly.
inline DoubleWord two_sum(double a, double b) {
    double s = a + b, bb = s - a;
    return {s, (a - (s - bb)) + (b - bb)};
}

// a b = p + e exactly.
inline DoubleWord two_prod(double a, double b) {
    double p = a * b;
    return {p, std::fma(a, b, -p)};
}

// x + y, error <= 3.02 u^2 (x + y). (sh, sl) is exact; t = RN(xl + yl) errs by at most
// u (xl + yl) <= u^2 (xh + yh); w = RN(sl + t), |sl + t| <= 2u (xh + yh), by at most 2u^2 (xh +
// yh).
inline DoubleWord add(DoubleWord x, DoubleWord y) {
    DoubleWord s = two_sum(x.hi, y.hi);
    double t = x.lo + y.lo;
    return fast_two_sum(s.hi, s.lo + t);
}

// x - y for x >= 2y > 0, error <= 7.1 u^2 (x - y): a difference at least half its larger
// operand. (sh, sl) is exact; t = RN(xl - yl) errs by u^2 (xh + yh) <= 1.5 u^2 xh; w = RN(sl + t),
// |sl + t| <= 2u xh, by 2u^2 xh; and x - y >= x / 2.
inline DoubleWord sub(DoubleWord x, DoubleWord y) {
    DoubleWord s = two_sum(x.hi, -y.hi);
    double t = x.lo - y.lo;
    return fast_two_sum(s.hi, s.lo + t);
}

// One of x, y over twice the other, with room for their low parts and errors: where sub()
// applies, and where a difference at most triples its terms' relative errors.
inline bool apart(DoubleWord x, DoubleWord y) {
    return x.hi > 2.01 * y.hi || y.hi > 2.01 * x.hi;
}

// x y, error <= 7.05 u^2 x y. (ph, pl) is exact; xl yl (<= u^2 xh yh) is dropped; the fused
// t = RN(xh yl + RN(xl yh)) errs by u^2 + 2u^2, and RN(pl + t) (|pl + t| <= 3u xh yh) by 3u^2.
inline DoubleWord mul(DoubleWord x, DoubleWord y) {
    DoubleWord p = two_prod(x.hi, y.hi);
    double t = std::fma(x.hi, y.lo, x.lo * y.hi);
    return fast_two_sum(p.hi, p.lo + t);
}

// x / y, error <= 12.2 u^2 x / y. With qh = RN(xh / yh), the remainder R = x - qh y is
// (xh - qh yh) + (xl - qh yl): xh - ph is exact (Sterbenz), so a - pl is exactly xh - qh yh
// (<= u xh), rounded once (u^2 xh); the fused xl - qh yl (<= 2u xh) errs by 2u^2 xh; their sum
// (<= 3u xh) by 3u^2 xh. ql = RN(d / yh) then errs from R / y by 6u^2 xh / yh in the remainder's
// errors, and by 2u |R| / yh <= 6u^2 xh / yh in dropping yl from the divisor and the division.
inline DoubleWord div(DoubleWord x, DoubleWord y) {
    double qh = x.hi / y.hi;
    DoubleWord p = two_prod(qh, y.hi);
    double b = (x.hi - p.hi) - p.lo;
    double c = std::fma(-qh, y.lo, x.lo);
    return fast_two_sum(qh, (b + c) / y.hi);
}

// sqrt(x), error <= 4.3 u^2 sqrt(x). With s = RN(sqrt(xh)), xh - s^2 is a double (the remainder of
// a correctly rounded square root is representable), so the fused a is exact; b = RN(a + xl)
// (|a + xl| <= 3u xh) errs by 3u^2 xh. sqrt(x) = s sqrt(1 + y), y = (a + xl) / s^2 (|y| <= 3u),
// and s + s y / 2 leaves s y^2 / 8 <= 1.15 u^2 s; the correction's own error is 3u^2 s.
inline DoubleWord sqrt(DoubleWord x) {
    double s = std::sqrt(x.hi);
    double a = std::fma(-s, s, x.hi);
    return fast_two_sum(s, (a + x.lo) / (2 * s));
}

// Far from underflow and overflow, where the bounds above hold (false for NaN).
inline bool in_range(double hi) {
    double m = std::fabs(hi);
    return m >= 0x1p-900 && m <= 0x1p900;
}

// 2^E for x in [2^E, 2^(E+1)), x a positive normal double: its exponent bits alone.
inline double binade(double x) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof x);
    bits &= 0x7ff0000000000000u;
    std::memcpy(&x, &bits, sizeof x);
    return x;
}

} // namespace linequad::exact::dw
