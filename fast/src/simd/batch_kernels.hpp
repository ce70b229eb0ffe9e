// What a batch kernel hands back for each lane: either "solve this line with the scalar solver"
// (a branch the lanes do not take together: parallel, tangent, underflow, bad input), or the
// roots' facts, from which assemble() (solve/finish.hpp) makes the Result as the scalar solver
// would.
#pragma once

#include "solve/finish.hpp"

#include <cstddef>
#include <type_traits>

namespace linequad::detail {

// A root's facts: t in the caller's units; t or z not finite; inside extent and range; its
// point fma(t, v, L0).
struct FinishedCandidate {
    double t;
    HitKind kind;
    bool bad, keep;
    Vec3 p;
};

struct LaneResult {
    bool generic = false; // false: use the scalar solver for this line
    int count = 0;        // 0 (misses) or 2
    FinishedCandidate root[2];

    double t(int i) const { return root[i].t; }
    HitKind kind(int i) const { return root[i].kind; }
    Part part(int) const { return Part::lateral; } // closed shapes take the scalar solver
    bool bad(int i) const { return root[i].bad; }
    bool keep(int i) const { return root[i].keep; }
    Vec3 point(int i) const { return root[i].p; }
};

// Lines [i, i + 4) of the arrays (x, y, z, vx, vy, vz) against the shape, in double lanes;
// AVX2 and FMA. shape_extent: the largest magnitude among the shape's points and vectors
// (prescaling).
template <class S>
void stable_x4(const S& s, double shape_extent, const double* const soa[6], std::size_t i,
               Interval range, LaneResult out[4]);
// Lines [i, i + 8) in double lanes; AVX-512F and DQ.
template <class S>
void stable_x8(const S& s, double shape_extent, const double* const soa[6], std::size_t i,
               Interval range, LaneResult out[8]);
// Lines [i, i + 8) in float lanes (stable32); AVX2 and FMA.
template <class S>
void stable32_x8(const S& s, double shape_extent, const float* const soa[6], std::size_t i,
                 Interval range, LaneResult out[8]);

} // namespace linequad::detail
