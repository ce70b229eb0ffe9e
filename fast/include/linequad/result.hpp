// What every solver returns: a small value type that names every case.
#pragma once

#include "linequad/vec3.hpp"

#include <cstdint>
#include <string>

namespace linequad {

enum class HitKind : std::uint8_t {
    cross,   // a simple root: the line passes through the surface
    tangent, // a double root: a tangent line, or a line through the cone's apex
};

// A hit is written whole by the solver that finds it; no field has a default.
struct Hit {
    double t;
    Vec3 p; // L0 + t v; zero when the query asked for no points
    // |t - exact t| <= bound, and whether this hit's existence, kind, extent and range are
    // proven: from the certified and correct solvers. NaN bound: the solver gives none.
    double bound;
    HitKind kind;
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
    not_a_number,    // a NaN coordinate (or range end)
    infinite,        // an infinite coordinate
    zero_direction,  // v = 0
    bad_radius,      // r <= 0
    degenerate_axis, // H = C
    singular_frame,  // a, b, c linearly dependent
    empty_range,     // t0 > t1, or an end that leaves no real t (t0 = +inf, t1 = -inf)
    out_of_range,    // inputs whose products overflow or underflow double
};

struct Error {
    ErrorCode code = ErrorCode::none;
    const char* field = ""; // the input that is wrong ("L0", "v", "r", "a,b,c", ...)
    bool ok() const { return code == ErrorCode::none; }
};

std::string message(const Error& e);
const char* code_name(ErrorCode c);

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

// 128 bytes (168 before the core redesign): hits and the interval share no storage, but
// nothing is kept that no caller reads.
struct Result {
    Hit hits[2]; // hits[0..count)
    // The line lies on the surface for t in [s0, s1] (either end may be infinite). When set,
    // count is 0: the points of the interval are all hits.
    double s0 = 0, s1 = 0;
    const char* error_field = "";
    ErrorCode error_code = ErrorCode::none;
    std::uint8_t count = 0;
    bool on_surface = false;
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
