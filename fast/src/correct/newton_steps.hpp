// The Newton rung's arithmetic (see newton_rung.hpp for the method), written once for a number
// type T: double for the scalar rung (newton_rung.cpp), a lane type for the batch correct solver
// (simd/correct_lanes.hpp). Each step returns its values and, where the scalar rung would branch,
// the mask of lanes whose bounds prove the step; the scalar rung branches on it, the lanes
// combine it. Same operations in the same order: the same bits, so a lane proves exactly what
// the scalar rung proves.
#pragma once

#include "correct/ladder.hpp"
#include "forms/line_form.hpp"

#include "numeric/compensated_sum.hpp"
#include "numeric/eft.hpp"

#include <cmath>
#include <type_traits>

namespace linequad::detail::newton {

using F = Binary64;
constexpr double u = F::u;

template <class T>
using Mask = MaskOf<T>;

template <class M>
LINEQUAD_INLINE M differ(M a, M b) {
    return (a & (!b)) | ((!a) & b);
}

// The components k of u that g uses: x and y always, z unless sigma_z = 0, and a fourth, with
// sigma -1, for four_terms (the frustum's).
template <int SigmaZ>
constexpr int used_components = SigmaZ == 0            ? 2
                                : SigmaZ == four_terms ? 4
                                                       : 3;
template <int SigmaZ>
constexpr double sigma(int k) {
    if constexpr (SigmaZ == four_terms) return k < 3 ? 1.0 : -1.0;
    return k < 2 ? 1.0 : double(SigmaZ);
}

// One more product and one more sum where there are four terms: the rounding bounds below are
// written for three, and grow by this many u per term.
template <int SigmaZ>
constexpr double more_terms = SigmaZ == four_terms ? 1.0 : 0.0;

// f(std::integral_constant<int, sigma_z>{}): each step is compiled for its sigma_z (1: the
// cylinder, 0: the elliptic cylinder, -1: the cone, four_terms: the frustum).
template <class F>
LINEQUAD_INLINE decltype(auto) with_sigma_z(int sigma_z, F&& f) {
    switch (sigma_z) {
    case 1:
        return f(std::integral_constant<int, 1>{});
    case 0:
        return f(std::integral_constant<int, 0>{});
    case four_terms:
        return f(std::integral_constant<int, four_terms>{});
    default:
        return f(std::integral_constant<int, -1>{});
    }
}
// The same for the batch kernels' lanes: a four-term form (the frustum's: FourTerms) compiled
// apart, so that the other shapes' kernels carry no fourth term.
template <bool FourTerms, class F>
LINEQUAD_INLINE decltype(auto) with_sigma_z_of_lanes(int sigma_z, F&& f) {
    if constexpr (FourTerms) {
        return f(std::integral_constant<int, four_terms>{});
    } else {
        switch (sigma_z) {
        case 1:
            return f(std::integral_constant<int, 1>{});
        case 0:
            return f(std::integral_constant<int, 0>{});
        default:
            return f(std::integral_constant<int, -1>{});
        }
    }
}

// ---- g near a point ----

// A = sum sigma_k U1_k^2, g's leading coefficient, in double: three products and two sums err
// by at most gamma_3 sum U1_k^2 (4u covers it; four terms, 5u), and U1's own bounds move each
// square by d (2 |U1_k| + d), d = |U1_k - hi|.
template <int SigmaZ, class T>
LINEQUAD_INLINE Leading<T> leading(const LineFormT<T>& f) {
    using std::fabs;
    T A(0.0), squares(-0.0), propagated(-0.0); // -0 + x = x: see CompensatedSumT
#pragma GCC unroll 4
    for (int k = 0; k < used_components<SigmaZ>; ++k) {
        T h = U1_of(f, k).hi, d = bound_of_hi(U1_of(f, k));
        A = A + T(sigma<SigmaZ>(k)) * (h * h);
        squares = squares + h * h;
        propagated = propagated + d * (T(2.0) * fabs(h) + d);
    }
    return {A, (T((4 + more_terms<SigmaZ>)*u) * squares + propagated) * T(F::cover(8192)) +
                   T(F::underflow_floor)};
}

// g(c + x) = A x^2 + G' x + G: G = g(c) in double-double, read as a double with its bound, and
// G' = 2 sum sigma_k u_k(c) U1_k in double. For N points at once: their chains of dependent
// operations are independent, so the processor overlaps them.
template <int SigmaZ, int N, class T>
void local_at(const LineFormT<T>& f, const T (&c)[N], Local<T> (&out)[N]) {
    using std::fabs;
    CompensatedSumT<T> g[N];
    T propagated[N], Gp[N], products[N], e_Gp[N];
    for (int n = 0; n < N; ++n)
        propagated[n] = T(f.K.e), Gp[n] = T(0.0), products[n] = e_Gp[n] = T(-0.0);
#pragma GCC unroll 4
    for (int k = 0; k < used_components<SigmaZ>; ++k) {
        const T sg(sigma<SigmaZ>(k)); // +-1: multiplying by it is exact
        const BoundedDDT<T>&a = U0_of(f, k), &b = U1_of(f, k);
#pragma GCC unroll 2
        for (int n = 0; n < N; ++n) {
            // u_k(c) = U0_k + c U1_k
            CompensatedSumT<T> s;
            s.add_product(c[n], b.hi);
            s.add_exact(a.hi);
            s.add_small(a.lo);
            s.add_small(c[n] * b.lo);
            BoundedDDT<T> uk = s.unnormalized(a.e + fabs(c[n]) * b.e);
            // sigma u_k^2 = sigma (hi^2 + 2 hi lo + lo^2); |u^2 - u'^2| <= e (2 |u'| + e)
            T sh = sg * uk.hi;
            g[n].add_product(sh, uk.hi);
            g[n].add_small(T(2.0) * sh * uk.lo);
            g[n].add_small(sg * uk.lo * uk.lo);
            propagated[n] = propagated[n] + uk.e * (T(2.0) * (fabs(uk.hi) + fabs(uk.lo)) + uk.e);
            // G' from u_k(c) rounded once, hi + lo: uk is unnormalized, and where U0 and c U1
            // cancel (a line from far away) lo lies far above hi's ulp. gamma_3 sum |u_k U1_k|
            // for the rounding (4u covers it; four terms, 5u), and the parts left out: u_k's
            // rounding, its bound, U1's low part and bound.
            T un = uk.hi + uk.lo, an = fabs(un);
            Gp[n] = Gp[n] + (sg * un) * b.hi;
            products[n] = products[n] + fabs(un * b.hi);
            e_Gp[n] = e_Gp[n] +
                      (an * bound_of_hi(b) + (T(u) * an + uk.e) * (fabs(b.hi) + bound_of_hi(b)));
        }
    }
    for (int n = 0; n < N; ++n) {
        g[n].add_exact(T(-f.K.hi));
        g[n].add_small(T(-f.K.lo));
        BoundedDDT<T> G = g[n].rounded(propagated[n]);
        out[n] = {G.hi, G.e, T(2.0) * Gp[n],
                  T(2.0) * (T((4 + more_terms<SigmaZ>)*u) * products[n] + e_Gp[n]) *
                          T(F::cover(8192)) +
                      T(F::underflow_floor)};
    }
}

// g(c + x) = A x^2 + G' x + G from the quick line form (values a_k, b_k, kappa in double, each
// within alpha_k, beta_k, e_kappa of U0_k, U1_k, K). With u_k = fma(c, b_k, a_k), one rounding:
//   |u_k - u*_k| <= E_k = alpha_k + |c| beta_k + u |u_k| (1 + 2u),
//   |u_k^2 - u*_k^2| <= E_k (2 |u_k| + E_k),
// and G = sum sigma_k fl(u_k^2) - kappa rounds at most five times, each by u of a partial sum
// no larger than S = sum u_k^2 + |kappa|: 6u S covers them with the squares' own rounding (four
// terms: 8u). G' = 2 sum sigma_k u_k b_k as the precise rung's: |u_k b_k - u*_k U1*_k| <=
// E_k |b_k| + (|u_k| + E_k) beta_k, and 4u sum |u_k b_k| for its roundings (four terms: 5u). Every
// bound is computed in a dozen roundings of nonnegative terms (cover(32)), and may have underflowed
// (the floor).
template <int SigmaZ, class T>
LINEQUAD_INLINE Local<T> quick_local_at(const LineFormT<T>& f, T c) {
    using std::fabs;
    using std::fma;
    T G(-f.K.hi), S(std::fabs(f.K.hi)), e_G(f.K.e), Gp(0.0), P(0.0), e_Gp(0.0);
    const T ac = fabs(c);
#pragma GCC unroll 4
    for (int k = 0; k < used_components<SigmaZ>; ++k) {
        const T a = U0_of(f, k).hi, b = U1_of(f, k).hi, beta = U1_of(f, k).e; // no low parts
        T uk = fma(c, b, a), au = fabs(uk);
        T E = U0_of(f, k).e + ac * beta + T(u * F::cover(2)) * au;
        T sq = uk * uk, ub = uk * b;
        G = G + T(sigma<SigmaZ>(k)) * sq;
        Gp = Gp + T(sigma<SigmaZ>(k)) * ub;
        S = S + sq;
        P = P + fabs(ub);
        e_G = e_G + E * (T(2.0) * au + E);
        e_Gp = e_Gp + (E * fabs(b) + (au + E) * beta);
    }
    return {G,
            (e_G + T((6 + 2 * more_terms<SigmaZ>)*u) * S) * T(F::cover(32)) + T(F::underflow_floor),
            T(2.0) * Gp,
            T(2.0) * (e_Gp + T((4 + more_terms<SigmaZ>)*u) * P) * T(F::cover(32)) +
                T(F::underflow_floor)};
}

// An upper bound of x y for upper bounds x, y >= 0 of two quantities: each may have underflowed
// by up to 2^-1074, and the product rounds (relatively, or by 2^-1074 below the normal range).
template <class T>
LINEQUAD_INLINE T upper_product(T x, T y) {
    return (x + T(F::denorm_min)) * (y + T(F::denorm_min)) * T(F::cover(8)) + T(F::denorm_min);
}

// A root of g proven to lie in c + x +- e (x and e not rounded into c), and whether it is the
// smaller of the two; `proven` where the local quadratic proves it.
template <class T>
struct Enclosure {
    T c, x, e;
    Mask<T> smaller, proven;
};

// The root next to c, where the local quadratic proves it (see newton_rung.hpp): with
// Y = 4 A G / G'^2 and |Y| <= 1/2 there are two distinct real roots (the discriminant is
// G'^2 (1 - Y) > 0); the one nearer c is x* = X0 phi(Y), X0 = -G/G', phi(Y) = 2 / (1 + sqrt(1 - Y))
// and |phi(Y) - 1| = |Y| / (1 + sqrt(1 - Y))^2 <= 0.35 |Y|. |X0 - x0| for the computed
// x0 = -G/G' is at most (e_G + |x0| e_G') / |G'| + u |x0| (the perturbed quotient and its
// rounding). The other root is at -G'/A - x*, on the side of -sgn(G' A): |2 x*| < |G'/A| when
// |Y| <= 1/2. The enclosure about x0 (root_near) is the first rung's, the lanes' too; the one about
// x0 phi(y) (root_near_tight) is narrower where the estimate is off in a large root's scale.
template <class T>
struct NearRoot {
    T P, inv_P, A_max, X0_max, y_max, x0;
    Mask<T> proven;
};
template <class T>
LINEQUAD_INLINE NearRoot<T> near_root(const Local<T>& L, const Leading<T>& A) {
    using std::fabs;
    T P = (fabs(L.Gp) - L.e_Gp) * T(F::shrink(8));              // |G'| >= P
    Mask<T> proven = (P >= T(0x1p-1000)) & (P <= T(0x1p+1000)); // not NaN
    // Bounds from 1/P (normal, so each rounding is relative: 1 + 2^-48 covers a dozen). y_max is
    // formed from two ratios of like quantities, so that no product of two small ones underflows.
    T inv_P = T(1.0) / P, A_max = fabs(A.A) + A.e, X0_max = (fabs(L.G) + L.e_G) * inv_P;
    T y_max = T(4.0) * upper_product(A_max * inv_P, X0_max);
    proven = proven & (y_max <= T(0.5));
    return {P, inv_P, A_max, X0_max, y_max, -L.G / L.Gp, proven};
}
template <class T>
LINEQUAD_INLINE Enclosure<T> root_near(const Local<T>& L, const Leading<T>& A, T c) {
    using std::fabs;
    NearRoot<T> n = near_root(L, A);
    T e = ((L.e_G + fabs(n.x0) * L.e_Gp) * n.inv_P + T(0.35) * n.y_max * n.X0_max +
           T(u) * fabs(n.x0)) *
              T(F::cover(32)) +
          T(F::subnormal_slack);
    return {c, n.x0, e, differ<Mask<T>>(T(0.0) < L.Gp, T(0.0) < A.A), n.proven};
}
// phi taken at y = -4 A x0 / G', not bounded by its first term: where the roots lie close (a
// near tangency seen from far away) an estimate an ulp off leaves |Y| near 2^-8, and the
// enclosure about x0 is some 2^-72 of t wide; this one, 2^-100. For |Y| <= 1/2,
// 0.89 <= phi <= 1.18 and |phi'| <= 0.57, so x1 = x0 phi(y) errs by at most
//  - 1.18 E0, E0 = (e_G + |x0| e_G') / |G'| + u |x0|: x0 from X0;
//  - 0.57 |x0| |Y - y|, |Y - y| <= 4 (e_A |X0| + |A| E0 + |A x0| e_G' / |G'|) / |G'| + 4u |y|;
//  - 6u |x1|: phi's and the product's roundings.
template <class T>
LINEQUAD_INLINE Enclosure<T> root_near_tight(const Local<T>& L, const Leading<T>& A, T c) {
    using std::fabs;
    using std::sqrt;
    NearRoot<T> n = near_root(L, A);
    T ax0 = fabs(n.x0), y = T(-4.0) * (A.A * n.x0) / L.Gp;
    T x1 = n.x0 * (T(2.0) / (T(1.0) + sqrt(fabs(T(1.0) - y)))); // |y| <= y_max where proven
    T E0 = (L.e_G + ax0 * L.e_Gp) * n.inv_P + T(u) * ax0;
    T e_y = T(4.0) *
                (upper_product(A.e, n.X0_max) + upper_product(n.A_max, E0) +
                 upper_product(n.A_max * ax0, L.e_Gp * n.inv_P)) *
                n.inv_P +
            T(4 * u) * fabs(y);
    T e =
        (T(1.18) * E0 + T(0.57) * upper_product(ax0, e_y) + T(6 * u) * fabs(x1)) * T(F::cover(32)) +
        T(F::subnormal_slack);
    return {c, x1, e, differ<Mask<T>>(T(0.0) < L.Gp, T(0.0) < A.A), n.proven};
}

// Whether g has no real root: at c (near the vertex), g(c + x) = A x^2 + G' x + G with
// G'^2 < 4 A G; L is the local expansion at c (the precise one, or the hit test's quick one).
template <class T>
LINEQUAD_INLINE Mask<T> no_root_proven(const Leading<T>& A, T c, const Local<T>& L) {
    using std::fabs;
    T A_min = (fabs(A.A) - A.e) * T(F::shrink(8)), G_min = fabs(L.G) - L.e_G;
    Mask<T> same_sign = !differ<Mask<T>>(T(0.0) < L.G, T(0.0) < A.A);
    Mask<T> finite = equal(c - c, T(0.0)); // not NaN, not infinite
    Mask<T> usable = finite & (T(0.0) < G_min) & (A_min >= T(0x1p-1000)) & same_sign;
    // G'^2 / A < 4 G, each side of like degree (no product of two small quantities).
    T slope = fabs(L.Gp) + L.e_Gp;
    return usable & (upper_product(slope, slope / A_min) <
                     T(4.0) * G_min * T(F::shrink(32)) - T(F::denorm_min));
}

// The root's t = c + x rounded once, and a linear function of t at the root, Z(t*) = Z0 + t* dZ
// (the axial coordinate, or a fourth term), from z = fma(t, dZ, Z0), each with its bound: the
// bounds of Z0 and dZ, |t* - t|, and z's rounding.
// t = c + x in double, within e_t of the root.
template <class T>
struct EnclosedT {
    T t, e_t;
};
template <class T>
LINEQUAD_INLINE EnclosedT<T> t_of(const Enclosure<T>& en) {
    using std::fabs;
    T t = en.c + en.x;
    return {t, en.e + T(u) * fabs(t) + T(F::denorm_min)};
}
template <class T>
struct Axial {
    T t, e_t, z, e_z;
};
template <class T>
LINEQUAD_INLINE Axial<T> linear_at(T Z0, T e_Z0, T dZ, T e_dZ, const Enclosure<T>& en) {
    using std::fabs;
    using std::fma;
    auto [t, e_t] = t_of(en);
    T z = fma(t, dZ, Z0);
    T e_z = (e_Z0 + e_t * (fabs(dZ) + e_dZ) + fabs(t) * e_dZ + T(u) * fabs(z)) * T(F::cover(32)) +
            T(F::subnormal_slack);
    return {t, e_t, z, e_z};
}
template <class T>
LINEQUAD_INLINE Axial<T> axial_at(const LineFormT<T>& f, const Enclosure<T>& en) {
    return linear_at(f.Z0, f.e_Z0, f.dZ, f.e_dZ, en);
}

// Whether a root is inside the extent and the range: `outside` where one bound is proven
// violated (outside, whatever the others say), `inside` where every bound is proven met; neither
// where the bounds cannot tell. Each side is a difference `d` proven positive or negative.
template <class T>
struct Kept {
    Mask<T> outside = T(0.0) < T(0.0), inside = T(0.0) <= T(0.0);
    LINEQUAD_INLINE void side(DifferenceTest<T> s) {
        outside = outside | (s.d < -s.bound);
        inside = inside & (s.bound < s.d);
    }
    LINEQUAD_INLINE Kept& range(Interval r, T t, T e_t) { // the range's ends are exact
        if (r.has_t0()) side(difference_test(t, e_t, T(r.t0), T(0.0)));
        if (r.has_t1()) side(difference_test(T(r.t1), T(0.0), t, e_t));
        inside = inside & !outside;
        return *this;
    }
};
template <class T>
LINEQUAD_INLINE Kept<T> kept(const LineFormT<T>& f, Interval range, const Enclosure<T>& en) {
    Axial<T> a = axial_at(f, en);
    Kept<T> k;
    if (f.lo_bounded) k.side(difference_test(a.z, a.e_z, T(f.lo), T(f.e_lo)));
    if (f.hi_bounded) k.side(difference_test(T(f.hi), T(f.e_hi), a.z, a.e_z));
    return k.range(range, a.t, a.e_t);
}

// t = c + x rounded to the nearest double in the caller's units (scale = t's factor).
template <class T>
LINEQUAD_INLINE Rounded<T> rounded_t(const Enclosure<T>& en, T scale) {
    TwoTermT<T> t = two_sum(en.c, en.x);
    return round_proven_to_double<T>({t.hi, t.lo, en.e}, scale);
}

// Coordinate k of the hit point L0_k + t v_k, rounded, for v_k != 0 (the caller keeps L0_k + 0
// where v_k = 0: an exact zero is +0, as the oracle's): L0_k + c v_k + x v_k, the first two
// exactly (hi + s.lo + cv.lo), the rest rounded three times: u (2 |x v_k| + |cv.lo| + |lo|) with
// the rounding of the bound. L0 and v are the scaled line's, scale its positions' factor.
template <class T>
LINEQUAD_INLINE Rounded<T> rounded_point(const Enclosure<T>& en, T L0_k, T v, T scale) {
    using std::fabs;
    TwoTermT<T> cv = two_prod(en.c, v), s = two_sum(L0_k, cv.hi);
    T xv = en.x * v, lo = s.lo + (cv.lo + xv);
    T e = (fabs(v) * en.e + T(u) * (T(2.0) * fabs(xv) + fabs(cv.lo) + fabs(lo))) * T(F::cover(32)) +
          T(F::underflow_floor);
    TwoTermT<T> n = two_sum(s.hi, lo);
    return round_proven_to_double<T>({n.hi, n.lo, e}, scale);
}

// The roots' double estimates, from the quadratic's coefficients in the high parts: the stable
// pair q / A, C0 / q (in that order) where the discriminant is positive (`real`); elsewhere the
// vertex -B / A, where no_root_proven() looks.
template <class T>
struct Estimates {
    Mask<T> real;
    T vertex;
    T root[2];
};
template <int SigmaZ, class T>
LINEQUAD_INLINE Estimates<T> estimates(const LineFormT<T>& f, const Leading<T>& A) {
    using std::copysign;
    using std::sqrt;
    T B(0.0), C0(-f.K.hi);
#pragma GCC unroll 4
    for (int k = 0; k < used_components<SigmaZ>; ++k) {
        B = B + T(sigma<SigmaZ>(k)) * (U0_of(f, k).hi * U1_of(f, k).hi);
        C0 = C0 + T(sigma<SigmaZ>(k)) * (U0_of(f, k).hi * U0_of(f, k).hi);
    }
    T D = difference_of_products(B, B, A.A, C0);
    if constexpr (std::is_same_v<T, double>) // one line: no root, no division by q
        if (!(D > 0)) return {false, -B / A.A, {0, 0}};
    T q = -(B + copysign(sqrt(D), B));
    return {T(0.0) < D, -B / A.A, {q / A.A, C0 / q}};
}

} // namespace linequad::detail::newton
