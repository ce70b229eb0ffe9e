// The Newton rung of the correct solver (see newton_rung.hpp for the method). Every bound is
// rigorous at any size of the scene (underflow enters as an absolute floor; overflow makes a bound
// infinite, which proves nothing), and every decision is taken only when a bound proves it.
#include "correct/newton_rung.hpp"

#include "numeric/compensated_sum.hpp"
#include "numeric/eft.hpp"

#include <cmath>
#include <optional>
#include <type_traits>
#include <utility>

namespace linequad::detail {

namespace {

using F = Binary64;
constexpr double u = F::u;

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
    return {A, (4 * u * squares + propagated) * F::cover(8192) + F::underflow_floor};
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
                  2 * (4 * u * products[n] + e_Gp[n]) * F::cover(8192) + F::underflow_floor};
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
    return (x + F::denorm_min) * (y + F::denorm_min) * F::cover(8) + F::denorm_min;
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
LINEQUAD_INLINE std::optional<Enclosure> root_near(const Local& L, const Leading& A, double c) {
    double P = (std::fabs(L.Gp) - L.e_Gp) * F::shrink(8);         // |G'| >= P
    if (!(P >= 0x1p-1000 && P <= 0x1p+1000)) return std::nullopt; // NaN too
    // Bounds from 1/P (normal, so each rounding is relative: 1 + 2^-48 covers a dozen). y is
    // formed from two ratios of like quantities, so that no product of two small ones underflows.
    double inv_P = 1 / P, G_max = std::fabs(L.G) + L.e_G;
    double y = 4 * upper_product((std::fabs(A.A) + A.e) * inv_P, G_max * inv_P);
    if (!(y <= 0.5)) return std::nullopt;
    double x0 = -L.G / L.Gp;
    double e = ((L.e_G + std::fabs(x0) * L.e_Gp + 0.35 * y * G_max) * inv_P + u * std::fabs(x0)) *
                   F::cover(32) +
               F::subnormal_slack;
    return Enclosure{c, x0, e, (L.Gp > 0) != (A.A > 0)};
}

// No real root: at c (near the vertex), g(c + x) = A x^2 + G' x + G with G'^2 < 4 A G; the
// local expansion from local_at (the precise one, or the hit test's quick one).
template <class LocalAt>
bool no_root_proven(const Leading& A, double c, LocalAt local_at) {
    if (!std::isfinite(c)) return false;
    Local L = local_at(c);
    double A_min = (std::fabs(A.A) - A.e) * F::shrink(8), G_min = std::fabs(L.G) - L.e_G;
    if (!(G_min > 0 && A_min >= 0x1p-1000) || (L.G > 0) != (A.A > 0)) return false;
    // G'^2 / A < 4 G, each side of like degree (no product of two small quantities).
    double slope = std::fabs(L.Gp) + L.e_Gp;
    return upper_product(slope, slope / A_min) < 4 * G_min * F::shrink(32) - F::denorm_min;
}

// 1: the root is inside the extent and the range; 0: outside; -1: the bounds cannot tell.
LINEQUAD_INLINE int kept(const LineForm& f, const Unit& unit, const Enclosure& en) {
    double t = en.c + en.x;
    double e_t = en.e + u * std::fabs(t) + F::denorm_min;
    // Z(t*) = Z0 + t* dZ from z = fma(t, dZ, Z0): the bounds of Z0 and dZ, |t* - t|, and z's
    // rounding.
    double z = std::fma(t, f.dZ, f.Z0);
    double e_z =
        (f.e_Z0 + e_t * (std::fabs(f.dZ) + f.e_dZ) + std::fabs(t) * f.e_dZ + u * std::fabs(z)) *
            F::cover(32) +
        F::subnormal_slack;
    int s[4] = {1, 1, 1, 1}; // Z - lo, hi - Z, t - t0, t1 - t
    if (f.lo_bounded) s[0] = certain_sign_of_difference(z, e_z, f.lo, f.e_lo);
    if (f.hi_bounded) s[1] = certain_sign_of_difference(f.hi, f.e_hi, z, e_z);
    const Interval& range = unit.line.range; // ends exact in the scaled parameter
    if (range.has_t0()) s[2] = certain_sign_of_difference(t, e_t, range.t0, 0);
    if (range.has_t1()) s[3] = certain_sign_of_difference(range.t1, 0, t, e_t);
    for (int si : s)
        if (si < 0) return 0; // outside one bound: outside, whatever the others say
    for (int si : s)
        if (si == 0) return -1;
    return 1;
}

// The hit, t and its point correctly rounded to Target in the caller's units; false when a bound
// does not prove a rounding.
template <class Target>
LINEQUAD_INLINE bool add_hit(const Enclosure& en, const Unit& unit, const Line& caller, Query q,
                             Result& r) {
    if constexpr (std::is_same_v<Target, Binary32>) {
        // A float's rounding cell is 2^29 times a double's: t = c + x and each coordinate
        // fma(t, v_k, L0_k) in double, each with one rounding added to its bound, nearly always
        // prove it.
        double t = en.c + en.x, e_t = en.e + u * std::fabs(t);
        std::optional<double> rounded =
            round_proven<Target>({t, 0, e_t * F::cover(4) + F::denorm_min}, unit.t_factor);
        if (!rounded) return false;
        Hit& h = r.hits[r.count];
        h.t = *rounded, h.kind = HitKind::cross, h.part = Part::lateral, h.p = {};
        if (q.points) {
            double p[3];
#pragma GCC unroll 3
            for (int k = 0; k < 3; ++k) {
                if (caller.v[k] == 0) { // an exact zero is +0, as the oracle's
                    p[k] = caller.L0[k] + 0.0;
                    continue;
                }
                double v = unit.line.v[k], pk = std::fma(t, v, unit.line.L0[k]);
                double e =
                    (std::fabs(v) * e_t + u * std::fabs(pk)) * F::cover(8) + F::underflow_floor;
                std::optional<double> rk = round_proven<Target>({pk, 0, e}, unit.pos_factor);
                if (!rk) return false;
                p[k] = *rk;
            }
            h.p = {p[0], p[1], p[2]};
        }
        ++r.count;
        return true;
    } else {
        TwoTerm t = two_sum(en.c, en.x);
        std::optional<double> rounded = round_proven<Target>({t.hi, t.lo, en.e}, unit.t_factor);
        if (!rounded) return false;
        Hit& h = r.hits[r.count];
        h.t = *rounded;
        h.kind = HitKind::cross;
        h.part = Part::lateral;
        h.p = {};
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
                double e = (std::fabs(v) * en.e +
                            u * (2 * std::fabs(xv) + std::fabs(cv.lo) + std::fabs(lo))) *
                               F::cover(32) +
                           F::underflow_floor;
                TwoTerm n = two_sum(s.hi, lo);
                std::optional<double> pk = round_proven<Target>({n.hi, n.lo, e}, unit.pos_factor);
                if (!pk) return false;
                p[k] = *pk;
            }
            h.p = {p[0], p[1], p[2]};
        }
        ++r.count;
        return true;
    }
}

} // namespace

