// A double together with a rigorous bound on its distance to the exact value it stands for
// (running error analysis, as pbrt-v3's EFloat). Every operation adds its own rounding error,
// u |result| with u = 2^-53, to the propagated bounds; the bound's own computation rounds too,
// so each new bound is inflated by (1 + 2^-49), far more than the few u that computing it can
// lose, plus 2^-1060 for anything that may have underflowed. Callers keep magnitudes far from
// overflow and underflow (the solvers prescale by powers of two and refuse fragile scenes).
#pragma once

#include <cmath>
#include <cstdlib>

namespace linequad {

struct Bounded {
    double v = 0; // the computed value
    double e = 0; // |v - exact| <= e

    static Bounded exact(double x) { return {x, 0}; }
    // The sign of the exact value when it is certain, else 0.
    int certain_sign() const { return v > e ? 1 : v < -e ? -1 : 0; }
};

namespace bounded_detail {
constexpr double u = 0x1p-53;
// The new bound, inflated to cover its own rounding. The floor 2^-1060 covers what underflow
// can hide; it is left out when the operation was exact (a zero error on an exact zero), so
// that exact zeros stay exact and can decide parallel, tangent and on-surface cases.
inline double up(double e, bool may_have_rounded) {
    return e * (1 + 0x1p-49) + (e != 0 || may_have_rounded ? 0x1p-1060 : 0.0);
}
inline bool exact_zero(Bounded x) {
    return x.v == 0 && x.e == 0;
}
} // namespace bounded_detail

// For exact operands the rounding error itself is known exactly (two_sum, fma): exact results
// keep a zero bound, which lets exact zeros decide the degenerate cases.
inline Bounded operator+(Bounded a, Bounded b) {
    double s = a.v + b.v; // a sum that rounds to zero is exactly zero
    if (a.e == 0 && b.e == 0) {
        double bb = s - a.v, err = (a.v - (s - bb)) + (b.v - bb);
        return {s, std::fabs(err)};
    }
    return {s, bounded_detail::up(a.e + b.e + bounded_detail::u * std::fabs(s), s != 0)};
}
inline Bounded operator-(Bounded a, Bounded b) {
    return a + Bounded{-b.v, b.e};
}
inline Bounded operator-(Bounded a) {
    return {-a.v, a.e};
}
inline Bounded operator*(Bounded a, Bounded b) {
    double p = a.v * b.v;
    if (a.e == 0 && b.e == 0) { // fma gives the exact error unless the product underflowed
        bool tiny = std::fabs(p) < 0x1p-960 && a.v != 0 && b.v != 0;
        return {p, std::fabs(std::fma(a.v, b.v, -p)) + (tiny ? 0x1p-1060 : 0.0)};
    }
    double e =
        std::fabs(a.v) * b.e + std::fabs(b.v) * a.e + a.e * b.e + bounded_detail::u * std::fabs(p);
    // Only an exact zero factor makes the product exact. Otherwise the bound's own products may
    // underflow to zero (2^-392 times an error of 2^-881), and the floor must stay.
    bool exact = bounded_detail::exact_zero(a) || bounded_detail::exact_zero(b);
    return {p, bounded_detail::up(e, !exact)};
}
// |b| > b.e is required (the divisor's sign is certain); otherwise the bound is infinite.
inline Bounded operator/(Bounded a, Bounded b) {
    double q = a.v / b.v;
    double gap = std::fabs(b.v) - b.e;
    if (!(gap > 0)) return {q, INFINITY};
    if (a.e == 0 && b.e == 0 && std::fabs(q) > 0x1p-960) { // remainder exact: |q - a/b| = |r/b|
        double r = std::fma(q, b.v, -a.v);
        return {q, r == 0 ? 0.0 : bounded_detail::up(std::fabs(r) / std::fabs(b.v), true)};
    }
    double e = (a.e + std::fabs(q) * b.e) / gap + bounded_detail::u * std::fabs(q);
    return {q, bounded_detail::up(e, !bounded_detail::exact_zero(a))};
}
// For an argument whose exact value is known to be >= 0.
inline Bounded sqrt(Bounded a) {
    double r = std::sqrt(std::fmax(a.v, 0.0));
    if (a.e == 0 && std::fma(r, r, -a.v) == 0) return {r, 0}; // a perfect square
    double low = std::sqrt(std::fmax(a.v - a.e, 0.0));
    double denom = r + low;
    double e = denom > 0 ? a.e / denom : std::sqrt(a.e); // |sqrt(x) - sqrt(y)| <= sqrt(|x - y|)
    return {r, bounded_detail::up(e + bounded_detail::u * r, !bounded_detail::exact_zero(a))};
}

} // namespace linequad
