// Line against an elliptic cone {C, H, a, b} (seed 002): every derivation of it, once.
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
// 1 / |det|) instead of divided by det, since the equation is homogeneous; the origin moved to
// the line's closest approach to the apex; each form x^2 + y^2 - z^2 with x^2 and y^2 exact
// inside fmas (squares_difference), except A, whose geometric form (rho - |z|)(rho + |z|),
// rho = sqrt(x^2 + y^2), decides lines along a generator better; B as a compensated dot product;
// and the discriminant in geometric form: with u = v' x w' = M^T (v x w) / det, Lagrange's
// identity in the metric diag(1, 1, -1) gives
//     D = B^2 - A C0 = ux^2 + uy^2 - uz^2,
// u by Kahan's cross product of the rounded v' and w', or, near tangency (|D| small beside the
// products u came from), from double-double triple products. Roots are the stable pair q / A,
// C0 / q, paired back as for the circular cylinder (cylinder.hpp); a line on the surface only
// from the certified computation.
//
// certified: the same quantities in bounded arithmetic (QuickBounded, then Bounded when needed),
// c = H - C exact (hi and bound); signs used only when certain.
//
// exact: as the elliptic cylinder's, with w = M^-1 (L0 - H); the equation is homogeneous, so
// the det^2 factor drops out; -|det| <= Z <= 0.
//
// correct (the Newton rung): g(t) = Ux^2 + Uy^2 - Uz^2 with U(t) = adj(M)(L0 - H) + t adj(M) v.
//
// Two nappes (OpenCascade's cones): the same equation, with the extent -1 <= z <= 1 (finite) or
// none; closed, each nappe is a solid of its own and they meet at the apex z = 0.
#pragma once

#include "forms/bounds.hpp"
#include "forms/certified.hpp"
#include "forms/exact_form.hpp"
#include "forms/frame.hpp"
#include "forms/line_form.hpp"
#include "forms/roots.hpp"
#include "forms/traits.hpp"
#include "shapes/seed_frame.hpp"

#include <type_traits>

namespace linequad::detail {

// The nappe z <= 0, down to the base z = -1 when finite; with two nappes z >= 0 too, up to z = 1.
// Caps close the base, and the top of the second nappe.
inline Extent cone_extent(const EllipticCone& s) {
    constexpr double inf = Binary64::inf;
    bool two = s.nappes == 2;
    Extent e{s.finite ? -1.0 : -inf, two ? (s.finite ? 1.0 : inf) : 0.0};
    e.caps = {s.caps, s.caps && two, s.caps && two};
    return e;
}

// The arithmetic of stable's cone solve, once, for a lane type T. The cone's equation
// x^2 + y^2 = z^2 is homogeneous: its roots do not change when every local coordinate is scaled
// by one factor. So the local coordinates here are M^-1 u times sigma = s det, s a power of two
// near 1 / |det| (frame.hpp): A, B and C0 carry sigma^2, D sigma^4, and no division by det is
// needed but in z itself (z_at), which the extent test needs as it is.
template <class T>
struct ConeStable {
    static constexpr bool parallel_is_miss = false; // A = 0: along a generator, one crossing
    using Mask = decltype(T() < T());
    DualFrameT<T> f;
    Vec3TwoTermT<T> w, c;
    Vec3T<T> a, b, v, vl;
    T s, A, tc, B, C_moved, D;
    Mask near_tangent; // D came from the double-double triple products (the scalar solver)

