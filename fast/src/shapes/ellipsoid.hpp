// Line against an ellipsoid {C, a, b, c}: every derivation of it, once.
//
// Derivation (checked against the surface equation). The frame M = [a b c] maps the unit sphere
// x^2 + y^2 + z^2 = 1 to the surface: P = C + M x, a, b, c any linearly independent vectors (as
// the elliptic cylinder's frame). The line maps back by M^-1 as a point and a vector:
//     w = M^-1 (L0 - C),   v' = M^-1 v,
// and |w + t v'|^2 = 1 gives
//     A t^2 + 2 B t + C0 = 0,   A = v'.v',   B = v'.w,   C0 = w.w - 1.
// A closed solid with no extent (the quadratic is negative inside), as the sphere.
//
// seed: M = T R S built and inverted as the seeds build their frames (shapes/seed_frame.hpp);
// the textbook quadratic on the unit sphere.
//
// stable: M^-1 as the dual frame (adjugate over determinant, in double-double); the origin moved
// to the line's closest approach to C; B compensated; C0 with the squares exact inside fmas; and
// the discriminant in geometric form. Lagrange's identity on the unit sphere gives
//     D = B^2 - A C0 = A - |v' x w|^2,   v' x w = M^T (v x w) / det M
// (the cofactor of M^-1 is M^T / det M), whose components a.(v x w), b.(v x w), c.(v x w) are
// triple products, each formed from v x w in double-double: D = (sqrt(A) - |u|)(sqrt(A) + |u|),
// the same at any origin on the line.
//
// certified: the same quantities in bounded arithmetic (QuickBounded, then Bounded).
//
// exact: multiplied through by det^2, with W = adj(M) (L0 - C) and V = adj(M) v (erratum 3 of
// the seeds): A = V.V, B = V.W, C0 = W.W - det^2; no extent.
//
// correct (the Newton rung): g(t) = |U(t)|^2 - det^2 with U(t) = adj(M)(L0 - C) + t adj(M) v,
// sigma = (1, 1, 1).
#pragma once

#include "forms/bounds.hpp"
#include "forms/certified.hpp"
#include "forms/exact_form.hpp"
#include "forms/frame.hpp"
#include "forms/line_form.hpp"
#include "forms/roots.hpp"
#include "forms/traits.hpp"
#include "shapes/on_frame.hpp"
#include "shapes/seed_frame.hpp"

namespace linequad::detail {

// The arithmetic of stable's ellipsoid solve, once, for a lane type T (as EllipticStable).
template <class T>
struct EllipsoidStable {
    static constexpr bool parallel_is_miss = true; // A = |M^-1 v|^2 = 0 only for v = 0 (refused)
    using Mask = decltype(T() < T());
    DualFrameT<T> f;
    Vec3TwoTermT<T> w;
    Vec3T<T> a, b, c, v, vl;
    T A, tc, B, C_moved, D;

