// bounded_dd.hpp's a + b and a / b for a lane type L (a value per lane): the same operations in
// the same order, each branch a select, so that every lane holds the bits the scalar operation
// gives its line. The lane types' own operations (simd/lanes_*.hpp) are found by
// argument-dependent lookup where these are instantiated; double uses bounded_dd.hpp's.
#pragma once

#include "numeric/bounded_dd.hpp"
#include "numeric/eft.hpp"
#include "numeric/format.hpp"

namespace linequad::detail {

// AccurateDWPlusDW, exact where both inputs are single exact doubles (operator+).
template <class L>
LINEQUAD_INLINE BoundedDDT<L> sum_lanes(const BoundedDDT<L>& a, const BoundedDDT<L>& b) {
    using F = Binary64;
    const L zero(0.0);
    TwoTermT<L> s = two_sum(a.hi, b.hi);
    auto exact = equal(a.lo, zero) & equal(b.lo, zero) & equal(a.e, zero) & equal(b.e, zero);
    TwoTermT<L> t = two_sum(a.lo, b.lo);
    TwoTermT<L> v = fast_two_sum(s.hi, s.lo + t.hi);
    TwoTermT<L> z = fast_two_sum(v.hi, t.lo + v.lo);
    L e = (a.e + b.e + L(4 * F::u * F::u) * fabs(z.hi)) * L(F::cover(8)) + L(F::underflow_floor);
    return {select(exact, s.hi, z.hi), select(exact, s.lo, z.lo), select(exact, zero, e)};
}

// DWDivDW2 with its bound; exact by a moderate power of two; an infinite bound unless the
// divisor's sign is certain (operator/).
template <class L>
LINEQUAD_INLINE BoundedDDT<L> quotient_lanes(const BoundedDDT<L>& a, const BoundedDDT<L>& b) {
    using F = Binary64;
    const L zero(0.0), size = fabs(b.hi);
    // By a power of two 2^k, |k| < 1000 (moderate_power_of_two): exact, far from underflow.
    auto by_power = equal(a.e, zero) & equal(b.e, zero) & equal(b.lo, zero) &
                    is_power_of_two(b.hi) & (L(0x1p-999) <= size) & (size <= L(0x1p+999));
    L inv = L(1.0) / b.hi;
    auto far = (equal(a.hi, zero) | (L(0x1p-900) <= fabs(a.hi * inv))) &
               (equal(a.lo, zero) | (L(0x1p-1000) <= fabs(a.lo * inv)));
    auto exact = by_power & far;
    L th = a.hi / b.hi;
    TwoTermT<L> r = two_prod(b.hi, th);
    L rl = fma(b.lo, th, r.lo);
    TwoTermT<L> rr = fast_two_sum(r.hi, rl);
    L d = (a.hi - rr.hi) + (a.lo - rr.lo);
    TwoTermT<L> z = fast_two_sum(th, d / b.hi);
    L gap = size * L(F::shrink(8)) - b.e;
    L q = fabs(z.hi) * L(F::cover(8));
    L e = (a.e + q * b.e) / gap + L(16 * F::u * F::u) * q;
    e = select(zero < gap, (e * L(F::cover(8))) * L(F::cover(8)) + L(F::underflow_floor),
               L(F::inf));
    return {select(exact, a.hi * inv, z.hi), select(exact, a.lo * inv, z.lo),
            select(exact, zero, e)};
}

} // namespace linequad::detail
