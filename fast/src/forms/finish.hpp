// The last step of the seed and stable solvers: roots to a Result (the extent, the range, what
// the caller needs, the points), written once, in place.
#pragma once

#include "forms/roots.hpp"

#include "linequad/result.hpp"

#include <cmath>
#include <limits>
#include <utility>

namespace linequad::detail {

constexpr double no_bound = std::numeric_limits<double>::quiet_NaN();

// A root before the extent and range tests: t in the caller's parameter, z its axial coordinate
// in the form's own units, both in the real type R the solver computes in.
template <class R>
struct CandidateT {
    R t;
    HitKind kind;
    R z;
    Part part = Part::lateral;
};

// r becomes an error result (its hits are no longer read).
inline void fail(Result& r, ErrorCode code, const char* field) {
    r.error_code = code, r.error_field = field;
    r.count = 0, r.on_surface = false;
}

// L0 + t v in R, one rounding per coordinate (the line's coordinates are R's values).
template <class R>
Vec3 point_at(const Line& l, R t) {
    Vec3T<R> L0 = in_real<R>(l.L0), v = in_real<R>(l.v);
    return {std::fma(t, v.x, L0.x), std::fma(t, v.y, L0.y), std::fma(t, v.z, L0.z)};
}

// A caller's buffer made a fresh result: the fields a result without hits has.
inline void reset(Result& r) {
    r.error_code = ErrorCode::none, r.error_field = "";
    r.count = 0, r.on_surface = false;
    r.certainty = Certainty::unknown, r.rung = Rung::none;
}

// The Result, into a fresh r, from candidates whose facts are known: c.t(i), c.kind(i), c.bad(i)
// (t or z not finite), c.keep(i) (inside extent and range), c.point(i). Keeps the candidates
// inside, sorted by t, as many as q.need asks for (a hit test takes the first in the order
// found), with their points when asked; a bad candidate, or a point that overflows, makes the
// result out_of_range.
template <class Candidates>
LINEQUAD_INLINE void assemble(const Candidates& c, int n, Query q, Result& r) {
    if (n == 0) return;
    bool two = n == 2;
    if (c.bad(0) | (two && c.bad(1))) return fail(r, ErrorCode::out_of_range, "t");
    int first = two && q.need != Need::any && c.t(1) < c.t(0) ? 1 : 0;
    bool points = q.points && q.need != Need::any;
    int count = 0;
    // Hit i as the next one; false when its point lies beyond double's range (refused, not
    // returned as inf).
    auto put = [&](int i) LINEQUAD_INLINE_LAMBDA {
        Hit& h = r.hits[count++];
        h.t = c.t(i), h.kind = c.kind(i), h.part = c.part(i), h.bound = no_bound, h.certain = false;
        h.p = points ? c.point(i) : Vec3{};
        return !points || is_finite(h.p);
    };
    if (c.keep(first)) {
        if (!put(first)) return fail(r, ErrorCode::out_of_range, "p");
        // sorted, so the first kept is also the nearest
        if (!two || q.need != Need::all) return void(r.count = std::uint8_t(count));
    }
    if (two && c.keep(1 - first) && !put(1 - first)) return fail(r, ErrorCode::out_of_range, "p");
    r.count = std::uint8_t(count);
}

// Candidates' facts from their t and z (the extent and range, R's values, compared exactly).
template <class R>
struct CandidateFacts {
    const CandidateT<R>* c;
    Extent e;
    const Line& l;
    double t(int i) const { return c[i].t; }
    HitKind kind(int i) const { return c[i].kind; }
    Part part(int i) const { return c[i].part; }
    bool bad(int i) const { return !(std::fabs(c[i].t) <= Format<R>::max) | (c[i].z != c[i].z); }
    bool keep(int i) const {
        return (c[i].z >= e.lo) & (c[i].z <= e.hi) & (c[i].t >= l.range.t0) &
               (c[i].t <= l.range.t1);
    }
    Vec3 point(int i) const { return point_at(l, c[i].t); }
};

// More than two candidates (a closed shape's): sorted by t first, then kept in that order. Out
// of line: the usual path's finish stays small.
template <class R>
[[gnu::noinline]] void assemble_sorted(CandidateT<R>* c, int n, Extent e, const Line& l, Query q,
                                       Result& r) {
    for (int i = 1; i < n; ++i)
        for (int j = i; j > 0 && c[j].t < c[j - 1].t; --j)
            std::swap(c[j], c[j - 1]);
    CandidateFacts<R> facts{c, e, l};
    bool points = q.points && q.need != Need::any;
    for (int i = 0; i < n; ++i)
        if (facts.bad(i)) return fail(r, ErrorCode::out_of_range, "t");
    for (int i = 0; i < n; ++i) {
        if (!facts.keep(i)) continue;
        Hit& h = r.hits[r.count++];
        h.t = c[i].t, h.kind = c[i].kind, h.part = c[i].part, h.bound = no_bound;
        h.certain = false;
        h.p = points ? facts.point(i) : Vec3{};
        if (points && !is_finite(h.p)) return fail(r, ErrorCode::out_of_range, "p");
        if (q.need != Need::all) return;
    }
}

template <class R>
LINEQUAD_INLINE Result finish(CandidateT<R>* c, int n, Extent e, const Line& l, Query q) {
    Result r;
    if (n <= 2)
        assemble(CandidateFacts<R>{c, e, l}, n, q, r);
    else
        assemble_sorted(c, n, e, l, q, r);
    return r;
}

// Roots to candidates (t scaled back by t_scale, z_of(roots, i) the axial coordinate of root
// i), then finish(). Lines on the surface never get here: see without_certification.
template <class R, class AxialOf>
LINEQUAD_INLINE Result finish_roots(const RootsT<R>& r, R t_scale, AxialOf z_of, Extent e,
                                    const Line& l, Query q) {
    CandidateT<R> c[2];
    int n = r.count();
    for (int i = 0; i < n; ++i)
        c[i] = {r.t[i] * t_scale, r.hit_kind(), z_of(r, i)};
    return finish(c, n, e, l, q);
}

// The line lies on the surface: z(t) = z0 + (t / t_scale) dz. The interval of t where it is
// inside the extent, intersected with the range.
inline Result finish_on_surface(double z0, double dz, double t_scale, Extent e, const Line& l) {
    constexpr double inf = Binary64::inf;
    const Interval& range = l.range;
    // dz != 0 on every surface line: it runs along the axis (cylinders) or a generator (cone).
    // The interval is cut to the range in the prescaled parameter, where neither end has
    // underflowed, and only then scaled back (an end may then round to +-0 or overflow).
    double a = (e.lo - z0) / dz, b = (e.hi - z0) / dz;
    if (std::isnan(a)) a = -inf; // guards (-inf) / 0-like cases for unbounded extents
    if (std::isnan(b)) b = inf;
    double s0 = std::min(a, b), s1 = std::max(a, b);
    if (range.has_t0()) s0 = std::max(s0, range.t0 == 0 ? 0.0 : range.t0 / t_scale);
    if (range.has_t1()) s1 = std::min(s1, range.t1 / t_scale);
    Result r;
    if (!(s0 <= s1)) return r;
    r.on_surface = true;
    // An unbounded end stays unbounded, even if t_scale underflowed (inf * 0 would be NaN).
    auto to_caller = [&](double x) { return std::isinf(x) ? x : x * t_scale; };
    r.s0 = to_caller(s0), r.s1 = to_caller(s1);
    if (range.has_t0()) r.s0 = std::max(r.s0, range.t0) + 0.0; // +0, never -0, at t0 = 0
    if (range.has_t1()) r.s1 = std::min(r.s1, range.t1);
    return r;
}

// A result from the certified solver, presented as an uncertified one (no bounds, no claims):
// how seed and stable settle the rare cases where their rounded zeros would otherwise claim
// that a line lies on the surface (infinitely many hits) without proof.
inline Result without_certification(Result r) {
    r.certainty = Certainty::unknown;
    for (int i = 0; i < r.count; ++i)
        r.hits[i].bound = no_bound, r.hits[i].certain = false;
    return r;
}

// A result for a solver that answers in R: every t and point rounded to R (the float solvers'
// rare lines on the surface, which the certified double solver settles).
template <class R>
Result answered_in(Result r) {
    if constexpr (std::is_same_v<R, float>) {
        for (int i = 0; i < r.count; ++i)
            r.hits[i].t = nearest_float(r.hits[i].t), r.hits[i].p = nearest_float(r.hits[i].p);
        r.s0 = nearest_float(r.s0), r.s1 = nearest_float(r.s1);
    }
    return r;
}

} // namespace linequad::detail