    template <class MakeFrame>
    EllipsoidStable(MakeFrame make_frame, Vec3T<T> a_, Vec3T<T> b_, Vec3T<T> c_, Vec3T<T> C,
                    Vec3T<T> L0, Vec3T<T> v_)
        : f(make_frame()), w(difference_exact(L0, C)), a(a_), b(b_), c(c_), v(v_) {
        vl = f.local(v);
        A = dot(vl, vl);
    }
    Mask smaller_than(Real<T> size) const {
        return lane_min(lane_min(max_abs_lanes(a), max_abs_lanes(b)), max_abs_lanes(c)) < T(size);
    }
    // A, B, C0 and D are formed in local coordinates: the frame's sizes are not factors of them.
    Mask zero_may_underflow() const { return Mask{}; }
    Mask scalar_only() const { return Mask{}; }
    static T unit_sphere(Vec3T<T> x) {
        using std::fma;
        return fma(x.x, x.x, fma(x.y, x.y, fma(x.z, x.z, T(-1.0))));
    }
    T C0_at_origin() const { return unit_sphere(f.local(w.rounded())); }
    void discriminant() {
        using std::fabs;
        using std::sqrt;
        tc = -dot(v, w.rounded()) / dot(v, v); // any tc is an exact move
        Vec3T<T> wc = moved_origin(w, tc, v);
        Vec3T<T> wcl = f.local(wc);
        const T vm[3] = {vl.x, vl.y, vl.z}, wm[3] = {wcl.x, wcl.y, wcl.z};
        B = dot2(vm, wm);
        C_moved = unit_sphere(wcl);
        Vec3TwoTermT<T> n = cross_dd(v, wc); // v x w, the same at any origin on the line
        Vec3T<T> u{dot2(a, n) / f.det, dot2(b, n) / f.det, dot2(c, n) / f.det};
        T sA = sqrt(A), su = sqrt(dot(u, u));
        T gap = sA - su;
        D = select(gap < T(0.0), T(-1.0), gap * (sA + su));
    }
    template <class Roots>
    T z_of(const Roots&, int) const {
        return T(0.0);
    }
    T z_lanes(T, T, Mask) const { return T(0.0); }
    T axial_moved() const { return T(0.0); }
    T axial_rate() const { return T(0.0); }
    ExtentT<T> extent(const Ellipsoid&) const { return {T(-Binary64::inf), T(Binary64::inf)}; }
};

template <>
struct ShapeTraits<Ellipsoid> : OnFrame<Ellipsoid, ShapeTraits<Ellipsoid>> {
    static constexpr const char* name = "ellipsoid";
    static constexpr auto fields =
        std::make_tuple(field("C", &Ellipsoid::C), field("a", &Ellipsoid::a),
                        field("b", &Ellipsoid::b), field("c", &Ellipsoid::c));
    static constexpr const char* scale_fields = "a,b,c";
    static constexpr const char* fragile_fields = "v,a,b,c";
    static constexpr bool has_line_form = true;

    static Validity validate(const Ellipsoid& s) {
        int orientation =
            s.a == Vec3{} || s.b == Vec3{} || s.c == Vec3{} ? 0 : det3_sign_exact(s.a, s.b, s.c);
        if (orientation == 0) return {{ErrorCode::singular_frame, "a,b,c"}};
        return {{}, orientation};
    }

    // ---- Bounds (a scene's culling) ----

    // |x a_i + y b_i + z c_i| <= sqrt(a_i^2 + b_i^2 + c_i^2) on the unit ball.
    static Box bounds(const Ellipsoid& s) {
        BoxBuilder box;
        for (int i = 0; i < 3; ++i) {
            // hypot scales before it squares: the squares of tiny axes underflow to 0, and a box
            // of no width culled lines through the surface (found by the fuzzer).
            double spread = std::hypot(s.a[i], s.b[i], s.c[i]);
            double m = std::fabs(s.C[i]) + spread;
            box.reach(i, s.C[i] - spread, m);
            box.reach(i, s.C[i] + spread, m);
        }
        return box.box();
    }
    static BoundingCapsule bounding_capsule(const Ellipsoid& s) {
        double up = Binary64::inf;
        return {s.C, {}, std::nextafter(spread_of(s.a, s.b) + std::nextafter(norm(s.c), up), up)};
    }

    // ---- What prepare() keeps ----

    // prepare(): OnFrame's.

    // ---- seed ----

    template <class R, class Source>
    static SeedFormT<R> seed_form(const Source& src, const Line& l) {
        const Ellipsoid& s = src.shape;
        Vec3T<R> w, v; // on the unit sphere around 0
        to_seed_frame<R>(src, s.C, s.a, s.b, s.c, l, w, v);
        R a = dot(v, v), b = 2 * dot(v, w), c = dot(w, w) - 1;
        bool usable = std::isfinite(a) && std::isfinite(b) && std::isfinite(c);
        return {a, b, c, R(0), R(0), Extent{-Binary64::inf, Binary64::inf}, usable};
    }

    // ---- stable ----

    template <class T>
    using Stable = EllipsoidStable<T>;
    template <class T, class Source, class Scale>
    static Stable<T> stable_core(const Source& src, const Scale& ps, Vec3T<T> L0, Vec3T<T> v) {
        const Ellipsoid& s = src.shape;
        Vec3T<T> a = ps.pos(s.a), b = ps.pos(s.b), c = ps.pos(s.c);
        return {dual_frame<T>(src, ps, a, b, c), a, b, c, ps.pos(s.C), ps.pos(L0), ps.dir(v)};
    }

