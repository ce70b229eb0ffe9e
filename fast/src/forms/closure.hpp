// Closed shapes (caps on) in the seed, stable and certified solvers: the line against a solid
// bounded by the lateral surface and its end discs, from the lateral roots and the discs, in
// any of their number types (double, QuickBounded, Bounded). The exact form's classify() is the
// same reasoning with every sign exact (shapes/exact_form.hpp):
//  - every shape's quadratic Q(s) = A s^2 + B2 s + C is negative inside the lateral surface
//    (within the nappe), so the disc at the end z = e is {z = e, Q <= 0}: the line meets it at
//    s_e = (e - z0) / dz when Q(s_e) <= 0;
//  - a lateral root counts where it is strictly inside a capped end (a rim belongs to its disc);
//  - each solid (the shape, or each nappe of a closed two-nappe cone) is convex: the line meets
//    its boundary at the two ends of a segment or touches it at one point. A point is `cross`
//    when it ends the segment of exactly one solid, `tangent` when it is a solid's only point or
//    the apex two solids share. Rounding can leave a solid more than two points (a rim found as
//    a lateral root and as a disc's): its segment's ends, the first and the last, stand.
#pragma once

#include "forms/finish.hpp"
#include "forms/roots.hpp"
#include "forms/traits.hpp"
#include "numeric/bounded.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <utility>

