// What the correct solver's rungs share: the scene scaled to unit size, and the rounding of a
// value whose error bound proves which double is nearest.
#pragma once

#include "forms/prescale.hpp"
#include "numeric/bounded_dd.hpp"
#include "numeric/format.hpp"

#include "linequad/result.hpp"
#include "linequad/shapes.hpp"

#include <cmath>
#include <optional>
#include <type_traits>

namespace linequad::detail {

// The scene scaled by powers of two towards unit size (exactly), so that the rungs in doubles
// stay far from overflow and underflow: t = t' 2^(k-j), points = p' 2^k. The line's range is
// scaled with t (its ends stay exact, or there is no Unit).
struct Unit {
    double pos_factor, t_factor; // 2^k, 2^(k-j)
    Line line;
};

// No value when scaling could lose bits (a component tiny beside the scene: fragile_scene; a
// range end that would leave the normal range) or leave t's scale out of range; the exact rung,
// which needs no scaling, answers those.
template <class Source>
std::optional<Unit> unit_scale(const Source& src, double extent, const Line& l) {
    using F = Binary64;
    if (fragile_scene(src, extent, l)) return std::nullopt;
    Prescale ps = prescale_for(extent, l.v);
    if (!(ps.t_factor >= F::pow2(-F::moderate_exponent) &&
          ps.t_factor <= F::pow2(F::moderate_exponent)))
        return std::nullopt;
    double end = ps.to_unit / ps.dir_to_unit; // 1 / t_factor, exactly
    Interval range{l.range.t0 * end, l.range.t1 * end};
    auto exact = [&](double scaled, double t) { return scaled * ps.t_factor == t; };
    if (!exact(range.t0, l.range.t0) || !exact(range.t1, l.range.t1)) return std::nullopt;
    return Unit{1 / ps.to_unit, ps.t_factor, Line{ps.pos(l.L0), ps.dir(l.v), range}};
}

// Binary64's bit steps for double, as the lane types have them (simd/lanes_avx2.hpp and
// lanes_avx512.hpp), so that the templates below serve both.
LINEQUAD_INLINE double half_ulp_of_normal(double x) {
    return Binary64::half_ulp_of_normal(x);
}
LINEQUAD_INLINE bool is_power_of_two(double x) {
    return Binary64::is_power_of_two(x);
}
LINEQUAD_INLINE double select(bool m, double a, double b) {
    return m ? a : b;
}
template <class T>
LINEQUAD_INLINE MaskOf<T> equal(T a, T b) {
    return !(a != b);
}

// The double nearest x 2^k (scale = 2^k), and whether x's bound proves which it is; T is double
// or a lane type (the batch correct solver's). Inline: every t and every coordinate of every
// point of the first two rungs passes through it.
template <class T>
struct Rounded {
    T value;
    MaskOf<T> proven;
};
template <class T>
LINEQUAD_INLINE Rounded<T> round_proven_to_double(const BoundedDDT<T>& x, T scale) {
    using F = Binary64;
    using std::copysign;
    using std::fabs;
    T zero(0.0);
    MaskOf<T> exact = equal(x.e, zero), is_zero = exact & equal(x.hi, zero); // an exact 0 is +0
    T hi = x.hi * scale, a = fabs(hi);
    MaskOf<T> normal = (a >= T(0x1p-960)) & (a <= T(0x1p+1000)); // not NaN
    if constexpr (std::is_same_v<T, double>) { // one value: the answers that need no cell
        if (is_zero) return {0.0, true};
        if (!normal) return {hi, false};
        if (exact && x.lo == 0) return {hi, true}; // exact
    }
    // Far from overflow and underflow, scaling is exact but for lo's last bits (the slack
    // covers them).
    T lo = x.lo * scale, e = x.e * scale + T(F::subnormal_slack);
    // The exact value, within [hi + lo - e, hi + lo + e], must be inside hi's rounding cell:
    // half an ulp each way, but only a quarter towards zero from a power of two.
    T half_away = half_ulp_of_normal(a);
    T half_toward = select(is_power_of_two(a), T(0.5) * half_away, half_away);
    T outward = copysign(T(1.0), hi) * lo; // lo's part away from zero
    T away = outward + e, toward = e - outward;
    MaskOf<T> inside =
        (away * T(F::cover(8)) < half_away) & (toward * T(F::cover(8)) < half_toward);
    MaskOf<T> proven = normal & ((exact & equal(x.lo, zero)) | inside);
    return {select(is_zero, zero, hi), MaskOf<T>(is_zero | proven)};
}
inline std::optional<double> round_proven(const BoundedDD& x, double scale, Binary64) {
    Rounded<double> r = round_proven_to_double(x, scale);
    if (!r.proven) return std::nullopt;
    return r.value;
}

// The float nearest x 2^k, held in a double, when x's bound proves which it is: y = hi + lo in
// double (one rounding more in the bound) and the float nearest y; the exact value must lie
// inside that float's rounding cell, whose half-width is some 2^29 times a double's, so that the
// first rung's enclosure nearly always proves it. Never through the nearest double rounded again
// (that would round twice). Floats outside the normal range (subnormal, zero, beyond 2^127) are
// left to the exact rung; so is a float that is a power of two when the value lies below it
// (the cell is half as wide there: tested on the narrower side both ways).
inline std::optional<double> round_proven(const BoundedDD& x, double scale, Binary32) {
    using F = Binary64;
    if (x.e == 0 && x.hi == 0) return 0.0;
    double y = (x.hi + x.lo) * scale, f = float(y), a = std::fabs(f);
    if (!(a >= 0x1p-126 && a <= 0x1p+127)) return std::nullopt; // NaN too
    // y - f is exact (y is near f, whose last bit is far above y's).
    double e = x.e * scale + F::u * std::fabs(y) + F::subnormal_slack;
    double half = F::power_of_two_floor(a) * 0x1p-24;
    if (F::is_power_of_two(a)) half *= 0.5;
    if ((std::fabs(y - f) + e) * F::cover(8) < half) return f;
    return std::nullopt;
}

// The target's value nearest x 2^k, when x's bound proves it.
template <class Target>
LINEQUAD_INLINE std::optional<double> round_proven(const BoundedDD& x, double scale) {
    return round_proven(x, scale, Target{});
}

} // namespace linequad::detail
