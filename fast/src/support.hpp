// Internal pieces every fast solver shares: input checks, power-of-two prescaling, and the
// last step that turns roots into a Result (extent, range, what the caller needs, points).
#pragma once

#include "linequad/result.hpp"
#include "linequad/shapes.hpp"
#include "linequad/validate.hpp"

#include <cmath>
#include <initializer_list>
#include <limits>

namespace linequad::detail {

constexpr double inf = std::numeric_limits<double>::infinity();

// A root before the extent and range tests: t in the caller's parameter, z its axial coordinate
// in the canonical frame (in the circular cylinder's own units for that shape).
struct Candidate {
    double t;
    HitKind kind;
    double z;
};

struct Extent {
    double lo, hi; // the hit must satisfy lo <= z <= hi; infinite bounds when not finite
};

inline bool in_range(double t, Range r) {
    switch (r) {
    case Range::line:
        return true;
    case Range::ray:
        return t >= 0;
    case Range::segment:
        return t >= 0 && t <= 1;
    }
    return false;
}

// Keeps the candidates inside extent and range, sorted by t, as many as q.need asks for, and
// their points when q.points. Candidates with a non-finite t or z, and points that overflow,
// give an out_of_range error.
Result finish(Candidate* c, int n, Extent e, const Line& l, Query q);

// finish() in two steps, so that the batch solvers can compute the first in vector lanes: each
// candidate's facts (t in the caller's units; not finite; inside extent and range; its point
// fma(t, v, L0)), then the Result (sorted, as many as the query needs).
struct FinishedCandidate {
    double t;
    HitKind kind;
    bool bad, keep;
    Vec3 p;
};
void assemble(FinishedCandidate* c, int n, Query q, Result& out);

// The line lies on the surface: z(t) = z0 + (t / t_scale) dz. The interval of t where it is
// inside the extent, intersected with the range.
Result finish_on_surface(double z0, double dz, double t_scale, Extent e, const Line& l);

// Power-of-two scales that bring a scene near unit size without any rounding: positions and
// lengths are multiplied by 2^-k, the direction by 2^-j, so t = t_scaled * 2^(k - j). The
// factors are kept as doubles (|k|, |j| <= 1000, so they are normal) because a multiply by a
// power of two is exact and far cheaper than ldexp.
struct Prescale {
    double to_unit = 1, dir_to_unit = 1, t_factor = 1;
    Vec3 pos(Vec3 p) const { return to_unit * p; }
    double len(double x) const { return to_unit * x; }
    Vec3 dir(Vec3 v) const { return dir_to_unit * v; }
    double t_scale() const { return t_factor; }
};
Prescale prescale_for(double max_position, Vec3 v);

// Exact zeros decide the parallel, tangent and on-surface cases. They can be trusted only when
// no product of the prescaled inputs can have underflowed: every nonzero component of a
// position at least min_relative_size of the scene's extent (and of v, of v's largest), so that
// products of four stay normal. Checked on the original inputs: prescaling itself may flush
// such a component to zero. Otherwise a zero, or a decisive quantity below tiny_decisive, may be
// an underflow, and the solvers refuse (out_of_range) rather than guess.
bool fragile_scene(double extent, std::initializer_list<Vec3> positions, Vec3 v);
constexpr double tiny_decisive = 0x1p-900;
inline bool underflow_zone(double x) {
    return x != 0 && std::fabs(x) < tiny_decisive;
}

// validate(), and the sign of det[a b c] (of det[a b H-C] for the cone) that it decided, exactly:
// for the solvers that need the orientation too (the correct solver), so that it is found once.
struct ValidFrame {
    Error error;
    int orientation = 0; // +-1 when error is none
};
ValidFrame validate_frame(const EllipticCylinder& s, const Line& l);
ValidFrame validate_frame(const EllipticCone& s, const Line& l);

// After prescaling, sizes below this (relative to the scene) would underflow when multiplied
// four times; the stable solvers refuse them with out_of_range rather than guess.
constexpr double min_relative_size = 0x1p-240;

} // namespace linequad::detail