    // make_frame() gives the dual frame of the prescaled a, b, c (built in place), with c = H - C
    // exactly (it is not a double); prescaled a, b, H, L0 and v.
    template <class MakeFrame>
    ConeStable(MakeFrame make_frame, const Vec3TwoTermT<T>& c_, Vec3T<T> a_, Vec3T<T> b_,
               Vec3T<T> H, Vec3T<T> L0, Vec3T<T> v_)
        : f(make_frame()), w(difference_exact(L0, H)), c(c_), a(a_), b(b_), v(v_) {
        s = power_of_two_inverse(f.det);
        vl = f.scaled_local(v, s);
        A = circle_minus_square(vl.x, vl.y, vl.z);
    }
    Mask smaller_than(Real<T> size) const {
        return lane_min(lane_min(max_abs_lanes(a), max_abs_lanes(b)), max_abs_lanes(c.hi)) <
               T(size);
    }
    // A, B, C0 and D are formed in local coordinates scaled to the frame (M^-1 times s det):
    // the frame's sizes are not factors of them.
    Mask zero_may_underflow() const { return Mask{}; }
    // Near tangency D comes from the double-double triple products, which only the scalar
    // solver computes.
    Mask scalar_only() const { return near_tangent; }
    T C0_at_origin() const {
        Vec3T<T> wl = f.scaled_local(w.rounded(), s);
        return squares_difference(wl.x, wl.y, wl.z);
    }
    // Origin moved to the line's closest approach to the apex; D = ux^2 + uy^2 - uz^2 with
    // u = v' x w' (sigma^2 u in the scaled coordinates), by Kahan's cross product of the rounded
    // local v' and w'. Its error is a few u of the products u came from, which is small beside D
    // but near tangency: where |D| is at most 1/8 of them, D comes from accurate_discriminant (in
    // the batch: the lane goes to the scalar solver, which does that).
    void discriminant() {
        using std::fabs;
        tc = -dot(v, w.rounded()) / dot(v, v); // any tc is an exact move
        Vec3T<T> wcw = moved_origin(w, tc, v), wc = f.scaled_local(wcw, s);
        const T vm[3] = {vl.x, vl.y, -vl.z}, wm[3] = {wc.x, wc.y, wc.z};
        B = dot2(vm, wm);
        C_moved = squares_difference(wc.x, wc.y, wc.z);
        Vec3T<T> u = cross_accurate(vl, wc);
        D = squares_difference(u.x, u.y, u.z);
        T size = triple_product_magnitude(u, vl, wc);
        near_tangent = fabs(D) <= T(0.125) * size; // and where u, and D with it, came out 0
        if constexpr (std::is_floating_point_v<T>)
            if (near_tangent) D = accurate_discriminant(wcw);
    }
    // u = M^T (v x w) / det with each component a double-double triple product, which stays
    // accurate when D nearly vanishes; sigma^2 u = s (s det) M^T (v x w), a product by an exact
    // power-of-two multiple of det.
    T accurate_discriminant(Vec3T<T> wcw) const {
        Vec3TwoTermT<T> vw = cross_dd(v, wcw);
        Vec3T<T> u{dot2(a, vw), dot2(b, vw), dot2(c.hi, vw) + dot(c.lo, vw.hi)};
        u = (s * (s * f.det)) * u;
        return squares_difference(u.x, u.y, u.z);
    }
    T z_at(T t) const { return f.local_z(moved_origin(w, t, v)); }
    template <class Roots>
    T z_of(const Roots& r, int i) const {
        return z_at(r.t[i]);
    }
    T z_lanes(T t, T, Mask) const { return z_at(t); }
    // z = zc + s dz from the moved origin: where the line meets the discs' planes.
    T axial_moved() const { return z_at(tc); }
    T axial_rate() const { return f.local_z(v); }
    ExtentT<T> extent(const EllipticCone& s) const {
        Extent e = cone_extent(s);
        return {T(e.lo), T(e.hi), e.caps};
    }
};

template <>
struct ShapeTraits<EllipticCone> {
    static constexpr const char* name = "elliptic_cone";
    static constexpr auto fields =
        std::make_tuple(field("C", &EllipticCone::C), field("H", &EllipticCone::H),
                        field("a", &EllipticCone::a), field("b", &EllipticCone::b));
    static constexpr const char* scale_fields = "a,b,H-C";
    static constexpr const char* fragile_fields = "v,a,b,H-C";
    static constexpr bool has_line_form = true;

    static Validity validate(const EllipticCone& s) {
        if (Error e = check_caps(s); !e.ok()) return {e};
        if (s.nappes != 1 && s.nappes != 2) return {{ErrorCode::bad_option, "nappes"}};
        if (s.H == s.C) return {{ErrorCode::degenerate_axis, "H-C"}};
        int orientation = cone_det_sign_exact(s.a, s.b, s.C, s.H);
        if (orientation == 0) return {{ErrorCode::singular_frame, "a,b,H-C"}};
        return {{}, orientation};
    }

