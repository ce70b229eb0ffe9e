// The inputs every solver shares: a line over an interval of its parameter, and the shapes.
#pragma once

#include "linequad/surfaces.hpp"
#include "linequad/vec3.hpp"

#include <cstdint>
#include <limits>
#include <type_traits>
#include <variant>

namespace linequad {

// The floating-point format a case is posed in and answered in: binary64 (double), or binary32
// (float, as renderers and GPUs intersect): every input a float, every answer a float, held in a
// double exactly. The float solvers (seed32, stable32, correct32) compute or round to float.
enum class Precision : std::uint8_t { binary64, binary32 };
const char* precision_name(Precision p); // "binary64", "binary32"

// The usual ranges, as shorthands for an Interval.
enum class Range : std::uint8_t { line, ray, segment }; // all t; t >= 0; 0 <= t <= 1

// The part of the line asked about: t0 <= t <= t1, either end possibly infinite. A renderer
// passes its [tMin, tMax] here as they are, without rescaling v.
struct Interval {
    double t0 = -std::numeric_limits<double>::infinity();
    double t1 = std::numeric_limits<double>::infinity();

    constexpr Interval() = default;
    constexpr Interval(double lo, double hi) : t0(lo), t1(hi) {}
    constexpr Interval(Range r) // NOLINT: Line{L0, v, Range::ray} reads as it should
        : t0(r == Range::line ? -std::numeric_limits<double>::infinity() : 0.0),
          t1(r == Range::segment ? 1.0 : std::numeric_limits<double>::infinity()) {}