namespace linequad::detail {

// A sign, and whether it is proven: a double's as it is (seed and stable claim nothing); a
// bounded number's when its bound excludes zero or it is an exact zero (else its value's sign).
struct Decided {
    int sign;
    bool certain;
};
template <class BT>
Decided decide(const BT& x) {
    if constexpr (std::is_floating_point_v<BT>) {
        return {(x > 0) - (x < 0), true};
    } else {
        if (x.v == 0 && x.e == 0) return {0, true};
        int s = x.certain_sign();
        return {s != 0 ? s : (x.v > 0) - (x.v < 0), s != 0};
    }
}

template <class BT>
BT exactly(double x) {
    if constexpr (std::is_floating_point_v<BT>)
        return BT(x);
    else
        return BT::exact(x);
}

// A value's rounded value: the real itself, or a bounded number's value.
template <class BT>
auto value(const BT& x) {
    if constexpr (std::is_floating_point_v<BT>)
        return x;
    else
        return x.v;
}

// t = (tc + s) t_scale in the caller's units, as the stable solver rounds it.
template <class R, std::enable_if_t<std::is_floating_point_v<R>, int> = 0>
R caller_t(R tc, R s, R t_scale) {
    return (tc + s) * t_scale;
}
// t = tc + s in the caller's units: exact scaling by a power of two, unless the result falls
// below the normal range, where it rounds: then the bound grows by a subnormal ulp.
template <class BT, std::enable_if_t<!std::is_floating_point_v<BT>, int> = 0>
BT caller_t(double tc, const BT& s, double t_scale) {
    BT t = BT::exact(tc) + s;
    double v = t.v * t_scale, e = t.bound() * t_scale;
    if (std::fabs(v) < 0x1p-1020 && (t.v != 0 || t.e != 0)) e += Binary64::denorm_min;
    return {v, e};
}

// The lateral quadratic in the parameter s moved by tc, and the axial line z(s) = z0 + s dz,
// in one layer's units.
template <class BT>
struct AxialQuadratic {
    BT A, B2, C; // Q(s) = A s^2 + B2 s + C
    BT z0, dz;
    // In the float solvers' float; double for the others (and the bounded types).
    std::conditional_t<std::is_floating_point_v<BT>, BT, double> tc, t_scale;
};

// A point where the line meets the closed shape's boundary (t in the caller's units).
template <class BT>
struct BoundaryPoint {
    BT t, z;
    Part part;
    HitKind kind;
    bool certain; // the root's existence proven (the certified solver's lateral roots)
};

template <class BT>
struct ClosedPoints {
    BoundaryPoint<BT> p[max_hits];
    int n = 0;
    bool certain = true; // every decision on the way was proven
};

// Which disc's plane holds the whole line (dz = 0 exactly, z0 at a capped end), or lateral.
template <class BT>
Part plane_holding(const AxialQuadratic<BT>& q, const Extent& e) {
    auto zero = [](const BT& x) {
        Decided d = decide(x);
        return d.sign == 0 && d.certain;
    };
    if (!zero(q.dz)) return Part::lateral;
    if (e.caps.lo && zero(q.z0 - exactly<BT>(e.lo))) return Part::base;
    if (e.caps.hi && zero(q.z0 - exactly<BT>(e.hi))) return Part::top;
    return Part::lateral;
}

// One solid's points (close() below): more than two (a rim found twice, through rounding) keep the
// ends of its segment, the first and the last in t, in their order; two cross, one is tangent.
template <class BT>
void keep_one_solid(ClosedPoints<BT>& out) {
    if (out.n > 2) {
        out.certain = false;
        int first = 0, last = 0;
        for (int i = 1; i < out.n; ++i) {
            if (value(out.p[i].t) < value(out.p[first].t)) first = i;
            if (value(out.p[i].t) > value(out.p[last].t)) last = i;
        }
        BoundaryPoint<BT> a = out.p[std::min(first, last)], b = out.p[std::max(first, last)];
        out.p[0] = a, out.p[1] = b;
        out.n = first == last ? 1 : 2;
    }
    for (int i = 0; i < out.n; ++i)
        out.p[i].kind = out.n == 2 ? HitKind::cross : HitKind::tangent;
}

// The boundary points of the closed shape: the lateral roots `lateral[0..n)` (z in the layer's
// units) that its extent keeps, the discs the line crosses, and each point's kind.
template <class BT>
ClosedPoints<BT> close(const BoundaryPoint<BT>* lateral, int n, const AxialQuadratic<BT>& q,
                       const Extent& e) {
    ClosedPoints<BT> out;
    auto sign_of = [&](const BT& x) {
        Decided d = decide(x);
        out.certain = out.certain && d.certain;
        return d.sign;
    };
    for (int i = 0; i < n; ++i) {
        const BoundaryPoint<BT>& p = lateral[i];
        out.certain = out.certain && p.certain;
        bool in = true;
        if (std::isfinite(e.lo)) {
            int s = sign_of(p.z - exactly<BT>(e.lo));
            in = in && (e.caps.lo ? s > 0 : s >= 0);
        }
        if (std::isfinite(e.hi)) {
            int s = sign_of(exactly<BT>(e.hi) - p.z);
            in = in && (e.caps.hi ? s > 0 : s >= 0);
        }
        if (in) out.p[out.n++] = p;
    }
    if (sign_of(q.dz) != 0) {
        auto disc = [&](double end, Part part) {
            BT s = (exactly<BT>(end) - q.z0) / q.dz;
            if (sign_of((q.A * s + q.B2) * s + q.C) <= 0)
                out.p[out.n++] = {caller_t(q.tc, s, q.t_scale), exactly<BT>(end), part,
                                  HitKind::cross, true};
        };
        if (e.caps.lo) disc(e.lo, Part::base);
        if (e.caps.hi) disc(e.hi, Part::top);
    }
    if (!e.caps.two_solids) {
        keep_one_solid(out);
        return out;
    }
    // Which solid each point is on: bit 0 the one at z <= 0 (or the only one), bit 1 z >= 0.
    int solids[max_hits];
    for (int i = 0; i < out.n; ++i) {
        const BoundaryPoint<BT>& p = out.p[i];
        if (p.part != Part::lateral)
            solids[i] = p.part == Part::base ? 1 : 2;
        else {
            int z = sign_of(p.z);
            solids[i] = z < 0 ? 1 : z > 0 ? 2 : 3;
        }
    }
    // A solid with more than two points (a rim found twice, through rounding) keeps the ends of
    // its segment: its first and its last.
    for (int b = 0; b < 2; ++b) {
        int first = -1, last = -1, k = 0;
        for (int i = 0; i < out.n; ++i) {
            if (!((solids[i] >> b) & 1)) continue;
            ++k;
            if (first < 0 || value(out.p[i].t) < value(out.p[first].t)) first = i;
            if (last < 0 || value(out.p[i].t) > value(out.p[last].t)) last = i;
        }
        if (k <= 2) continue;
        out.certain = false;
        for (int i = 0; i < out.n; ++i)
            if (i != first && i != last) solids[i] &= ~(1 << b);
    }
    int m = 0, count[2] = {0, 0};
    for (int i = 0; i < out.n; ++i) {
        if (solids[i] == 0) continue;
        out.p[m] = out.p[i], solids[m] = solids[i];
        for (int b = 0; b < 2; ++b)
            count[b] += (solids[m] >> b) & 1;
        ++m;
    }
    out.n = m;
    for (int i = 0; i < m; ++i) {
        bool ends_segment = solids[i] != 3 && count[solids[i] == 1 ? 0 : 1] == 2;
        out.p[i].kind = ends_segment ? HitKind::cross : HitKind::tangent;
    }
    return out;
}

// close() for one convex solid in a real type R (seed and stable), straight into the
// candidates: each sign is a comparison, which for two R values is the sign of their difference,
// and a NaN falls as close() lets it (a NaN z stays where an end is open, for finish to refuse; a
// NaN disc test counts as inside). At most two points remain.
template <class R, class AxialOf>
int close_convex(const RootsT<R>& r, AxialOf z_of, const AxialQuadratic<R>& q, const Extent& e,
                 CandidateT<R>* c) {
    int n = 0;
    for (int i = 0; i < r.count(); ++i) {
        R z = z_of(r, i);
        bool above_lo = !std::isfinite(e.lo) || (e.caps.lo ? z > e.lo : !(z < e.lo));
        bool below_hi = !std::isfinite(e.hi) || (e.caps.hi ? z < e.hi : !(z > e.hi));
        if (above_lo && below_hi) c[n++] = {r.t[i] * q.t_scale, HitKind::cross, z};
    }
    if (q.dz > 0 || q.dz < 0) {
        auto disc = [&](double end, Part part) {
            R s = (R(end) - q.z0) / q.dz;
            if (!((q.A * s + q.B2) * s + q.C > 0))
                c[n++] = {caller_t(q.tc, s, q.t_scale), HitKind::cross, R(end), part};
        };
        if (e.caps.lo) disc(e.lo, Part::base);
        if (e.caps.hi) disc(e.hi, Part::top);
    }
    if (n > 2) { // a rim found twice, through rounding: the segment's first and last stand
        int first = 0, last = 0;
        for (int i = 1; i < n; ++i) {
            if (c[i].t < c[first].t) first = i;
            if (c[i].t > c[last].t) last = i;
        }
        CandidateT<R> a = c[std::min(first, last)], b = c[std::max(first, last)];
        c[0] = a, c[1] = b;
        n = first == last ? 1 : 2;
    }
    if (n == 1) c[0].kind = HitKind::tangent;
    return n;
}

// The seed's and stable's last step for a closed shape: the roots (t in the form's parameter,
// scaled by q.t_scale), their axial coordinates z_of(roots, i), and the discs. A line in a
// disc's plane is a claim of infinitely many hits: in_plane() (the certified result) settles it.
template <class R, class AxialOf, class InPlane>
[[gnu::noinline]] Result finish_closed(const RootsT<R>& r, AxialOf z_of, const AxialQuadratic<R>& q,
                                       const Extent& e, const Line& l, Query query,
                                       InPlane in_plane) {
    if (plane_holding(q, e) != Part::lateral) return in_plane();
    if (!e.caps.two_solids) {
        CandidateT<R> c[max_hits];
        int n = close_convex(r, z_of, q, e, c);
        return finish(c, n, e, l, query);
    }
    BoundaryPoint<R> lateral[2];
    int n = r.count();
    for (int i = 0; i < n; ++i)
        lateral[i] = {r.t[i] * q.t_scale, z_of(r, i), Part::lateral, r.hit_kind(), true};
    ClosedPoints<R> cp = close(lateral, n, q, e);
    CandidateT<R> c[max_hits];
    for (int i = 0; i < cp.n; ++i)
        c[i] = {cp.p[i].t, cp.p[i].kind, cp.p[i].z, cp.p[i].part};
    return finish(c, cp.n, e, l, query);
}

} // namespace linequad::detail
