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
//
// A closed shape (caps on) adds its end discs. Q(t) = A t^2 + 2 B t + C0 is negative inside the
// lateral surface (within the nappe) in every shape's form, so the disc at the end Z = e is
// {Z = e, Q <= 0}: the line meets it at t = (e - Z0) / dZ, a rational root (N = e - Z0,
// Den = dZ, S = 0), when A N^2 + 2 B N Den + C0 Den^2 <= 0 (Q times Den^2). A lateral root counts
// where it is strictly inside a capped end (a rim belongs to its disc). Each solid (the shape,
// or each nappe of a closed two-nappe cone) is convex, so the line meets its boundary at the two
// ends of a segment or touches it at one point: a point is `cross` when it ends a segment of
// exactly one solid, `tangent` when it is a solid's only point or the apex two solids share. A
// line in a disc's plane meets the closed shape in the chord Q <= 0 of that disc: an interval
// with ends (-B -+ sqrt(D)) / A, or the one point where it grazes the rim.
#pragma once

#include "numeric/bounded_dd.hpp"
#include "numeric/vector.hpp"

#include "linequad/result.hpp"
#include "linequad/shapes.hpp"

#include <cstdint>
#include <utility>

namespace linequad::exact_form {

// What sign() returns when a filtered number type cannot decide.
inline constexpr int undecided = undecided_sign;

// Z(t) = Z0 + t dZ along the line, with the extent lo <= Z <= hi where bounded: all that an
// end's crossing and the point there need, for a few products where the quadratic takes dozens
// (each shape's exact_axial gives these same values, in the same units, alone).
template <class NT>
struct LineAxial {
    NT Z0, dZ, lo, hi;
    bool lo_bounded = true, hi_bounded = true;
};

// A t^2 + 2 B t + C0 = 0 along the line, and its extent.
template <class NT>
struct LineQuadratic : LineAxial<NT> {
    NT A, B, C0;
    // Discs at the bounded ends (lo: base, hi: top), and two solids meeting at Z = 0.
    bool lo_capped = false, hi_capped = false, two_solids = false;
    // Bounded ends that another part owns (a capsule's side at its seams): a root exactly there
    // is not kept, as at a capped end, but no disc closes it.
    bool lo_open = false, hi_open = false;
};

template <class NT>
Vec3T<NT> lift(Vec3 p) {
    return {NT(p.x), NT(p.y), NT(p.z)};
}

// A line through a point given in NT (exactly, or enclosed: a point of a line moved along it), for
// an exact form at that point rather than at the line's own origin: the shapes' exact_quadratic
// take either line.
template <class NT>
struct LineThrough {
    Vec3T<NT> L0;
    Vec3 v;
    Vec3 line_L0; // the line's own origin (where a coincident surface's g is 0)
};
// g's local quadratic at a point t of the line, g(t + x) = A x^2 + 2 half_slope x + G, enclosed:
// what a shape gives where it has a cheaper form of it than its exact quadratic (a sphere's).
struct LocalQuadratic {
    BoundedDD A, half_slope, G;
};

// The line's origin in NT.
template <class NT>
Vec3T<NT> origin(const Line& l) {
    return lift<NT>(l.L0);
}
template <class NT>
const Vec3T<NT>& origin(const LineThrough<NT>& l) {
    return l.L0;
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

// A root of some quadratic, (N + S sqrt(D)) / Den, its parts where they are kept.
template <class NT>
struct SurdView {
    const NT& N;
    int S;
    const NT& Den;
    const NT& D;
};

// sgn(a - b) for roots of two quadratics, in an exact number type. With sigma = sgn(Den_a Den_b),
//     sgn(a - b) = sigma sgn(P + Q),  P = A + B sqrt(D_a),  Q = C sqrt(D_b),
//     A = N_a Den_b - N_b Den_a,  B = S_a Den_b,  C = -S_b Den_a;
// P and Q of one sign: the sum has it; of opposite signs, the larger in magnitude wins:
//     sgn(P^2 - Q^2) = sgn((A^2 + B^2 D_a - C^2 D_b) + 2 A B sqrt(D_a)).
// The scene's exact order (fast/, BigFloat) and the oracle's (robust/, Mpzf) are this.
template <class NT>
int compare_roots(SurdView<NT> a, SurdView<NT> b) {
    int sigma = sign(a.Den) * sign(b.Den);
    NT A = a.N * b.Den - b.N * a.Den;
    NT B = NT(double(a.S)) * b.Den, C = NT(double(-b.S)) * a.Den;
    int sp = sign_surd(A, B, a.D);
    int sq = sign(b.D) == 0 ? 0 : int(sign(C));
    if (sq == 0) return sigma * sp;
    if (sp == 0 || sp == sq) return sigma * sq;
    int larger = sign_surd(NT(A * A + B * B * a.D - C * C * b.D), NT(NT(2.0) * A * B), a.D);
    return sigma * (larger == 0 ? 0 : larger > 0 ? sp : sq);
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
    Part part = Part::lateral;
    // A disc's crossing, (end - Z0) / dZ; else a root of the quadratic (part names a disc there
    // too for a line in its plane grazing the rim).
    bool disc = false;
};

// The exact root that a filter's root (classified in a bounded or interval type) stands for,
// formed from the exact quadratic q as classify() formed it: a disc's crossing at
// (end - Z0) / dZ, a root of the quadratic at (-B + S sqrt(D)) / A, or -C0 / 2B where A = 0.
template <class NT, class Filtered>
SurdRoot<NT> exact_root(const LineQuadratic<NT>& q, const SurdRoot<Filtered>& r) {
    if (r.disc) return {(r.part == Part::base ? q.lo : q.hi) - q.Z0, q.dZ, 0, r.kind, r.part, true};
    if (sign(q.A) == 0) return {-q.C0, NT(2) * q.B, 0, r.kind, r.part};
    return {-q.B, q.A, r.S, r.kind, r.part};
}

// An end of the on-surface interval: (num + S sqrt(D)) / den with den > 0, or unbounded. S is 0
// but for a chord of a disc.
template <class NT>
struct Fraction {
    bool bounded = false;
    NT num, den;
    int S = 0;
};

enum class Outcome : std::uint8_t { none, hits, on_surface, undecided };

template <class NT>
struct Classification {
    Outcome outcome = Outcome::none;
    // B^2 - A C0 (zero for a single rational root, or none). Its sign is read by every surd
    // sign, even of a rational root (Y = 0): a number type whose default is uninitialised
    // (Interval_nt, without CGAL's assertions) would leave that sign to chance.
    NT D = NT(0);
    int count = 0; // hits: roots[0..count) kept, by increasing t, as the query needs
    SurdRoot<NT> roots[max_hits];
    Fraction<NT> s0, s1; // on_surface: the interval of t
    Part surface_part = Part::lateral;
};

namespace detail {

// Z(t) within [lo, hi]: Z(t) - lo = (Den (Z0 - lo) + dZ N + S dZ sqrt(D)) / Den, and so on; a
// capped end excludes its rim (it belongs to the disc), an open end its seam.
template <class NT>
int in_extent(const SurdRoot<NT>& r, const SurdSign<NT>& surd, const LineQuadratic<NT>& q,
              int sden) {
    NT SdZ = r.S > 0 ? q.dZ : r.S < 0 ? NT(-q.dZ) : NT(0);
    if (q.lo_bounded) {
        int s = surd(NT(r.Den * (q.Z0 - q.lo) + q.dZ * r.N), SdZ);
        if (s == undecided) return undecided;
        if (s * sden < 0 || ((q.lo_capped || q.lo_open) && s == 0)) return 0;
    }
    if (q.hi_bounded) {
        int s = surd(NT(r.Den * (q.hi - q.Z0) - q.dZ * r.N), NT(-SdZ));
        if (s == undecided) return undecided;
        if (s * sden < 0 || ((q.hi_capped || q.hi_open) && s == 0)) return 0;
    }
    return 1;
}

// sgn Z(t) at a root: which solid of a closed two-nappe cone it is on (0: the apex, both).
template <class NT>
int axial_sign(const SurdRoot<NT>& r, const SurdSign<NT>& surd, const LineQuadratic<NT>& q,
               int sden) {
    NT SdZ = r.S > 0 ? q.dZ : r.S < 0 ? NT(-q.dZ) : NT(0);
    int s = surd(NT(r.Den * q.Z0 + q.dZ * r.N), SdZ);
    return s == undecided ? undecided : s * sden;
}

// sgn(x - y) for two roots over one D: (Nx Dy - Ny Dx + (Sx Dy - Sy Dx) sqrt(D)) / (Dx Dy).
template <class NT>
int compare(const SurdRoot<NT>& x, int sx, const SurdRoot<NT>& y, int sy,
            const SurdSign<NT>& surd) {
    int s = surd(NT(x.N * y.Den - y.N * x.Den), NT(NT(x.S) * y.Den - NT(y.S) * x.Den));
    return s == undecided ? undecided : s * sx * sy;
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
    const Fraction<NT> unbounded{false, NT(0), NT(1)};
    Fraction<NT> lo = unbounded, hi = unbounded;
    if (sdz == 0) {
        // Z constant along the line (the radius coordinate of a frustum that is a cylinder):
        // the whole line is inside the extent, or none of it.
        int below = q.lo_bounded ? sign(NT(q.Z0 - q.lo)) : 1;
        int above = q.hi_bounded ? sign(NT(q.hi - q.Z0)) : 1;
        if (below == undecided || above == undecided) return c;
        if (below < 0 || above < 0) return c.outcome = Outcome::none, c;
    } else {
        Fraction<NT> a = q.lo_bounded ? frac(NT(q.lo - q.Z0)) : unbounded;
        Fraction<NT> b = q.hi_bounded ? frac(NT(q.hi - q.Z0)) : unbounded;
        // Which bound of Z limits t from below depends on the direction dZ.
        lo = sdz > 0 ? a : b, hi = sdz > 0 ? b : a;
    }
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

// A root at t = num / den, num / -den as the interval's end (den > 0).
template <class NT>
Fraction<NT> end_at(const SurdRoot<NT>& r, int sden) {
    if (sden > 0) return {true, r.N, r.Den, r.S};
    return {true, NT(-r.N), NT(-r.Den), -r.S};
}

// The line in the plane of a disc (dZ = 0, Z0 at a capped end): it meets the closed shape in
// the chord Q <= 0 of the disc. A > 0 there (v has no axial part, so Q's leading form is
// positive definite), and the chord is the interval between Q's roots, or the one point where
// the line grazes the rim (D = 0).
template <class NT>
Classification<NT> in_disc_plane(const LineQuadratic<NT>& q, const ParameterRange<NT>& range,
                                 Part part) {
    Classification<NT> c;
    c.outcome = Outcome::undecided;
    int sa = sign(q.A);
    if (sa == undecided) return c;
    if (sa <= 0) return c.outcome = Outcome::none, c; // not a line of a disc's plane
    c.D = q.B * q.B - q.A * q.C0;
    int sd = sign(c.D);
    if (sd == undecided) return c;
    if (sd < 0) return c.outcome = Outcome::none, c;
    SurdSign<NT> surd(c.D);
    if (sd == 0) {
        SurdRoot<NT> rim{-q.B, q.A, 0, HitKind::tangent, part};
        int inside = in_range(rim, surd, range, 1);
        if (inside == undecided) return c;
        c.outcome = Outcome::none;
        if (inside) c.roots[c.count++] = rim, c.outcome = Outcome::hits;
        return c;
    }
    SurdRoot<NT> lo{-q.B, q.A, -1}, hi{-q.B, q.A, 1};
    // Each end of the chord, or the range's end where that is nearer; empty when they cross.
    SurdRoot<NT> first = lo, last = hi; // every Den here is positive (A > 0, 1)
    if (range.has_t0) {
        SurdRoot<NT> t0{range.t0, NT(1)};
        int before = compare(lo, 1, t0, 1, surd);
        if (before == undecided) return c;
        if (before < 0) first = t0;
    }
    if (range.has_t1) {
        SurdRoot<NT> t1{range.t1, NT(1)};
        int after = compare(hi, 1, t1, 1, surd);
        if (after == undecided) return c;
        if (after > 0) last = t1;
    }
    int order = compare(first, 1, last, 1, surd);
    if (order == undecided) return c;
    if (order > 0) return c.outcome = Outcome::none, c;
    c.outcome = Outcome::on_surface;
    c.s0 = end_at(first, 1), c.s1 = end_at(last, 1);
    c.surface_part = part;
    return c;
}

// The closed shape's boundary points: the lateral roots kept (strictly inside a capped end),
// then the discs the line crosses, each with the sign of its Den; their kinds from the solids.
template <class NT>
bool close(const LineQuadratic<NT>& q, const SurdSign<NT>& surd, SurdRoot<NT>* roots, int* sden,
           int& n, int sdz) {
    if (sdz != 0) {
        auto disc = [&](const NT& end, Part part) {
            NT N = end - q.Z0;
            int inside = sign(NT((q.A * N + NT(2) * q.B * q.dZ) * N + q.C0 * q.dZ * q.dZ));
            if (inside == undecided) return false;
            if (inside <= 0) sden[n] = sdz, roots[n++] = {N, q.dZ, 0, HitKind::cross, part, true};
            return true;
        };
        if (q.lo_capped && !disc(q.lo, Part::base)) return false;
        if (q.hi_capped && !disc(q.hi, Part::top)) return false;
    }
    // Which solid each point is on (bit 0: Z <= 0, bit 1: Z >= 0, both at the apex), and how
    // many points each solid has.
    int solids[max_hits], count[2] = {0, 0};
    for (int i = 0; i < n; ++i) {
        if (!q.two_solids) {
            solids[i] = 1;
        } else if (roots[i].part != Part::lateral) {
            solids[i] = roots[i].part == Part::base ? 1 : 2;
        } else {
            int z = axial_sign(roots[i], surd, q, sden[i]);
            if (z == undecided) return false;
            solids[i] = z < 0 ? 1 : z > 0 ? 2 : 3;
        }
        for (int b = 0; b < 2; ++b)
            count[b] += (solids[i] >> b) & 1;
    }
    for (int i = 0; i < n; ++i) {
        bool one = solids[i] != 3;
        bool ends_segment = one && count[solids[i] == 1 ? 0 : 1] == 2;
        roots[i].kind = ends_segment ? HitKind::cross : HitKind::tangent;
    }
    // In order of t: at most four, so insertion.
    for (int i = 1; i < n; ++i)
        for (int j = i; j > 0; --j) {
            int order = compare(roots[j - 1], sden[j - 1], roots[j], sden[j], surd);
            if (order == undecided) return false;
            if (order <= 0) break;
            std::swap(roots[j - 1], roots[j]);
            std::swap(sden[j - 1], sden[j]);
        }
    return true;
}

} // namespace detail

// Which roots of q are hits of a line over `range`, in the order of t, as many as `need` asks
// for; or the on-surface interval; or undecided (only for a filtered NT). `given_D`, where the
// caller has it: B^2 - A C0 formed elsewhere (exactly, or enclosed from its exact value).
template <class NT>
Classification<NT> classify(const LineQuadratic<NT>& q, const ParameterRange<NT>& range, Need need,
                            const NT* given_D = nullptr) {
    Classification<NT> c;
    c.outcome = Outcome::undecided;
    bool closed = q.lo_capped || q.hi_capped;
    int sdz = 0;
    if (closed) {
        sdz = sign(q.dZ);
        if (sdz == undecided) return c;
        for (int end = 0; sdz == 0 && end < 2; ++end) {
            if (!(end == 0 ? q.lo_capped : q.hi_capped)) continue;
            int at = sign(NT(q.Z0 - (end == 0 ? q.lo : q.hi)));
            if (at == undecided) return c;
            if (at == 0) return detail::in_disc_plane(q, range, end == 0 ? Part::base : Part::top);
        }
    }
    int sa = sign(q.A);
    if (sa == undecided) return c;
    SurdRoot<NT> roots[max_hits];
    int sden[max_hits];
    int n = 0;
    if (sa == 0) {
        int sb = sign(q.B);
        if (sb == undecided) return c;
        if (sb == 0) {
            int sc = sign(q.C0);
            if (sc == undecided) return c;
            if (sc == 0) return detail::on_surface(q, range);
        } else {
            c.D = NT(0);
            sden[n] = sb, roots[n++] = {-q.C0, NT(2) * q.B, 0, HitKind::cross};
        }
    } else {
        c.D = given_D ? *given_D : NT(q.B * q.B - q.A * q.C0);
        int sd = sign(c.D);
        if (sd == undecided) return c;
        if (sd > 0) {
            int first = sa > 0 ? -1 : 1; // the smaller root first
            sden[n] = sa, roots[n++] = {-q.B, q.A, first, HitKind::cross};
            sden[n] = sa, roots[n++] = {-q.B, q.A, -first, HitKind::cross};
        } else if (sd == 0) {
            sden[n] = sa, roots[n++] = {-q.B, q.A, 0, HitKind::tangent};
        } else {
            c.D = NT(0); // no irrational root
        }
    }
    if (n == 0 && !closed) return c.outcome = Outcome::none, c;
    SurdSign<NT> surd(c.D);
    int kept = 0;
    for (int i = 0; i < n; ++i) {
        int inside = detail::in_extent(roots[i], surd, q, sden[i]);
        if (inside == undecided) return c;
        if (inside) sden[kept] = sden[i], roots[kept++] = roots[i];
    }
    n = kept;
    if (closed && !detail::close(q, surd, roots, sden, n, sdz)) return c;
    for (int i = 0; i < n; ++i) {
        int inside = detail::in_range(roots[i], surd, range, sden[i]);
        if (inside == undecided) return c;
        if (!inside) continue;
        c.roots[c.count++] = roots[i];
        if (need != Need::all) break;
    }
    c.outcome = c.count > 0 ? Outcome::hits : Outcome::none;
    return c;
}

} // namespace linequad::exact_form

// X + Y sqrt(D) evaluated, sqrt(D) once per quadratic: cheaper than squaring, and as decisive.
template <>
struct linequad::exact_form::SurdSign<linequad::BoundedDD> {
    BoundedDD root;
    explicit SurdSign(const BoundedDD& D) : root(sign(D) == 0 ? BoundedDD() : sqrt(D)) {}
    int operator()(const BoundedDD& X, const BoundedDD& Y) const { return sign(X + Y * root); }
};
