// Line against an elliptic cylinder {C, a, b, c} (seed 000): every derivation of it, once.
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
// and the roots paired as for the circular cylinder (cylinder.hpp). A = 0 exactly when v' is
// along the axis (on the surface only from the certified computation).
//
// certified: the same quantities in bounded arithmetic (QuickBounded, then Bounded when needed),
// the dual frame as adjugate rows over a bounded determinant; signs used only when certain.
//
// exact: M^-1 = adj(M) / det(M) (erratum 3); with W = det w and V = det v' the equation is
// multiplied through by det^2: W and V are polynomials in the inputs, and z = Z / det with the
// sign of det folded into the extent, 0 <= Z <= |det|.
//
// correct (the Newton rung): g(t) = Ux^2 + Uy^2 - det^2 with U(t) = adj(M)(L0 - C) + t adj(M) v,
// the exact form's W + t V.
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

#include <type_traits>

namespace linequad::detail {

// The arithmetic of stable's elliptic cylinder solve, once, for a lane type T (as CylinderStable
// is for the cylinder): the scalar solver and the batch kernels share it.
template <class T>
struct EllipticStable {
    static constexpr bool parallel_is_miss = true; // A = 0: along the axis, no crossing
    using Mask = decltype(T() < T());
    DualFrameT<T> f;
    Vec3TwoTermT<T> w;
    Vec3T<T> a, b, c, v, vl;
    T A, tc, B, C_moved, D;

    // make_frame() gives the dual frame of the prescaled a, b, c (built in place); prescaled a,
    // b, c, C, L0 and v.
    template <class MakeFrame>
    EllipticStable(MakeFrame make_frame, Vec3T<T> a_, Vec3T<T> b_, Vec3T<T> c_, Vec3T<T> C,
                   Vec3T<T> L0, Vec3T<T> v_)
        : f(make_frame()), w(difference_exact(L0, C)), a(a_), b(b_), c(c_), v(v_) {
        vl = f.local(v);
        A = vl.x * vl.x + vl.y * vl.y;
    }
    // Whether an axis is shorter than `size` (of the prescaled scene).
    Mask smaller_than(Real<T> size) const {
        return lane_min(lane_min(max_abs_lanes(a), max_abs_lanes(b)), max_abs_lanes(c)) < T(size);
    }
    // A, B, C0 and D are formed in local coordinates (M^-1 u): the frame's sizes are not
    // factors of them.
    Mask zero_may_underflow() const { return Mask{}; }
    Mask scalar_only() const { return Mask{}; }
    // C0 at the caller's origin: for lines along the axis, and for Vieta's product.
    T C0_at_origin() const {
        Vec3T<T> wl = f.local(w.rounded());
        return squares_difference(wl.x, wl.y, T(1));
    }
    // Origin moved to the closest approach to the axis' midpoint (see cylinder.hpp); then, with
    // u = v'x w'y - v'y w'x = c . (v x w) / det, D = A - u^2 = (sqrt(A) - |u|)(sqrt(A) + |u|).
    void discriminant() {
        using std::fabs;
        using std::sqrt;
        tc = -dot(v, w.rounded() - T(0.5) * c) / dot(v, v); // any tc is an exact move
        Vec3T<T> wc = moved_origin(w, tc, v);
        Vec3T<T> wcl = f.local(wc);
        const T vxy[2] = {vl.x, vl.y}, wxy[2] = {wcl.x, wcl.y};
        B = dot2(vxy, wxy);
        C_moved = squares_difference(wcl.x, wcl.y, T(1));
        T u = fabs(dot2(c, cross_dd(v, wc)) / f.det);
        T sA = sqrt(A);
        T gap = sA - u;
        D = select(gap < T(0), T(-1), gap * (sA + u));
    }
    // The local z of a hit point itself, in compensated arithmetic: near the extent's ends,
    // where it decides, a sum of moved-origin terms would cancel.
    T z_at(T t) const { return f.local_z(moved_origin(w, t, v)); }
    template <class Roots>
    T z_of(const Roots& r, int i) const {
        return z_at(r.t[i]);
    }
    T z_lanes(T t, T, Mask) const { return z_at(t); }
    // z = zc + s dz from the moved origin: where the line meets the discs' planes.
    T axial_moved() const { return z_at(tc); }
    T axial_rate() const { return f.local_z(v); }
    ExtentT<T> extent(const EllipticCylinder& s) const {
        if (s.finite) return {T(0.0), T(1.0), both_ends(s.caps)};
        return {T(-Binary64::inf), T(Binary64::inf)};
    }
};

template <>
struct ShapeTraits<EllipticCylinder> : OnFrame<EllipticCylinder, ShapeTraits<EllipticCylinder>> {
    static constexpr const char* name = "elliptic_cylinder";
    static constexpr auto fields =
        std::make_tuple(field("C", &EllipticCylinder::C), field("a", &EllipticCylinder::a),
                        field("b", &EllipticCylinder::b), field("c", &EllipticCylinder::c));
    static constexpr const char* scale_fields = "a,b,c";
    static constexpr const char* fragile_fields = "v,a,b,c";
    static constexpr bool has_line_form = true;

