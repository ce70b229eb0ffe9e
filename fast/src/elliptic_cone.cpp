// Line against an elliptic cone {C, H, a, b} (seed 002), in double precision.
//
// Derivation. With c = H - C (erratum 4), the frame M = [a b c] with origin H maps the unit cone
// (apex at the origin, base centre (0, 0, -1), base radius 1) to the shape: P = H + M (x, y, z).
// Seed 002 derives the unit cone as |P - H'|^2 = 2 ((P - H') . h)^2 with h = (0, 0, -1), i.e.
//     x^2 + y^2 = z^2,
// a double cone (erratum 5: the nappe z <= 0 is kept; finite keeps -1 <= z <= 0). Its section
// "Intersections calculation" then substitutes into the cylinder's equation; substituting into
// the cone's own (erratum 1), with w = M^-1 (L0 - H) and v' = M^-1 v:
//     A t^2 + 2 B t + C0 = 0,
//     A = v'x^2 + v'y^2 - v'z^2,  B = v'x wx + v'y wy - v'z wz,  C0 = wx^2 + wy^2 - wz^2.
// Cases the seed does not name (erratum 6): A = 0 when v' is along a generator (one root when
// B != 0; when B = 0 too, the line lies on the cone if C0 = 0, and there is no hit otherwise);
// a line through the apex gives a double root there (reported as tangent).
//
// seed: M = T R S as written; a = v'.v' - 2 (v'.h)^2, b = 2 (v'.w - 2 (v'.h)(w.h)),
// c = w.w - 2 (w.h)^2; textbook roots.
//
// stable: the dual frame in double-double; local coordinates times s det (s a power of two near
// 1 / |det|) instead of divided by det, since the equation is homogeneous (elliptic_stable.hpp);
// the origin moved to the line's closest approach to the apex; each form x^2 + y^2 - z^2 with
// x^2 and y^2 exact inside fmas (squares_difference), except A, whose geometric form
// (rho - |z|)(rho + |z|), rho = sqrt(x^2 + y^2), decides lines along a generator better; B as a
// compensated dot product; and the discriminant in geometric form: with u = v' x w' =
// M^T (v x w) / det, Lagrange's identity in the metric diag(1, 1, -1) gives
//     D = B^2 - A C0 = ux^2 + uy^2 - uz^2,
// u by Kahan's cross product of the rounded v' and w', or, near tangency (|D| small beside the
// products u came from), from double-double triple products.
// Roots are the stable pair q / A, C0 / q, paired back as for the circular cylinder
// (src/cylinder.cpp); a line on the surface only from the certified computation.
//
// certified: the same quantities in bounded arithmetic (QuickBounded, then Bounded when needed),
// c = H - C exact (hi and bound); signs used only when certain (see cylinder.cpp).
#include "linequad/elliptic_cone.hpp"

#include "elliptic_stable.hpp"
#include "frame.hpp"
#include "roots.hpp"

namespace linequad {

using namespace detail;

Result seed::intersect(const EllipticCone& s, const Line& l, Query q) {
    if (Error e = validate(s, l); e.code != ErrorCode::none) return Result::failure(e);
    Eigen::Matrix4d m_inv = seed_inverse_frame(s.H, s.a, s.b, s.c());
    Vec3 w = apply_point(m_inv, l.L0), v = apply_vector(m_inv, l.v); // H' = 0
    const Vec3 h{0, 0, -1};
    double vh = dot(v, h), wh = dot(w, h);
    double a = dot(v, v) - 2 * vh * vh;
    double b = 2 * (dot(v, w) - 2 * vh * wh);
    double c = dot(w, w) - 2 * wh * wh;
    if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(c))
        return Result::failure(ErrorCode::out_of_range, "coefficients");
    Extent e = s.finite ? Extent{-1, 0} : Extent{-inf, 0};
    auto z_of = [&](const Roots& r, int i) { return w.z + r.t[i] * v.z; };
    Roots roots = textbook_roots(a, b, c);
    if (seed_undecidable(roots, a, b * b - 4 * a * c, {s.C, s.H, s.a, s.b, l.L0, l.v}))
        return Result::failure(ErrorCode::out_of_range, "coefficients");
    // A line on the surface is a claim of infinitely many hits: only with proof (see roots.hpp).
    if (roots.kind == Roots::on_surface)
        return without_certification(certified::intersect(s, l, q));
    return finish_roots(roots, 1, z_of, e, l, q);
}

