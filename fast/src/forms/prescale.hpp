// Power-of-two prescaling and the guards against underflow that the double solvers share.
#pragma once

#include "forms/traits.hpp"
#include "numeric/format.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace linequad::detail {

// The real type a lane type computes in: itself, or (specialised beside each batch lane type)
// its lanes' type.
template <class T>
struct RealOf {
    using type = T;
};
template <class T>
using Real = typename RealOf<T>::type;
// Whether T computes in double (what prepare() keeps is in double: a float solver builds its own).
template <class T>
constexpr bool in_double = std::is_same_v<Real<T>, double>;

// What the stable and seed solvers can decide in a real type R, from its exponent range:
//  - after prescaling, sizes below min_relative_size (relative to the scene) would underflow
//    when multiplied four times; the stable solvers refuse them with out_of_range rather than
//    guess. The seed solvers, which do not prescale, refuse scenes beyond its inverse;
//  - a decisive quantity (A, D) below tiny_decisive, and not zero, may be what underflow left of
//    it.
//  - an exact zero of A or D, which decides tangency, lines parallel to the axis or along a
//    generator and lines on the surface, is trusted only when the shape's sizes are at least
//    min_zero_size of the scene, where they are factors of A and D (the circular shapes: up to
//    ten, in the frustum's h.h (|G|^2 - K^2)): below it they underflow to an exact zero.
// double: 2^-240 (products of four near 2^-960), 2^-900, 2^-100 (products of ten near 2^-1000);
// float, the same proportions of its range: 2^-28 (2^-112), 2^-100, 2^-12 (2^-120).
template <class R>
struct Guards;
template <>
struct Guards<double> {
    static constexpr double min_relative_size = 0x1p-240;
    static constexpr double tiny_decisive = 0x1p-900;
    static constexpr double min_zero_size = 0x1p-100;
};
template <>
struct Guards<float> {
    static constexpr float min_relative_size = 0x1p-28f;
    static constexpr float tiny_decisive = 0x1p-100f;
    static constexpr float min_zero_size = 0x1p-12f;
};
template <class R>
bool underflow_zone(R x) {
    return x != 0 && std::fabs(x) < Guards<R>::tiny_decisive;
}

// The exponent of a magnitude, clamped to where 2^e and 2^-e are normal in R.
template <class R = double>
LINEQUAD_INLINE int scale_exponent(double m) {
    using F = Format<R>;
    return std::clamp(Binary64::exponent(m), -F::moderate_exponent, F::moderate_exponent);
}

// A double vector's coordinates in R (exact for the float solvers' inputs, which are floats).
template <class R, class T>
LINEQUAD_INLINE Vec3T<R> in_real(const Vec3T<T>& p) {
    if constexpr (std::is_same_v<R, T>)
        return p;
    else
        return {R(p.x), R(p.y), R(p.z)};
}

// Power-of-two scales that bring a scene near unit size without any rounding: positions and
// lengths are multiplied by 2^-k, the direction by 2^-j, so t = t_scaled 2^(k - j). The factors
// are kept in R (|k|, |j| <= R's moderate exponent, so they are normal) because a multiply by a
// power of two is exact and far cheaper than ldexp.
// (The batch kernels have a lane version, with the same pos, len and dir.)
template <class R>
struct PrescaleT {
    int k = 0; // positions times 2^-k
    R to_unit = 1, dir_to_unit = 1, t_factor = 1;
    template <class T>
    Vec3T<R> pos(const Vec3T<T>& p) const {
        return to_unit * in_real<R>(p);
    }
    R len(double x) const { return to_unit * R(x); }
    template <class T>
    Vec3T<R> dir(const Vec3T<T>& v) const {
        return dir_to_unit * in_real<R>(v);
    }
    R t_scale() const { return t_factor; }
};
using Prescale = PrescaleT<double>;

// max |component|, and the smaller of two, for any lane type (std::max and std::min semantics).
template <class R, std::enable_if_t<std::is_floating_point_v<R>, int> = 0>
R select(bool m, R a, R b) {
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
template <class R = double>
LINEQUAD_INLINE PrescaleT<R> prescale_for(double max_position, Vec3 v) {
    using F = Format<R>;
    int k = scale_exponent<R>(max_position), j = scale_exponent<R>(max_abs(v));
    PrescaleT<R> p;
    p.k = k;
    p.to_unit = F::pow2(-k);
    p.dir_to_unit = F::pow2(-j);
    // k - j may leave R's range: ldexp then overflows to inf or underflows, and finish()
    // reports out_of_range for the non-finite t that follows.
    p.t_factor = std::abs(k - j) <= F::moderate_exponent ? F::pow2(k - j) : std::ldexp(R(1), k - j);
    return p;
}

// Exact zeros decide the parallel, tangent and on-surface cases. They can be trusted only when
// no product of the prescaled inputs can have underflowed: every nonzero component of a
// position at least min_relative_size of the scene's extent (and of v, of v's largest), so that
// products of four stay normal in R. Checked on the original inputs: prescaling itself may
// flush such a component to zero. Otherwise a zero, or a decisive quantity below tiny_decisive,
// may be an underflow, and the solvers refuse (out_of_range) rather than guess. `smallest` is
// the shape's smallest nonzero component.
template <class R = double>
LINEQUAD_INLINE bool fragile_scene(double extent, double smallest, Vec3 L0, Vec3 v) {
    constexpr double min_size = Guards<R>::min_relative_size;
    double below = min_size * extent; // 0 when it underflowed: nothing is below it
    return std::fmin(smallest, min_nonzero(L0)) < below || min_nonzero(v) < min_size * max_abs(v);
}
template <class R = double, class Source>
bool fragile_scene(const Source& src, double extent, const Line& l) {
    return fragile_scene<R>(extent, src.smallest(), l.L0, l.v);
}

} // namespace linequad::detail