    static Validity validate(const EllipticCylinder& s) {
        if (Error e = check_caps(s); !e.ok()) return {e};
        int orientation =
            s.a == Vec3{} || s.b == Vec3{} || s.c == Vec3{} ? 0 : det3_sign_exact(s.a, s.b, s.c);
        if (orientation == 0) return {{ErrorCode::singular_frame, "a,b,c"}};
        return {{}, orientation};
    }

    // ---- Bounds (a scene's culling) ----

    static Box bounds(const EllipticCylinder& s) {
        return s.finite ? frame_box(s.C, s.a, s.b, s.c, 0, 1, true) : everything();
    }
    static BoundingCapsule bounding_capsule(const EllipticCylinder& s) {
        return {s.C, s.c, spread_of(s.a, s.b)};
    }

    // ---- What prepare() keeps ----

    // prepare(): OnFrame's.

    // ---- seed ----

    template <class R, class Source>
    static SeedFormT<R> seed_form(const Source& src, const Line& l) {
        const EllipticCylinder& s = src.shape;
        Vec3T<R> w, v; // C' = 0
        to_seed_frame<R>(src, s.C, s.a, s.b, s.c, l, w, v);
        const Vec3T<R> h{0, 0, 1};
        R vh = dot(v, h), wh = dot(w, h);
        R a = dot(v, v) - vh * vh;
        R b = 2 * (dot(v, w) - vh * wh);
        R c = dot(w, w) - wh * wh - 1;
        bool usable = std::isfinite(a) && std::isfinite(b) && std::isfinite(c);
        Extent e =
            s.finite ? Extent{0, 1, both_ends(s.caps)} : Extent{-Binary64::inf, Binary64::inf};
        return {a, b, c, w.z, v.z, e, usable};
    }

    // ---- stable ----

    template <class T>
    using Stable = EllipticStable<T>;
    // The core for the line L0 + t v (a lane type's values for the batch), prescaled by ps; a
    // prepared shape's dual frame, when it rescales to ps exactly (frame.hpp).
    template <class T, class Source, class Scale>
    static Stable<T> stable_core(const Source& src, const Scale& ps, Vec3T<T> L0, Vec3T<T> v) {
        const EllipticCylinder& s = src.shape;
        Vec3T<T> a = ps.pos(s.a), b = ps.pos(s.b), c = ps.pos(s.c);
        return {dual_frame<T>(src, ps, a, b, c), a, b, c, ps.pos(s.C), ps.pos(L0), ps.dir(v)};
    }

    // ---- certified ----

    template <class B, class Source>
    static CertifiedForm<B> certified_form(const Source& src, const Prescale& ps, const Line& l) {
        const EllipticCylinder& s = src.shape;
        Vec3 c = ps.pos(s.c), v = ps.dir(l.v);
        Vec3TwoTerm w = difference_exact(ps.pos(l.L0), ps.pos(s.C));
        BoundedVec3<B> a3 = exact<B>(ps.pos(s.a)), b3 = exact<B>(ps.pos(s.b)), c3 = exact<B>(c),
                       V = exact<B>(v);
        BoundedDualFrame<B> frame(a3, b3, c3);
        BoundedVec3<B> vl = frame.local(V);
        B A = vl.x * vl.x + vl.y * vl.y;
        // Not moved along the axis (exact zeros decide), nor across it when a disc may hold it.
        bool keep = exactly_zero(A) || (s.caps && exactly_zero(vl.z));
        double tc = keep ? 0 : -dot(v, w.rounded() - 0.5 * c) / dot(v, v);
        BoundedVec3<B> wc = moved_origin_bounded<B>(w, tc, v), wl = frame.local(wc);
        B u = dot(c3, cross(V, wc)) / frame.det;
        BoundedQuadratic<B> quad{A, vl.x * wl.x + vl.y * wl.y,
                                 wl.x * wl.x + wl.y * wl.y - B::exact(1), A - u * u};
        Extent e =
            s.finite ? Extent{0, 1, both_ends(s.caps)} : Extent{-Binary64::inf, Binary64::inf};
        return {quad, tc, wl.z, vl.z, e};
    }

    // ---- exact ----

