// Error-free transformations and the accurate products built on them.
//
// Everything here relies on std::fma being a true fused multiply-add and on the compiler not
// contracting other expressions (fast/ is built with -ffp-contract=off). Barring underflow:
//  - two_sum / two_prod return the rounded result and its exact rounding error;
//  - difference_of_products_dd is a*b - c*d in double-double (Kahan's 2x2 determinant carried
//    one word further), exactly zero iff a*b == c*d;
//  - dot2 is Ogita-Rump-Oishi's Dot2: as accurate as if computed in twice the precision.
#pragma once

#include "numeric/vector.hpp"

#include <cmath>

namespace linequad {

template <class T>
struct TwoTermT {
    T hi, lo; // value = hi + lo exactly, |lo| <= ulp(hi)/2
};
using TwoTerm = TwoTermT<double>;

// Inside these templates fma and sqrt are found by argument-dependent lookup for the batch
// lane type, and are std::fma and std::sqrt for double.
template <class T>
LINEQUAD_INLINE TwoTermT<T> two_sum(T a, T b) {
    T s = a + b;
    T bb = s - a;
    return {s, (a - (s - bb)) + (b - bb)};
}

template <class T>
LINEQUAD_INLINE TwoTermT<T> two_prod(T a, T b) {
    using std::fma;
    T p = a * b;
    return {p, fma(a, b, -p)};
}

// sum_i x_i*y_i for n terms, Dot2 of Ogita, Rump and Oishi.
template <class T, int N>
LINEQUAD_INLINE T dot2(const T (&x)[N], const T (&y)[N]) {
    TwoTermT<T> p = two_prod(x[0], y[0]);
    T s = p.hi, c = p.lo;
    for (int i = 1; i < N; ++i) {
        TwoTermT<T> q = two_prod(x[i], y[i]);
        TwoTermT<T> t = two_sum(s, q.hi);
        s = t.hi;
        c = c + (q.lo + t.lo);
    }
    return s + c;
}

template <class T>
LINEQUAD_INLINE T dot2(Vec3T<T> a, Vec3T<T> b) {
    const T x[3] = {a.x, a.y, a.z};
    const T y[3] = {b.x, b.y, b.z};
    return dot2(x, y);
}

// a + b when |a| >= |b| or a = 0 (Dekker): exact as hi + lo.
template <class T>
LINEQUAD_INLINE TwoTermT<T> fast_two_sum(T a, T b) {
    T s = a + b;
    return {s, b - (s - a)};
}

// a*b - c*d as hi + lo, accurate to a few units of u^2 |ab| + u |ab - cd| (a double-double):
// what a tiny cross product of nearly parallel vectors needs.
template <class T>
LINEQUAD_INLINE TwoTermT<T> difference_of_products_dd(T a, T b, T c, T d) {
    TwoTermT<T> p = two_prod(a, b), q = two_prod(c, d);
    TwoTermT<T> s = two_sum(p.hi, -q.hi);
    return fast_two_sum(s.hi, s.lo + (p.lo - q.lo));
}

// a*b - c*d within 2 ulps, by Kahan's algorithm with a fused multiply-add (the bound is
// Jeannerod, Louvet and Muller's): a third of difference_of_products_dd's work, for a product
// that is rounded to double anyway.
template <class T>
LINEQUAD_INLINE T difference_of_products(T a, T b, T c, T d) {
    using std::fma;
    T cd = c * d;
    T err = fma(-c, d, cd); // cd - c*d, exactly
    return fma(a, b, -cd) + err;
}

template <class T>
struct Vec3TwoTermT {
    Vec3T<T> hi, lo;
    Vec3T<T> rounded() const { return hi + lo; }
};
using Vec3TwoTerm = Vec3TwoTermT<double>;

// a x b in double-double.
template <class T>
LINEQUAD_INLINE Vec3TwoTermT<T> cross_dd(Vec3T<T> a, Vec3T<T> b) {
    TwoTermT<T> x = difference_of_products_dd(a.y, b.z, a.z, b.y);
    TwoTermT<T> y = difference_of_products_dd(a.z, b.x, a.x, b.z);
    TwoTermT<T> z = difference_of_products_dd(a.x, b.y, a.y, b.x);
    return {{x.hi, y.hi, z.hi}, {x.lo, y.lo, z.lo}};
}

// a x (b_hi + b_lo): the small part's cross product joins the low part (its own rounding is
// of order u |a| |b_lo| <= u^2 |a| |b|).
template <class T>
LINEQUAD_INLINE Vec3TwoTermT<T> cross_dd(Vec3T<T> a, const Vec3TwoTermT<T>& b) {
    Vec3TwoTermT<T> r = cross_dd(a, b.hi);
    r.lo = r.lo + cross(a, b.lo);
    return r;
}
template <class T>
LINEQUAD_INLINE Vec3TwoTermT<T> cross_dd(const Vec3TwoTermT<T>& a, Vec3T<T> b) {
    Vec3TwoTermT<T> r = cross_dd(a.hi, b);
    r.lo = r.lo + cross(a.lo, b);
    return r;
}

// a x b, each component within 2 ulps of the exact cross product (Kahan's, above).
template <class T>
LINEQUAD_INLINE Vec3T<T> cross_accurate(Vec3T<T> a, Vec3T<T> b) {
    return {difference_of_products(a.y, b.z, a.z, b.y), difference_of_products(a.z, b.x, a.x, b.z),
            difference_of_products(a.x, b.y, a.y, b.x)};
}
// a x (b_hi + b_lo), each component within a few ulps of the exact cross product.
template <class T>
LINEQUAD_INLINE Vec3T<T> cross_accurate(Vec3T<T> a, const Vec3TwoTermT<T>& b) {
    return cross_accurate(a, b.hi) + cross(a, b.lo);
}

// u . (n_hi + n_lo), compensated: a triple product accurate even when it nearly vanishes.
template <class T>
LINEQUAD_INLINE T dot2(Vec3T<T> u, const Vec3TwoTermT<T>& n) {
    const T x[6] = {u.x, u.y, u.z, u.x, u.y, u.z};
    const T y[6] = {n.hi.x, n.hi.y, n.hi.z, n.lo.x, n.lo.y, n.lo.z};
    return dot2(x, y);
}

// (p - q) as an unevaluated sum, per component: exact.
template <class T>
LINEQUAD_INLINE Vec3TwoTermT<T> difference_exact(Vec3T<T> p, Vec3T<T> q) {
    TwoTermT<T> x = two_sum(p.x, -q.x), y = two_sum(p.y, -q.y), z = two_sum(p.z, -q.z);
    return {{x.hi, y.hi, z.hi}, {x.lo, y.lo, z.lo}};
}

// (hi + lo) + s*v with one rounding per component up to the tiny lo term: how the stable
// solvers move a line's origin to its point of closest approach without losing it.
template <class T>
LINEQUAD_INLINE Vec3T<T> moved_origin(const Vec3TwoTermT<T>& w, T s, Vec3T<T> v) {
    using std::fma;
    return {fma(s, v.x, w.hi.x) + w.lo.x, fma(s, v.y, w.hi.y) + w.lo.y,
            fma(s, v.z, w.hi.z) + w.lo.z};
}

// x^2 + y^2 - z^2 with x^2 and y^2 exact inside two fmas: one rounding of z^2 and two of
// partial results, about 2u z^2 near cancellation, and no square root. For inputs that are
// rounded already it is at least as accurate as the factored form below (in the audit, fewer
// misclassified cases in the extent_edge and near_tangent families).
template <class T>
LINEQUAD_INLINE T squares_difference(T x, T y, T z) {
    using std::fma;
    return fma(x, x, fma(y, y, -(z * z)));
}

// sqrt(x^2 + y^2) - |z| times sqrt(x^2 + y^2) + |z|: x^2 + y^2 - z^2 in geometric form. The
// cone's A keeps it: along a generator it decides better than squares_difference (in the
// audit's generator family).
template <class T>
LINEQUAD_INLINE T circle_minus_square(T x, T y, T z) {
    using std::fabs;
    using std::sqrt;
    T rho = sqrt(x * x + y * y);
    T az = fabs(z);
    return (rho - az) * (rho + az);
}

} // namespace linequad