    // ---- Bounds (a scene's culling) ----

    // c = H - C is rounded here, by at most 2^-53 |c|: the slack, which counts |c|, covers it.
    static Box bounds(const EllipticCone& s) {
        if (!s.finite) return everything();
        return frame_box(s.H, s.a, s.b, s.H - s.C, -1, s.nappes == 2 ? 1 : 0, false);
    }
    // The nappes reach from H - c (z = -1) to H + c (z = 1) with |z| (|a| + |b|) around the
    // axis: within |a| + |b| of the segment.
    static BoundingCapsule bounding_capsule(const EllipticCone& s) {
        Vec3 c = s.H - s.C;
        if (s.nappes == 2) return {s.H - c, 2 * c, spread_of(s.a, s.b)};
        return {s.H - c, c, spread_of(s.a, s.b)};
    }

    // ---- What prepare() keeps ----

    static void prepare(const EllipticCone& s, Facts<EllipticCone>& f) {
        seed_inverse_frame(s.H, s.a, s.b, s.c(), f.seed_inverse);
        f.exponent = scale_exponent(f.magnitude);
        double to_unit = Binary64::pow2(-f.exponent);
        Vec3TwoTerm c = difference_exact(to_unit * s.H, to_unit * s.C);
        f.c_hi = c.hi, f.c_lo = c.lo;
        f.dual = DualFrame(to_unit * s.a, to_unit * s.b, c).rows();
        f.lowest_exponent = lowest_exponent({s.a, s.b, s.H, s.C}, to_unit);
        store(adjugate_rows(AsGiven<EllipticCone>{s}), f);
    }

    // ---- seed ----

    template <class R, class Source>
    static SeedFormT<R> seed_form(const Source& src, const Line& l) {
        const EllipticCone& s = src.shape;
        Vec3T<R> w, v;                                     // H' = 0
        Vec3T<R> axis = in_real<R>(s.H) - in_real<R>(s.C); // H - C, rounded to R
        to_seed_frame<R>(src, s.H, s.a, s.b, in_real<double>(axis), l, w, v);
        const Vec3T<R> h{0, 0, -1};
        R vh = dot(v, h), wh = dot(w, h);
        R a = dot(v, v) - 2 * vh * vh;
        R b = 2 * (dot(v, w) - 2 * vh * wh);
        R c = dot(w, w) - 2 * wh * wh;
        bool usable = std::isfinite(a) && std::isfinite(b) && std::isfinite(c);
        return {a, b, c, w.z, v.z, cone_extent(s), usable};
    }

    // ---- stable ----

    template <class T>
    using Stable = ConeStable<T>;
    // The core for the line L0 + t v (a lane type's values for the batch), prescaled by ps; a
    // prepared shape's dual frame, when it rescales to ps exactly (frame.hpp).
    template <class T, class Source, class Scale>
    static Stable<T> stable_core(const Source& src, const Scale& ps, Vec3T<T> L0, Vec3T<T> v) {
        const EllipticCone& s = src.shape;
        Vec3T<T> a = ps.pos(s.a), b = ps.pos(s.b), H = ps.pos(s.H);
        Vec3TwoTermT<T> c;
        bool rescaled = false;
        int delta = 0;
        if constexpr (Source::prepared && in_double<T>) {
            const FrameFacts& f = src.facts;
            delta = ps.k - f.exponent;
            rescaled = dual_frame_rescales(f, delta);
            if (rescaled) {
                double scale = Binary64::pow2(-delta); // c = H - C scales as the rows do
                c = {scale * f.c_hi, scale * f.c_lo};
            }
        }
        if (!rescaled) c = difference_exact(H, ps.pos(s.C)); // c = H - C exactly: not a double
        auto frame = [&]() -> DualFrameT<T> {
            if constexpr (Source::prepared && in_double<T>)
                if (rescaled) return rescaled_dual_frame(src.facts, delta);
            return {a, b, c};
        };
        return {frame, c, a, b, H, ps.pos(L0), ps.dir(v)};
    }

    // ---- certified ----

