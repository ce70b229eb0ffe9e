// Line against a capsule {C, H, r}: the points within distance r of the segment CH. Every
// derivation of it, once.
//
// Derivation. The capsule's surface is three quadric patches, each a part of the shape:
//   lateral: the cylinder |(P - C) x h|^2 = r^2 (h.h), h = H - C, strictly between the planes
//            through C and H (0 < u < h.h, u = (P - C).h): cylinder.hpp's quadratic;
//   base:    the sphere |P - C|^2 = r^2 where (P - C).(C - H) >= 0, its seam circle included;
//   top:     the sphere |P - H|^2 = r^2 where (P - H).(H - C) >= 0, likewise (sphere.hpp).
// The capsule is convex, so a line meets its surface at two points (entering and leaving), or
// touches it at one, or lies along the lateral surface (parallel to the axis at distance r: no
// hits, and the interval 0 <= u <= h.h on the surface). Each patch's kind (cross or tangent) is
// its own quadratic's, which is right for the capsule: the surface is smooth across the seams
// (the sphere and the cylinder share their tangent plane there), so a simple root of a patch is
// a crossing of the capsule and a double root a touch.
//
// Every solver solves each patch as a shape of its own (CapsuleSide, CapsuleEnd below) and
// merges the hits (solve/solve.hpp: solve_shape); a seam point belongs to exactly one patch,
// because the side's ends are open (LineQuadratic::lo_open, Closure::open_lo) and the round
// ends' are closed. A renderer's capsule test is the same three steps (the infinite cylinder's
// roots kept between the planes, then the end spheres'), which is what `seed` does with the
// seeds' textbook forms.
#pragma once

#include "forms/bounds.hpp"
#include "forms/traits.hpp"
#include "shapes/cylinder.hpp"
#include "shapes/sphere.hpp"

#include <tuple>

namespace linequad::detail {

// The lateral patch: the cylinder {C, H, r} strictly between its end planes.
struct CapsuleSide {
    Vec3 C{}, H{};
    double r = 0;
};
// A round end: the half of the sphere of radius r around `centre` facing away from `other`, its
// seam circle included: (P - centre).(centre - other) >= 0.
struct CapsuleEnd {
    Vec3 centre{}, other{};
    double r = 0;
};

inline Cylinder side_cylinder(const CapsuleSide& s) {
    return {s.C, s.H, s.r, true, false};
}
inline Closure open_ends() {
    Closure c;
    c.open_lo = c.open_hi = true;
    return c;
}

template <class T>
struct CapsuleSideStable : CylinderStable<T> {
    using CylinderStable<T>::CylinderStable;
    ExtentT<T> extent(const CapsuleSide& s) const {
        ExtentT<T> e = CylinderStable<T>::extent(side_cylinder(s));
        e.caps = open_ends();
        return e;
    }
};

template <>
struct ShapeTraits<CapsuleSide> {
    using Of = ShapeTraits<Cylinder>;
    static constexpr const char* name = "capsule";
    static constexpr auto fields = std::make_tuple(
        field("C", &CapsuleSide::C), field("H", &CapsuleSide::H), field("r", &CapsuleSide::r));
    static constexpr const char* scale_fields = Of::scale_fields;
    static constexpr const char* fragile_fields = Of::fragile_fields;
    static constexpr bool has_line_form = true;

    static Validity validate(const CapsuleSide& s) { return Of::validate(side_cylinder(s)); }

    template <class R, class Source>
    static SeedFormT<R> seed_form(const Source& src, const Line& l) {
        Cylinder c = side_cylinder(src.shape);
        SeedFormT<R> f = Of::seed_form<R>(AsGiven<Cylinder>{c}, l);
        f.extent.caps = open_ends();
        return f;
    }

    template <class T>
    using Stable = CapsuleSideStable<T>;
    template <class T, class Source, class Scale>
    static Stable<T> stable_core(const Source& src, const Scale& ps, Vec3T<T> L0, Vec3T<T> v) {
        const CapsuleSide& s = src.shape;
        return {ps.pos(s.C), ps.pos(s.H), ps.pos(L0), ps.dir(v), ps.len(s.r)};
    }

