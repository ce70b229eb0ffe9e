// The Newton rung of the correct solver (see newton_rung.hpp for the method). Every bound is
// rigorous at any size of the scene (underflow enters as an absolute floor; overflow makes a bound
// infinite, which proves nothing), and every decision is taken only when a bound proves it.
#include "newton_rung.hpp"

#include "compensated_sum.hpp"

#include "linequad/eft.hpp"

#include <cmath>
#include <optional>
#include <type_traits>
#include <utility>

namespace linequad::detail {

namespace {

constexpr double u = 0x1p-53;

// ---- The line forms: U0, U1 and K in double-double ----

// Vectors enter as doubles (Vec3) or as exact two-term values (Vec3TwoTerm, a difference of two
// points); the low parts only add small terms.
template <class V>
constexpr bool has_low_part = std::is_same_v<V, Vec3TwoTerm>;
inline Vec3 high(const Vec3& a) {
    return a;
}
inline Vec3 high(const Vec3TwoTerm& a) {
    return a.hi;
}
inline Vec3 magnitudes(Vec3 a) {
    return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)};
}

// (a x b)_k = a_i b_j - a_j b_i with (i, j) = (k + 1, k + 2) mod 3.
template <class P, class Q>
LINEQUAD_INLINE BoundedDD cross_component(const P& a, const Q& b, int k) {
    int i = (k + 1) % 3, j = (k + 2) % 3;
    Vec3 ah = high(a), bh = high(b);
    CompensatedSum s;
    s.add_product(ah[i], bh[j]);
    s.add_product(-ah[j], bh[i]);
    if constexpr (has_low_part<Q>) {
        s.add_small(ah[i] * b.lo[j]);
        s.add_small(-ah[j] * b.lo[i]);
    }
    if constexpr (has_low_part<P>) {
        s.add_small(a.lo[i] * bh[j]);
        s.add_small(-a.lo[j] * bh[i]);
    }
    if constexpr (has_low_part<P> && has_low_part<Q>) {
        s.add_small(a.lo[i] * b.lo[j]);
        s.add_small(-a.lo[j] * b.lo[i]);
    }
    return s.result();
}

// n . w for a row n of bounded values: their bounds propagate by |w|.
template <class Q>
LINEQUAD_INLINE BoundedDD dot_row(const BoundedDD (&n)[3], const Q& w) {
    Vec3 wh = high(w);
    CompensatedSum s;
    double propagated = 0;
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k) {
        s.add_product(n[k].hi, wh[k]);
        s.add_small(n[k].lo * wh[k]);
        double size = std::fabs(wh[k]);
        if constexpr (has_low_part<Q>) {
            s.add_small(n[k].hi * w.lo[k]);
            s.add_small(n[k].lo * w.lo[k]);
            size += std::fabs(w.lo[k]);
        }
        propagated += n[k].e * size;
    }
    return s.result(propagated);
}

// a b, from a and b within their bounds: a'b' - ab = a' eb + b' ea + ea eb.
BoundedDD product(const BoundedDD& a, const BoundedDD& b) {
    CompensatedSum s;
    s.add_product(a.hi, b.hi);
    s.add_small(a.hi * b.lo);
    s.add_small(a.lo * b.hi);
    s.add_small(a.lo * b.lo);
    double propagated = a.e * (std::fabs(b.hi) + std::fabs(b.lo)) +
                        b.e * (std::fabs(a.hi) + std::fabs(a.lo)) + a.e * b.e;
    return s.result(propagated);
}

