// Line against a right circular cylinder {C, H, r} (seed 001): every derivation of it, once.
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
// numeric/bounded.hpp: QuickBounded first, Bounded when that leaves anything uncertain), with
// h = H - C exact (hi, bound |lo|) and the moved origin bounded; a sign is used only when the
// bound excludes zero, so a certain classification is never wrong.
//
// exact: the quadratic above, times nothing, in any exact number type; Z = (P - C) . h with
// 0 <= Z <= h.h.
//
// correct (the Newton rung): g(t) = |u(t)|^2 - K with u(t) = w x h + t (v x h) and K = r^2 (h.h),
// by Lagrange's identity.
#pragma once

#include "forms/bounds.hpp"
#include "forms/certified.hpp"
#include "forms/exact_form.hpp"
#include "forms/line_form.hpp"
#include "forms/roots.hpp"
#include "forms/traits.hpp"

namespace linequad::detail {

// The arithmetic of stable's cylinder solve, once, for a lane type T: double for the scalar
// solver, the 4-lane type for the batch solver. The scalar solver calls these steps with its
// branches; the batch calls them for all lanes and sends the lanes that would branch to the
// scalar solver. Same operations in the same order: the same bits.
template <class T>
struct CylinderStable {
    static constexpr bool parallel_is_miss = true; // A = 0: along the axis, no crossing
    using Mask = decltype(T() < T());
    // Prescaled inputs and what depends on the shape and the line's direction.
    Vec3TwoTermT<T> hx, w;
    Vec3T<T> h, v, vh;
    T r, hh, r2, r2hh, A, inv_vv, dz;
    // From the moved origin.
    T tc, B, C_moved, D, zc;
    Vec3T<T> wc;

    CylinderStable(Vec3T<T> C, Vec3T<T> H, Vec3T<T> L0, Vec3T<T> v_, T r_) : v(v_), r(r_) {
        // h = H - C exactly, as hi + lo: for a line nearly along the axis, v x h is a tiny
        // difference that the rounding of H - C alone would swamp.
        hx = difference_exact(H, C);
        h = hx.rounded();
        hh = dot(h, h);
        w = difference_exact(L0, C);
        vh = cross_accurate(v, hx);
        A = dot(vh, vh);
        r2 = r * r;
        r2hh = r2 * hh;
        inv_vv = T(1) / dot(v, v); // tc need not be a rounded quotient: any tc is an exact move
        dz = dot(v, h);
    }

    // Whether the shape's sizes are below `size` (of the prescaled scene: near unit size).
    Mask smaller_than(Real<T> size) const { return (r < T(size)) | (hh < T(size * size)); }
    // Whether an exact zero of A or D may be underflow: they are products of up to six of the
    // shape's sizes.
    Mask zero_may_underflow() const { return smaller_than(Guards<Real<T>>::min_zero_size); }
    // Lanes that only the scalar solver can finish, beyond the usual branches: none here.
    Mask scalar_only() const { return Mask{}; }
    // C0 at the caller's origin: for lines parallel to the axis, and for Vieta's product. Out of
    // line with its inputs by value: the core's address does not escape, so GCC keeps the core
    // in registers on the usual path (about 20 instructions per solve).
    LINEQUAD_INLINE T C0_at_origin() const { return C0_at(w.rounded(), hx, r2hh); }
    [[gnu::noinline]] static T C0_at(Vec3T<T> w0, Vec3TwoTermT<T> hx, T r2hh) {
        Vec3T<T> wh = cross_accurate(w0, hx);
        return dot(wh, wh) - r2hh;
    }

    // The origin moved to the line's closest approach to the axis' midpoint: never farther
    // than the caller's origin, so every later product is as small as the geometry allows.
    // Then B, C_moved and the discriminant in geometric form. The rounded products of C_moved and D
    // are no less accurate than a factored (sqrt - r|h|)(sqrt + r|h|) form would be: their inputs
    // are rounded already.
    LINEQUAD_INLINE void discriminant() {
        using std::fma;
        tc = -dot(v, w.rounded() - T(0.5) * h) * inv_vv;
        wc = moved_origin(w, tc, v);
        Vec3T<T> whc = cross_accurate(wc, hx);
        B = dot2(vh, whc);
        zc = dot(wc, h);
        C_moved = dot(whc, whc) - r2hh;
        T det = dot2(vh, wc);
        D = hh * fma(-det, det, r2 * A);
    }