Result stable::intersect(const EllipticCone& s, const Line& l, Query q) {
    if (Error e = validate(s, l); e.code != ErrorCode::none) return Result::failure(e);
    double extent =
        std::max({max_abs(l.L0), max_abs(s.C), max_abs(s.H), max_abs(s.a), max_abs(s.b)});
    Prescale ps = prescale_for(extent, l.v);
    Vec3 a = ps.pos(s.a), b = ps.pos(s.b);
    ConeStable<double> k(a, b, ps.pos(s.H), ps.pos(s.C), ps.pos(l.L0), ps.dir(l.v));
    if (std::min({max_abs(a), max_abs(b), max_abs(k.c.hi)}) < min_relative_size)
        return Result::failure(ErrorCode::out_of_range, "a,b,H-C");
    Extent e = s.finite ? Extent{-1, 0} : Extent{-inf, 0};

    auto fragile = [&] { return fragile_scene(extent, {s.C, s.H, s.a, s.b, l.L0}, l.v); };
    auto z_of = [](const ConeStable<double>& k, const Roots& r, int i) { return k.z_at(r.t[i]); };
    auto on_surface = [&] { return without_certification(certified::intersect(s, l, q)); };
    return stable_solve(k, false, fragile, on_surface, z_of, ps.t_scale(), e, l, q, "v,a,b,H-C");
}

Result certified::intersect(const EllipticCone& s, const Line& l, Query q) {
    if (Error e = validate(s, l); e.code != ErrorCode::none) return Result::failure(e);
    double extent =
        std::max({max_abs(l.L0), max_abs(s.C), max_abs(s.H), max_abs(s.a), max_abs(s.b)});
    if (fragile_scene(extent, {s.C, s.H, s.a, s.b, l.L0}, l.v))
        return Result::failure(ErrorCode::out_of_range, "v,a,b,H-C");
    Prescale ps = prescale_for(extent, l.v);
    Vec3 H = ps.pos(s.H), v = ps.dir(l.v);
    Vec3TwoTerm w = difference_exact(ps.pos(l.L0), H);
    Extent e = s.finite ? Extent{-1, 0} : Extent{-inf, 0};
    return certified_solve([&](auto number) {
        using B = decltype(number);
        BoundedVec3<B> a3 = exact<B>(ps.pos(s.a)), b3 = exact<B>(ps.pos(s.b)), V = exact<B>(v);
        BoundedVec3<B> c3 = difference_bounded<B>(H, ps.pos(s.C)); // c = H - C exactly
        BoundedDualFrame<B> frame(a3, b3, c3);
        BoundedVec3<B> vl = frame.local(V);
        B A = vl.x * vl.x + vl.y * vl.y - vl.z * vl.z;
        // Closest approach to the apex; not moved along a generator, where exact zeros decide.
        double tc = exactly_zero(A) ? 0 : -dot(v, w.rounded()) / dot(v, v);
        BoundedVec3<B> wc = moved_origin_bounded<B>(w, tc, v), wl = frame.local(wc);
        BoundedVec3<B> vw = cross(V, wc);
        BoundedVec3<B> u{dot(a3, vw) / frame.det, dot(b3, vw) / frame.det, dot(c3, vw) / frame.det};
        BoundedQuadratic<B> quad{A, vl.x * wl.x + vl.y * wl.y - vl.z * wl.z,
                                 wl.x * wl.x + wl.y * wl.y - wl.z * wl.z,
                                 u.x * u.x + u.y * u.y - u.z * u.z};
        return certified_result(certified_roots(quad), tc, wl.z, vl.z, ps.t_scale(), e, l, q);
    });
}

} // namespace linequad