// The elliptic shapes: the rows of adj(M), M = [a b c], are b x c, c x a, a x b; U0 = adj(M) w
// and U1 = adj(M) v (the exact form's W and V, line_quadratic.hpp). c is a double for the
// elliptic cylinder, the exact difference H - C for the cone.
template <class CVec>
LineForm elliptic_form(Vec3 a, Vec3 b, const CVec& c, const Vec3TwoTerm& w, Vec3 v,
                       bool negative_det, BoundedDD& det) {
    BoundedDD nx[3], ny[3], nz[3];
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k) {
        nx[k] = cross_component(b, c, k);
        ny[k] = cross_component(c, a, k);
        nz[k] = cross_component(a, b, k);
    }
    det = dot_row(nx, a);
    LineForm f;
    f.U0[0] = dot_row(nx, w), f.U0[1] = dot_row(ny, w), f.U0[2] = dot_row(nz, w);
    f.U1[0] = dot_row(nx, v), f.U1[1] = dot_row(ny, v), f.U1[2] = dot_row(nz, v);
    // z = Z / det: with det's sign folded into Z, the extent is in units of |det|.
    double sign = negative_det ? -1 : 1;
    f.Z0 = sign * f.U0[2].hi, f.e_Z0 = bound_of_hi(f.U0[2]);
    f.dZ = sign * f.U1[2].hi, f.e_dZ = bound_of_hi(f.U1[2]);
    det.hi *= sign, det.lo *= sign; // |det|
    return f;
}

// ---- g near a point ----

// The components k of u that g uses: x and y always, z unless sigma_z = 0.
template <int SigmaZ>
constexpr int used_components = SigmaZ == 0 ? 2 : 3;
template <int SigmaZ>
constexpr double sigma(int k) {
    return k < 2 ? 1.0 : double(SigmaZ);
}

// A = sum sigma_k U1_k^2, g's leading coefficient, in double: three products and two sums err
// by at most gamma_3 sum U1_k^2 (4u covers it), and U1's own bounds move each square by
// d (2 |U1_k| + d), d = |U1_k - hi|.
struct Leading {
    double A, e;
};
template <int SigmaZ>
Leading leading(const LineForm& f) {
    double A = 0, squares = 0, propagated = 0;
#pragma GCC unroll 3
    for (int k = 0; k < used_components<SigmaZ>; ++k) {
        double h = f.U1[k].hi, d = bound_of_hi(f.U1[k]);
        A += sigma<SigmaZ>(k) * (h * h);
        squares += h * h;
        propagated += d * (2 * std::fabs(h) + d);
    }
    return {A, (4 * u * squares + propagated) * (1 + 0x1p-40) + 0x1p-1060};
}

// g(c + x) = A x^2 + G' x + G: G = g(c) in double-double, read as a double with its bound, and
// G' = 2 sum sigma_k u_k(c) U1_k in double. For N points at once: their chains of dependent
// operations are independent, so the processor overlaps them.
struct Local {
    double G, e_G, Gp, e_Gp;
};
template <int SigmaZ, int N>
void local_at(const LineForm& f, const double (&c)[N], Local (&out)[N]) {
    CompensatedSum g[N];
    double propagated[N], Gp[N], products[N], e_Gp[N];
    for (int n = 0; n < N; ++n)
        propagated[n] = f.K.e, Gp[n] = products[n] = e_Gp[n] = 0;
#pragma GCC unroll 3
    for (int k = 0; k < used_components<SigmaZ>; ++k) {
        const double sg = sigma<SigmaZ>(k); // +-1: multiplying by it is exact
        const BoundedDD &a = f.U0[k], &b = f.U1[k];
#pragma GCC unroll 2
        for (int n = 0; n < N; ++n) {
            // u_k(c) = U0_k + c U1_k
            CompensatedSum s;
            s.add_product(c[n], b.hi);
            s.add_exact(a.hi);
            s.add_small(a.lo);
            s.add_small(c[n] * b.lo);
            BoundedDD uk = s.unnormalized(a.e + std::fabs(c[n]) * b.e);
            // sigma u_k^2 = sigma (hi^2 + 2 hi lo + lo^2); |u^2 - u'^2| <= e (2 |u'| + e)
            double sh = sg * uk.hi;
            g[n].add_product(sh, uk.hi);
            g[n].add_small(2 * sh * uk.lo);
            g[n].add_small(sg * uk.lo * uk.lo);
            propagated[n] += uk.e * (2 * (std::fabs(uk.hi) + std::fabs(uk.lo)) + uk.e);
            // G': gamma_3 sum |u_k U1_k| for the rounding (4u covers it), and the parts left out
            Gp[n] += sh * b.hi;
            products[n] += std::fabs(uk.hi * b.hi);
            e_Gp[n] += std::fabs(uk.hi) * bound_of_hi(b) +
                       (std::fabs(uk.lo) + uk.e) * (std::fabs(b.hi) + bound_of_hi(b));
        }
    }
    for (int n = 0; n < N; ++n) {
        g[n].add_exact(-f.K.hi);
        g[n].add_small(-f.K.lo);
        BoundedDD G = g[n].rounded(propagated[n]);
        out[n] = {G.hi, G.e, 2 * Gp[n],
                  2 * (4 * u * products[n] + e_Gp[n]) * (1 + 0x1p-40) + 0x1p-1060};
    }
}
template <int SigmaZ>
Local local_at(const LineForm& f, double c) {
    const double at[1] = {c};
    Local out[1];
    local_at<SigmaZ>(f, at, out);
    return out[0];
}