    // z = (P - C) . h at a root: from the moved origin, or from the caller's for a root that
    // came from Vieta's product (near the caller's origin); one fma either way.
    T z_moved(T s) const {
        using std::fma;
        return fma(s, dz, zc);
    }
    T z_at_origin(T t) const {
        using std::fma;
        return fma(t, dz, dot2(w.rounded(), h));
    }
    template <class Roots>
    T z_of(const Roots& r, int i) const {
        return r.from_vieta[i] ? z_at_origin(r.t[i]) : z_moved(r.s[i]);
    }
    T z_lanes(T t, T s, Mask from_vieta) const {
        return select(from_vieta, z_at_origin(t), z_moved(s));
    }
    // z = zc + s dz from the moved origin: where the line meets the discs' planes.
    T axial_moved() const { return zc; }
    T axial_rate() const { return dz; }
    ExtentT<T> extent(const Cylinder& s) const {
        if (s.finite) return {T(0.0), hh, both_ends(s.caps)};
        return {T(-Binary64::inf), T(Binary64::inf)};
    }
};

// The axis h = to - from of a circular shape as seed 001 normalises it: h / |h| and |h|, in R;
// what prepare() keeps (AxisFacts, in double), or worked out.
template <class R>
struct SeedAxisT {
    Vec3T<R> unit;
    R length;
};
using SeedAxis = SeedAxisT<double>;
template <class R = double, class Source>
SeedAxisT<R> seed_axis(const Source& src, Vec3 from, Vec3 to) {
    if constexpr (Source::prepared && in_double<R>) {
        return {src.facts.seed_axis, src.facts.seed_length};
    } else {
        Vec3T<R> h = in_real<R>(to) - in_real<R>(from);
        R hn = std::sqrt(dot(h, h));
        return {(1 / hn) * h, hn};
    }
}

// Z = (P - C).h = w.h + t v.h in double from w and h within u of their exact values (and v
// exact): gamma_5 of the products' magnitudes for w.h (two inputs, a product, two sums), gamma_4
// for v.h; 6u and 5u cover them with the magnitudes' own rounding. Both line forms' Z.
template <class T>
LINEQUAD_INLINE void cylinder_axial(LineFormT<T>& f, Vec3T<T> w, Vec3T<T> h, Vec3T<T> v) {
    using F = Binary64;
    f.Z0 = dot(w, h);
    f.e_Z0 = T(6 * F::u) * dot(magnitudes(w), magnitudes(h)) + T(F::underflow_floor);
    f.dZ = dot(v, h);
    f.e_dZ = T(5 * F::u) * dot(magnitudes(v), magnitudes(h)) + T(F::underflow_floor);
    f.lo = 0, f.e_lo = 0;
}

template <>
struct ShapeTraits<Cylinder> {
    static constexpr const char* name = "cylinder";
    static constexpr auto fields = std::make_tuple(
        field("C", &Cylinder::C), field("H", &Cylinder::H), field("r", &Cylinder::r));
    // What a double solver names when the scene is beyond its reach: sizes too small beside the
    // scene, and components too small for its zeros to be trusted.
    static constexpr const char* scale_fields = "r,H-C";
    static constexpr const char* fragile_fields = "v,H-C";
    static constexpr bool has_line_form = true;

    static Validity validate(const Cylinder& s) {
        if (Error e = check_caps(s); !e.ok()) return {e};
        if (!(s.r > 0)) return {{ErrorCode::bad_radius, "r"}};
        if (s.H == s.C) return {{ErrorCode::degenerate_axis, "H-C"}};
        return {};
    }

    // ---- Bounds (a scene's culling) ----

    static Box bounds(const Cylinder& s) {
        return s.finite ? circular_box(s.C, s.r, s.H, s.r) : everything();
    }
    static BoundingCapsule bounding_capsule(const Cylinder& s) { return {s.C, s.H - s.C, s.r}; }

    // ---- What prepare() keeps ----

