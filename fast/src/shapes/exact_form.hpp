// The exact classification of a line against any shape, as one template over the number type.
// Each shape's derivation (shapes/*.hpp, exact_quadratic()) turns it into one quadratic in the
// line's parameter whose coefficients are polynomials in the double inputs, plus the axial
// coordinate that the extent test needs. Nothing here divides, takes a root or rounds.
//
// The number type NT needs NT(double) (exact), +, -, * and a sign(const NT&) found by
// argument-dependent lookup. Three instantiate it:
//  - CGAL::Mpzf in robust/ (the oracle): exact ring arithmetic, every sign decided;
//  - BigFloat in fast/ (the correct solver's exact rung): the same, without GMP;
//  - BoundedDD in fast/ (the correct solver's double-double rung): a filter, whose sign is
//    `undecided` when its error bound cannot exclude zero; classify() then says so and the
//    caller moves to an exact type.
//
// Roots are kept as t = (N + S sqrt(D)) / Den with S in {-1, 0, +1}:
//   A != 0, D > 0:  N = -B, S = -1 and +1, Den = A   (two crossings)
//   A != 0, D = 0:  N = -B, S = 0,         Den = A   (tangent: double root)
//   A = 0, B != 0:  N = -C0, S = 0,        Den = 2B  (one crossing: parallel to a generator)
//   A = B = 0:      on the surface if C0 = 0, else no hit
// and every test on a root (inside the extent, inside the range) is the sign of an X + Y sqrt(D).
#pragma once

#include "numeric/vector.hpp"

#include "linequad/result.hpp"
#include "linequad/shapes.hpp"

#include <cstdint>

