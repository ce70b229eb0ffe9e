// The certified solver's toolkit: the shapes' quadratics with a rigorous bound on every
// quantity, decided only on certain signs. Each piece is a template over the bounded type BT:
// QuickBounded (the first try) or Bounded (exact zeros kept exact; the degenerate cases), see
// numeric/bounded.hpp.
#pragma once

#include "forms/closure.hpp"
#include "forms/finish.hpp"
#include "forms/frame.hpp"
#include "numeric/bounded.hpp"
#include "numeric/eft.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace linequad::detail {

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
        mid.e = mid.bound() * Binary64::cover(16) + spread * Binary64::cover(16);
        r.root[r.count++] = {mid, HitKind::tangent, false};
        return r;
    }
    }
}

// The exact moved origin w + tc v (w = hi + lo exactly), with the bound of its two roundings.
template <class BT>
BT moved_origin_bounded(double hi, double lo, double tc, double v) {
    using F = Binary64;
    double x = std::fma(tc, v, hi), y = x + lo;
    return {y, (std::fabs(x) + std::fabs(y)) * F::u * F::cover(16) + F::underflow_floor};
}

template <class BT>
using BoundedVec3 = Vec3T<BT>;
template <class BT>
BoundedVec3<BT> moved_origin_bounded(const Vec3TwoTerm& w, double tc, Vec3 v) {
    if (tc == 0) return within_low_part<BT>(w); // not moved: hi is within |lo|
    return {moved_origin_bounded<BT>(w.hi.x, w.lo.x, tc, v.x),
            moved_origin_bounded<BT>(w.hi.y, w.lo.y, tc, v.y),
            moved_origin_bounded<BT>(w.hi.z, w.lo.z, tc, v.z)};
}

// Candidates (t in the caller's units, its axial coordinate) to a Result: a hit is kept when its
// computed value is inside the extent and the range, and is certain when the root is and every
// one of those signs is; the result is certain when every decision, kept or not, is.
template <class BT>
struct CertifiedCandidate {
    BT t, z;
    HitKind kind;
    bool certain;
    Part part = Part::lateral;
};
template <class BT>
Result finish_certified(CertifiedCandidate<BT>* c, int n, bool classification_certain, Extent e,
                        const Line& l, Query q) {
    Result r; // every return is of r: it is built in place
    for (int i = 0; i < n; ++i)
        if (!std::isfinite(c[i].t.v)) {
            fail(r, ErrorCode::out_of_range, "t");
            return r;
        }
    for (int i = 1; i < n; ++i) // at most four: insertion
        for (int j = i; j > 0 && c[j].t.v < c[j - 1].t.v; --j)
            std::swap(c[j], c[j - 1]);
    bool all_certain = classification_certain, points = q.points && q.need != Need::any;
    const Interval& range = l.range;
    for (int i = 0; i < n; ++i) {
        // Each test is a sign: certain when the bound excludes zero (or the value is exactly 0).
        bool certain = c[i].certain;
        bool inside = true;
        auto test = [&](BT x, bool strict = false) {
            inside = inside && (strict ? x.v > 0 : x.v >= 0);
            certain = certain && (x.certain_sign() != 0 || exactly_zero(x));
        };
        if (std::isfinite(e.lo)) test(c[i].z - BT::exact(e.lo), e.caps.open_lo);
        if (std::isfinite(e.hi)) test(BT::exact(e.hi) - c[i].z, e.caps.open_hi);
        // t >= 0 is the sign of t itself: subtracting an exact zero would only widen its bound.
        if (range.has_t0()) test(range.t0 == 0 ? c[i].t : c[i].t - BT::exact(range.t0));
        if (range.has_t1()) test(BT::exact(range.t1) - c[i].t);
        all_certain = all_certain && certain;
        if (!inside) continue;
        if (r.count > 0 && q.need != Need::all) continue;
        Hit& h = r.hits[r.count++];
        h.t = c[i].t.v;
        h.bound = c[i].t.bound();
        h.kind = c[i].kind;
        h.part = c[i].part;
        h.certain = certain;
        h.p = points ? point_at(l, h.t) : Vec3{};
        if (points && !is_finite(h.p)) {
            fail(r, ErrorCode::out_of_range, "p");
            return r;
        }
    }
    r.certainty = all_certain ? Certainty::certain : Certainty::uncertain;
    return r;
}

