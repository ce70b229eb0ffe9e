// Line against a right circular frustum {C0, r0, C1, r1}: every derivation of it, once. No seed
// derives it; it is the cylinder's derivation (seed 001, cylinder.hpp) with a radius that grows
// linearly along the axis, and r0 = r1 gives the cylinder's roots exactly.
//
// Derivation (checked against the surface equation). With h = C1 - C0, w = L0 - C0 and the axial
// coordinate u = (P - C0) . h (0 at C0, h.h at C1), the radius at P is
//     rho = r0 + (r1 - r0) u / (h.h),
// and P is on the surface iff its distance to the axis, |(P - C0) x h| / |h|, is rho. Squared
// and multiplied by (h.h)^2 (no square root, no division), with R = (h.h) rho:
//     (h.h) |(P - C0) x h|^2 - R^2 = 0,   R = r0 (h.h) + (r1 - r0) u.
// Substituting P = L0 + t v, with X = v x h, Y = w x h, R(t) = R0 + t dR:
//     A t^2 + 2 B t + C0 = 0,
//     A  = (h.h) |X|^2 - dR^2,        dR = (r1 - r0) (v.h),
//     B  = (h.h) X.Y - R0 dR,         R0 = r0 (h.h) + (r1 - r0) (w.h),
//     C0 = (h.h) |Y|^2 - R0^2.
// For r0 = r1 = r this is (h.h) times the cylinder's quadratic. The quadratic is negative inside
// the surface (nearer the axis than rho), in either nappe of the double cone it describes; the
// extent keeps one: finite, 0 <= u <= h.h; not finite, the nappe R >= 0 (the whole cylinder when
// r0 = r1, where R is the constant r0 (h.h)). The axial coordinate is u when finite and R
// otherwise, so that each bound is 0, h.h or none, never the apex's u = -r0 (h.h) / (r1 - r0).
// A = 0: a line along a generator (one crossing) or, for r0 = r1, along the axis (then B = 0 too:
// no hit, or on the surface when C0 = 0).
//
// Discriminant in geometric form. (v x h) x (w x h) = det h with det = (v x h) . w (the triple
// product), so Lagrange's identity gives
//     D = B^2 - A C0 = (h.h) (|R0 X - dR Y|^2 - ((h.h) det)^2),
// a difference of two squares of accurate numbers (for r0 = r1: (h.h)^3 (r^2 |X|^2 - det^2),
// the cylinder's). R0 X - dR Y and det do not change when the origin moves along the line.
//
// seed: the textbook cone quadratic with the unit axis h^ = h / |h| and the slope
// k = (r1 - r0) / |h|: |w + t v|^2 - (s(t))^2 - (r0 + k s(t))^2 = 0 with s = (P - C0) . h^.
//
// stable: the quantities above in double, h = C1 - C0 exactly (hi + lo) inside v x h and w x h
// (Kahan's fma difference of products), dR^2, R0 dR, R0^2 and ((h.h) det)^2 exact inside fmas,
// the stable root pair, and the scene prescaled by powers of two. Everything is measured from
// an apex where the frustum has one (w = L0 - E, u_E = (P - E) . h, R = r_E (h.h) + (r1 - r0) u_E
// with E the apex), so that near it R, Y and the discriminant are small rather than cancelled,
// and the origin moves to the line's closest approach to the apex (as the cone's), or to the
// middle of the axis (as the cylinder's).
//
// certified: the same in bounded arithmetic (QuickBounded, then Bounded), h exact (hi and bound).
//
// exact: the quadratic above in any exact number type, with Z = u in [0, h.h] (finite) or
// Z = R >= 0 (not finite).
//
// correct: the Newton rung's form with four terms. Divided by h.h > 0 (which moves no root),
//     g(t) = |Y + t X|^2 - (R(t) / |h|)^2,
// three squares of the cylinder's cross products and a fourth, negative, whose U0 = R0 / |h| and
// U1 = dR / |h| are bounded double-doubles (|h| = sqrt(h.h) is irrational, but the rung needs only
// bounds). The axial coordinate and its extent are the exact form's.
#pragma once

#include "forms/bounds.hpp"
#include "forms/certified.hpp"
#include "forms/exact_form.hpp"
#include "forms/line_form.hpp"
#include "forms/roots.hpp"
#include "forms/traits.hpp"
#include "numeric/bounded_dd_lanes.hpp"
#include "shapes/cylinder.hpp"

