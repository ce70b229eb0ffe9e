// Line against an elliptic cylinder {C, a, b, c} (seed 000), in double precision.
//
// Derivation. The frame M maps the unit cylinder x^2 + y^2 = 1 (0 <= z <= 1) to the shape:
// P = C + M (x, y, z). The line maps back by M^-1 as a point and a vector (erratum 2):
//     w = M^-1 (L0 - C),   v' = M^-1 v,
// and on the unit cylinder, with h = (0, 0, 1), seed 000's equation |P|^2 - (P.h)^2 = 1 gives
//     A t^2 + 2 B t + C0 = 0,  A = v'x^2 + v'y^2,  B = v'x wx + v'y wy,  C0 = wx^2 + wy^2 - 1.
// The extent is 0 <= wz + t v'z <= 1.
//
// seed: M = T R S built and inverted as the seed writes it; the textbook roots.
//
// stable: M^-1 as the dual frame (adjugate / determinant in double-double, no normalisation),
// then in the plane of the unit circle, with u = v'x wy - v'y wx = c . (v x w) / det,
//     D = B^2 - A C0 = A - u^2 = (sqrt(A) - |u|)(sqrt(A) + |u|)
// (|u| / sqrt(A) is the distance from the axis to the line: D < 0 iff it exceeds 1), u as a
// double-double triple product; C0 = wx^2 + wy^2 - 1 with the squares exact inside fmas
// (squares_difference); the origin moved to the closest approach to the axis' midpoint,
// and the roots paired as for the circular cylinder (src/cylinder.cpp). A = 0 exactly when v'
// is along the axis (on the surface only from the certified computation).
//
// certified: the same quantities in bounded arithmetic (QuickBounded, then Bounded when needed),
// the dual frame as adjugate rows over a bounded determinant; signs used only when certain (see
// cylinder.cpp).
#include "linequad/elliptic_cylinder.hpp"

#include "elliptic_stable.hpp"
#include "frame.hpp"
#include "roots.hpp"

namespace linequad {

using namespace detail;

Result seed::intersect(const EllipticCylinder& s, const Line& l, Query q) {
    if (Error e = validate(s, l); e.code != ErrorCode::none) return Result::failure(e);
    Eigen::Matrix4d m_inv = seed_inverse_frame(s.C, s.a, s.b, s.c);
    Vec3 w = apply_point(m_inv, l.L0), v = apply_vector(m_inv, l.v); // C' = 0
    const Vec3 h{0, 0, 1};
    double vh = dot(v, h), wh = dot(w, h);
    double a = dot(v, v) - vh * vh;
    double b = 2 * (dot(v, w) - vh * wh);
    double c = dot(w, w) - wh * wh - 1;
    if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(c))
        return Result::failure(ErrorCode::out_of_range, "coefficients");
    Extent e = s.finite ? Extent{0, 1} : Extent{-inf, inf};
    auto z_of = [&](const Roots& r, int i) { return w.z + r.t[i] * v.z; };
    Roots roots = textbook_roots(a, b, c);
    if (seed_undecidable(roots, a, b * b - 4 * a * c, {s.C, s.a, s.b, s.c, l.L0, l.v}))
        return Result::failure(ErrorCode::out_of_range, "coefficients");
    // A line on the surface is a claim of infinitely many hits: only with proof (see roots.hpp).
    if (roots.kind == Roots::on_surface)
        return without_certification(certified::intersect(s, l, q));
    return finish_roots(roots, 1, z_of, e, l, q);
}

Result stable::intersect(const EllipticCylinder& s, const Line& l, Query q) {
    if (Error e = validate(s, l); e.code != ErrorCode::none) return Result::failure(e);
    double extent =
        std::max({max_abs(l.L0), max_abs(s.C), max_abs(s.a), max_abs(s.b), max_abs(s.c)});
    Prescale ps = prescale_for(extent, l.v);
    Vec3 a = ps.pos(s.a), b = ps.pos(s.b), c = ps.pos(s.c);
    if (std::min({max_abs(a), max_abs(b), max_abs(c)}) < min_relative_size)
        return Result::failure(ErrorCode::out_of_range, "a,b,c");
    EllipticStable<double> k(a, b, c, ps.pos(s.C), ps.pos(l.L0), ps.dir(l.v));
    auto fragile = [&] { return fragile_scene(extent, {s.C, s.a, s.b, s.c, l.L0}, l.v); };
    Extent e = s.finite ? Extent{0, 1} : Extent{-inf, inf};

    auto z_of = [](const EllipticStable<double>& k, const Roots& r, int i) {
        return k.z_at(r.t[i]);
    };
    auto on_surface = [&] { return without_certification(certified::intersect(s, l, q)); };
    return stable_solve(k, true, fragile, on_surface, z_of, ps.t_scale(), e, l, q, "v,a,b,c");
}

Result certified::intersect(const EllipticCylinder& s, const Line& l, Query q) {
    if (Error e = validate(s, l); e.code != ErrorCode::none) return Result::failure(e);
    double extent =
        std::max({max_abs(l.L0), max_abs(s.C), max_abs(s.a), max_abs(s.b), max_abs(s.c)});
    if (fragile_scene(extent, {s.C, s.a, s.b, s.c, l.L0}, l.v))
        return Result::failure(ErrorCode::out_of_range, "v,a,b,c");
    Prescale ps = prescale_for(extent, l.v);
    Vec3 c = ps.pos(s.c), v = ps.dir(l.v);
    Vec3TwoTerm w = difference_exact(ps.pos(l.L0), ps.pos(s.C));
    Extent e = s.finite ? Extent{0, 1} : Extent{-inf, inf};
    return certified_solve([&](auto number) {
        using B = decltype(number);
        BoundedVec3<B> a3 = exact<B>(ps.pos(s.a)), b3 = exact<B>(ps.pos(s.b)), c3 = exact<B>(c),
                       V = exact<B>(v);
        BoundedDualFrame<B> frame(a3, b3, c3);
        BoundedVec3<B> vl = frame.local(V);
        B A = vl.x * vl.x + vl.y * vl.y;
        double tc = exactly_zero(A) ? 0 : -dot(v, w.rounded() - 0.5 * c) / dot(v, v);
        BoundedVec3<B> wc = moved_origin_bounded<B>(w, tc, v), wl = frame.local(wc);
        B u = dot(c3, cross(V, wc)) / frame.det;
        BoundedQuadratic<B> quad{A, vl.x * wl.x + vl.y * wl.y,
                                 wl.x * wl.x + wl.y * wl.y - B::exact(1), A - u * u};
        return certified_result(certified_roots(quad), tc, wl.z, vl.z, ps.t_scale(), e, l, q);
    });
}

} // namespace linequad
