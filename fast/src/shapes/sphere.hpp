// Line against a sphere {C, r}: every derivation of it, once.
//
// Derivation (checked against the surface equation). P is on the sphere iff |P - C|^2 = r^2.
// Substituting P = L0 + t v, with w = L0 - C:
//     A t^2 + 2 B t + C0 = 0,   A = v.v,   B = v.w,   C0 = w.w - r^2.
// The quadratic is negative inside, and the sphere is a closed solid with no extent: a line meets
// it in [t1, t2] (two crossings), touches it (a double root: tangent) or misses it. A = 0 only for
// v = 0, which every solver refuses first.
//
// seed: the textbook quadratic a = v.v, b = 2 v.w, c = w.w - r^2, solved as written.
//
// stable: w = L0 - C exactly (hi + lo); the origin moved to the line's closest approach to C,
// tc = -v.w / v.v (B is then nearly 0 and C0 = |wc|^2 - r^2, r^2 exact inside an fma); and the
// discriminant in geometric form. Lagrange's identity, |v|^2 |w|^2 - (v.w)^2 = |v x w|^2, gives
//     D = B^2 - A C0 = r^2 (v.v) - |v x w|^2,
// a difference of two accurate numbers (v x w by Kahan's cross product, the same at any origin
// on the line: |v x w| / |v| is the line's distance from C), not of the large squares B^2 and
// A C0. Then the stable root pair, and the scene prescaled by powers of two.
//
// certified: the same quantities in bounded arithmetic (QuickBounded, then Bounded).
//
// exact: the quadratic above in any exact number type; no extent (Z unbounded).
//
// correct (the Newton rung): g(t) = |w + t v|^2 - r^2: U0 = w (exact, in double-double), U1 = v,
// K = r^2 (exact), sigma = (1, 1, 1).
#pragma once

#include "forms/bounds.hpp"
#include "forms/certified.hpp"
#include "forms/exact_form.hpp"
#include "forms/line_form.hpp"
#include "forms/roots.hpp"
#include "forms/traits.hpp"
#include "numeric/bounded_dd.hpp"
#include "numeric/expansion.hpp"

namespace linequad::detail {

// The arithmetic of stable's sphere solve, once, for a lane type T (as CylinderStable).
template <class T>
struct SphereStable {
    static constexpr bool parallel_is_miss = true; // A = v.v = 0 only for v = 0 (refused)
    using Mask = decltype(T() < T());
    Vec3TwoTermT<T> w;
    Vec3T<T> v;
    T r, A, inv_vv;
    // From the moved origin.
    T tc, B, C_moved, D;
    Vec3T<T> wc;

    SphereStable(Vec3T<T> C, Vec3T<T> L0, Vec3T<T> v_, T r_)
        : w(difference_exact(L0, C)), v(v_), r(r_) {
        A = dot(v, v);
        inv_vv = T(1) / A;
    }