namespace linequad::detail {

// The disc at each end whose radius is not 0.
inline Closure frustum_closure(const Frustum& s) {
    return {s.caps && s.r0 > 0, s.caps && s.r1 > 0, false};
}

// The end the stable and certified forms measure from: an apex where there is one (its radius
// is then 0, and the quantities that vanish there are small rather than cancelled), else C0. The
// axial coordinate is u_E = (P - E) . h, whose extent is [0, h.h] from C0 and [-h.h, 0] from C1.
// The origin then moves to the line's closest approach to E + middle h: the apex, or the
// middle of the axis.
struct Reference {
    bool top;      // E = C1 (else C0)
    double middle; // 0 or 1/2
};
inline Reference reference(const Frustum& s) {
    bool apex = s.r0 == 0 || s.r1 == 0;
    return {s.r1 == 0, apex ? 0.0 : 0.5};
}

// A frustum's ends in a lane type (prescaled).
template <class T>
struct FrustumEnds {
    Vec3T<T> C0, C1;
    T r0, r1;
};

// stable's frustum solve for a lane type T (double, or the batch's lanes), as CylinderStable.
template <class T>
struct FrustumStable {
    // A = 0: along a generator (one root), or along a cylinder's axis (B = 0: none or on it).
    static constexpr bool parallel_is_miss = false;
    using Mask = decltype(T() < T());
    Vec3TwoTermT<T> hx, w; // h = C1 - C0 and w = L0 - E exactly
    Vec3T<T> h, v, X;
    T r0, r1, dr, hh, R_end, dz, dR, A, inv_vv;
    T middle; // the origin moves to the closest approach to E + middle h
    bool top, finite;
    // From the moved origin.
    T tc, B, C_moved, D, zc;

    FrustumStable(const FrustumEnds<T>& ends, Vec3T<T> L0, Vec3T<T> v_, Reference ref, bool finite_)
        : v(v_), r0(ends.r0), r1(ends.r1), middle(ref.middle), top(ref.top), finite(finite_) {
        using std::fma;
        const Vec3T<T>&C0 = ends.C0, &C1 = ends.C1;
        hx = difference_exact(C1, C0);
        h = hx.rounded();
        hh = dot(h, h);
        R_end = (top ? r1 : r0) * hh;
        w = difference_exact(L0, top ? C1 : C0);
        X = cross_accurate(v, hx);
        dr = r1 - r0;
        dz = dot(v, h);
        dR = dr * dz;
        A = fma(-dR, dR, hh * dot(X, X));
        inv_vv = T(1) / dot(v, v);
    }

    Mask smaller_than(Real<T> size) const {
        return (lane_max(r0, r1) < T(size)) | (hh < T(size * size));
    }
    // Whether an exact zero of A or D may be underflow: D = h.h (|G|^2 - K^2) is a product of
    // up to ten of the shape's sizes.
    Mask zero_may_underflow() const { return smaller_than(Guards<Real<T>>::min_zero_size); }
    Mask scalar_only() const { return Mask{}; }

    // R = rE (h.h) + (r1 - r0) u_E from u_E = (P - E) . h.
    T radius_times_hh(T u) const {
        using std::fma;
        return fma(dr, u, R_end);
    }
    // The extent's coordinate from u_E: u_E itself (finite), or R (the nappe R >= 0).
    T axial(T u) const { return finite ? u : radius_times_hh(u); }
    T axial_rate() const { return finite ? dz : dR; }

    T C0_at_origin() const {
        using std::fma;
        Vec3T<T> w0 = w.rounded();
        Vec3T<T> Y = cross_accurate(w0, hx);
        T R0 = radius_times_hh(dot2(w0, h));
        return fma(-R0, R0, hh * dot(Y, Y));
    }

    // The origin moved to the line's closest approach to the apex, or to the axis' middle; then
    // B, C_moved and the discriminant in geometric form (see the derivation). Not moved along a
    // generator or a cylinder's axis (A = 0), where B and C_moved are exact zeros for a line on the
    // surface only at the caller's origin.
    void discriminant() {
        using std::fma;
        tc = select(A != T(0.0), -dot(v, w.rounded() - middle * h) * inv_vv, T(0.0));
        Vec3T<T> wc = moved_origin(w, tc, v);
        Vec3T<T> Y = cross_accurate(wc, hx);
        zc = dot(wc, h);
        T R0 = radius_times_hh(zc);
        B = fma(-R0, dR, hh * dot2(X, Y));
        C_moved = fma(-R0, R0, hh * dot(Y, Y));
        T K = hh * dot2(X, wc);
        Vec3T<T> G = R0 * X - dR * Y;
        D = hh * fma(-K, K, dot(G, G));
    }