// An upper bound of x y for upper bounds x, y >= 0 of two quantities: each may have underflowed
// by up to 2^-1074, and the product rounds (relatively, or by 2^-1074 below the normal range).
LINEQUAD_INLINE double upper_product(double x, double y) {
    return (x + 0x1p-1074) * (y + 0x1p-1074) * (1 + 0x1p-50) + 0x1p-1074;
}

// A root of g proven to lie in c + x +- e (x and e not rounded into c), and whether it is the
// smaller of the two.
struct Enclosure {
    double c, x, e;
    bool smaller;
};

// The root next to c, when the local quadratic proves it (see newton_rung.hpp): with
// y = 4 A G / G'^2 and |y| <= 1/2 there are two distinct real roots (the discriminant is
// G'^2 (1 - y) > 0); the one nearer c is x* = (-G/G') phi(y), phi(y) = 2 / (1 + sqrt(1 - y)),
// and |phi(y) - 1| = |y| / (1 + sqrt(1 - y))^2 <= 0.35 |y|. |-G/G' - x0| is at most
// (e_G + |x0| e_G') / |G'| + u |x0| (the perturbed quotient and its rounding). The other root is
// at -G'/A - x*, on the side of -sgn(G' A): |2 x*| < |G'/A| when |y| <= 1/2.
std::optional<Enclosure> root_near(const Local& L, const Leading& A, double c) {
    double P = (std::fabs(L.Gp) - L.e_Gp) * (1 - 0x1p-50);        // |G'| >= P
    if (!(P >= 0x1p-1000 && P <= 0x1p+1000)) return std::nullopt; // NaN too
    // Bounds from 1/P (normal, so each rounding is relative: 1 + 2^-48 covers a dozen). y is
    // formed from two ratios of like quantities, so that no product of two small ones underflows.
    double inv_P = 1 / P, G_max = std::fabs(L.G) + L.e_G;
    double y = 4 * upper_product((std::fabs(A.A) + A.e) * inv_P, G_max * inv_P);
    if (!(y <= 0.5)) return std::nullopt;
    double x0 = -L.G / L.Gp;
    double e = ((L.e_G + std::fabs(x0) * L.e_Gp + 0.35 * y * G_max) * inv_P + u * std::fabs(x0)) *
                   (1 + 0x1p-48) +
               0x1p-1070;
    return Enclosure{c, x0, e, (L.Gp > 0) != (A.A > 0)};
}

// No real root: at c (near the vertex), g(c + x) = A x^2 + G' x + G with G'^2 < 4 A G.
template <int SigmaZ>
bool no_root_proven(const LineForm& f, const Leading& A, double c) {
    if (!std::isfinite(c)) return false;
    Local L = local_at<SigmaZ>(f, c);
    double A_min = (std::fabs(A.A) - A.e) * (1 - 0x1p-50), G_min = std::fabs(L.G) - L.e_G;
    if (!(G_min > 0 && A_min >= 0x1p-1000) || (L.G > 0) != (A.A > 0)) return false;
    // G'^2 / A < 4 G, each side of like degree (no product of two small quantities).
    double slope = std::fabs(L.Gp) + L.e_Gp;
    return upper_product(slope, slope / A_min) < 4 * G_min * (1 - 0x1p-48) - 0x1p-1074;
}