    Mask smaller_than(Real<T> size) const { return r < T(size); }
    // A zero of D may be underflow when the sphere is tiny: D is a product of up to four sizes.
    Mask zero_may_underflow() const { return smaller_than(Guards<Real<T>>::min_zero_size); }
    Mask scalar_only() const { return Mask{}; }
    // |w|^2 - r^2 at the caller's origin (for Vieta's product).
    T C0_at_origin() const {
        using std::fma;
        Vec3T<T> w0 = w.rounded();
        return fma(-r, r, dot(w0, w0));
    }
    LINEQUAD_INLINE void discriminant() {
        using std::fma;
        tc = -dot(v, w.rounded()) * inv_vv; // any tc is an exact move
        wc = moved_origin(w, tc, v);
        B = dot2(v, wc);
        C_moved = fma(-r, r, dot(wc, wc));
        Vec3T<T> u = cross_accurate(v, wc);
        D = fma(r * r, A, -dot(u, u));
    }
    // No extent: every root is on the surface.
    template <class Roots>
    T z_of(const Roots&, int) const {
        return T(0.0);
    }
    T z_lanes(T, T, Mask) const { return T(0.0); }
    T axial_moved() const { return T(0.0); }
    T axial_rate() const { return T(0.0); }
    ExtentT<T> extent(const Sphere&) const { return {T(-Binary64::inf), T(Binary64::inf)}; }
};

// The pieces of a sphere around `centre` that the sphere and the capsule's round ends share.

// The certified quantities with the origin moved to the closest approach to the centre.
template <class B>
struct SphereCertified {
    BoundedQuadratic<B> quad;
    double tc;
    BoundedVec3<B> wc, V;
};
template <class B>
SphereCertified<B> sphere_certified(Vec3 centre, double r, const Prescale& ps, const Line& l) {
    Vec3 v = ps.dir(l.v);
    Vec3TwoTerm w = difference_exact(ps.pos(l.L0), ps.pos(centre));
    BoundedVec3<B> V = exact<B>(v);
    B R = B::exact(ps.len(r)), A = dot(V, V);
    double tc = -dot(v, w.rounded()) / dot(v, v);
    BoundedVec3<B> wc = moved_origin_bounded<B>(w, tc, v), u = cross(V, wc);
    return {{A, dot(V, wc), dot(wc, wc) - R * R, R * R * A - dot(u, u)}, tc, wc, V};
}

// |P - centre|^2 = r^2 with P = L0 + t v, w = L0 - centre; no extent (the caller sets one).
template <class NT, class L>
exact_form::LineQuadratic<NT> sphere_quadratic(Vec3 centre, double r, const L& l) {
    using exact_form::lift;
    Vec3T<NT> w = exact_form::origin<NT>(l) - lift<NT>(centre), v = lift<NT>(l.v);
    NT R(r);
    exact_form::LineQuadratic<NT> q;
    q.A = dot(v, v);
    q.B = dot(v, w);
    q.C0 = dot(w, w) - R * R;
    q.Z0 = q.dZ = q.lo = q.hi = NT(0);
    q.lo_bounded = q.hi_bounded = false;
    return q;
}

// The sign of the sphere's D = B^2 - A C0: r^2 v.v - |v x w|^2 (Lagrange's identity).
template <class NT>
int sphere_discriminant_sign(Vec3 centre, double r, const Line& l) {
    using exact_form::lift;
    Vec3T<NT> w = lift<NT>(l.L0) - lift<NT>(centre), v = lift<NT>(l.v);
    Vec3T<NT> vw = cross(v, w);
    NT R(r);
    return sign(R * R * dot(v, v) - dot(vw, vw));
}

// The sphere's at t (the line's own parameter), for a root a few ulps from a point the rung's
// absolute bounds cannot resolve (a line starting on or just off the sphere):
//   G = C0 + t (2 B + A t),  C0 = |w|^2 - r^2 exactly,
// an expansion of w = L0 - centre's two doubles a component, so that G is enclosed relative to
// itself rather than to |w|^2; B and A in bounded double-double. Some forty products and sums,
// where the exact form's BigFloat quadratic takes thousands of instructions. None
//  - where |t| max|v_k| > r: a point farther than about r from the line's origin (a line from far
//    away), where t (2 B + A t) cancels C0 as much as C0's own terms would, and the
//    double-double products lose what C0's exactness won;
//  - where a product may not be exact (underflow, overflow);
//  - where G's sign is not decided and G is not exactly 0 (t = 0 on the sphere).
// The exact form's answers those.
inline std::optional<exact_form::LocalQuadratic> sphere_local_at(Vec3 centre, double r,
                                                                 const Line& l, double t) {
    if (!(std::fabs(t) * max_abs(l.v) <= r)) return std::nullopt;
    Expansion<20> C0; // 20 doubles: three squares of two-double components, and r^2
    bool exact = true;
    auto add_product = [&](double a, double b) {
        double p = a * b;
        exact = exact && std::isfinite(p) && dd_detail::product_exact(a, b, p);
        C0.add_product(a, b);
    };
    BoundedDD B(0), A(0);
    for (int k = 0; k < 3; ++k) {
        TwoTerm w = two_sum(l.L0[k], -centre[k]); // exact: w_k = hi + lo
        add_product(w.hi, w.hi);
        add_product(2 * w.hi, w.lo);
        add_product(w.lo, w.lo);
        BoundedDD v(l.v[k]);
        B = B + BoundedDD(w.hi, w.lo, 0) * v;
        A = A + v * v;
    }
    add_product(-r, r);
    if (!exact) return std::nullopt;
    BoundedDD c0 = enclosure(C0);
    if (t == 0) return exact_form::LocalQuadratic{A, B, c0};
    BoundedDD at(t), half_slope = B + A * at, G = c0 + at * (half_slope + B);
    if (int s = sign(G); s != 1 && s != -1) return std::nullopt;
    return exact_form::LocalQuadratic{A, half_slope, G};
}

// g(t) = |w + t v|^2 - r^2, w = L0 - centre. precise: w exact in double-double; else w rounded,
// its bound the low part it dropped. v and K = r^2 are exact either way (K from two_prod). No
// extent (the caller sets one).
template <bool precise, class T>
LineFormT<T> sphere_line_form(Vec3 centre, double r, Vec3T<T> L0, Vec3T<T> v) {
    using std::fabs;
    Vec3TwoTermT<T> w = difference_exact(L0, lanes_of<T>(centre));
    LineFormT<T> f;
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k) {
        f.U0[k] = precise ? BoundedDDT<T>{w.hi[k], w.lo[k], T(0.0)}
                          : BoundedDDT<T>{w.hi[k], T(0.0), fabs(w.lo[k])};
        f.U1[k] = {v[k], T(0.0), T(0.0)};
    }
    f.sigma_z = 1;
    TwoTerm r2 = two_prod(r, r);
    f.K = precise ? BoundedDD{r2.hi, r2.lo, 0} : BoundedDD{r2.hi, 0, std::fabs(r2.lo)};
    f.Z0 = f.e_Z0 = f.dZ = f.e_dZ = T(0.0);
    f.lo = f.e_lo = f.hi = f.e_hi = 0;
    f.lo_bounded = f.hi_bounded = false;
    return f;
}