    T z_moved(T s) const {
        using std::fma;
        return fma(s, axial_rate(), axial(zc));
    }
    T z_at_origin(T t) const {
        using std::fma;
        return fma(t, axial_rate(), axial(dot2(w.rounded(), h)));
    }
    template <class Roots>
    T z_of(const Roots& r, int i) const {
        return r.from_vieta[i] ? z_at_origin(r.t[i]) : z_moved(r.s[i]);
    }
    T z_lanes(T t, T s, Mask from_vieta) const {
        return select(from_vieta, z_at_origin(t), z_moved(s));
    }
    T axial_moved() const { return axial(zc); }
    ExtentT<T> extent(const Frustum& s) const {
        if (!s.finite) return {T(0.0), T(Binary64::inf)};
        if (top) return {-hh, T(0.0), frustum_closure(s)};
        return {T(0.0), hh, frustum_closure(s)};
    }
};

template <>
struct ShapeTraits<Frustum> {
    static constexpr const char* name = "frustum";
    static constexpr auto fields =
        std::make_tuple(field("C0", &Frustum::C0), field("r0", &Frustum::r0),
                        field("C1", &Frustum::C1), field("r1", &Frustum::r1));
    static constexpr const char* scale_fields = "r0,r1,C1-C0";
    static constexpr const char* fragile_fields = "v,C1-C0";
    static constexpr bool has_line_form = true;

    static Validity validate(const Frustum& s) {
        if (Error e = check_caps(s); !e.ok()) return {e};
        if (!(s.r0 >= 0)) return {{ErrorCode::bad_radius, "r0"}};
        if (!(s.r1 >= 0)) return {{ErrorCode::bad_radius, "r1"}};
        if (s.r0 == 0 && s.r1 == 0) return {{ErrorCode::bad_radius, "r0,r1"}};
        if (s.C1 == s.C0) return {{ErrorCode::degenerate_axis, "C1-C0"}};
        return {};
    }

    static Box bounds(const Frustum& s) {
        return s.finite ? circular_box(s.C0, s.r0, s.C1, s.r1) : everything();
    }
    static BoundingCapsule bounding_capsule(const Frustum& s) {
        return {s.C0, s.C1 - s.C0, std::max(s.r0, s.r1)};
    }

    static void prepare(const Frustum& s, Facts<Frustum>& f) {
        SeedAxis axis = seed_axis(AsGiven<Frustum>{s}, s.C0, s.C1);
        f.seed_axis = axis.unit, f.seed_length = axis.length;
    }

    // ---- seed ----

    // s = (P - C0) . h^ along the unit axis, rho = r0 + k s: |P - C0|^2 - s^2 - rho^2 = 0; the
    // extent's coordinate is s (finite: 0 <= s <= |h|) or rho (the nappe rho >= 0).
    template <class R, class Source>
    static SeedFormT<R> seed_form(const Source& src, const Line& l) {
        const Frustum& s = src.shape;
        SeedAxisT<R> axis = seed_axis<R>(src, s.C0, s.C1);
        R r0 = R(s.r0), k = (R(s.r1) - r0) / axis.length;
        Vec3T<R> v = in_real<R>(l.v), w = in_real<R>(l.L0) - in_real<R>(s.C0);
        R vh = dot(v, axis.unit), wh = dot(w, axis.unit), rho = r0 + k * wh;
        R a = dot(v, v) - vh * vh - k * k * vh * vh;
        R b = 2 * (dot(v, w) - vh * wh - k * vh * rho);
        R c = dot(w, w) - wh * wh - rho * rho;
        bool usable = std::isfinite(a) && std::isfinite(b) && std::isfinite(c) &&
                      std::isfinite(axis.length) && std::isfinite(k);
        if (s.finite) return {a, b, c, wh, vh, {0, axis.length, frustum_closure(s)}, usable};
        return {a, b, c, rho, k * vh, {0, Binary64::inf}, usable};
    }

    // ---- stable ----

