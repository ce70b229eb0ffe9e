// What the correct solver's rungs share (correct.cpp): the scene scaled to unit size, and the
// rounding of a value whose error bound proves which double is nearest.
#pragma once

#include "bounded_dd.hpp"

#include "linequad/shapes.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <optional>

namespace linequad::detail {

// The scene scaled by powers of two towards unit size (exactly), so that the rungs in doubles
// stay far from overflow and underflow: t = t' 2^(k-j), points = p' 2^k.
struct Unit {
    double pos_factor, t_factor, end; // 2^k, 2^(k-j), and 2^(j-k) where a segment ends
    Line line;
};

// No value when scaling could lose bits (a component tiny beside the scene: fragile_scene) or
// leave t's scale out of range; the exact rung, which needs no scaling, answers those.
std::optional<Unit> unit_scale(const Line& l, double extent, std::initializer_list<Vec3> positions);

// The double nearest x 2^k (scale = 2^k) when x's bound proves which it is. Inline: every t and
// every coordinate of every point of the first two rungs passes through it.
inline std::optional<double> round_proven(const BoundedDD& x, double scale) {
    if (x.e == 0 && x.hi == 0) return 0.0; // an exact zero is +0
    double hi = x.hi * scale, a = std::fabs(hi);
    if (!(a >= 0x1p-960 && a <= 0x1p+1000)) return std::nullopt; // NaN too
    if (x.e == 0 && x.lo == 0) return hi;                        // exact
    // Far from overflow and underflow, scaling is exact but for lo's last bits (2^-1070 covers).
    double lo = x.lo * scale, e = x.e * scale + 0x1p-1070;
    // The exact value, within [hi + lo - e, hi + lo + e], must be inside hi's rounding cell:
    // half an ulp each way, but only a quarter towards zero from a power of two. Half an ulp of
    // a normal |hi| >= 2^-960 is 2^(E - 53) for its exponent E: its bits less 53 in the exponent.
    std::uint64_t bits;
    std::memcpy(&bits, &a, sizeof bits);
    std::uint64_t half_bits = (bits & 0x7ff0000000000000u) - (std::uint64_t(53) << 52);
    double half_away;
    std::memcpy(&half_away, &half_bits, sizeof half_away);
    bool power_of_two = (bits & 0x000fffffffffffffu) == 0;
    double half_toward = power_of_two ? 0.5 * half_away : half_away;
    double outward = std::copysign(1.0, hi) * lo; // lo's part away from zero
    double away = outward + e, toward = e - outward;
    if (away * (1 + 0x1p-50) < half_away && toward * (1 + 0x1p-50) < half_toward) return hi;
    return std::nullopt;
}

} // namespace linequad::detail
