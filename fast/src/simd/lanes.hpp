// What every lane type (lanes_avx2.hpp: D4, F8; lanes_avx512.hpp: D8) shares: prescaling's
// powers of two per lane, and the helpers written once over the lane type's operations.
#pragma once

#include "forms/prescale.hpp"

namespace linequad::detail {

// prescale_for()'s powers of two per lane, from the exponents' bits: 2^-k for positions, 2^-j for
// directions, 2^(k - j) for t, with k and j the exponents of the scene's extent and of max |v|.
// `ok` drops the lanes that prescale_for() would take down another path (a subnormal magnitude,
// exponents or k - j beyond the moderate range): they go back to the scalar solver.
template <class L>
struct ScaleLanes {
    L to_unit, dir_to_unit, t_scale;
    decltype(L() < L()) ok;
};

// max |coordinate| by the max instructions (the batch's own prescaling, whose inputs are finite).
template <class L>
L max_abs(Vec3T<L> a) {
    return maximum(maximum(fabs(a.x), fabs(a.y)), fabs(a.z));
}

template <class L>
constexpr int lane_count = sizeof(L) / sizeof(Real<L>);

// The lanes whose line the scalar checks pass: every coordinate finite (0 x is 0 only for
// finite x), v nonzero. The others go back to the scalar solver, which names what is wrong.
template <class L>
auto usual_line(const Vec3T<L>& L0, const Vec3T<L>& v) {
    L zero(Real<L>(0));
    L sum = (L0.x * zero + L0.y * zero) + (L0.z * zero + v.x * zero) + (v.y * zero + v.z * zero);
    auto finite = !(sum != zero);
    return finite & ((v.x != zero) | (v.y != zero) | (v.z != zero));
}

} // namespace linequad::detail