    template <class T>
    using Stable = FrustumStable<T>;
    template <class T, class Source, class Scale>
    static Stable<T> stable_core(const Source& src, const Scale& ps, Vec3T<T> L0, Vec3T<T> v) {
        const Frustum& s = src.shape;
        FrustumEnds<T> ends{ps.pos(s.C0), ps.pos(s.C1), ps.len(s.r0), ps.len(s.r1)};
        return {ends, ps.pos(L0), ps.dir(v), reference(s), s.finite};
    }

    // ---- certified ----

    template <class B, class Source>
    static CertifiedForm<B> certified_form(const Source& src, const Prescale& ps, const Line& l) {
        const Frustum& s = src.shape;
        auto [top, middle] = reference(s);
        Vec3 C0 = ps.pos(s.C0), C1 = ps.pos(s.C1), v = ps.dir(l.v);
        Vec3TwoTerm w = difference_exact(ps.pos(l.L0), top ? C1 : C0); // from E
        BoundedVec3<B> h = difference_bounded<B>(C1, C0), V = exact<B>(v);
        B r0 = B::exact(ps.len(s.r0)), r1 = B::exact(ps.len(s.r1)), dr = r1 - r0;
        B hh = dot(h, h), rE = top ? r1 : r0;
        BoundedVec3<B> X = cross(V, h);
        B dz = dot(V, h), dR = dr * dz;
        B A = hh * dot(X, X) - dR * dR;
        // Not moved along a generator or a cylinder's axis, where exact zeros decide, nor across
        // the axis when a disc may hold the line (as the cylinder's). Otherwise to the closest
        // approach to the apex, or to the axis' middle.
        Vec3 hm{h.x.v, h.y.v, h.z.v};
        bool keep = exactly_zero(A) || (s.caps && exactly_zero(dz));
        double tc = keep ? 0 : -dot(v, w.rounded() - middle * hm) / dot(v, v);
        BoundedVec3<B> wc = moved_origin_bounded<B>(w, tc, v), Y = cross(wc, h);
        B u = dot(wc, h), R0 = rE * hh + dr * u, K = hh * dot(X, wc);
        BoundedVec3<B> G = R0 * X - dR * Y;
        BoundedQuadratic<B> quad{A, hh * dot(X, Y) - R0 * dR, hh * dot(Y, Y) - R0 * R0,
                                 hh * (dot(G, G) - K * K)};
        // z = u_E / h.h in [0, 1] (from C0) or [-1, 0] (from C1), or the radius R / h.h >= 0.
        if (!s.finite) return {quad, tc, R0 / hh, dR / hh, {0, Binary64::inf}};
        return {quad, tc, u / hh, dz / hh, {top ? -1.0 : 0.0, top ? 0.0 : 1.0, frustum_closure(s)}};
    }

    // ---- exact ----

    template <class NT>
    static int exact_orientation(const Frustum&) {
        return 0;
    }

    template <class NT, class L>
    static exact_form::LineQuadratic<NT> exact_quadratic(const Frustum& s, const L& l,
                                                         int /*orientation*/) {
        using exact_form::lift;
        Vec3T<NT> h = lift<NT>(s.C1) - lift<NT>(s.C0),
                  w = exact_form::origin<NT>(l) - lift<NT>(s.C0);
        Vec3T<NT> v = lift<NT>(l.v);
        NT r0(s.r0), dr = NT(s.r1) - r0, hh = dot(h, h), vh = dot(v, h), wh = dot(w, h);
        Vec3T<NT> X = cross(v, h), Y = cross(w, h);
        NT R0 = r0 * hh + dr * wh, dR = dr * vh;
        exact_form::LineQuadratic<NT> q;
        q.A = hh * dot(X, X) - dR * dR;
        q.B = hh * dot(X, Y) - R0 * dR;
        q.C0 = hh * dot(Y, Y) - R0 * R0;
        q.lo = NT(0);
        if (s.finite) {
            q.Z0 = wh, q.dZ = vh, q.hi = hh;
            Closure c = frustum_closure(s);
            q.lo_capped = c.lo, q.hi_capped = c.hi;
        } else {
            q.Z0 = R0, q.dZ = dR, q.hi = NT(0);
            q.hi_bounded = false;
        }
        return q;
    }
    // Its Z alone: dot products with h (and the radii where the frustum runs on as a cone).
    template <class NT>
    static exact_form::LineAxial<NT> exact_axial(const Frustum& s, const Line& l,
                                                 int /*orientation*/) {
        using exact_form::lift;
        Vec3T<NT> h = lift<NT>(s.C1) - lift<NT>(s.C0);
        NT hh = dot(h, h), vh = dot(lift<NT>(l.v), h), wh = dot(lift<NT>(l.L0) - lift<NT>(s.C0), h);
        if (s.finite) return {wh, vh, NT(0), hh, true, true};
        NT r0(s.r0), dr = NT(s.r1) - r0;
        return {r0 * hh + dr * wh, dr * vh, NT(0), NT(0), true, false};
    }