// 1: the root is inside the extent and the range; 0: outside; -1: the bounds cannot tell.
int kept(const LineForm& f, const Unit& unit, const Enclosure& en) {
    double t = en.c + en.x;
    double e_t = en.e + u * std::fabs(t) + 0x1p-1074;
    // Z(t*) = Z0 + t* dZ from z = fma(t, dZ, Z0): the bounds of Z0 and dZ, |t* - t|, and z's
    // rounding.
    double z = std::fma(t, f.dZ, f.Z0);
    double e_z =
        (f.e_Z0 + e_t * (std::fabs(f.dZ) + f.e_dZ) + std::fabs(t) * f.e_dZ + u * std::fabs(z)) *
            (1 + 0x1p-48) +
        0x1p-1070;
    int s[4] = {1, 1, 1, 1}; // Z - lo, hi - Z, t, end - t
    if (f.lo_bounded) s[0] = certain_sign_of_difference(z, e_z, f.lo, f.e_lo);
    if (f.hi_bounded) s[1] = certain_sign_of_difference(f.hi, f.e_hi, z, e_z);
    Range range = unit.line.range;
    if (range != Range::line) s[2] = certain_sign_of_difference(t, e_t, 0, 0);
    if (range == Range::segment) s[3] = certain_sign_of_difference(unit.end, 0, t, e_t);
    for (int si : s)
        if (si < 0) return 0; // outside one bound: outside, whatever the others say
    for (int si : s)
        if (si == 0) return -1;
    return 1;
}

// The hit, t and its point correctly rounded in the caller's units; false when a bound does
// not prove a rounding.
bool add_hit(const Enclosure& en, const Unit& unit, const Line& caller, Query q, Result& r) {
    TwoTerm t = two_sum(en.c, en.x);
    std::optional<double> rounded = round_proven({t.hi, t.lo, en.e}, unit.t_factor);
    if (!rounded) return false;
    Hit& h = r.hits[r.count];
    h.t = *rounded;
    h.kind = HitKind::cross;
    if (q.points) {
        double p[3];
#pragma GCC unroll 3
        for (int k = 0; k < 3; ++k) {
            // L0_k + t v_k is L0_k exactly when v_k = 0 (an exact zero is +0, as the oracle's).
            if (caller.v[k] == 0) {
                p[k] = caller.L0[k] + 0.0;
                continue;
            }
            // L0_k + c v_k + x v_k: the first two exactly (hi + s.lo + cv.lo), the rest rounded
            // three times: u (2 |x v_k| + |cv.lo| + |lo|) with the rounding of the bound.
            double v = unit.line.v[k];
            TwoTerm cv = two_prod(en.c, v), s = two_sum(unit.line.L0[k], cv.hi);
            double xv = en.x * v, lo = s.lo + (cv.lo + xv);
            double e =
                (std::fabs(v) * en.e + u * (2 * std::fabs(xv) + std::fabs(cv.lo) + std::fabs(lo))) *
                    (1 + 0x1p-48) +
                0x1p-1060;
            TwoTerm n = two_sum(s.hi, lo);
            std::optional<double> pk = round_proven({n.hi, n.lo, e}, unit.pos_factor);
            if (!pk) return false;
            p[k] = *pk;
        }
        h.p = {p[0], p[1], p[2]};
    }
    ++r.count;
    return true;
}

} // namespace

LineForm line_form(const Cylinder& s, const Line& l) {
    Vec3TwoTerm h = difference_exact(s.H, s.C), w = difference_exact(l.L0, s.C);
    LineForm f;
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k) {
        f.U0[k] = cross_component(w, h, k);
        f.U1[k] = cross_component(l.v, h, k);
    }
    f.sigma_z = 1;
    CompensatedSum hh_sum; // h.h
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k) {
        hh_sum.add_product(h.hi[k], h.hi[k]);
        hh_sum.add_small(2 * h.hi[k] * h.lo[k]);
        hh_sum.add_small(h.lo[k] * h.lo[k]);
    }
    BoundedDD hh = hh_sum.result();
    TwoTerm r2 = two_prod(s.r, s.r);
    f.K = product({r2.hi, r2.lo, 0}, hh);
    // Z = (P - C).h = w.h + t v.h, from the high parts in double: gamma_3 of the sum of products'
    // magnitudes for the rounding, and 2u (1 + u) of it for the low parts left out; 6u covers
    // both (5u for v.h, whose v has no low part).
    f.Z0 = dot(w.hi, h.hi);
    f.e_Z0 = 6 * u * dot(magnitudes(w.hi), magnitudes(h.hi)) + 0x1p-1060;
    f.dZ = dot(l.v, h.hi);
    f.e_dZ = 5 * u * dot(magnitudes(l.v), magnitudes(h.hi)) + 0x1p-1060;
    f.lo = 0, f.e_lo = 0;
    f.hi = hh.hi, f.e_hi = bound_of_hi(hh);
    f.lo_bounded = f.hi_bounded = s.finite;
    return f;
}

