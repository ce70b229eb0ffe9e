// Root algebra shared by the fast solvers. Shape-specific geometry stays in each shape's file.
#pragma once

#include "support.hpp"

#include <algorithm>
#include <cmath>

namespace linequad::detail {

// What a quadratic A t^2 + (linear) t + C = 0 has, before any extent or range test.
struct Roots {
    enum Kind { none, one, two, tangent, on_surface } kind = none;
    double t[2] = {0, 0};
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
// is tc + s with no cancellation; the other comes from Vieta, t_near = product / t_far, where
// product = C0 / A is formed at the original origin. This keeps both roots accurate to a few
// ulps even when a root lies near the original origin (tc ~ -s).
inline void shift_back(Roots& r, double tc, double product) {
    if (r.kind == Roots::one || r.kind == Roots::tangent) r.t[0] += tc;
    if (r.kind != Roots::two) return;
    double s0 = r.t[0], s1 = r.t[1];
    r.t[0] = tc + s0, r.t[1] = tc + s1;
    if (tc == 0) return;
    int far = std::fabs(r.t[0]) >= std::fabs(r.t[1]) ? 0 : 1;
    if (r.t[far] != 0) r.t[1 - far] = product / r.t[far];
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
inline bool undecidable(const Roots& r, bool fragile, double A, double D) {
    if (underflow_zone(A) || underflow_zone(D)) return true;
    if (!fragile) return false;
    return A == 0 || D == 0 || r.kind == Roots::on_surface || r.kind == Roots::tangent;
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
    return undecidable(r, fragile || extreme, a, disc) || (extreme && underflow_zone(disc));
}

// Turns roots into candidates (t scaled back by t_scale, z from the functor) and finishes.
template <class AxialOf>
Result finish_roots(const Roots& r, double t_scale, AxialOf z_of, Extent e, const Line& l, Query q,
                    double on_surface_z0 = 0, double on_surface_dz = 0) {
    if (r.kind == Roots::on_surface)
        return finish_on_surface(on_surface_z0, on_surface_dz, t_scale, e, l);
    Candidate c[2];
    int n = 0;
    HitKind kind = r.kind == Roots::tangent ? HitKind::tangent : HitKind::cross;
    int count = r.kind == Roots::none ? 0 : r.kind == Roots::two ? 2 : 1;
    for (int i = 0; i < count; ++i)
        c[n++] = {r.t[i] * t_scale, kind, z_of(r.t[i])};
    return finish(c, n, e, l, q);
}

} // namespace linequad::detail