    // ---- correct: the Newton rung's line form (four terms) ----

    // For the line L0 + t v in T: double, or a lane type (a line per lane). The shape's own
    // values (h, h.h, r1 - r0, |h|) are formed once in double; each lane's are formed from them
    // as the scalar form forms its line's, operation for operation.
    template <class T = double, class Source>
    static LineFormT<T> line_form(const Source& src, Vec3T<T> L0, Vec3T<T> v, int /*orientation*/) {
        const Frustum& s = src.shape;
        Vec3TwoTerm h_shape = difference_exact(s.C1, s.C0);
        Vec3TwoTermT<T> h{lanes_of<T>(h_shape.hi), lanes_of<T>(h_shape.lo)};
        Vec3TwoTermT<T> w = difference_exact(L0, lanes_of<T>(s.C0));
        LineFormT<T> f;
#pragma GCC unroll 3
        for (int k = 0; k < 3; ++k) {
            f.U0[k] = cross_component(w, h, k);
            f.U1[k] = cross_component(v, h, k);
        }
        BoundedDD hh = dot_dd(h_shape, h_shape);
        BoundedDDT<T> wh = dot_dd(w, h), vh = dot_dd(v, h);
        TwoTerm dr_exact = two_sum(s.r1, -s.r0);
        BoundedDD dr(dr_exact.hi, dr_exact.lo, 0), length = sqrt(hh);
        BoundedDD base = product(BoundedDD(s.r0), hh); // r0 h.h
        BoundedDDT<T> R0, dR = product(lanes_of<T>(dr), vh);
        if constexpr (std::is_same_v<T, double>) {
            R0 = base + product(dr, wh);
            f.fourth = FourthTerm<T>{R0 / length, dR / length};
        } else {
            R0 = sum_lanes(lanes_of<T>(base), product(lanes_of<T>(dr), wh));
            f.fourth = FourthTerm<T>{quotient_lanes(R0, lanes_of<T>(length)),
                                     quotient_lanes(dR, lanes_of<T>(length))};
        }
        f.sigma_z = four_terms;
        f.K = BoundedDD(0);
        // Z = u in [0, h.h] (finite), or R >= 0 (the nappe).
        const BoundedDDT<T>& Z0 = s.finite ? wh : R0;
        const BoundedDDT<T>& dZ = s.finite ? vh : dR;
        f.Z0 = Z0.hi, f.e_Z0 = bound_of_hi(Z0), f.dZ = dZ.hi, f.e_dZ = bound_of_hi(dZ);
        f.lo = 0, f.e_lo = 0, f.lo_bounded = true;
        f.hi = hh.hi, f.e_hi = bound_of_hi(hh), f.hi_bounded = s.finite;
        f.discs = discs_of(s);
        if (s.finite) { // the ends' planes, from what the form has: discs where closed
            Closure discs = frustum_closure(s); // none where open
            f.planes = DiscPlanesT<T>{wh, vh, BoundedDD(0), hh, discs.lo, discs.hi};
            f.planes->axis = s.caps ? axis_along(s.C1 - s.C0) : -1; // only discs have points there
            if (f.planes->axis >= 0)
                f.planes->lo_at = s.C0[f.planes->axis], f.planes->hi_at = s.C1[f.planes->axis];
        }
        return f;
    }

    // The hit test's: the same values as doubles with their bounds (no cheaper form of the
    // fourth term).
    template <class T = double, class Source>
    static LineFormT<T> quick_line_form(const Source& src, Vec3T<T> L0, Vec3T<T> v,
                                        int orientation) {
        LineFormT<T> f = line_form<T>(src, L0, v, orientation);
        auto quick = [](BoundedDDT<T>& x) { x = {x.hi, T(0.0), bound_of_hi(x)}; };
        for (int k = 0; k < 3; ++k)
            quick(f.U0[k]), quick(f.U1[k]);
        quick(f.fourth->U0), quick(f.fourth->U1);
        f.K = {f.K.hi, 0, bound_of_hi(f.K)};
        f.planes.reset();
        return f;
    }
};

} // namespace linequad::detail