    template <class B, class Source>
    static CertifiedForm<B> certified_form(const Source& src, const Prescale& ps, const Line& l) {
        Cylinder c = side_cylinder(src.shape);
        CertifiedForm<B> f = Of::certified_form<B>(AsGiven<Cylinder>{c}, ps, l);
        f.extent.caps = open_ends();
        return f;
    }

    // Both seams belong to the caps, for every line: known without an exact form.
    static constexpr bool ends_open = true;

    template <class NT>
    static int exact_orientation(const CapsuleSide&) {
        return 0;
    }
    template <class NT, class L>
    static exact_form::LineQuadratic<NT> exact_quadratic(const CapsuleSide& s, const L& l,
                                                         int orientation) {
        exact_form::LineQuadratic<NT> q = Of::exact_quadratic<NT>(side_cylinder(s), l, orientation);
        q.lo_open = q.hi_open = ends_open;
        return q;
    }
    template <class NT>
    static exact_form::LineAxial<NT> exact_axial(const CapsuleSide& s, const Line& l,
                                                 int orientation) {
        return Of::exact_axial<NT>(side_cylinder(s), l, orientation);
    }
    template <class NT>
    static int discriminant_sign(const CapsuleSide& s, const Line& l, int orientation) {
        return Of::discriminant_sign<NT>(side_cylinder(s), l, orientation);
    }

    // The rung proves an extent decision only strictly, so an open end needs nothing more: a
    // root exactly at a seam is never proven inside, and goes to the exact rungs.
    template <class T = double, class Source>
    static LineFormT<T> line_form(const Source& src, Vec3T<T> L0, Vec3T<T> v, int orientation) {
        Cylinder c = side_cylinder(src.shape);
        return Of::line_form<T>(AsGiven<Cylinder>{c}, L0, v, orientation);
    }
    // Its ends' planes, the seams' (ExtentEnds::end_planes): the cylinder's.
    template <class Source>
    static std::optional<DiscPlanes> end_planes(const Source& src, Vec3 L0, Vec3 v) {
        Cylinder c = side_cylinder(src.shape);
        return Of::end_planes(AsGiven<Cylinder>{c}, L0, v);
    }
    template <class T = double, class Source>
    static LineFormT<T> quick_line_form(const Source& src, Vec3T<T> L0, Vec3T<T> v,
                                        int orientation) {
        Cylinder c = side_cylinder(src.shape);
        return Of::quick_line_form<T>(AsGiven<Cylinder>{c}, L0, v, orientation);
    }
};

// The sphere's stable core with the axial coordinate Z = (P - centre).h, h = centre - other,
// whose extent Z >= 0 keeps the end's half.
template <class T>
struct CapsuleEndStable : SphereStable<T> {
    using Mask = typename SphereStable<T>::Mask;
    Vec3T<T> h;
    T dz, zc = T(0.0);

    CapsuleEndStable(Vec3T<T> centre, Vec3T<T> other, Vec3T<T> L0, Vec3T<T> v, T r)
        : SphereStable<T>(centre, L0, v, r), h(centre - other), dz(dot(v, h)) {}
    LINEQUAD_INLINE void discriminant() {
        SphereStable<T>::discriminant();
        zc = dot(this->wc, h);
    }
    T z_moved(T s) const {
        using std::fma;
        return fma(s, dz, zc);
    }
    T z_at_origin(T t) const {
        using std::fma;
        return fma(t, dz, dot2(this->w.rounded(), h));
    }
    template <class Roots>
    T z_of(const Roots& r, int i) const {
        return r.from_vieta[i] ? z_at_origin(r.t[i]) : z_moved(r.s[i]);
    }
    T z_lanes(T t, T s, Mask from_vieta) const {
        return select(from_vieta, z_at_origin(t), z_moved(s));
    }
    T axial_moved() const { return zc; }
    T axial_rate() const { return dz; }
    ExtentT<T> extent(const CapsuleEnd&) const { return {T(0.0), T(Binary64::inf)}; }
};

template <>
struct ShapeTraits<CapsuleEnd> {
    static constexpr const char* name = "capsule";
    static constexpr auto fields =
        std::make_tuple(field("C", &CapsuleEnd::centre), field("H", &CapsuleEnd::other),
                        field("r", &CapsuleEnd::r));
    static constexpr const char* scale_fields = "r,H-C";
    static constexpr const char* fragile_fields = "v,H-C";
    static constexpr bool has_line_form = true;

