// Many lines against one shape, the lines in structure-of-arrays form: what a renderer's
// packet of rays or a sweep of cases needs. The shape is checked once (pass a prepared shape to
// check it once for many batches). Every result equals the scalar solver's bit for bit; the AVX2
// path is chosen at run time when the CPU has AVX2 and FMA, a scalar loop otherwise.
#pragma once

#include "linequad/solvers.hpp"

#include <cstddef>

namespace linequad {

// The lines' coordinates in R: double for stable, float for stable32 (a renderer's packet).
template <class R>
struct LineArraysT {
    const R *x, *y, *z;    // L0
    const R *vx, *vy, *vz; // v
    std::size_t count;
    Interval range; // shared by every line (floats, for float lines)
};
using LineArrays = LineArraysT<double>;
using LineArrays32 = LineArraysT<float>;

namespace stable {
// out[i] = stable::intersect(shape, line i, query) for every i < lines.count.
template <class S, if_solvable<S> = 0>
void intersect(const S& shape, const LineArrays& lines, Query query, Result* out);
} // namespace stable

namespace stable32 {
// out[i] = stable32::intersect(shape, line i, query) for every i < lines.count: eight float
// lanes at a time.
template <class S, if_solvable<S> = 0>
void intersect(const S& shape, const LineArrays32& lines, Query query, Result* out);
} // namespace stable32

// Whether the batch solvers run their AVX2 path on this machine (or the scalar loop).
bool batch_uses_avx2();

} // namespace linequad
