// The surfaces transport codes build their geometry from, and the sense of a point against them:
// a plane and a general quadric (MCNP's and OpenMC's GQ), each coefficient a double taken exactly.
#pragma once

#include "linequad/result.hpp"
#include "linequad/vec3.hpp"

#include <array>
#include <cstdint>

namespace linequad {

// The plane n . x = d (OpenMC's plane A B C D): f(x) = n . x - d.
//
// As a shape a line is solved against (linequad/shapes.hpp): the hits are the t in the line's
// range where f(L0 + t v) = 0, a line in the plane on_surface. `coincident`: the caller states
// that L0 lies on the surface (a transport code's "on this surface" flag), and g(t) = f(L0 + t v)
// is taken with its constant term exactly 0, as OpenMC and ORANGE do.
struct Plane {
    Vec3 n{};
    double d = 0;
    bool coincident = false;
};

// f(x) = A x^2 + B y^2 + C z^2 + D xy + E yz + F zx + G x + H y + J z + K, with
// q = {A, B, C, D, E, F, G, H, J, K}: the GQ order of MCNP and OpenMC (some codes order the cross
// terms otherwise, or write them with a factor of 2). Every degree of degeneracy is a surface:
// a plane, a pair of planes, a line, a point, nothing (f > 0 everywhere).
// As a shape: the hits of a line are the t where f(L0 + t v) = 0 (a simple root a cross, a double
// root a tangent, f = 0 all along the line on_surface), and `coincident` as the plane's.
struct Quadric {
    std::array<double, 10> q{};
    bool coincident = false;
};

// Which side of the surface a point is on: the sign of f there. The half-spaces f < 0 and f > 0
// are the negative and positive senses cells are built from.
enum class Sense : std::int8_t { negative = -1, on = 0, positive = 1 };

struct SenseResult {
    Sense sense;
    Error error; // NaN or infinite inputs, an all-zero n or q, a zero direction
    bool ok() const { return error.ok(); }
};

// The exact sign of f(p), whatever the magnitudes (no overflow, no underflow, no rounding).
SenseResult sense(const Plane& s, Vec3 p);
SenseResult sense(const Quadric& s, Vec3 p);

// As a transport code asks it of a particle at p moving along u: the sign of f(p); for p exactly
// on the surface, the side u points into, the sign of f(p + t u) for every small t > 0 (that of
// grad f(p) . u, else of the quadratic part of f at u); `on` only when the line p + t u lies in
// the surface.
SenseResult sense(const Plane& s, Vec3 p, Vec3 u);
SenseResult sense(const Quadric& s, Vec3 p, Vec3 u);

// The refusals sense() makes, in its order (the oracle's are the same): the surface (NaN or
// infinite coefficients, all of n or q zero), then p, then u when given (NaN, infinite, zero).
Error check_sense(const Plane& s, Vec3 p, const Vec3* u = nullptr);
Error check_sense(const Quadric& s, Vec3 p, const Vec3* u = nullptr);

const char* sense_name(Sense s); // "negative", "on", "positive"

} // namespace linequad
