// The quadratic's roots, as the seed and stable solvers find them, and the guards that decide
// when their rounded zeros cannot be trusted. Shape-specific geometry stays in shapes/.
#pragma once

#include "forms/prescale.hpp"

#include <algorithm>
#include <cmath>

namespace linequad::detail {

// What a quadratic A t^2 + (linear) t + C = 0 has, before any extent or range test.
struct RootKinds {
    enum Kind { none, one, two, tangent, on_surface };
};
// R is the real type the roots were found in.
template <class R>
struct RootsT : RootKinds {
    Kind kind = none;
    R t[2] = {0, 0};
    // After shift_back: each root's parameter from the moved origin (s = t - tc, not rounded
    // through t), and whether t came from Vieta (a root near the caller's origin).
    R s[2] = {0, 0};
    bool from_vieta[2] = {false, false};

    int count() const { return kind == two ? 2 : kind == one || kind == tangent ? 1 : 0; }
    HitKind hit_kind() const { return kind == tangent ? HitKind::tangent : HitKind::cross; }
};
using Roots = RootsT<double>;

// What each shape's seed derivation gives: a t^2 + b t + c = 0 as the seed writes it, the axial
// coordinate z0 + t dz and its extent; `usable` is false when a coefficient is not finite.
template <class R>
struct SeedFormT {
    R a, b, c;
    R z0, dz;
    Extent extent;
    bool usable;
};
using SeedForm = SeedFormT<double>;

// The seed documents' last step, a t^2 + b t + c = 0 solved as written ((-b +- sqrt(b^2-4ac))/2a),
// with erratum 6 fixed: a = 0 is linear (b != 0) or identically zero (the line on the surface).
template <class R>
RootsT<R> textbook_roots(R a, R b, R c) {
    RootsT<R> r;
    if (a == 0) {
        if (b != 0)
            r.kind = Roots::one, r.t[0] = -c / b;
        else if (c == 0)
            r.kind = Roots::on_surface;
        return r;
    }
    R disc = b * b - 4 * a * c;
    if (disc < 0) return r;
    if (disc == 0) {
        r.kind = Roots::tangent, r.t[0] = -b / (2 * a);
        return r;
    }
    R sq = std::sqrt(disc);
    r.kind = Roots::two;
    r.t[0] = (-b - sq) / (2 * a);
    r.t[1] = (-b + sq) / (2 * a);
    return r;
}

// A s^2 + 2 B s + C_moved = 0 where D > 0: the stable pair, smaller first, for any lane type (the
// batch kernels' lanes, and stable_roots' two roots).
template <class T>
void stable_pair(T A, T B, T C_moved, T D, T s[2]) {
    using std::copysign;
    using std::sqrt;
    T q = -(B + copysign(sqrt(D), B));
    T t0 = q / A, t1 = C_moved / q;
    s[0] = lane_min(t0, t1), s[1] = lane_max(t0, t1);
}

// A t^2 + 2 B t + C = 0 (half-b form) solved without cancellation: the discriminant D = B^2 - AC
// is supplied by the caller in a geometric form that is accurate near tangency, and the roots
// are the stable pair q / A, C / q with q = -(B + sign(B) sqrt(D)).
template <class R>
LINEQUAD_INLINE RootsT<R> stable_roots(R A, R B, R C, R D) {
    RootsT<R> r;
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
    r.kind = Roots::two;
    stable_pair(A, B, C, D, r.t);
    return r;
}

// Roots t = tc + s of a quadratic whose origin was moved by tc. The root of larger magnitude
// is tc + s with no cancellation. The other, when tc + s cancelled (|t| < |tc| / 2), comes from
// Vieta, t_near = product / t_far, where product() = C0 / A is formed at the caller's origin;
// otherwise its error is at most an ulp of tc <= 2 ulps of t and it stands. Either way both
// roots are accurate to a few ulps, and product() is only computed when it is needed.
template <class R, class Product>
void shift_back(RootsT<R>& r, R tc, Product product) {
    r.s[0] = r.t[0], r.s[1] = r.t[1];
    if (r.kind == Roots::one || r.kind == Roots::tangent) r.t[0] += tc;
    if (r.kind != Roots::two) return;
    r.t[0] = tc + r.s[0], r.t[1] = tc + r.s[1];
    int far = std::fabs(r.t[0]) >= std::fabs(r.t[1]) ? 0 : 1, near = 1 - far;
    if (r.t[far] != 0 && std::fabs(r.t[near]) < R(0.5) * std::fabs(tc)) {
        r.t[near] = product() / r.t[far];
        r.from_vieta[near] = true;
    }
}

// Whether a decision rests on a zero: only then can underflow have made it, and only then are
// the scene's components worth checking (fragile() may cost a little).
template <class R>
bool rests_on_zero(const RootsT<R>& r, R A, R D) {
    return A == 0 || D == 0 || r.kind == Roots::on_surface || r.kind == Roots::tangent;
}
template <class R, class Fragile>
bool undecidable(const RootsT<R>& r, Fragile fragile, R A, R D) {
    if (underflow_zone(A) || underflow_zone(D)) return true;
    return rests_on_zero(r, A, D) && fragile();
}

// The seed solvers do not prescale: the same guard, with the raw inputs' own magnitudes (the
// largest `largest`, the smallest nonzero `smallest`). A scene whose nonzero components span
// more than 1 / min_relative_size cannot decide a zero in R (2^240 in double), nor can one
// beyond that size or below its inverse. Both magnitudes are asked for only when the answer
// matters.
template <class R, class Magnitudes>
bool seed_undecidable(const RootsT<R>& r, R a, R disc, Magnitudes magnitudes) {
    if (underflow_zone(a) || underflow_zone(disc)) return true;
    if (!rests_on_zero(r, a, disc)) return false;
    auto [largest, smallest] = magnitudes();
    constexpr double min_size = Guards<R>::min_relative_size;
    bool extreme = largest > 1 / min_size || largest < min_size;
    return smallest < min_size * largest || extreme;
}

} // namespace linequad::detail
