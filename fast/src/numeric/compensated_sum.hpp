// A sum of exact products and small terms in double-double, with one a-priori error bound: the
// arithmetic of the correct solver's Newton rung (newton_rung.cpp).
//
// BoundedDD (bounded_dd.hpp) bounds every operation as it goes. Here a value is one sum: its
// high parts are added exactly (two_prod, two_sum), every low part and every small term (a
// correction of order u beside the sum's terms, such as a product with a low part) is added
// into one double, and the bound is computed once, at the end, from two magnitudes.
//
// The bound. Let S = sum x_i + sum Y_j: x_i exact doubles (a product a*b enters as its exact
// two_prod pair), Y_j small terms, each given as a double y_j rounded at most once from Y_j
// (|y_j - Y_j| <= u |y_j|, u = 2^-53). two_sum and two_prod are exact, so hi plus the exact sum
// of what entered lo is sum x_i + sum y_j. lo receives m terms by recursive summation, which
// errs by at most gamma_m times the sum of their magnitudes (Higham, "Accuracy and Stability of
// Numerical Algorithms", 2nd ed., (4.4)); gamma_m = m u / (1 - m u). Those terms are:
//  - two_sum errors, each at most u |partial sum of x| <= u (1 + u)^m mag, mag = sum |x_i|;
//  - two_prod low parts, at most u |product| each, so at most u mag together;
//  - the small terms, small = sum |y_j|.
// So |hi + lo - S| <= gamma_m ((m + 1) u (1 + u)^m mag + small) + u small, and
// (m + 1) u ((m + 1) u mag + small) (1 + 2^-40) covers it for m <= 64, with the rounding of mag,
// small and the bound itself (each a handful of rounded operations on nonnegative terms).
// Underflow: a two_prod whose product is below 2^-969, or an addition in lo in the subnormal
// range, errs by up to 2^-1074 absolute instead; 2^-1060 covers m <= 64 such errors.
// The final two_sum(hi, lo) is exact, so the result hi + lo has the same bound, and |lo| is at
// most half an ulp of hi.
#pragma once

#include "numeric/bounded_dd.hpp"
#include "numeric/eft.hpp"

#include <cmath>

namespace linequad::detail {

// T is double, or a lane type (one sum per lane, every lane given the same sequence of terms).
template <class T>
class CompensatedSumT {
    using F = Binary64;

  public:
    LINEQUAD_INLINE void add_exact(T x) {
        using std::fabs;
        mag_ = mag_ + fabs(x);
        if (empty_) { // the first term needs no two_sum (empty_ is known where this is inlined)
            hi_ = x, empty_ = false;
            return;
        }
        TwoTermT<T> t = two_sum(hi_, x);
        hi_ = t.hi;
        lo_ = lo_ + t.lo;
        ++terms_;
    }
    LINEQUAD_INLINE void add_product(T a, T b) {
        TwoTermT<T> p = two_prod(a, b);
        add_exact(p.hi);
        lo_ = lo_ + p.lo;
        ++terms_;
    }
    // y: small beside the sum's terms, and either exact or rounded once from what it stands for.
    LINEQUAD_INLINE void add_small(T y) {
        using std::fabs;
        lo_ = lo_ + y;
        small_ = small_ + fabs(y);
        ++terms_;
    }
    // The sum, with the bound above plus `propagated`: the caller's bound on how far the terms
    // themselves are from the exact terms they stand for (nonnegative terms, rounded: the factor
    // 1 + 2^-40 covers a few dozen roundings of its computation too).
    LINEQUAD_INLINE BoundedDDT<T> result(T propagated = T(0)) const {
        TwoTermT<T> s = two_sum(hi_, lo_);
        return {s.hi, s.lo, bound(propagated)};
    }
    // hi + lo as they are: the same bound, but |lo| may exceed half an ulp of hi (where the
    // high parts cancelled). For a value that only enters further sums.
    LINEQUAD_INLINE BoundedDDT<T> unnormalized(T propagated = T(0)) const {
        return {hi_, lo_, bound(propagated)};
    }
    // The sum rounded to one double, and its bound (the rounding adds at most u |value|).
    LINEQUAD_INLINE BoundedDDT<T> rounded(T propagated = T(0)) const {
        using std::fabs;
        T v = hi_ + lo_;
        return {v, T(0), (bound(propagated) + T(F::u) * fabs(v)) * T(F::cover(8))};
    }

  private:
    // The magnitudes start at -0: -0 + x is x exactly for every x, so the first addition folds
    // away (+0 + x would not: it is +0 for x = -0, which fabs never gives, but the compiler
    // cannot know that).
    T hi_ = T(0), lo_ = T(0), mag_ = T(-0.0), small_ = T(-0.0);
    int terms_ = 0; // additions into lo: at most 64 (every use in this library makes fewer than 20)
    bool empty_ = true;

    LINEQUAD_INLINE T bound(T propagated) const {
        T m1(double(terms_ + 1) * F::u);
        return (m1 * (m1 * mag_ + small_) + propagated) * T(F::cover(8192)) + T(F::underflow_floor);
    }
};
using CompensatedSum = CompensatedSumT<double>;

// |x - exact| for a BoundedDD x read as the one double x.hi.
template <class T>
LINEQUAD_INLINE T bound_of_hi(const BoundedDDT<T>& x) {
    using std::fabs;
    return x.e + fabs(x.lo);
}

// sgn(a - b) for a within ea and b within eb of the values they stand for; 0 when the bounds do
// not settle it (NaN too). a - b rounds with an error of at most u |a - b| (2^-1074 below the
// normal range), which 2^-50 (|a| + |b|) + 2^-1070 covers with the rounding of the bound itself.
// The difference and its bound, for a lane type too: sgn is +1 where bound < d, -1 where
// d < -bound.
template <class T>
struct DifferenceTest {
    T d, bound;
};
template <class T>
LINEQUAD_INLINE DifferenceTest<T> difference_test(T a, T ea, T b, T eb) {
    using F = Binary64;
    using std::fabs;
    T d = a - b;
    T e = (ea + eb + T(8 * F::u) * (fabs(a) + fabs(b))) * T(F::cover(32)) + T(F::subnormal_slack);
    return {d, e};
}
LINEQUAD_INLINE int certain_sign_of_difference(double a, double ea, double b, double eb) {
    DifferenceTest<double> t = difference_test(a, ea, b, eb);
    return t.d > t.bound ? 1 : t.d < -t.bound ? -1 : 0;
}

} // namespace linequad::detail