    template <class R = double, class Source>
    static SeedAxisT<R> seed_axis(const Source& src) {
        return linequad::detail::seed_axis<R>(src, src.shape.C, src.shape.H);
    }
    struct NewtonAxis {
        Vec3TwoTerm h;
        BoundedDD hh, K; // h.h and r^2 h.h
    };
    template <class Source>
    static NewtonAxis newton_axis(const Source& src) {
        if constexpr (Source::prepared) {
            const Facts<Cylinder>& f = src.facts;
            return {{f.h_hi, f.h_lo}, bounded_dd(f.hh), bounded_dd(f.K)};
        } else {
            const Cylinder& s = src.shape;
            NewtonAxis a;
            a.h = difference_exact(s.H, s.C);
            CompensatedSum hh_sum; // h.h
#pragma GCC unroll 3
            for (int k = 0; k < 3; ++k) {
                hh_sum.add_product(a.h.hi[k], a.h.hi[k]);
                hh_sum.add_small(2 * a.h.hi[k] * a.h.lo[k]);
                hh_sum.add_small(a.h.lo[k] * a.h.lo[k]);
            }
            a.hh = hh_sum.result();
            TwoTerm r2 = two_prod(s.r, s.r);
            a.K = product(BoundedDD{r2.hi, r2.lo, 0}, a.hh);
            return a;
        }
    }
    static void prepare(const Cylinder& s, Facts<Cylinder>& f) {
        SeedAxis axis = seed_axis(AsGiven<Cylinder>{s});
        f.seed_axis = axis.unit, f.seed_length = axis.length;
        NewtonAxis n = newton_axis(AsGiven<Cylinder>{s});
        f.h_hi = n.h.hi, f.h_lo = n.h.lo;
        store(n.hh, f.hh), store(n.K, f.K);
    }

    // ---- seed ----

    template <class R, class Source>
    static SeedFormT<R> seed_form(const Source& src, const Line& l) {
        const Cylinder& s = src.shape;
        SeedAxisT<R> axis = seed_axis<R>(src);
        Vec3T<R> v = in_real<R>(l.v), w = in_real<R>(l.L0) - in_real<R>(s.C);
        R r = R(s.r);
        R vh = dot(v, axis.unit), wh = dot(w, axis.unit);
        R a = dot(v, v) - vh * vh;
        R b = 2 * (dot(v, w) - vh * wh);
        R c = dot(w, w) - wh * wh - r * r;
        bool usable =
            std::isfinite(a) && std::isfinite(b) && std::isfinite(c) && std::isfinite(axis.length);
        Extent e = s.finite ? Extent{0, axis.length, both_ends(s.caps)}
                            : Extent{-Binary64::inf, Binary64::inf};
        return {a, b, c, wh, vh, e, usable};
    }

    // ---- stable ----

    template <class T>
    using Stable = CylinderStable<T>;
    // The core for the line L0 + t v (a lane type's values for the batch), prescaled by ps.
    template <class T, class Source, class Scale>
    static Stable<T> stable_core(const Source& src, const Scale& ps, Vec3T<T> L0, Vec3T<T> v) {
        const Cylinder& s = src.shape;
        return {ps.pos(s.C), ps.pos(s.H), ps.pos(L0), ps.dir(v), ps.len(s.r)};
    }

    // ---- certified ----

    template <class B, class Source>
    static CertifiedForm<B> certified_form(const Source& src, const Prescale& ps, const Line& l) {
        const Cylinder& s = src.shape;
        Vec3 C = ps.pos(s.C), v = ps.dir(l.v);
        Vec3TwoTerm w = difference_exact(ps.pos(l.L0), C);
        BoundedVec3<B> h = difference_bounded<B>(ps.pos(s.H), C), V = exact<B>(v);
        B R = B::exact(ps.len(s.r)), hh = dot(h, h);
        BoundedVec3<B> vxh = cross(V, h);
        B A = dot(vxh, vxh);
        // Any tc is an exact move of the origin; the closest approach to the axis' middle keeps
        // the bounded quantities small. A line exactly parallel to the axis is not moved, so
        // that its exact zeros stay exact; nor is one exactly across it (z constant) when a disc
        // may hold it.
        Vec3 hm{h.x.v, h.y.v, h.z.v};
        B dz = dot(V, h);
        bool keep = exactly_zero(A) || (s.caps && exactly_zero(dz));
        double tc = keep ? 0 : -dot(v, w.rounded() - 0.5 * hm) / dot(v, v);
        BoundedVec3<B> wc = moved_origin_bounded<B>(w, tc, v), wxh = cross(wc, h);
        B det = dot(V, wxh);
        BoundedQuadratic<B> quad{A, dot(vxh, wxh), dot(wxh, wxh) - R * R * hh,
                                 hh * (R * R * A - det * det)};
        // z = (P - C) . h / h.h
        Extent e =
            s.finite ? Extent{0, 1, both_ends(s.caps)} : Extent{-Binary64::inf, Binary64::inf};
        return {quad, tc, dot(wc, h) / hh, dz / hh, e};
    }

