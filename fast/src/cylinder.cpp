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
// stable: the cross-product form above, each cross product a Kahan difference of products, and
//  - the discriminant in geometric form. With det = (v x h) . w (the triple product, which is
//    |v x h| times the distance from the axis to the line, times |h|),
//        D = B^2 - A C0 = (h.h) (r^2 A - det^2) = (h.h) (r sqrt(A) - |det|)(r sqrt(A) + |det|),
//    so the sign of D is decided by a difference of two accurate numbers, not of two squares;
//  - the origin moved to the point of closest approach to the axis, t_c = -B / A, before det is
//    formed (det does not change, but its rounding error shrinks with |w|);
//  - the roots t_c +- sqrt(D) / A, the smaller in magnitude from Vieta (t1 t2 = C0 / A) with
//    C0 = (|w x h| - r|h|)(|w x h| + r|h|);
//  - A = 0 exactly when the line is parallel to the axis: on the surface when C0 = 0, else no hit;
//  - the scene prescaled by powers of two (exact) so no product overflows or underflows.
#include "linequad/cylinder.hpp"

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
    auto z_of = [&](double t) { return wh + t * vh; };
    return finish_roots(textbook_roots(a, b, c), 1, z_of, e, l, q, wh, vh);
}

Result stable::intersect(const Cylinder& s, const Line& l, Query q) {
    if (Error e = validate(s, l); e.code != ErrorCode::none) return Result::failure(e);
    double extent = std::max(std::max(max_abs(l.L0), max_abs(s.C)), std::max(max_abs(s.H), s.r));
    Prescale ps = prescale_for(extent, l.v);
    Vec3 C = ps.pos(s.C), L0 = ps.pos(l.L0), v = ps.dir(l.v);
    double r = ps.len(s.r);
    Vec3 h = ps.pos(s.H) - C;
    double hh = dot(h, h), hn = std::sqrt(hh);
    if (r < min_relative_size || hn < min_relative_size)
        return Result::failure(ErrorCode::out_of_range, "r,H-C");

    Vec3TwoTerm w = difference_exact(L0, C);
    Vec3 w0 = w.hi + w.lo;
    Vec3 vh = cross_accurate(v, h), wh = cross_accurate(w0, h);
    double A = dot(vh, vh);
    double rh = r * hn, wn = norm(wh);
    double C0 = (wn - rh) * (wn + rh);
    Extent e = s.finite ? Extent{0, hh} : Extent{-inf, inf};
    auto z_of = [&](double t) { return dot2(moved_origin(w, t, v), h); };

    Roots roots;
    if (A == 0) { // parallel to the axis
        roots.kind = C0 == 0 ? Roots::on_surface : Roots::none;
        return finish_roots(roots, ps.t_scale(), z_of, e, l, q, dot2(w0, h), dot(v, h));
    }
    double tc = -dot2(vh, wh) / A;
    double det = std::fabs(dot2(vh, moved_origin(w, tc, v)));
    double rA = r * std::sqrt(A);
    double gap = rA - det;
    if (gap < 0) return finish_roots(roots, ps.t_scale(), z_of, e, l, q);
    if (gap == 0) {
        roots.kind = Roots::tangent, roots.t[0] = tc;
    } else {
        double half = hn * std::sqrt(gap * (rA + det)) / A;
        const double s_[2] = {-half, half};
        roots.kind = Roots::two;
        unshift(tc, s_, C0 / A, roots.t);
    }
    return finish_roots(roots, ps.t_scale(), z_of, e, l, q);
}

} // namespace linequad