// The textbook quadratic a t^2 + b t + c around `centre`, in R (the seed's).
template <class R>
SeedFormT<R> sphere_seed(Vec3 centre, double radius, const Line& l) {
    Vec3T<R> v = in_real<R>(l.v), w = in_real<R>(l.L0) - in_real<R>(centre);
    R r = R(radius);
    R a = dot(v, v), b = 2 * dot(v, w), c = dot(w, w) - r * r;
    bool usable = std::isfinite(a) && std::isfinite(b) && std::isfinite(c);
    return {a, b, c, R(0), R(0), Extent{-Binary64::inf, Binary64::inf}, usable};
}

template <>
struct ShapeTraits<Sphere> {
    static constexpr const char* name = "sphere";
    static constexpr auto fields = std::make_tuple(field("C", &Sphere::C), field("r", &Sphere::r));
    static constexpr const char* scale_fields = "r";
    static constexpr const char* fragile_fields = "v";
    static constexpr bool has_line_form = true;

    static Validity validate(const Sphere& s) {
        if (!(s.r > 0)) return {{ErrorCode::bad_radius, "r"}};
        return {};
    }

    // ---- Bounds (a scene's culling) ----

    static Box bounds(const Sphere& s) { return circular_box(s.C, s.r, s.C, s.r); }
    static BoundingCapsule bounding_capsule(const Sphere& s) { return {s.C, {}, s.r}; }

    // Nothing to keep beyond the common facts.
    static void prepare(const Sphere&, Facts<Sphere>&) {}

    // ---- seed ----

    template <class R, class Source>
    static SeedFormT<R> seed_form(const Source& src, const Line& l) {
        return sphere_seed<R>(src.shape.C, src.shape.r, l);
    }

    // ---- stable ----

    template <class T>
    using Stable = SphereStable<T>;
    template <class T, class Source, class Scale>
    static Stable<T> stable_core(const Source& src, const Scale& ps, Vec3T<T> L0, Vec3T<T> v) {
        const Sphere& s = src.shape;
        return {ps.pos(s.C), ps.pos(L0), ps.dir(v), ps.len(s.r)};
    }

    // ---- certified ----

    template <class B, class Source>
    static CertifiedForm<B> certified_form(const Source& src, const Prescale& ps, const Line& l) {
        SphereCertified<B> c = sphere_certified<B>(src.shape.C, src.shape.r, ps, l);
        return {c.quad, c.tc, B::exact(0), B::exact(0), {-Binary64::inf, Binary64::inf}};
    }

    // ---- exact ----

    template <class NT>
    static int exact_orientation(const Sphere&) {
        return 0;
    }

    template <class NT, class L>
    static exact_form::LineQuadratic<NT> exact_quadratic(const Sphere& s, const L& l,
                                                         int /*orientation*/) {
        return sphere_quadratic<NT>(s.C, s.r, l);
    }

    // The sign of D = B^2 - A C0 alone: (v.w)^2 - v.v (w.w - r^2) = r^2 v.v - |v x w|^2
    // (Lagrange's identity), w = L0 - C.
    template <class NT>
    static int discriminant_sign(const Sphere& s, const Line& l, int /*orientation*/) {
        return sphere_discriminant_sign<NT>(s.C, s.r, l);
    }

    // g's local quadratic at t, cheaper than the exact form's (sphere_local_at).
    static std::optional<exact_form::LocalQuadratic> local_at(const Sphere& s, const Line& l,
                                                              double t) {
        return sphere_local_at(s.C, s.r, l, t);
    }

    // ---- correct: the Newton rung's line form, and the hit test's quick one ----

    template <class T = double, class Source>
    static LineFormT<T> line_form(const Source& src, Vec3T<T> L0, Vec3T<T> v, int /*orientation*/) {
        return sphere_line_form<true, T>(src.shape.C, src.shape.r, L0, v);
    }
    template <class T = double, class Source>
    static LineFormT<T> quick_line_form(const Source& src, Vec3T<T> L0, Vec3T<T> v,
                                        int /*orientation*/) {
        return sphere_line_form<false, T>(src.shape.C, src.shape.r, L0, v);
    }
};

} // namespace linequad::detail
