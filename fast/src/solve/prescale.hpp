// Power-of-two prescaling and the guards against underflow that the double solvers share.
#pragma once

#include "numeric/format.hpp"
#include "shapes/traits.hpp"

#include <algorithm>
#include <cmath>

namespace linequad::detail {

// After prescaling, sizes below this (relative to the scene) would underflow when multiplied
// four times; the stable solvers refuse them with out_of_range rather than guess.
constexpr double min_relative_size = 0x1p-240;
// A decisive quantity (A, D) this small, and not zero, may be what underflow left of it.
constexpr double tiny_decisive = 0x1p-900;
inline bool underflow_zone(double x) {
    return x != 0 && std::fabs(x) < tiny_decisive;
}

// The exponent of a magnitude, clamped to where 2^e and 2^-e are normal.
LINEQUAD_INLINE int scale_exponent(double m) {
    using F = Binary64;
    return std::clamp(F::exponent(m), -F::moderate_exponent, F::moderate_exponent);
}

// Power-of-two scales that bring a scene near unit size without any rounding: positions and
// lengths are multiplied by 2^-k, the direction by 2^-j, so t = t_scaled 2^(k - j). The factors
// are kept as doubles (|k|, |j| <= 1000, so they are normal) because a multiply by a power of two
// is exact and far cheaper than ldexp.
// (The batch kernels have a lane version, with the same pos, len and dir.)
struct Prescale {
    int k = 0; // positions times 2^-k
    double to_unit = 1, dir_to_unit = 1, t_factor = 1;
    Vec3 pos(Vec3 p) const { return to_unit * p; }
    double len(double x) const { return to_unit * x; }
    Vec3 dir(Vec3 v) const { return dir_to_unit * v; }
    double t_scale() const { return t_factor; }
};

// max |component|, and the smaller of two, for any lane type (std::max and std::min semantics).
inline double select(bool m, double a, double b) {
    return m ? a : b;
}
template <class T>
T lane_min(T a, T b) {
    return select(b < a, b, a);
}
template <class T>
T lane_max(T a, T b) {
    return select(a < b, b, a);
}
template <class T>
T max_abs_lanes(const Vec3T<T>& a) {
    using std::fabs;
    return lane_max(lane_max(fabs(a.x), fabs(a.y)), fabs(a.z));
}
LINEQUAD_INLINE Prescale prescale_for(double max_position, Vec3 v) {
    using F = Binary64;
    int k = scale_exponent(max_position), j = scale_exponent(max_abs(v));
    Prescale p;
    p.k = k;
    p.to_unit = F::pow2(-k);
    p.dir_to_unit = F::pow2(-j);
    // k - j may leave double's range: ldexp then overflows to inf or underflows, and finish()
    // reports out_of_range for the non-finite t that follows.
    p.t_factor = std::abs(k - j) <= F::moderate_exponent ? F::pow2(k - j) : std::ldexp(1.0, k - j);
    return p;
}

// Exact zeros decide the parallel, tangent and on-surface cases. They can be trusted only when
// no product of the prescaled inputs can have underflowed: every nonzero component of a
// position at least min_relative_size of the scene's extent (and of v, of v's largest), so that
// products of four stay normal. Checked on the original inputs: prescaling itself may flush
// such a component to zero. Otherwise a zero, or a decisive quantity below tiny_decisive, may be
// an underflow, and the solvers refuse (out_of_range) rather than guess. `smallest` is the
// shape's smallest nonzero component.
LINEQUAD_INLINE bool fragile_scene(double extent, double smallest, Vec3 L0, Vec3 v) {
    double below = min_relative_size * extent; // 0 when it underflowed: nothing is below it
    return std::fmin(smallest, min_nonzero(L0)) < below ||
           min_nonzero(v) < min_relative_size * max_abs(v);
}
template <class Source>
bool fragile_scene(const Source& src, double extent, const Line& l) {
    return fragile_scene(extent, src.smallest(), l.L0, l.v);
}

} // namespace linequad::detail