    bool contains(double t) const { return t >= t0 && t <= t1; }
    bool has_t0() const { return t0 > -std::numeric_limits<double>::infinity(); }
    bool has_t1() const { return t1 < std::numeric_limits<double>::infinity(); }
};
inline bool operator==(Interval a, Interval b) {
    return a.t0 == b.t0 && a.t1 == b.t1;
}
inline bool operator!=(Interval a, Interval b) {
    return !(a == b);
}

// L(t) = L0 + t v for t in range; v need not have unit length.
struct Line {
    Vec3 L0{};
    Vec3 v{};
    Interval range = Range::line;
};

// Every finite shape may be closed: with `caps` its end discs are part of the surface, and a
// hit on one names it (Part::base, Part::top). Without caps a finite shape is its lateral
// surface alone, closed at its ends (a hit on a rim is a hit). Caps on a shape that is not
// finite are refused (ErrorCode::bad_option, "caps").

// Seed 001: the right circular cylinder of radius r around the axis from C to H.
// Finite: the lateral surface between the planes through C and H; caps: the discs there too
// (base at C, top at H).
struct Cylinder {
    Vec3 C{}, H{};
    double r = 0;
    bool finite = true;
    bool caps = false;
};

// Seed 000: points C + x a + y b + z c with x^2 + y^2 = 1; finite keeps 0 <= z <= 1, caps adds
// the elliptic discs z = 0 (base) and z = 1 (top). a, b, c may be any linearly independent
// vectors (oblique and sheared frames included).
struct EllipticCylinder {
    Vec3 C{}, a{}, b{}, c{};
    bool finite = true;
    bool caps = false;
};

// Seed 002: base centre C, apex H, c = H - C; points H + x a + y b + z c with x^2 + y^2 = z^2.
// One nappe, z <= 0 (towards the base): finite keeps -1 <= z <= 0, caps adds the base disc
// z = -1. Two nappes (as OpenCascade's cones are) add the mirror nappe z >= 0: finite keeps
// -1 <= z <= 1, caps adds the top disc z = 1 too, and the closed shape is two solids that meet
// at the apex (a line can then meet it in four points).
struct EllipticCone {
    Vec3 C{}, H{}, a{}, b{};
    bool finite = true;
    bool caps = false;
    int nappes = 1; // 1 or 2
    Vec3 c() const { return H - C; }
};

// The right circular frustum (truncated cone) between the disc of radius r0 centred at C0 and
// the disc of radius r1 centred at C1, both perpendicular to C1 - C0; r0, r1 >= 0, not both 0.
// r0 = r1 is a cylinder, a zero radius an apex. Not finite: the whole nappe (or cylinder) that
// holds it. Caps: the disc at each end whose radius is not 0 (base at C0, top at C1), as
// Embree's cone curves with end discs are.
struct Frustum {
    Vec3 C0{};
    double r0 = 0;
    Vec3 C1{};
    double r1 = 0;
    bool finite = true;
    bool caps = false;
};

// The sphere of radius r > 0 around C: a closed solid by definition (no options), whose one
// part is its surface (Part::lateral).
struct Sphere {
    Vec3 C{};
    double r = 0;
};

// The ellipsoid: points C + x a + y b + z c with x^2 + y^2 + z^2 = 1, a, b, c any linearly
// independent vectors (as the elliptic cylinder's frame); a closed solid by definition.
struct Ellipsoid {
    Vec3 C{}, a{}, b{}, c{};
};

// The capsule: the points within distance r > 0 of the segment from C to H (H != C), a closed
// solid by definition. Its parts: Part::lateral, the cylinder strictly between the planes through
// C and H perpendicular to the axis; Part::base and Part::top, the hemispheres around C and H,
// each with its seam circle (as a rim belongs to its disc). A line along the lateral surface has
// no hits: the interval where it lies on it, ends included.
struct Capsule {
    Vec3 C{}, H{};
    double r = 0;
};

// Every shape. The solvers, the case format, the families and the benchmarks take their list
// of shapes from here (and each shape's derivation from fast/src/shapes/).
// Plane and Quadric (linequad/surfaces.hpp) are unbounded surfaces: what a transport code's cells
// are built from, the region f < 0 their inside.
using Shape = std::variant<Cylinder, EllipticCylinder, EllipticCone, Frustum, Sphere, Ellipsoid,
                           Capsule, Plane, Quadric>;

// The options a shape may have: `finite` and `caps` (the shapes with an axis), `nappes` (the
// cone), `coincident` (the plane and the quadric). The closed solids by definition (sphere,
// ellipsoid, capsule) have none: they are finite, closed and one solid.
namespace detail {
template <class S, class = void>
struct HasExtentOptions : std::false_type {};
template <class S>
struct HasExtentOptions<S, std::void_t<decltype(&S::finite), decltype(&S::caps)>> : std::true_type {
};
template <class S, class = void>
struct HasCoincident : std::false_type {};
template <class S>
struct HasCoincident<S, std::void_t<decltype(&S::coincident)>> : std::true_type {};
template <class S, class = void>
struct HasNappes : std::false_type {};
template <class S>
struct HasNappes<S, std::void_t<decltype(&S::nappes)>> : std::true_type {};
} // namespace detail
template <class S>
inline constexpr bool has_extent_options = detail::HasExtentOptions<S>::value;
template <class S>
inline constexpr bool has_nappes = detail::HasNappes<S>::value;
// `coincident` (the plane and the quadric): the caller's word that L0 is on the surface.
template <class S>
inline constexpr bool has_coincident = detail::HasCoincident<S>::value;

// The unbounded surfaces (plane, quadric): not finite; the region f < 0 they bound is closed by
// them alone, and is not convex in general.
template <class S>
inline constexpr bool is_unbounded_surface = std::is_same_v<S, Plane> || std::is_same_v<S, Quadric>;

template <class S>
bool has_finite_extent(const S& s) {
    if constexpr (has_extent_options<S>)
        return s.finite;
    else
        return !is_unbounded_surface<S>;
}
// Whether end discs close it.
template <class S>
bool has_caps(const S& s) {
    if constexpr (has_extent_options<S>)
        return s.caps;
    else
        return false;
}
template <class S>
int nappes_of(const S& s) {
    if constexpr (has_nappes<S>)
        return s.nappes;
    else
        return 1;
}
// Whether the shape bounds a region a line can start inside: closed by its discs, a closed solid
// by definition, or not finite (the inside of an infinite cylinder or cone).
template <class S>
bool bounds_solid(const S& s) {
    return has_caps(s) || !has_finite_extent(s) || !has_extent_options<S>;
}
// Whether it is a closed solid: its surface bounds what it holds on every side.
template <class S>
bool is_closed(const S& s) {
    return has_caps(s) || !has_extent_options<S>;
}
inline bool is_closed(const Shape& s) {
    return std::visit([](const auto& x) { return is_closed(x); }, s);
}
inline bool bounds_solid(const Shape& s) {
    return std::visit([](const auto& x) { return bounds_solid(x); }, s);
}

// The same shape and line with every input rounded to the nearest float (to pose a case in
// binary32; range ends included).
Shape rounded_to_binary32(const Shape& s);
Line rounded_to_binary32(const Line& l);

// "cylinder", "elliptic_cylinder", "elliptic_cone", "frustum", "sphere", "ellipsoid", "capsule",
// "plane", "quadric".
const char* shape_name(const Shape& s);
template <class S>
const char* shape_name();
const char* range_name(Range r);

} // namespace linequad