    // ---- exact ----

    // The circular cylinder has no frame to orient.
    template <class NT>
    static int exact_orientation(const Cylinder&) {
        return 0;
    }

    // Multiplied through by h.h: |P - C|^2 (h.h) - ((P - C).h)^2 = r^2 (h.h),
    // 0 <= (P - C).h <= h.h, with P = L0 + t v, w = L0 - C, h = H - C.
    template <class NT, class L>
    static exact_form::LineQuadratic<NT> exact_quadratic(const Cylinder& s, const L& l,
                                                         int /*orientation*/) {
        using exact_form::lift;
        Vec3T<NT> h = lift<NT>(s.H) - lift<NT>(s.C), w = exact_form::origin<NT>(l) - lift<NT>(s.C);
        Vec3T<NT> v = lift<NT>(l.v);
        NT hh = dot(h, h), vh = dot(v, h), wh = dot(w, h), r(s.r);
        exact_form::LineQuadratic<NT> q;
        q.A = dot(v, v) * hh - vh * vh;
        q.B = dot(v, w) * hh - vh * wh;
        q.C0 = dot(w, w) * hh - wh * wh - r * r * hh;
        q.Z0 = wh, q.dZ = vh, q.lo = NT(0), q.hi = hh;
        q.lo_bounded = q.hi_bounded = s.finite;
        q.lo_capped = q.hi_capped = s.caps;
        return q;
    }
    // The sign of D = B^2 - A C0 alone, from a form of lower degree: with U0 = w x h, U1 = v x h
    // and K = r^2 h.h, Lagrange's identity gives D = K |U1|^2 - |U0 x U1|^2, and U0 x U1 =
    // -det[w h v] h, so D = h.h (r^2 |v x h|^2 - det[w v h]^2): degree 6 in the inputs, not 8, and
    // no A, B or C0 (where a tangency is to be shown, at a fraction of the whole form's cost).
    template <class NT>
    static int discriminant_sign(const Cylinder& s, const Line& l, int /*orientation*/) {
        using exact_form::lift;
        Vec3T<NT> h = lift<NT>(s.H) - lift<NT>(s.C), w = lift<NT>(l.L0) - lift<NT>(s.C);
        Vec3T<NT> vh = cross(lift<NT>(l.v), h);
        NT det = dot(w, vh), r(s.r);
        return sign(r * r * dot(vh, vh) - det * det);
    }
    // At a double root t* = -B/A (A > 0), the sign of Z(t*) - end, the tangency's side of the
    // base (top = false) or the top: A (Z0 - end) - dZ B = h.h (h x v) . (w_e x v), w_e = L0 less
    // that end's centre (Lagrange's identity twice): degree 4, not 6. None where the cylinder
    // has no ends.
    template <class NT>
    static std::optional<int> tangency_against_end(const Cylinder& s, const Line& l, bool top) {
        if (!s.finite) return std::nullopt;
        using exact_form::lift;
        Vec3T<NT> v = lift<NT>(l.v), h = lift<NT>(s.H) - lift<NT>(s.C);
        Vec3T<NT> w = lift<NT>(l.L0) - lift<NT>(top ? s.H : s.C);
        return sign(dot(cross(h, v), cross(w, v)));
    }
    // Its Z alone: three dot products.
    template <class NT>
    static exact_form::LineAxial<NT> exact_axial(const Cylinder& s, const Line& l,
                                                 int /*orientation*/) {
        using exact_form::lift;
        Vec3T<NT> h = lift<NT>(s.H) - lift<NT>(s.C);
        return {dot(lift<NT>(l.L0) - lift<NT>(s.C), h),
                dot(lift<NT>(l.v), h),
                NT(0),
                dot(h, h),
                s.finite,
                s.finite};
    }

    // ---- correct: the Newton rung's line form ----