    static Validity validate(const CapsuleEnd& s) {
        if (!(s.r > 0)) return {{ErrorCode::bad_radius, "r"}};
        if (s.centre == s.other) return {{ErrorCode::degenerate_axis, "H-C"}};
        return {};
    }

    // The sphere's textbook quadratic; z along the unit axis h / |h|, as a renderer takes it.
    template <class R, class Source>
    static SeedFormT<R> seed_form(const Source& src, const Line& l) {
        const CapsuleEnd& s = src.shape;
        SeedFormT<R> f = sphere_seed<R>(s.centre, s.r, l);
        SeedAxisT<R> axis = seed_axis<R>(src, s.other, s.centre);
        Vec3T<R> w = in_real<R>(l.L0) - in_real<R>(s.centre);
        f.z0 = dot(w, axis.unit), f.dz = dot(in_real<R>(l.v), axis.unit);
        f.usable = f.usable && std::isfinite(axis.length);
        f.extent = {0, Binary64::inf};
        return f;
    }

    template <class T>
    using Stable = CapsuleEndStable<T>;
    template <class T, class Source, class Scale>
    static Stable<T> stable_core(const Source& src, const Scale& ps, Vec3T<T> L0, Vec3T<T> v) {
        const CapsuleEnd& s = src.shape;
        return {ps.pos(s.centre), ps.pos(s.other), ps.pos(L0), ps.dir(v), ps.len(s.r)};
    }

    template <class B, class Source>
    static CertifiedForm<B> certified_form(const Source& src, const Prescale& ps, const Line& l) {
        const CapsuleEnd& s = src.shape;
        SphereCertified<B> c = sphere_certified<B>(s.centre, s.r, ps, l);
        BoundedVec3<B> h = difference_bounded<B>(ps.pos(s.centre), ps.pos(s.other));
        return {c.quad, c.tc, dot(c.wc, h), dot(c.V, h), {0, Binary64::inf}};
    }

    template <class NT>
    static int exact_orientation(const CapsuleEnd&) {
        return 0;
    }
    template <class NT, class L>
    static exact_form::LineQuadratic<NT> exact_quadratic(const CapsuleEnd& s, const L& l,
                                                         int /*orientation*/) {
        using exact_form::lift;
        exact_form::LineQuadratic<NT> q = sphere_quadratic<NT>(s.centre, s.r, l);
        Vec3T<NT> h = lift<NT>(s.centre) - lift<NT>(s.other);
        q.Z0 = dot(exact_form::origin<NT>(l) - lift<NT>(s.centre), h);
        q.dZ = dot(lift<NT>(l.v), h);
        q.lo = NT(0);
        q.lo_bounded = true; // the seam belongs to the end: Z >= 0, closed
        return q;
    }
    template <class NT>
    static int discriminant_sign(const CapsuleEnd& s, const Line& l, int /*orientation*/) {
        return sphere_discriminant_sign<NT>(s.centre, s.r, l);
    }
    static std::optional<exact_form::LocalQuadratic> local_at(const CapsuleEnd& s, const Line& l,
                                                              double t) {
        return sphere_local_at(s.centre, s.r, l, t);
    }
    template <class NT>
    static exact_form::LineAxial<NT> exact_axial(const CapsuleEnd& s, const Line& l,
                                                 int /*orientation*/) {
        using exact_form::lift;
        Vec3T<NT> h = lift<NT>(s.centre) - lift<NT>(s.other);
        return {dot(lift<NT>(l.L0) - lift<NT>(s.centre), h),
                dot(lift<NT>(l.v), h),
                NT(0),
                NT(0),
                true,
                false};
    }