// A closed shape (caps on). A line in a disc's plane (proven by exact zeros) meets it in the
// chord between the quadratic's roots there, or grazes the rim; otherwise the lateral roots and
// the discs (solve/closure.hpp).
template <class BT>
[[gnu::noinline]] Result certified_closed(const CertifiedRoots<BT>& cr,
                                          const AxialQuadratic<BT>& aq, Extent e, const Line& l,
                                          Query q) {
    CertifiedCandidate<BT> c[max_hits];
    if (Part plane = plane_holding(aq, e); plane != Part::lateral) {
        BT end = exactly<BT>(plane == Part::base ? e.lo : e.hi);
        if (cr.count == 2) {
            double t0 = caller_t(aq.tc, cr.root[0].s, aq.t_scale).v;
            double t1 = caller_t(aq.tc, cr.root[1].s, aq.t_scale).v;
            Result r;
            r.certainty = cr.certain ? Certainty::certain : Certainty::uncertain;
            double s0 = std::max(t0, l.range.t0), s1 = std::min(t1, l.range.t1);
            if (!(s0 <= s1)) return r;
            if (!std::isfinite(t0) || !std::isfinite(t1)) {
                fail(r, ErrorCode::out_of_range, "t");
                return r;
            }
            r.on_surface = true, r.surface_part = plane;
            r.s0 = s0 + 0.0, r.s1 = s1; // +0, never -0, at t0 = 0
            return r;
        }
        for (int i = 0; i < cr.count; ++i)
            c[i] = {caller_t(aq.tc, cr.root[i].s, aq.t_scale), end, HitKind::tangent,
                    cr.root[i].certain, plane};
        return finish_certified(c, cr.count, cr.certain, e, l, q);
    }
    BoundaryPoint<BT> lateral[2];
    for (int i = 0; i < cr.count; ++i)
        lateral[i] = {caller_t(aq.tc, cr.root[i].s, aq.t_scale), aq.z0 + cr.root[i].s * aq.dz,
                      Part::lateral, cr.root[i].kind, cr.root[i].certain};
    ClosedPoints<BT> cp = close(lateral, cr.count, aq, e);
    for (int i = 0; i < cp.n; ++i)
        c[i] = {cp.p[i].t, cp.p[i].z, cp.p[i].kind, cp.p[i].certain, cp.p[i].part};
    return finish_certified(c, cp.n, cr.certain && cp.certain, e, l, q);
}

// What each shape's certified derivation gives: the quadratic in the parameter s moved by tc,
// and the axial coordinate z0 + s dz with its extent.
template <class BT>
struct CertifiedForm {
    BoundedQuadratic<BT> quad;
    double tc;
    BT z0, dz;
    Extent extent;
};

// The last step of every certified solve: the roots s (moved by tc), their axial coordinate
// z0 + s dz, and the result; a line on the surface only from exact zeros (certified_roots).
// t_scale: what prescaling did to t.
template <class BT>
Result certified_result(const CertifiedForm<BT>& f, double t_scale, const Line& l, Query q) {
    const BoundedQuadratic<BT>& quad = f.quad;
    const BT &z0 = f.z0, &dz = f.dz;
    double tc = f.tc;
    const Extent& e = f.extent;
    CertifiedRoots<BT> cr = certified_roots(quad);
    if (cr.on_surface) {
        Result r = finish_on_surface(z0.v - tc * dz.v, dz.v, t_scale, e, l);
        r.certainty = Certainty::certain;
        return r;
    }
    if (e.caps.any())
        return certified_closed(cr, {quad.A, BT::exact(2) * quad.B, quad.C, z0, dz, tc, t_scale}, e,
                                l, q);
    CertifiedCandidate<BT> c[2];
    for (int i = 0; i < cr.count; ++i)
        c[i] = {caller_t(tc, cr.root[i].s, t_scale), z0 + cr.root[i].s * dz, cr.root[i].kind,
                cr.root[i].certain};
    return finish_certified(c, cr.count, cr.certain, e, l, q);
}

// The certified solve: solve(QuickBounded()) first; again in Bounded when that leaves anything
// uncertain (or fails), so that exact zeros can decide. Both compute the same values.
template <class Solve>
Result quick_then_bounded(Solve solve) {
    Result r = solve(QuickBounded());
    if (!r.ok() || r.certainty != Certainty::certain) r = solve(Bounded());
    return r; // one named result: returned in place, not copied
}

// M^-1 of the elliptic shapes' frame in bounded arithmetic: the exact form's adjugate rows,
// over the determinant.
template <class BT>
struct BoundedDualFrame : exact_form::AdjugateFrame<BT> {
    using exact_form::AdjugateFrame<BT>::AdjugateFrame;
    LINEQUAD_INLINE BoundedVec3<BT> local(const BoundedVec3<BT>& u) const {
        BoundedVec3<BT> s = this->scaled_local(u);
        return {s.x / this->det, s.y / this->det, s.z / this->det};
    }
};

} // namespace linequad::detail