    template <class B, class Source>
    static CertifiedForm<B> certified_form(const Source& src, const Prescale& ps, const Line& l) {
        const EllipticCone& s = src.shape;
        Vec3 H = ps.pos(s.H), v = ps.dir(l.v);
        Vec3TwoTerm w = difference_exact(ps.pos(l.L0), H);
        BoundedVec3<B> a3 = exact<B>(ps.pos(s.a)), b3 = exact<B>(ps.pos(s.b)), V = exact<B>(v);
        BoundedVec3<B> c3 = difference_bounded<B>(H, ps.pos(s.C)); // c = H - C exactly
        BoundedDualFrame<B> frame(a3, b3, c3);
        BoundedVec3<B> vl = frame.local(V);
        B A = vl.x * vl.x + vl.y * vl.y - vl.z * vl.z;
        // Closest approach to the apex; not moved along a generator, where exact zeros decide,
        // nor across the axis when a disc may hold the line.
        bool keep = exactly_zero(A) || (s.caps && exactly_zero(vl.z));
        double tc = keep ? 0 : -dot(v, w.rounded()) / dot(v, v);
        BoundedVec3<B> wc = moved_origin_bounded<B>(w, tc, v), wl = frame.local(wc);
        BoundedVec3<B> vw = cross(V, wc);
        BoundedVec3<B> u{dot(a3, vw) / frame.det, dot(b3, vw) / frame.det, dot(c3, vw) / frame.det};
        BoundedQuadratic<B> quad{A, vl.x * wl.x + vl.y * wl.y - vl.z * wl.z,
                                 wl.x * wl.x + wl.y * wl.y - wl.z * wl.z,
                                 u.x * u.x + u.y * u.y - u.z * u.z};
        return {quad, tc, wl.z, vl.z, cone_extent(s)};
    }

    // ---- exact ----

    // sgn det[a b H-C], in NT (the oracle decides it in its own arithmetic).
    template <class NT>
    static int exact_orientation(const EllipticCone& s) {
        using exact_form::lift;
        return sign(exact_form::AdjugateFrame<NT>(lift<NT>(s.a), lift<NT>(s.b),
                                                  lift<NT>(s.H) - lift<NT>(s.C))
                        .det);
    }

    // x^2 + y^2 = z^2 (homogeneous, so the det^2 factor drops out), -1 <= z <= 0 (erratum 5;
    // with two nappes -1 <= z <= 1), with W = det M^-1 (L0 - H), V = det M^-1 v.
    template <class NT, class L>
    static exact_form::LineQuadratic<NT> exact_quadratic(const EllipticCone& s, const L& l,
                                                         int orientation) {
        using exact_form::lift;
        bool negative_det = orientation < 0;
        exact_form::AdjugateFrame<NT> f(lift<NT>(s.a), lift<NT>(s.b),
                                        lift<NT>(s.H) - lift<NT>(s.C));
        Vec3T<NT> W = f.scaled_local(exact_form::origin<NT>(l) - lift<NT>(s.H));
        Vec3T<NT> V = f.scaled_local(lift<NT>(l.v));
        exact_form::LineQuadratic<NT> q;
        q.A = V.x * V.x + V.y * V.y - V.z * V.z;
        q.B = V.x * W.x + V.y * W.y - V.z * W.z;
        q.C0 = W.x * W.x + W.y * W.y - W.z * W.z;
        q.Z0 = negative_det ? -W.z : W.z;
        q.dZ = negative_det ? -V.z : V.z;
        bool two = s.nappes == 2;
        q.lo = negative_det ? f.det : -f.det;
        q.hi = two ? NT(-q.lo) : NT(0);
        q.lo_bounded = s.finite;
        q.hi_bounded = !two || s.finite; // the nappe z <= 0, or the top z = 1
        Extent e = cone_extent(s);
        q.lo_capped = e.caps.lo, q.hi_capped = e.caps.hi, q.two_solids = e.caps.two_solids;
        return q;
    }
    // Its Z alone: W.z, V.z and det from adj(M)'s last row a x b, without the other two.
    // The sign of D = B^2 - A C0 alone. With sigma = (1, 1, -1) and K = 0, Lagrange's identity
    // gives D = X.x^2 + X.y^2 - X.z^2 for X = W x V, and (adj(M) w) x (adj(M) v) = det M^T (w x v)
    // (the cofactor of adj(M) is det M^T): D = det^2 (det[a w v]^2 + det[b w v]^2 - det[c w v]^2),
    // c = H - C, w = L0 - H: three triple products of doubles, degree 6 rather than 12.
    template <class NT>
    static int discriminant_sign(const EllipticCone& s, const Line& l, int /*orientation*/) {
        using exact_form::lift;
        Vec3T<NT> wv = cross(lift<NT>(l.L0) - lift<NT>(s.H), lift<NT>(l.v));
        NT x = dot(lift<NT>(s.a), wv), y = dot(lift<NT>(s.b), wv);
        NT z = dot(lift<NT>(s.H) - lift<NT>(s.C), wv);
        return sign(x * x + y * y - z * z);
    }
    template <class NT>
    static exact_form::LineAxial<NT> exact_axial(const EllipticCone& s, const Line& l,
                                                 int orientation) {
        using exact_form::lift;
        exact_form::FrameZ<NT> Z(lift<NT>(s.a), lift<NT>(s.b), orientation);
        NT det = Z(lift<NT>(s.H) - lift<NT>(s.C)); // |det|
        bool two = s.nappes == 2;
        return {Z(lift<NT>(l.L0) - lift<NT>(s.H)),
                Z(lift<NT>(l.v)),
                -det,
                two ? det : NT(0),
                s.finite,
                !two || s.finite};
    }