    template <bool precise, class T>
    static LineFormT<T> form(const CapsuleEnd& s, Vec3T<T> L0, Vec3T<T> v) {
        LineFormT<T> f = sphere_line_form<precise, T>(s.centre, s.r, L0, v);
        Vec3TwoTerm h = difference_exact(s.centre, s.other);
        Vec3TwoTermT<T> w = difference_exact(L0, lanes_of<T>(s.centre));
        // Z = w.h + t v.h, w and h within u of their exact values
        cylinder_axial(f, w.hi, lanes_of<T>(h.hi), v);
        f.lo_bounded = true;
        return f;
    }
    template <class T = double, class Source>
    static LineFormT<T> line_form(const Source& src, Vec3T<T> L0, Vec3T<T> v, int /*orientation*/) {
        return form<true, T>(src.shape, L0, v);
    }
    // The seam's plane Z = 0, from the exact differences (ExtentEnds::end_planes).
    template <class Source>
    static std::optional<DiscPlanes> end_planes(const Source& src, Vec3 L0, Vec3 v) {
        const CapsuleEnd& s = src.shape;
        Vec3TwoTerm h = difference_exact(s.centre, s.other), w = difference_exact(L0, s.centre);
        return DiscPlanes{dot_dd(w, h), dot_dd(v, h), BoundedDD(0), BoundedDD(0), false, false};
    }
    template <class T = double, class Source>
    static LineFormT<T> quick_line_form(const Source& src, Vec3T<T> L0, Vec3T<T> v,
                                        int /*orientation*/) {
        return form<false, T>(src.shape, L0, v);
    }
};

template <>
struct ShapeTraits<Capsule> {
    static constexpr const char* name = "capsule";
    static constexpr auto fields =
        std::make_tuple(field("C", &Capsule::C), field("H", &Capsule::H), field("r", &Capsule::r));
    static constexpr const char* scale_fields = "r,H-C";
    static constexpr const char* fragile_fields = "v,H-C";
    static constexpr bool has_line_form = false; // its patches have, each

    static Validity validate(const Capsule& s) {
        if (!(s.r > 0)) return {{ErrorCode::bad_radius, "r"}};
        if (s.H == s.C) return {{ErrorCode::degenerate_axis, "H-C"}};
        return {};
    }

    // ---- Bounds (a scene's culling): the end discs' boxes reach the spheres' too ----

    static Box bounds(const Capsule& s) { return circular_box(s.C, s.r, s.H, s.r); }
    static BoundingCapsule bounding_capsule(const Capsule& s) { return {s.C, s.H - s.C, s.r}; }

    static void prepare(const Capsule&, Facts<Capsule>&) {}

    // ---- The patches, each solved as a shape of its own, in this order, with their parts ----

    static constexpr bool composite = true;
    static constexpr Part parts[3] = {Part::lateral, Part::base, Part::top};
    static std::tuple<CapsuleSide, CapsuleEnd, CapsuleEnd> patches(const Capsule& s) {
        return {CapsuleSide{s.C, s.H, s.r}, CapsuleEnd{s.C, s.H, s.r}, CapsuleEnd{s.H, s.C, s.r}};
    }

    // Whether the line provably misses patch i's whole quadric, so that no solver need solve it:
    // it passes farther than r from the axis (the side), or from the end's centre. In double,
    // with every rounding covered: |x - x~| <= 16 u X for X the sum of the magnitudes of the
    // products x is formed from (a few products and sums of rounded differences), and both
    // sides compared with that margin; anything out of double's comfortable range is not
    // skipped.
    static bool patch_misses(const Capsule& s, int i, const Line& l) {
        constexpr double u = Binary64::u;
        Vec3 w = l.L0 - (i == 2 ? s.H : s.C), h = s.H - s.C, v = l.v;
        double size = std::max({max_abs(w), max_abs(h), max_abs(v), s.r});
        if (!(size < 0x1p120) || !(size > 0x1p-120)) return false;
        double far, near, margin;
        if (i == 0) { // |w.(v x h)| > r |v x h|: the line's distance to the axis exceeds r
            Vec3 n = cross(v, h), m = cross_magnitudes(v, h);
            double d = dot(w, n), e = dot(magnitudes(w), m);
            far = d * d, near = s.r * s.r * dot(n, n);
            margin = 16 * u * (e * e + s.r * s.r * dot(m, m));
        } else { // |v x w| > r |v|: the line's distance to the centre exceeds r
            Vec3 n = cross(v, w), m = cross_magnitudes(v, w);
            far = dot(n, n), near = s.r * s.r * dot(v, v);
            margin = 16 * u * (dot(m, m) + near);
        }
        return far - near > margin;
    }
};

} // namespace linequad::detail
