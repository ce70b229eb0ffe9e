// A ray leaving a hit (a reflection, a refraction, a shadow ray towards a light) must not find
// the crossing it leaves again: floating point puts the returned hit point a little off the
// surface, on either side, and a ray started there can cross the surface at t ~ 0 (shadow acne,
// self-intersection). Renderers start it at t = epsilon, or offset its origin along the normal by
// an error bound (pbrt-v4's OffsetRayOrigin); neither is proven, and no epsilon suits every
// scale. spawn_ray moves the origin off the surface to the side the new direction points to and
// proves, in exact arithmetic, that the ray leaves the surface from there:
//     auto r = linequad::correct::intersect(cylinder, camera_ray, {Need::nearest, true});
//     linequad::SpawnedRay s = linequad::spawn_ray(cylinder, r.hits[0], reflected);
//     auto next = linequad::correct::intersect(cylinder, s.line, {Need::nearest, true});
//
// The proof. Along the new line o + t d, the surface the hit is on (its part: the lateral
// quadric, or a disc's plane) is Q(t) = A t^2 + 2 B t + C0 (a plane: Z(t) = Z0 + t dZ measured
// from the disc), with Q < 0 inside (each shape's exact form, fast/src/shapes/exact_form.hpp).
// The origin is accepted when C0 = Q(0) and B = Q'(0) / 2 have one nonzero sign sigma, decided
// exactly (double-double with an error bound, big floats where that cannot decide): o is
// strictly on side sigma, and the ray heads further into it. Then every crossing ahead of o goes
// from side sigma to the other: for A sigma >= 0 there is none, for A sigma < 0 exactly one,
// at t >= 2 |B| / |A| (the far wall of a concave side, a real crossing). The crossing the ray
// leaves went into side sigma (the side its direction points to), so it lies behind o. sigma is
// the sign of B at the hit point p, required to hold over the box of an ulp around p (where the
// exact hit of a correctly rounded point lies). Into a closed shape, o must also be strictly
// inside the solid, so that the line leaves it once ahead and does not re-enter at a rim. A ray
// started at the hit point itself has C0 of either sign, and its crossing at t ~ 0 is the one it
// left about half the time (`linequad spawn`, README: Spawned rays).
#pragma once

#include "linequad/prepared.hpp"
#include "linequad/result.hpp"
#include "linequad/shapes.hpp"

namespace linequad {

struct SpawnedRay {
    // origin o, the direction as given, range t >= 0. Solve it over any range that starts at
    // t >= 0: the proof holds from o on.
    Line line;
    Error error;       // why no origin could be proven (then line is empty)
    double offset = 0; // max |o_k - p_k|: how far the origin moved from the hit point
    int side = 0;      // sigma: +1 outside the surface the hit is on, -1 inside
    bool ok() const { return error.ok(); }
};

// From the hit `hit` on `shape` (any solver's, or any point near the surface: hit.p and
// hit.part are read), a ray in `direction`. Refused, with an error naming the input: a shape
// that does not validate, a NaN or infinite point or direction, a zero direction
// (zero_direction), a direction that does not leave the surface at the hit within rounding
// (along_surface, "direction": within rounding of the tangent plane, or of a point where the side
// changes, such as a cone's apex crossed rather than touched), and a point whose offset would
// leave double (out_of_range, "p"). A hit of kind tangent at a cone's apex (the normal vanishes)
// moves along the direction itself, and either side is then proven.
template <class S>
SpawnedRay spawn_ray(const Prepared<S>& shape, const Hit& hit, Vec3 direction);
SpawnedRay spawn_ray(const Shape& shape, const Hit& hit, Vec3 direction);

// The outward unit normal of the surface at a hit (of its part: the lateral surface, or a
// disc), in double: within a few ulps of direction for a point on the surface, as shading
// needs. Zero where there is none: at a cone's apex, and for a shape that does not validate or
// a point that is not finite (or so far out that the gradient overflows).
template <class S>
Vec3 normal(const Prepared<S>& shape, const Hit& hit);
Vec3 normal(const Shape& shape, const Hit& hit);

} // namespace linequad