namespace linequad::exact_form {

// What sign() returns when a filtered number type cannot decide.
inline constexpr int undecided = 2;

// A t^2 + 2 B t + C0 = 0 along the line, and Z(t) = Z0 + t dZ with the extent lo <= Z <= hi.
template <class NT>
struct LineQuadratic {
    NT A, B, C0;
    NT Z0, dZ, lo, hi;
    bool lo_bounded = true, hi_bounded = true;
};

template <class NT>
Vec3T<NT> lift(Vec3 p) {
    return {NT(p.x), NT(p.y), NT(p.z)};
}

// The line's range t0 <= t <= t1 in NT (ends exact: doubles, possibly scaled by a power of two).
template <class NT>
struct ParameterRange {
    bool has_t0 = false, has_t1 = false;
    bool t0_zero = false; // t >= 0: the sign of t itself, no product needed
    NT t0, t1;
};
template <class NT>
ParameterRange<NT> parameter_range(Interval r) {
    ParameterRange<NT> p;
    p.has_t0 = r.has_t0(), p.has_t1 = r.has_t1();
    p.t0_zero = p.has_t0 && r.t0 == 0;
    if (p.has_t0) p.t0 = NT(r.t0);
    if (p.has_t1) p.t1 = NT(r.t1);
    return p;
}

// sgn(X + Y sqrt(D)) given sy = sgn(Y sqrt(D)) and Y2D = Y^2 D, or undecided. When X and Y
// differ in sign, |X| is compared with |Y| sqrt(D) through X^2 - Y^2 D.
template <class NT>
int sign_surd(const NT& X, int sy, const NT& Y2D) {
    int sx = sign(X);
    if (sx == undecided || sy == undecided) return undecided;
    if (sy == 0) return sx;
    if (sx == 0 || sx == sy) return sy;
    int cmp = sign(NT(X * X - Y2D));
    if (cmp == undecided) return undecided;
    return cmp > 0 ? sx : cmp < 0 ? sy : 0;
}

// sgn(X + Y sqrt(D)) for D >= 0, or undecided.
template <class NT>
int sign_surd(const NT& X, const NT& Y, const NT& D) {
    int sd = sign(D);
    if (sd == undecided) return undecided;
    int sy = sd == 0 ? 0 : int(sign(Y));
    if (sy == 0 || sy == undecided) return sign_surd(X, sy, X); // Y2D unused
    return sign_surd(X, sy, NT(Y * Y * D));
}

// sgn(X + Y sqrt(D)) for one D. Exact types compare squares (sign_surd); a filtered type may
// specialise it to evaluate X + Y sqrt(D) with sqrt(D) computed once.
template <class NT>
struct SurdSign {
    NT D;
    explicit SurdSign(const NT& d) : D(d) {}
    int operator()(const NT& X, const NT& Y) const { return sign_surd(X, Y, D); }
};

// t = (N + S sqrt(D)) / Den.
template <class NT>
struct SurdRoot {
    NT N, Den;
    int S = 0;
    HitKind kind = HitKind::cross;
};

// An end of the on-surface interval: num / den with den > 0, or unbounded.
template <class NT>
struct Fraction {
    bool bounded = false;
    NT num, den;
};

enum class Outcome : std::uint8_t { none, hits, on_surface, undecided };

template <class NT>
struct Classification {
    Outcome outcome = Outcome::none;
    NT D;          // B^2 - A C0 (zero for a single rational root)
    int count = 0; // hits: roots[0..count) kept, by increasing t, as the query needs
    SurdRoot<NT> roots[2];
    Fraction<NT> s0, s1; // on_surface: the interval of t
};

namespace detail {

// Z(t) within [lo, hi]: Z(t) - lo = (Den (Z0 - lo) + dZ N + S dZ sqrt(D)) / Den, and so on.
template <class NT>
int in_extent(const SurdRoot<NT>& r, const SurdSign<NT>& surd, const LineQuadratic<NT>& q,
              int sden) {
    NT SdZ = r.S > 0 ? q.dZ : r.S < 0 ? NT(-q.dZ) : NT(0);
    if (q.lo_bounded) {
        int s = surd(NT(r.Den * (q.Z0 - q.lo) + q.dZ * r.N), SdZ);
        if (s == undecided) return undecided;
        if (s * sden < 0) return 0;
    }
    if (q.hi_bounded) {
        int s = surd(NT(r.Den * (q.hi - q.Z0) - q.dZ * r.N), NT(-SdZ));
        if (s == undecided) return undecided;
        if (s * sden < 0) return 0;
    }
    return 1;
}

// t0 <= t <= t1: t - t0 = (N - Den t0 + S sqrt(D)) / Den, t1 - t = (Den t1 - N - S sqrt(D)) / Den.
template <class NT>
int in_range(const SurdRoot<NT>& r, const SurdSign<NT>& surd, const ParameterRange<NT>& range,
             int sden) {
    NT S(r.S);
    if (range.has_t0) {
        int s = range.t0_zero ? surd(r.N, S) : surd(NT(r.N - r.Den * range.t0), S);
        if (s == undecided) return undecided;
        if (s * sden < 0) return 0;
    }
    if (range.has_t1) {
        int s = surd(NT(r.Den * range.t1 - r.N), NT(-S));
        if (s == undecided) return undecided;
        if (s * sden < 0) return 0;
    }
    return 1;
}

// x < y for two bounded ends, or undecided.
template <class NT>
int less(const Fraction<NT>& x, const Fraction<NT>& y) {
    int s = sign(NT(y.num * x.den - x.num * y.den));
    return s == undecided ? undecided : s > 0;
}

// The line on the surface: Z(t) = Z0 + t dZ within the extent and t within the range.
template <class NT>
Classification<NT> on_surface(const LineQuadratic<NT>& q, const ParameterRange<NT>& range) {
    Classification<NT> c;
    c.outcome = Outcome::undecided;
    int sdz = sign(q.dZ);
    if (sdz == undecided) return c;
    auto frac = [&](const NT& num) {
        Fraction<NT> f{true, num, q.dZ};
        if (sdz < 0) f.num = -f.num, f.den = -f.den;
        return f;
    };
    Fraction<NT> a = q.lo_bounded ? frac(NT(q.lo - q.Z0)) : Fraction<NT>{false, NT(0), NT(1)};
    Fraction<NT> b = q.hi_bounded ? frac(NT(q.hi - q.Z0)) : Fraction<NT>{false, NT(0), NT(1)};
    // Which bound of Z limits t from below depends on the direction dZ.
    Fraction<NT> lo = sdz > 0 ? a : b, hi = sdz > 0 ? b : a;
    if (range.has_t0) {
        Fraction<NT> first{true, range.t0, NT(1)};
        int below = lo.bounded ? less(lo, first) : 1;
        if (below == undecided) return c;
        if (below) lo = first;
    }
    if (range.has_t1) {
        Fraction<NT> last{true, range.t1, NT(1)};
        int above = hi.bounded ? less(last, hi) : 1;
        if (above == undecided) return c;
        if (above) hi = last;
    }
    if (lo.bounded && hi.bounded) {
        int empty = less(hi, lo);
        if (empty == undecided) return c;
        if (empty) return c.outcome = Outcome::none, c;
    }
    c.outcome = Outcome::on_surface;
    c.s0 = lo, c.s1 = hi;
    return c;
}

} // namespace detail

// Which roots of q are hits of a line over `range`, in the order of t, as many as `need` asks
// for; or the on-surface interval; or undecided (only for a filtered NT).
template <class NT>
Classification<NT> classify(const LineQuadratic<NT>& q, const ParameterRange<NT>& range,
                            Need need) {
    Classification<NT> c;
    c.outcome = Outcome::undecided;
    int sa = sign(q.A);
    if (sa == undecided) return c;
    SurdRoot<NT> roots[2];
    int n = 0, sden = sa; // the sign of the roots' Den: A, or 2B
    if (sa == 0) {
        int sb = sign(q.B);
        if (sb == undecided) return c;
        if (sb == 0) {
            int sc = sign(q.C0);
            if (sc == undecided) return c;
            if (sc == 0) return detail::on_surface(q, range);
            return c.outcome = Outcome::none, c;
        }
        c.D = NT(0);
        sden = sb;
        roots[n++] = {-q.C0, NT(2) * q.B, 0, HitKind::cross};
    } else {
        c.D = q.B * q.B - q.A * q.C0;
        int sd = sign(c.D);
        if (sd == undecided) return c;
        if (sd > 0) {
            int first = sa > 0 ? -1 : 1; // the smaller root first
            roots[n++] = {-q.B, q.A, first, HitKind::cross};
            roots[n++] = {-q.B, q.A, -first, HitKind::cross};
        } else if (sd == 0) {
            roots[n++] = {-q.B, q.A, 0, HitKind::tangent};
        } else {
            return c.outcome = Outcome::none, c;
        }
    }
    SurdSign<NT> surd(c.D);
    for (int i = 0; i < n; ++i) {
        int inside = detail::in_extent(roots[i], surd, q, sden);
        if (inside == 1) inside = detail::in_range(roots[i], surd, range, sden);
        if (inside == undecided) return c;
        if (!inside) continue;
        c.roots[c.count++] = roots[i];
        if (need != Need::all) break;
    }
    c.outcome = c.count > 0 ? Outcome::hits : Outcome::none;
    return c;
}

} // namespace linequad::exact_form