LineForm line_form(const EllipticCylinder& s, const Line& l, bool negative_det) {
    BoundedDD det;
    LineForm f = elliptic_form(s.a, s.b, s.c, difference_exact(l.L0, s.C), l.v, negative_det, det);
    f.sigma_z = 0;
    f.K = product(det, det);
    f.lo = 0, f.e_lo = 0;
    f.hi = det.hi, f.e_hi = bound_of_hi(det); // 0 <= Z <= |det|
    f.lo_bounded = f.hi_bounded = s.finite;
    return f;
}

LineForm line_form(const EllipticCone& s, const Line& l, bool negative_det) {
    BoundedDD det;
    LineForm f = elliptic_form(s.a, s.b, difference_exact(s.H, s.C), difference_exact(l.L0, s.H),
                               l.v, negative_det, det);
    f.sigma_z = -1;
    f.K = BoundedDD(0);
    f.lo = -det.hi, f.e_lo = bound_of_hi(det); // -|det| <= Z <= 0: the nappe z <= 0
    f.hi = 0, f.e_hi = 0;
    f.lo_bounded = s.finite;
    f.hi_bounded = true;
    return f;
}

namespace {

template <int SigmaZ>
bool solve(const LineForm& f, const Unit& unit, const Line& caller, Query query, Result& r) {
    Leading A = leading<SigmaZ>(f);
    if (!(std::fabs(A.A) > A.e)) return false; // nearly parallel to the axis or to a generator
    // The estimates: the quadratic's coefficients from the high parts, the stable root pair.
    double B = 0, C0 = -f.K.hi;
#pragma GCC unroll 3
    for (int k = 0; k < used_components<SigmaZ>; ++k) {
        B += sigma<SigmaZ>(k) * (f.U0[k].hi * f.U1[k].hi);
        C0 += sigma<SigmaZ>(k) * (f.U0[k].hi * f.U0[k].hi);
    }
    double D = difference_of_products(B, B, A.A, C0);
    if (!(D > 0)) return no_root_proven<SigmaZ>(f, A, -B / A.A);
    double q = -(B + std::copysign(std::sqrt(D), B));
    double estimate[2] = {q / A.A, C0 / q};
    if (estimate[1] < estimate[0]) std::swap(estimate[0], estimate[1]);
    // Both roots at once when both are needed; otherwise the second only if the first is not kept.
    Local local[2];
    if (query.need == Need::all) local_at<SigmaZ>(f, estimate, local);
    for (int i = 0; i < 2; ++i) {
        if (query.need != Need::all) local[i] = local_at<SigmaZ>(f, estimate[i]);
        std::optional<Enclosure> en = root_near(local[i], A, estimate[i]);
        if (!en || en->smaller != (i == 0)) return false;
        int inside = kept(f, unit, *en);
        if (inside < 0) return false;
        if (inside == 0) continue;
        if (!add_hit(*en, unit, caller, query, r)) return false;
        if (query.need != Need::all) break; // the smaller root first: also the nearest
    }
    return true;
}

} // namespace

bool newton_rung(const LineForm& f, const Unit& unit, const Line& caller, Query query, Result& r) {
    switch (f.sigma_z) {
    case 1:
        return solve<1>(f, unit, caller, query, r);
    case 0:
        return solve<0>(f, unit, caller, query, r);
    default:
        return solve<-1>(f, unit, caller, query, r);
    }
}

} // namespace linequad::detail