    // ---- correct: the Newton rung's line form ----

    // The rows of adj(M) and det in bounded double-double: what prepare() keeps, or computed.
    template <class Source>
    static AdjugateRowsDD adjugate_rows(const Source& src) {
        if constexpr (Source::prepared) {
            return adjugate_rows_dd(src.facts);
        } else {
            const EllipticCone& s = src.shape;
            return adjugate_rows_dd(s.a, s.b, difference_exact(s.H, s.C));
        }
    }

    // For the line L0 + t v in T: double, or a lane type (a line per lane). precise: the Newton
    // rung's, in double-double; else the hit test's quick form, in doubles with bounds. The
    // precise form carries its ends' planes (U0_z and U1_z: no more work), discs where closed.
    template <bool precise, class T, class Source>
    static LineFormT<T> form(const Source& src, Vec3T<T> L0, Vec3T<T> v, int orientation) {
        const EllipticCone& s = src.shape;
        return elliptic_line_form<precise>(
            adjugate_rows(src), L0, s.H, v, orientation,
            [&](LineFormT<T>& f, const BoundedDD& det, auto) {
                f.sigma_z = -1;
                f.K = BoundedDD(0);
                // -|det| <= Z <= 0: the nappe z <= 0; with two nappes Z <= |det| when finite, no
                // bound otherwise.
                bool two = s.nappes == 2;
                double e_det = bound_of_hi(det);
                f.lo = -det.hi, f.e_lo = e_det;
                f.hi = two ? det.hi : 0, f.e_hi = two ? e_det : 0;
                f.lo_bounded = s.finite;
                f.hi_bounded = !two || s.finite;
                f.discs = discs_of(s);
                // The base disc at z = -1 (and the top at z = 1).
                // The batch lanes use planes only where there are discs.
                if (precise && (s.caps || std::is_same_v<T, double>)) {
                    f.planes = DiscPlanesT<T>{{},     {},           -det, two ? det : BoundedDD(0),
                                              s.caps, s.caps && two};
                    // The base's plane through C, spanned by a and b: an exact coordinate for
                    // the base disc's points (one nappe's only).
                    int k = s.caps ? axis_across(s.a, s.b) : -1;
                    if (k >= 0 && !two) f.planes->axis = k, f.planes->lo_at = s.C[k];
                }
            });
    }
    template <class T = double, class Source>
    static LineFormT<T> line_form(const Source& src, Vec3T<T> L0, Vec3T<T> v, int orientation) {
        return form<true, T>(src, L0, v, orientation);
    }

    // ---- correct: the hit test's quick line form (the same, in doubles with bounds) ----

    template <class T = double, class Source>
    static LineFormT<T> quick_line_form(const Source& src, Vec3T<T> L0, Vec3T<T> v,
                                        int orientation) {
        return form<false, T>(src, L0, v, orientation);
    }
};

} // namespace linequad::detail
