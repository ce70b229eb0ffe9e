// What a batch kernel hands back for each lane: either "solve this line with the scalar solver"
// (a branch the lanes do not take together: parallel, tangent, underflow, bad input), or the
// roots and their axial coordinates, from which the scalar finishing step makes the Result.
#pragma once

#include "linequad/shapes.hpp"
#include "support.hpp"

#include <cstddef>

namespace linequad::detail {

struct LaneResult {
    bool generic = false; // false: use the scalar solver for this line
    int count = 0;        // 0 (misses) or 2
    FinishedCandidate root[2];
};

// Lines [i, i + 4) of the arrays (x, y, z, vx, vy, vz) against the shape; AVX2 and FMA.
// shape_extent: the largest magnitude among the shape's points and vectors (prescaling).
void cylinder_stable_x4(const Cylinder& s, double shape_extent, const double* const soa[6],
                        std::size_t i, Range range, LaneResult out[4]);
void elliptic_cylinder_stable_x4(const EllipticCylinder& s, double shape_extent,
                                 const double* const soa[6], std::size_t i, Range range,
                                 LaneResult out[4]);
void elliptic_cone_stable_x4(const EllipticCone& s, double shape_extent, const double* const soa[6],
                             std::size_t i, Range range, LaneResult out[4]);

} // namespace linequad::detail
