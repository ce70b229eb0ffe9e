// Root algebra shared by the fast solvers. Shape-specific geometry stays in each shape's file.
#pragma once

#include "linequad/bounded.hpp"
#include "linequad/eft.hpp"
#include "linequad/line_quadratic.hpp"
#include "support.hpp"

#include <algorithm>
#include <cmath>

namespace linequad::detail {

// What a quadratic A t^2 + (linear) t + C = 0 has, before any extent or range test.
struct Roots {
    enum Kind { none, one, two, tangent, on_surface } kind = none;
    double t[2] = {0, 0};
    // After shift_back: each root's parameter from the moved origin (s = t - tc, not rounded
    // through t), and whether t came from Vieta (a root near the caller's origin).
    double s[2] = {0, 0};
    bool from_vieta[2] = {false, false};
};

// The seed documents' last step, a t^2 + b t + c = 0 solved as written ((-b +- sqrt(b^2-4ac))/2a),
// with erratum 6 fixed: a = 0 is linear (b != 0) or identically zero (the line on the surface).
inline Roots textbook_roots(double a, double b, double c) {
    Roots r;
    if (a == 0) {
        if (b != 0)
            r.kind = Roots::one, r.t[0] = -c / b;
        else if (c == 0)
            r.kind = Roots::on_surface;
        return r;
    }
    double disc = b * b - 4 * a * c;
    if (disc < 0) return r;
    if (disc == 0) {
        r.kind = Roots::tangent, r.t[0] = -b / (2 * a);
        return r;
    }
    double sq = std::sqrt(disc);
    r.kind = Roots::two;
    r.t[0] = (-b - sq) / (2 * a);
    r.t[1] = (-b + sq) / (2 * a);
    return r;
}

// Roots t = tc + s of a quadratic whose origin was moved by tc. The root of larger magnitude
// is tc + s with no cancellation. The other, when tc + s cancelled (|t| < |tc| / 2), comes from
// Vieta, t_near = product / t_far, where product() = C0 / A is formed at the caller's origin;
// otherwise its error is at most an ulp of tc <= 2 ulps of t and it stands. Either way both
// roots are accurate to a few ulps, and product() is only computed when it is needed.
template <class Product>
void shift_back(Roots& r, double tc, Product product) {
    r.s[0] = r.t[0], r.s[1] = r.t[1];
    if (r.kind == Roots::one || r.kind == Roots::tangent) r.t[0] += tc;
    if (r.kind != Roots::two) return;
    r.t[0] = tc + r.s[0], r.t[1] = tc + r.s[1];
    int far = std::fabs(r.t[0]) >= std::fabs(r.t[1]) ? 0 : 1, near = 1 - far;
    if (r.t[far] != 0 && std::fabs(r.t[near]) < 0.5 * std::fabs(tc)) {
        r.t[near] = product() / r.t[far];
        r.from_vieta[near] = true;
    }
}

// A t^2 + 2 B t + C = 0 (half-b form) solved without cancellation: the discriminant D = B^2 - AC
// is supplied by the caller in a geometric form that is accurate near tangency, and the roots
// are the stable pair q / A, C / q with q = -(B + sign(B) sqrt(D)).
inline Roots stable_roots(double A, double B, double C, double D) {
    Roots r;
    if (A == 0) {
        if (B != 0)
            r.kind = Roots::one, r.t[0] = -C / (2 * B);
        else if (C == 0)
            r.kind = Roots::on_surface;
        return r;
    }
    if (D < 0) return r;
    if (D == 0) {
        r.kind = Roots::tangent, r.t[0] = -B / A;
        return r;
    }
    double q = -(B + std::copysign(std::sqrt(D), B));
    double t0 = q / A, t1 = C / q;
    r.kind = Roots::two;
    r.t[0] = std::min(t0, t1), r.t[1] = std::max(t0, t1);
    return r;
}

// True when a decision rests on a zero or a near-underflow that underflow may have produced
// (see has_tiny_component): the solver must refuse.
// fragile() is only asked when a decision rests on a zero (rare), so it may cost a little.
template <class Fragile>
bool undecidable(const Roots& r, Fragile fragile, double A, double D) {
    if (underflow_zone(A) || underflow_zone(D)) return true;
    bool rests_on_zero =
        A == 0 || D == 0 || r.kind == Roots::on_surface || r.kind == Roots::tangent;
    return rests_on_zero && fragile();
}

// The seed solvers do not prescale: the same guard, with the raw inputs' own magnitudes. A
// scene whose nonzero components span more than 2^480 cannot decide a zero in double.
inline bool seed_undecidable(const Roots& r, double a, double disc,
                             std::initializer_list<Vec3> inputs) {
    double largest = 0;
    for (Vec3 u : inputs)
        largest = std::max(largest, max_abs(u));
    bool fragile = false;
    for (Vec3 u : inputs)
        for (int i = 0; i < 3; ++i)
            if (u[i] != 0 && std::fabs(u[i]) < min_relative_size * largest) fragile = true;
    bool extreme = largest > 0x1p+240 || largest < 0x1p-240;
    return undecidable(
               r, [&] { return fragile || extreme; }, a, disc) ||
           (extreme && underflow_zone(disc));
}

// Turns roots into candidates (t scaled back by t_scale, z_of(roots, i) the axial coordinate
// of root i) and finishes. Lines on the surface never get here: see without_certification.
template <class AxialOf>
Result finish_roots(const Roots& r, double t_scale, AxialOf z_of, Extent e, const Line& l,
                    Query q) {
    Candidate c[2];
    int n = 0;
    HitKind kind = r.kind == Roots::tangent ? HitKind::tangent : HitKind::cross;
    int count = r.kind == Roots::one       ? 1
                : r.kind == Roots::two     ? 2
                : r.kind == Roots::tangent ? 1
                                           : 0;
    for (int i = 0; i < count; ++i)
        c[n++] = {r.t[i] * t_scale, kind, z_of(r, i)};
    return finish(c, n, e, l, q);
}

// The scalar stable solve around a shape's core k (cylinder_stable.hpp, elliptic_stable.hpp):
// the branches that the batch kernels send back here. `parallel_first`: the cylinders, whose
// A = 0 (a line along the axis) means no hit or a line on the surface; for the cone A = 0 is a
// line along a generator, a linear equation that stable_roots solves. on_surface() supplies the
// certified result (a claim of infinitely many hits needs proof); z_of(k, roots, i) is root i's
// axial coordinate.
template <class Core, class Fragile, class OnSurface, class AxialOf>
Result stable_solve(Core& k, bool parallel_first, Fragile fragile, OnSurface on_surface,
                    AxialOf z_of, double t_scale, Extent e, const Line& l, Query q,
                    const char* field) {
    Roots roots;
    if (parallel_first && k.A == 0) {
        double C0 = k.C0_at_origin();
        roots.kind = C0 == 0 ? Roots::on_surface : Roots::none;
        if (undecidable(roots, fragile, k.A, C0))
            return Result::failure(ErrorCode::out_of_range, field);
        return roots.kind == Roots::on_surface ? on_surface() : Result{};
    }
    k.discriminant();
    roots = stable_roots(k.A, k.B, k.Cc, k.D);
    if (undecidable(roots, fragile, k.A, k.D) || (k.A == 0 && fragile()))
        return Result::failure(ErrorCode::out_of_range, field);
    if (roots.kind == Roots::on_surface) return on_surface();
    shift_back(roots, k.tc, [&] { return k.C0_at_origin() / k.A; });
    return finish_roots(
        roots, t_scale, [&](const Roots& r, int i) { return z_of(k, r, i); }, e, l, q);
}

// A result from the certified rung, presented as an uncertified one (no bounds, no claims):
// how stable settles the rare cases where its rounded zeros would otherwise claim that a line
// lies on the surface (infinitely many hits) without proof.
inline Result without_certification(Result r) {
    r.certainty = Certainty::unknown;
    for (Hit& h : r.hits)
        h.bound = std::numeric_limits<double>::quiet_NaN(), h.certain = false;
    return r;
}

// ---- The certified rung: the same quadratic with rigorous bounds on every quantity. ----
// Each piece is a template over the bounded type BT: QuickBounded (the first try) or Bounded
// (exact zeros kept exact; the degenerate cases), see bounded.hpp.

// A s^2 + 2 B s + C = 0 in the moved parameter s, with D = B^2 - A C supplied in the shape's
// geometric form; every term carries its bound.
template <class BT>
struct BoundedQuadratic {
    BT A, B, C, D;
};

template <class BT>
struct CertifiedRoot {
    BT s;
    HitKind kind;
    bool certain; // existence and kind proven
};

template <class BT>
struct CertifiedRoots {
    int count = 0;
    CertifiedRoot<BT> root[2];
    bool on_surface = false;
    bool certain = true; // the classification (count, kinds, interval) is proven
};

template <class BT>
bool exactly_zero(BT x) {
    return x.v == 0 && x.e == 0;
}

// Each decision is taken only on a certain sign. Where one is not certain the result is marked
// uncertain, and the roots it reports (if any) carry bounds that cover every possibility.
template <class BT>
CertifiedRoots<BT> certified_roots(const BoundedQuadratic<BT>& q) {
    CertifiedRoots<BT> r;
    if (exactly_zero(q.A)) { // linear or identically zero: A = 0 is exact here
        if (exactly_zero(q.B)) {
            r.on_surface = exactly_zero(q.C);
            r.certain = r.on_surface || q.C.certain_sign() != 0;
            return r;
        }
        r.certain = q.B.certain_sign() != 0;
        if (r.certain) r.root[r.count++] = {-q.C / (BT::exact(2) * q.B), HitKind::cross, true};
        return r;
    }
    if (q.A.certain_sign() == 0) { // nearly parallel: a root may be arbitrarily far
        r.certain = false;
        return r;
    }
    switch (q.D.certain_sign()) {
    case -1:
        return r;
    case 1: {
        BT sq = sqrt(q.D);
        BT qq = -(q.B + (q.B.v < 0 ? -sq : sq));
        r.root[r.count++] = {qq / q.A, HitKind::cross, true};
        r.root[r.count++] = {q.C / qq, HitKind::cross, true};
        if (r.root[1].s.v < r.root[0].s.v) std::swap(r.root[0], r.root[1]);
        return r;
    }
    default: {
        BT mid = -q.B / q.A;
        if (exactly_zero(q.D)) {
            r.root[r.count++] = {mid, HitKind::tangent, true};
            return r;
        }
        // D's sign is unknown: no root, a double root, or two close ones. Report the double root
        // with a bound that covers the two roots there may be: |s - mid| <= sqrt(max D) / |A|.
        r.certain = false;
        double spread =
            std::sqrt(std::fmax(q.D.v + q.D.bound(), 0.0)) / (std::fabs(q.A.v) - q.A.bound());
        mid.e = mid.bound() * (1 + 0x1p-49) + spread * (1 + 0x1p-49);
        r.root[r.count++] = {mid, HitKind::tangent, false};
        return r;
    }
    }
}

// The exact moved origin w + tc v (w = hi + lo exactly), with the bound of its two roundings.
template <class BT>
BT moved_origin_bounded(double hi, double lo, double tc, double v) {
    double x = std::fma(tc, v, hi), y = x + lo;
    return {y, (std::fabs(x) + std::fabs(y)) * 0x1p-53 * (1 + 0x1p-49) + 0x1p-1060};
}

template <class BT>
using BoundedVec3 = Vec3T<BT>;
template <class BT>
BoundedVec3<BT> exact(Vec3 a) {
    return {BT::exact(a.x), BT::exact(a.y), BT::exact(a.z)};
}
// An exact difference p - q, as hi with the bound |lo|.
template <class BT>
BoundedVec3<BT> difference_bounded(Vec3 p, Vec3 q) {
    Vec3TwoTerm d = difference_exact(p, q);
    return {{d.hi.x, std::fabs(d.lo.x)}, {d.hi.y, std::fabs(d.lo.y)}, {d.hi.z, std::fabs(d.lo.z)}};
}
template <class BT>
BoundedVec3<BT> moved_origin_bounded(const Vec3TwoTerm& w, double tc, Vec3 v) {
    if (tc == 0) // not moved: w = hi + lo exactly, so hi is within |lo|
        return {
            {w.hi.x, std::fabs(w.lo.x)}, {w.hi.y, std::fabs(w.lo.y)}, {w.hi.z, std::fabs(w.lo.z)}};
    return {moved_origin_bounded<BT>(w.hi.x, w.lo.x, tc, v.x),
            moved_origin_bounded<BT>(w.hi.y, w.lo.y, tc, v.y),
            moved_origin_bounded<BT>(w.hi.z, w.lo.z, tc, v.z)};
}

// t = tc + s in the caller's units: exact scaling by a power of two, unless the result falls
// below the normal range, where it rounds: then the bound grows by a subnormal ulp.
template <class BT>
BT caller_t(double tc, const BT& s, double t_scale) {
    BT t = BT::exact(tc) + s;
    double v = t.v * t_scale, e = t.bound() * t_scale;
    if (std::fabs(v) < 0x1p-1020 && (t.v != 0 || t.e != 0)) e += 0x1p-1074;
    return {v, e};
}

// Candidates (t in the caller's units, its axial coordinate) to a Result: a hit is kept when its
// computed value is inside the extent and the range, and is certain when the root is and every
// one of those signs is; the result is certain when every decision, kept or not, is.
template <class BT>
struct CertifiedCandidate {
    BT t, z;
    HitKind kind;
    bool certain;
};
template <class BT>
Result finish_certified(CertifiedCandidate<BT>* c, int n, bool classification_certain, Extent e,
                        const Line& l, Query q);

// The last step of every certified solve: the roots s (moved by tc), their axial coordinate
// z0 + s dz, and the result; a line on the surface only from exact zeros (certified_roots).
template <class BT>
Result certified_result(const CertifiedRoots<BT>& cr, double tc, BT z0, BT dz, double t_scale,
                        Extent e, const Line& l, Query q) {
    if (cr.on_surface) {
        Result r = finish_on_surface(z0.v - tc * dz.v, dz.v, t_scale, e, l);
        r.certainty = Certainty::certain;
        return r;
    }
    CertifiedCandidate<BT> c[2];
    for (int i = 0; i < cr.count; ++i)
        c[i] = {caller_t(tc, cr.root[i].s, t_scale), z0 + cr.root[i].s * dz, cr.root[i].kind,
                cr.root[i].certain};
    return finish_certified(c, cr.count, cr.certain, e, l, q);
}

// The certified solve: solve(QuickBounded()) first; again in Bounded when that leaves anything
// uncertain (or fails), so that exact zeros can decide. Both compute the same values.
template <class Solve>
Result certified_solve(Solve solve) {
    Result r = solve(QuickBounded());
    if (r.error.code != ErrorCode::none || r.certainty != Certainty::certain) r = solve(Bounded());
    return r; // one named result: returned in place, not copied
}

// M^-1 of the elliptic shapes' frame in bounded arithmetic: the exact form's adjugate rows
// (line_quadratic.hpp), over the determinant.
template <class BT>
struct BoundedDualFrame : exact_form::AdjugateFrame<BT> {
    using exact_form::AdjugateFrame<BT>::AdjugateFrame;
    BoundedVec3<BT> local(const BoundedVec3<BT>& u) const {
        BoundedVec3<BT> s = this->scaled_local(u);
        return {s.x / this->det, s.y / this->det, s.z / this->det};
    }
};

} // namespace linequad::detail
