// Many lines against one shape, the lines in structure-of-arrays form: what a renderer's
// packet of rays or a sweep of cases needs. The shape is checked once. Every result equals the
// scalar solver's bit for bit (the same arithmetic, see src/cylinder_stable.hpp); the AVX2 path
// is chosen at run time when the CPU has AVX2 and FMA, a scalar loop otherwise.
#pragma once

#include "linequad/result.hpp"
#include "linequad/shapes.hpp"

#include <cstddef>

namespace linequad {

struct LineArrays {
    const double *x, *y, *z;    // L0
    const double *vx, *vy, *vz; // v
    std::size_t count;
    Range range = Range::line;
};

namespace stable {
// out[i] = stable::intersect(s, line i, q) for every i < lines.count.
void intersect(const Cylinder& s, const LineArrays& lines, Query q, Result* out);
void intersect(const EllipticCylinder& s, const LineArrays& lines, Query q, Result* out);
void intersect(const EllipticCone& s, const LineArrays& lines, Query q, Result* out);
} // namespace stable

// Whether the batch solvers run their AVX2 path on this machine (or the scalar loop).
bool batch_uses_avx2();

} // namespace linequad