    // x^2 + y^2 = 1, 0 <= z <= 1, times det^2 with W = det w, V = det v'. The sign of det is
    // folded into the extent: the caller gives it (validation decided it exactly), so that a
    // filtered number type need not.
    template <class NT, class L>
    static exact_form::LineQuadratic<NT> exact_quadratic(const EllipticCylinder& s, const L& l,
                                                         int orientation) {
        using exact_form::lift;
        bool negative_det = orientation < 0;
        exact_form::AdjugateFrame<NT> f(lift<NT>(s.a), lift<NT>(s.b), lift<NT>(s.c));
        Vec3T<NT> W = f.scaled_local(exact_form::origin<NT>(l) - lift<NT>(s.C));
        Vec3T<NT> V = f.scaled_local(lift<NT>(l.v));
        exact_form::LineQuadratic<NT> q;
        q.A = V.x * V.x + V.y * V.y;
        q.B = V.x * W.x + V.y * W.y;
        q.C0 = W.x * W.x + W.y * W.y - f.det * f.det;
        // z = Z / det in [0, 1]: with the sign of det folded into Z, 0 <= Z <= |det|.
        q.Z0 = negative_det ? -W.z : W.z;
        q.dZ = negative_det ? -V.z : V.z;
        q.lo = NT(0), q.hi = negative_det ? -f.det : f.det;
        q.lo_bounded = q.hi_bounded = s.finite;
        q.lo_capped = q.hi_capped = s.caps;
        return q;
    }
    // The sign of D = B^2 - A C0 alone. With sigma = (1, 1, 0) and K = det^2, Lagrange's identity
    // gives D = det^2 A - (V.x W.y - V.y W.x)^2, and for the rows n of adj(M) (b x c, c x a):
    // (n_x . v)(n_y . w) - (n_y . v)(n_x . w) = (n_x x n_y) . (v x w) = det c . (v x w). So D =
    // det^2 (A - det[c w v]^2), A = det[v b c]^2 + det[v c a]^2: three triple products of
    // doubles (w = L0 - C), degree 6 rather than 12.
    template <class NT>
    static int discriminant_sign(const EllipticCylinder& s, const Line& l, int /*orientation*/) {
        using exact_form::lift;
        Vec3T<NT> a = lift<NT>(s.a), b = lift<NT>(s.b), c = lift<NT>(s.c), v = lift<NT>(l.v);
        Vec3T<NT> wv = cross(lift<NT>(l.L0) - lift<NT>(s.C), v);
        NT x = dot(v, cross(b, c)), y = dot(v, cross(c, a)), z = dot(c, wv);
        return sign(x * x + y * y - z * z);
    }
    // Its Z alone: W.z, V.z and det from adj(M)'s last row a x b, without the other two.
    template <class NT>
    static exact_form::LineAxial<NT> exact_axial(const EllipticCylinder& s, const Line& l,
                                                 int orientation) {
        using exact_form::lift;
        exact_form::FrameZ<NT> Z(lift<NT>(s.a), lift<NT>(s.b), orientation);
        return {Z(lift<NT>(l.L0) - lift<NT>(s.C)),
                Z(lift<NT>(l.v)),
                NT(0),
                Z(lift<NT>(s.c)),
                s.finite,
                s.finite};
    }

    // ---- correct: the Newton rung's line form ----

    // For the line L0 + t v in T: double, or a lane type (a line per lane). precise: the Newton
    // rung's, in double-double; else the hit test's quick form, in doubles with bounds.
    // The precise form of a finite one carries its ends' planes (U0_z and U1_z: no more work),
    // with discs where it is closed.
    template <bool precise, class T, class Source>
    static LineFormT<T> form(const Source& src, Vec3T<T> L0, Vec3T<T> v, int orientation) {
        const EllipticCylinder& s = src.shape;
        auto own = [&](LineFormT<T>& f, const BoundedDD& det, auto square) {
            f.sigma_z = 0;
            f.K = square();
            f.lo = 0, f.e_lo = 0;
            f.hi = det.hi, f.e_hi = bound_of_hi(det); // 0 <= Z <= |det|
            f.lo_bounded = f.hi_bounded = s.finite;
            f.discs = discs_of(s);
            // The batch lanes use planes only where there are discs.
            if (precise && s.finite && (s.caps || std::is_same_v<T, double>)) {
                f.planes = DiscPlanesT<T>{{}, {}, BoundedDD(0), det, s.caps, s.caps};
                // The discs' planes through C and C + c, spanned by a and b (only discs have
                // points there).
                int k = s.caps ? axis_across(s.a, s.b) : -1;
                TwoTerm top = k >= 0 ? two_sum(s.C[k], s.c[k]) : TwoTerm{0, 0};
                if (k >= 0 && top.lo == 0)
                    f.planes->axis = k, f.planes->lo_at = s.C[k], f.planes->hi_at = top.hi;
            }
        };
        return elliptic_line_form<precise>(adjugate_rows(src), L0, s.C, v, orientation, own);
    }
};

} // namespace linequad::detail
