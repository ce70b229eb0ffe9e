// Line against a right circular cylinder {C, H, r} (seed 001), in double precision.
//
// Derivation (checked against the surface equation). With h = H - C, w = L0 - C, a point P is on
// the infinite cylinder iff its distance to the axis is r:
//     |P - C|^2 - ((P - C) . h)^2 / (h . h) = r^2.
// Substituting P = L0 + t v and multiplying by h . h (no square root, erratum 3):
//     A t^2 + 2 B t + C0 = 0,
//     A  = (v.v)(h.h) - (v.h)^2 = |v x h|^2,
//     B  = (v.w)(h.h) - (v.h)(w.h) = (v x h) . (w x h),
//     C0 = (w.w)(h.h) - (w.h)^2 - r^2 (h.h) = |w x h|^2 - r^2 (h.h)
// (Lagrange's identity turns each Gram difference into a cross product). The extent is the
// projection on the axis: 0 <= (P - C) . h <= h . h.
//
// seed: seed 001 as written, with the unit axis h^ = h / |h| and a = v.v - (v.h^)^2 etc.
//
// stable: the cross-product form above, and
//  - the discriminant in geometric form. With det = (v x h) . w (the triple product: |v x h|
//    times the line's distance from the axis, times |h|; any point of the line will do for w),
//        D = B^2 - A C0 = (h.h) (r^2 A - det^2),
//    a difference of two accurate numbers, with det^2 exact inside one fma, not of the two
//    large squares B^2 and A C0. v x h from h = H - C exactly (hi + lo) by Kahan's fma
//    difference of products: a line nearly along the axis makes it a tiny difference. det is a
//    compensated dot product with the moved origin below, whose own rounding is what remains
//    (a few ulps of |v x h| |w|, as for any rounded point of the line);
//  - the origin moved to the line's point of closest approach to the middle of the axis before
//    B and C0 are formed (never farther than the caller's origin; det does not change);
//  - the stable root pair q / A, C0 / q, then t = t_c + s; a root that cancels there (near the
//    caller's origin) from Vieta instead (t1 t2 = C0 / A, with C0 = |w x h|^2 - r^2 (h.h));
//  - A = 0 exactly when the line is parallel to the axis: no hit, or on the surface when
//    C0 = 0, which only the certified computation may claim (rounded zeros are no proof);
//  - the scene prescaled by powers of two (exact) so no product overflows or underflows.
//
// certified: the same quantities in bounded arithmetic (value and rigorous error bound, see
// bounded.hpp: QuickBounded first, Bounded when that leaves anything uncertain), with
// h = H - C exact (hi, bound |lo|) and the moved origin bounded; a sign is used only when the
// bound excludes zero, so a certain classification is never wrong.
#include "linequad/cylinder.hpp"

#include "cylinder_stable.hpp"
#include "linequad/eft.hpp"
#include "roots.hpp"

namespace linequad {

using namespace detail;

Result seed::intersect(const Cylinder& s, const Line& l, Query q) {
    if (Error e = validate(s, l); e.code != ErrorCode::none) return Result::failure(e);
    Vec3 h = s.H - s.C;
    double hn = norm(h);
    Vec3 hu = (1 / hn) * h;
    Vec3 w = l.L0 - s.C;
    double vh = dot(l.v, hu), wh = dot(w, hu);
    double a = dot(l.v, l.v) - vh * vh;
    double b = 2 * (dot(l.v, w) - vh * wh);
    double c = dot(w, w) - wh * wh - s.r * s.r;
    if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(c) || !std::isfinite(hn))
        return Result::failure(ErrorCode::out_of_range, "coefficients");
    Extent e = s.finite ? Extent{0, hn} : Extent{-inf, inf};
    auto z_of = [&](const Roots& r, int i) { return wh + r.t[i] * vh; };
    Roots roots = textbook_roots(a, b, c);
    if (seed_undecidable(roots, a, b * b - 4 * a * c, {s.C, s.H, l.L0, l.v, {s.r, 0, 0}}))
        return Result::failure(ErrorCode::out_of_range, "coefficients");
    // A line on the surface is a claim of infinitely many hits: only with proof (see roots.hpp).
    if (roots.kind == Roots::on_surface)
        return without_certification(certified::intersect(s, l, q));
    return finish_roots(roots, 1, z_of, e, l, q);
}