namespace {

// The roots' double estimates, from the quadratic's coefficients in the high parts: the stable
// pair q / A, C0 / q (in that order) when the discriminant is positive; otherwise the vertex
// -B / A, where no_root_proven() looks.
struct Estimates {
    bool real;
    double vertex;
    double root[2];
};
template <int SigmaZ>
LINEQUAD_INLINE Estimates estimates(const LineForm& f, const Leading& A) {
    double B = 0, C0 = -f.K.hi;
#pragma GCC unroll 3
    for (int k = 0; k < used_components<SigmaZ>; ++k) {
        B += sigma<SigmaZ>(k) * (f.U0[k].hi * f.U1[k].hi);
        C0 += sigma<SigmaZ>(k) * (f.U0[k].hi * f.U0[k].hi);
    }
    double D = difference_of_products(B, B, A.A, C0);
    if (!(D > 0)) return {false, -B / A.A, {0, 0}};
    double q = -(B + std::copysign(std::sqrt(D), B));
    return {true, 0, {q / A.A, C0 / q}};
}

// g(c + x) = A x^2 + G' x + G from the quick line form (values a_k, b_k, kappa in double, each
// within alpha_k, beta_k, e_kappa of U0_k, U1_k, K). With u_k = fma(c, b_k, a_k), one rounding:
//   |u_k - u*_k| <= E_k = alpha_k + |c| beta_k + u |u_k| (1 + 2u),
//   |u_k^2 - u*_k^2| <= E_k (2 |u_k| + E_k),
// and G = sum sigma_k fl(u_k^2) - kappa rounds at most five times, each by u of a partial sum
// no larger than S = sum u_k^2 + |kappa|: 6u S covers them with the squares' own rounding. G' =
// 2 sum sigma_k u_k b_k as the precise rung's: |u_k b_k - u*_k U1*_k| <= E_k |b_k| +
// (|u_k| + E_k) beta_k, and 4u sum |u_k b_k| for its roundings. Every bound is computed in a
// dozen roundings of nonnegative terms (cover(32)), and may have underflowed (the floor).
template <int SigmaZ>
Local quick_local_at(const LineForm& f, double c) {
    double G = -f.K.hi, S = std::fabs(f.K.hi), e_G = f.K.e, Gp = 0, P = 0, e_Gp = 0;
    const double ac = std::fabs(c);
#pragma GCC unroll 3
    for (int k = 0; k < used_components<SigmaZ>; ++k) {
        const double a = f.U0[k].hi, b = f.U1[k].hi, beta = f.U1[k].e; // no low parts
        double uk = std::fma(c, b, a), au = std::fabs(uk);
        double E = f.U0[k].e + ac * beta + u * F::cover(2) * au;
        double sq = uk * uk, ub = uk * b;
        G += sigma<SigmaZ>(k) * sq;
        Gp += sigma<SigmaZ>(k) * ub;
        S += sq;
        P += std::fabs(ub);
        e_G += E * (2 * au + E);
        e_Gp += E * std::fabs(b) + (au + E) * beta;
    }
    return {G, (e_G + 6 * u * S) * F::cover(32) + F::underflow_floor, 2 * Gp,
            2 * (e_Gp + 4 * u * P) * F::cover(32) + F::underflow_floor};
}

// G in double-double (the precise line form), or in double from the quick line form: enough for
// a float rounding, which has 29 bits more room.
template <int SigmaZ, Residual R>
Local local_near(const LineForm& f, double c) {
    if constexpr (R == Residual::quick)
        return quick_local_at<SigmaZ>(f, c);
    else
        return local_at<SigmaZ>(f, c);
}

template <int SigmaZ, class Target, Residual R>
bool solve(const LineForm& f, const Unit& unit, const Line& caller, Query query, Result& r) {
    Leading A = leading<SigmaZ>(f);
    if (!(std::fabs(A.A) > A.e)) return false; // nearly parallel to the axis or to a generator
    Estimates est = estimates<SigmaZ>(f, A);
    if (!est.real)
        return no_root_proven(A, est.vertex, [&](double c) { return local_near<SigmaZ, R>(f, c); });
    double estimate[2] = {est.root[0], est.root[1]};
    if (estimate[1] < estimate[0]) std::swap(estimate[0], estimate[1]);
    // Both roots at once when both are needed; otherwise the second only if the first is not kept.
    Local local[2];
    bool both = R == Residual::double_double && query.need == Need::all;
    if (both) local_at<SigmaZ>(f, estimate, local);
    for (int i = 0; i < 2; ++i) {
        if (!both) local[i] = local_near<SigmaZ, R>(f, estimate[i]);
        std::optional<Enclosure> en = root_near(local[i], A, estimate[i]);
        if (!en || en->smaller != (i == 0)) return false;
        int inside = kept(f, unit, *en);
        if (inside < 0) return false;
        if (inside == 0) continue;
        if (!add_hit<Target>(*en, unit, caller, query, r)) return false;
        if (query.need != Need::all) break; // the smaller root first: also the nearest
    }
    return true;
}

// ---- The hit test ----

// Any root proven inside the extent and the range is a hit, whichever it is: the first one
// found is the answer. No hit needs both roots proven outside, or none proven real.
template <int SigmaZ>
bool hit_test(const LineForm& f, const Unit& unit, Result& r) {
    Leading A = leading<SigmaZ>(f);
    if (!(std::fabs(A.A) > A.e)) return false;
    auto local = [&](double c) { return quick_local_at<SigmaZ>(f, c); };
    Estimates est = estimates<SigmaZ>(f, A);
    if (!est.real) return no_root_proven(A, est.vertex, local); // r has no hit
    bool outside[2] = {false, false}; // the smaller, the larger root proven outside
    for (double c : est.root) {
        std::optional<Enclosure> en = root_near(local(c), A, c);
        if (!en) continue;
        int inside = kept(f, unit, *en);
        if (inside == 1) {
            // t = c + x rounded once: within e + u |t| of the root (the sum's rounding).
            double t = en->c + en->x;
            r.hits[0] = {t,
                         {},
                         (en->e + u * std::fabs(t)) * F::cover(8) + F::denorm_min,
                         HitKind::cross,
                         Part::lateral,
                         true};
            r.count = 1;
            return true;
        }
        if (inside == 0) outside[en->smaller ? 0 : 1] = true;
    }
    return outside[0] && outside[1];
}

} // namespace

bool hit_test_rung(const LineForm& f, const Unit& unit, Result& r) {
    switch (f.sigma_z) {
    case 1:
        return hit_test<1>(f, unit, r);
    case 0:
        return hit_test<0>(f, unit, r);
    default:
        return hit_test<-1>(f, unit, r);
    }
}

template <class Target, Residual R>
bool newton_rung(const LineForm& f, const Unit& unit, const Line& caller, Query query, Result& r) {
    switch (f.sigma_z) {
    case 1:
        return solve<1, Target, R>(f, unit, caller, query, r);
    case 0:
        return solve<0, Target, R>(f, unit, caller, query, r);
    default:
        return solve<-1, Target, R>(f, unit, caller, query, r);
    }
}

template bool newton_rung<Binary64, Residual::double_double>(const LineForm&, const Unit&,
                                                             const Line&, Query, Result&);
template bool newton_rung<Binary32, Residual::double_double>(const LineForm&, const Unit&,
                                                             const Line&, Query, Result&);
template bool newton_rung<Binary32, Residual::quick>(const LineForm&, const Unit&, const Line&,
                                                     Query, Result&);

} // namespace linequad::detail
