// What every solver returns: a small value type that names every case.
#pragma once

#include "linequad/vec3.hpp"

#include <cstdint>
#include <string>

namespace linequad {

// Without caps, the lateral surface's roots: cross for a simple root, tangent for a double one
// (a tangent line, or a line through the cone's apex). With caps (a closed solid): cross where
// the line passes between the solid's outside and inside (through an apex included), tangent
// where it touches the solid without entering it (tangent to the lateral surface, grazing a
// rim, touching an apex from outside, or passing through a two-nappe cone's apex from one solid
// into the other).
enum class HitKind : std::uint8_t {
    cross,
    tangent,
};

// Which part of the surface a hit lies on. base: the disc at the cylinder's C, the elliptic
// cylinder's z = 0, the cone's z = -1; top: the cylinder's H, z = 1. A hit on a rim belongs to
// its disc; without caps every hit is lateral.
enum class Part : std::uint8_t { lateral, base, top };

// A hit is written whole by the solver that finds it; no field has a default.
struct Hit {
    double t;
    Vec3 p; // L0 + t v; zero when the query asked for no points
    // |t - exact t| <= bound, and whether this hit's existence, kind, extent and range are
    // proven: from the certified and correct solvers. NaN bound: the solver gives none.
    double bound;
    HitKind kind;
    Part part;
    bool certain;
};

// Whether a result's classification (how many hits, their kinds, the interval) is proven.
enum class Certainty : std::uint8_t {
    unknown,   // the solver does not say (seed, stable, exact: the oracle is exact by construction)
    certain,   // proven: every decision's sign was certain
    uncertain, // some decision could not be certified: the hits are best guesses
};

// Which rung of the correct solver's ladder gave a result (Ziv's strategy): the Newton rung (a
// double estimate, one Newton step with a double-double residual, a proven enclosure), the
// double-double rung (the exact form in bounded double-double), or the exact one. The first two
// answer only when their error bounds prove every sign and every rounding.
enum class Rung : std::uint8_t { none, newton, double_double, exact };

// Why an input was refused. Never a hit, never undefined behaviour.
enum class ErrorCode : std::uint8_t {
    none,
    not_a_number,      // a NaN coordinate (or range end)
    infinite,          // an infinite coordinate
    zero_direction,    // v = 0
    bad_radius,        // r <= 0
    degenerate_axis,   // H = C
    singular_frame,    // a, b, c linearly dependent
    empty_range,       // t0 > t1, or an end that leaves no real t (t0 = +inf, t1 = -inf)
    out_of_range,      // inputs whose products overflow or underflow double
    bad_option,        // caps on a shape that is not finite; nappes other than 1 or 2
    not_binary32,      // a float solver given an input that is not a float
    along_surface,     // spawn_ray: a direction that does not leave the surface at the hit
    zero_coefficients, // a plane's n or a quadric's q all zero: no surface
    // Another library's own refusal, which fits none of the above; field names it. linequad's
    // solvers never return it: the audit grades it as a refusal the oracle does not make.
    foreign,
};

struct Error {
    ErrorCode code = ErrorCode::none;
    const char* field = ""; // the input that is wrong ("L0", "v", "r", "a,b,c", ...)
    bool ok() const { return code == ErrorCode::none; }
};

std::string message(const Error& e);
const char* code_name(ErrorCode c);
const char* part_name(Part p); // "lateral", "base", "top"

// What the caller needs; a solver does no more than that.
enum class Need : std::uint8_t {
    // A hit test: one hit inside the range, the first the solver proves, not necessarily the
    // nearest; it stops there, orders nothing and rounds nothing (the correct solver's t is the
    // midpoint of its proven enclosure, within `bound`). No point is computed.
    any,
    nearest, // the hit with the smallest t in the range
    all,     // every hit, sorted by t
};

struct Query {
    Need need = Need::all;
    bool points = true; // compute hit points (not for Need::any)
};

// A closed two-nappe cone is two solids, which a line can meet in four points; every other
// shape in at most two.
inline constexpr int max_hits = 4;

// 224 bytes: hits and the interval share no storage, but nothing is kept that no caller reads.
struct Result {
    Hit hits[max_hits]; // hits[0..count)
    // The line lies on the surface for t in [s0, s1] (either end may be infinite), on the part
    // surface_part (a cap's plane across its disc, or the lateral surface). When set, count is
    // 0: the points of the interval are all hits.
    double s0 = 0, s1 = 0;
    const char* error_field = "";
    ErrorCode error_code = ErrorCode::none;
    std::uint8_t count = 0;
    bool on_surface = false;
    Part surface_part = Part::lateral;
    Certainty certainty = Certainty::unknown;
    Rung rung = Rung::none; // set by the correct solver only

    bool ok() const { return error_code == ErrorCode::none; }
    Error error() const { return {error_code, error_field}; }
    bool any_hit() const { return count > 0 || on_surface; }
    static Result failure(Error e) {
        Result r;
        r.error_code = e.code;
        r.error_field = e.field;
        return r;
    }
    static Result failure(ErrorCode c, const char* field) { return failure(Error{c, field}); }
};

} // namespace linequad