    // For the line L0 + t v in T: double, or a lane type (a line per lane).
    template <class T = double, class Source>
    static LineFormT<T> line_form(const Source& src, Vec3T<T> L0, Vec3T<T> v, int /*orientation*/) {
        const Cylinder& s = src.shape;
        NewtonAxis axis = newton_axis(src);
        Vec3TwoTermT<T> h{lanes_of<T>(axis.h.hi), lanes_of<T>(axis.h.lo)};
        Vec3TwoTermT<T> w = difference_exact(L0, lanes_of<T>(s.C));
        LineFormT<T> f;
#pragma GCC unroll 3
        for (int k = 0; k < 3; ++k) {
            f.U0[k] = cross_component(w, h, k);
            f.U1[k] = cross_component(v, h, k);
        }
        f.sigma_z = 1;
        f.K = axis.K;
        // Z from the high parts, each within u of its exact value (the low parts left out).
        cylinder_axial(f, w.hi, h.hi, v);
        f.hi = axis.hh.hi, f.e_hi = bound_of_hi(axis.hh);
        f.lo_bounded = f.hi_bounded = s.finite;
        f.discs = discs_of(s);
        if (s.caps) set_planes<T>(f.planes, s, axis, w, v);
        return f;
    }
    // The ends' planes of a finite open cylinder, which its form does not carry, for the line as
    // given (ExtentEnds::end_planes asks for them): two dot products, not the whole form.
    template <class Source>
    static std::optional<DiscPlanes> end_planes(const Source& src, Vec3 L0, Vec3 v) {
        const Cylinder& s = src.shape;
        std::optional<DiscPlanes> p;
        if (s.finite) set_planes<double>(p, s, newton_axis(src), difference_exact(L0, s.C), v);
        return p;
    }

  private:
    // The ends at Z = 0 and Z = h.h, with discs where the cylinder is closed; built in place.
    template <class T>
    LINEQUAD_INLINE static void set_planes(std::optional<DiscPlanesT<T>>& p, const Cylinder& s,
                                           const NewtonAxis& axis, const Vec3TwoTermT<T>& w,
                                           Vec3T<T> v) {
        Vec3TwoTermT<T> h{lanes_of<T>(axis.h.hi), lanes_of<T>(axis.h.lo)};
        p = DiscPlanesT<T>{dot_dd(w, h), dot_dd(v, h), BoundedDD(0), axis.hh, s.caps, s.caps};
        p->axis = axis_along(s.H - s.C);
        if (p->axis >= 0) p->lo_at = s.C[p->axis], p->hi_at = s.H[p->axis];
    }

  public:
    // ---- correct: the hit test's quick line form (the same, in doubles with bounds) ----

    // Every value is a sum of products of the rounded w = L0 - C, h = H - C (each coordinate
    // within u of its exact value), v and r, evaluated in double: with n perturbations of at
    // most u along its deepest path, its error is at most gamma_n times the same expression in
    // absolute values (Higham, (3.5)). cross: two inputs, a product, a difference (n = 4, 5u
    // covers gamma_4 with the magnitude's own rounding); with v exact, n = 3 (4u); h.h and
    // w.h: n = 5 (6u); v.h: 5u; K = r^2 h.h: n = 7 (8u).
    template <class T = double, class Source>
    static LineFormT<T> quick_line_form(const Source& src, Vec3T<T> L0, Vec3T<T> v,
                                        int /*orientation*/) {
        using F = Binary64;
        const Cylinder& s = src.shape;
        Vec3 h_shape = [&] {
            if constexpr (Source::prepared)
                return src.facts.h_hi; // h.hi of the exact difference: within u
            else
                return s.H - s.C;
        }();
        Vec3T<T> h = lanes_of<T>(h_shape), w = L0 - lanes_of<T>(s.C);
        Vec3T<T> U0 = cross(w, h), U1 = cross(v, h);
        Vec3T<T> m0 = cross_magnitudes(w, h), m1 = cross_magnitudes(v, h);
        double hh = dot(h_shape, h_shape), K = (s.r * s.r) * hh;
        LineFormT<T> f;
#pragma GCC unroll 3
        for (int k = 0; k < 3; ++k) {
            f.U0[k] = {U0[k], T(0.0), T(5 * F::u) * m0[k] + T(F::underflow_floor)};
            f.U1[k] = {U1[k], T(0.0), T(4 * F::u) * m1[k] + T(F::underflow_floor)};
        }
        f.sigma_z = 1;
        f.K = BoundedDD(K, 0, 8 * F::u * K + F::underflow_floor);
        cylinder_axial(f, w, h, v);
        f.hi = hh, f.e_hi = 6 * F::u * hh + F::underflow_floor;
        f.lo_bounded = f.hi_bounded = s.finite;
        f.discs = discs_of(s);
        return f;
    }
};

} // namespace linequad::detail