Result stable::intersect(const Cylinder& s, const Line& l, Query q) {
    if (Error e = validate(s, l); e.code != ErrorCode::none) return Result::failure(e);
    double extent = std::max({max_abs(l.L0), max_abs(s.C), max_abs(s.H), s.r});
    Prescale ps = prescale_for(extent, l.v);
    CylinderStable<double> k(ps.pos(s.C), ps.pos(s.H), ps.pos(l.L0), ps.dir(l.v), ps.len(s.r));
    if (k.r < min_relative_size || k.hh < min_relative_size * min_relative_size)
        return Result::failure(ErrorCode::out_of_range, "r,H-C");
    auto fragile = [&] { return fragile_scene(extent, {s.C, s.H, l.L0, {s.r, 0, 0}}, l.v); };
    Extent e = s.finite ? Extent{0, k.hh} : Extent{-inf, inf};

    auto z_of = [](const CylinderStable<double>& k, const Roots& r, int i) {
        return r.from_vieta[i] ? k.z_at_origin(r.t[i]) : k.z_moved(r.s[i]);
    };
    auto on_surface = [&] { return without_certification(certified::intersect(s, l, q)); };
    return stable_solve(k, true, fragile, on_surface, z_of, ps.t_scale(), e, l, q, "v,H-C");
}

Result certified::intersect(const Cylinder& s, const Line& l, Query q) {
    if (Error e = validate(s, l); e.code != ErrorCode::none) return Result::failure(e);
    double extent = std::max({max_abs(l.L0), max_abs(s.C), max_abs(s.H), s.r});
    // Prescaling is exact unless a component is tiny enough to lose bits: refuse those.
    if (fragile_scene(extent, {s.C, s.H, l.L0, {s.r, 0, 0}}, l.v))
        return Result::failure(ErrorCode::out_of_range, "v,H-C");
    Prescale ps = prescale_for(extent, l.v);
    Vec3 C = ps.pos(s.C), v = ps.dir(l.v);
    Vec3TwoTerm w = difference_exact(ps.pos(l.L0), C);
    Extent e = s.finite ? Extent{0, 1} : Extent{-inf, inf};
    return certified_solve([&](auto number) {
        using B = decltype(number);
        BoundedVec3<B> h = difference_bounded<B>(ps.pos(s.H), C), V = exact<B>(v);
        // Any tc is an exact move of the origin; the closest approach to the axis' middle keeps
        // the bounded quantities small.
        // A line exactly parallel to the axis is not moved, so that its exact zeros stay exact.
        B R = B::exact(ps.len(s.r)), hh = dot(h, h);
        BoundedVec3<B> vxh = cross(V, h);
        B A = dot(vxh, vxh);
        Vec3 hm{h.x.v, h.y.v, h.z.v};
        double tc = exactly_zero(A) ? 0 : -dot(v, w.rounded() - 0.5 * hm) / dot(v, v);
        BoundedVec3<B> wc = moved_origin_bounded<B>(w, tc, v), wxh = cross(wc, h);
        B det = dot(V, wxh);
        BoundedQuadratic<B> quad{A, dot(vxh, wxh), dot(wxh, wxh) - R * R * hh,
                                 hh * (R * R * A - det * det)};
        B z0 = dot(wc, h) / hh, dz = dot(V, h) / hh; // z = (P - C) . h / h.h
        return certified_result(certified_roots(quad), tc, z0, dz, ps.t_scale(), e, l, q);
    });
}

} // namespace linequad