    // ---- certified ----

    template <class B, class Source>
    static CertifiedForm<B> certified_form(const Source& src, const Prescale& ps, const Line& l) {
        const Ellipsoid& s = src.shape;
        Vec3 v = ps.dir(l.v);
        Vec3TwoTerm w = difference_exact(ps.pos(l.L0), ps.pos(s.C));
        BoundedVec3<B> a3 = exact<B>(ps.pos(s.a)), b3 = exact<B>(ps.pos(s.b)),
                       c3 = exact<B>(ps.pos(s.c)), V = exact<B>(v);
        BoundedDualFrame<B> frame(a3, b3, c3);
        BoundedVec3<B> vl = frame.local(V);
        B A = dot(vl, vl);
        double tc = -dot(v, w.rounded()) / dot(v, v);
        BoundedVec3<B> wc = moved_origin_bounded<B>(w, tc, v), wl = frame.local(wc);
        BoundedVec3<B> n = cross(V, wc);
        BoundedVec3<B> u{dot(a3, n) / frame.det, dot(b3, n) / frame.det, dot(c3, n) / frame.det};
        BoundedQuadratic<B> quad{A, dot(vl, wl), dot(wl, wl) - B::exact(1), A - dot(u, u)};
        return {quad, tc, B::exact(0), B::exact(0), {-Binary64::inf, Binary64::inf}};
    }

    // ---- exact ----

    // |W + t V|^2 = det^2 with W = adj(M) (L0 - C), V = adj(M) v; no extent.
    template <class NT, class L>
    static exact_form::LineQuadratic<NT> exact_quadratic(const Ellipsoid& s, const L& l,
                                                         int /*orientation*/) {
        using exact_form::lift;
        exact_form::AdjugateFrame<NT> f(lift<NT>(s.a), lift<NT>(s.b), lift<NT>(s.c));
        Vec3T<NT> W = f.scaled_local(exact_form::origin<NT>(l) - lift<NT>(s.C));
        Vec3T<NT> V = f.scaled_local(lift<NT>(l.v));
        exact_form::LineQuadratic<NT> q;
        q.A = dot(V, V);
        q.B = dot(V, W);
        q.C0 = dot(W, W) - f.det * f.det;
        q.Z0 = q.dZ = q.lo = q.hi = NT(0);
        q.lo_bounded = q.hi_bounded = false;
        return q;
    }

    // The sign of D = B^2 - A C0 alone: with sigma = (1, 1, 1) and K = det^2, Lagrange's identity
    // and (adj(M) w) x (adj(M) v) = det M^T (w x v) give D = det^2 (A - |M^T (w x v)|^2), with
    // A = |adj(M) v|^2 = det[v b c]^2 + det[v c a]^2 + det[v a b]^2: six triple products of
    // doubles (w = L0 - C), degree 6 rather than 12.
    template <class NT>
    static int discriminant_sign(const Ellipsoid& s, const Line& l, int /*orientation*/) {
        using exact_form::lift;
        Vec3T<NT> a = lift<NT>(s.a), b = lift<NT>(s.b), c = lift<NT>(s.c), v = lift<NT>(l.v);
        Vec3T<NT> wv = cross(lift<NT>(l.L0) - lift<NT>(s.C), v);
        NT x = dot(v, cross(b, c)), y = dot(v, cross(c, a)), z = dot(v, cross(a, b));
        NT p = dot(a, wv), q = dot(b, wv), r = dot(c, wv);
        return sign(x * x + y * y + z * z - p * p - q * q - r * r);
    }

    // ---- correct: the Newton rung's line form, and the hit test's quick one ----

    template <bool precise, class T, class Source>
    static LineFormT<T> form(const Source& src, Vec3T<T> L0, Vec3T<T> v, int orientation) {
        return elliptic_line_form<precise>(adjugate_rows(src), L0, src.shape.C, v, orientation,
                                           [&](LineFormT<T>& f, const BoundedDD&, auto square) {
                                               f.sigma_z = 1;
                                               f.K = square();
                                               f.lo = f.e_lo = f.hi = f.e_hi = 0;
                                               f.lo_bounded = f.hi_bounded = false;
                                           });
    }
};

} // namespace linequad::detail
