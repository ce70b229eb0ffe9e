// Many lines against one shape, the lines in structure-of-arrays form: what a renderer's
// packet of rays or a sweep of cases needs. The shape is checked once (pass a prepared shape to
// check it once for many batches; correct prepares a plain shape once per batch). Every result
// equals the scalar solver's bit for bit, on whichever lanes the CPU offers, chosen at run time:
// AVX-512 (eight double lanes), AVX2 (four double or eight float lanes), or a scalar loop.
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

// The instruction sets a batch runs on, narrowest first.
enum class Lanes {
    scalar, // one line at a time: the scalar solver in a loop
    avx2,   // AVX2 and FMA: four double lanes, eight float lanes
    avx512, // AVX-512 F and DQ: eight double lanes (float lines stay on AVX2's eight)
};
const char* lanes_name(Lanes l);
// The widest this machine runs: what the batch solvers use unless told otherwise.
Lanes batch_lanes();

namespace stable {
// out[i] = stable::intersect(shape, line i, query) for every i < lines.count, on `lanes` (at most
// batch_lanes(): a wider request runs on the widest there is).
template <class S, if_solvable<S> = 0>
void intersect(const S& shape, const LineArrays& lines, Query query, Result* out,
               Lanes lanes = batch_lanes());
} // namespace stable

namespace correct {
// out[i] = correct::intersect(shape, line i, query) for every i < lines.count, bit for bit, on
// `lanes` (at most batch_lanes()). The Newton rung (a hit test's quick rung) runs in lanes for
// every shape but the capsule (made of patches), open or closed; the lines it cannot prove are
// solved one at a time.
template <class S, if_solvable<S> = 0>
void intersect(const S& shape, const LineArrays& lines, Query query, Result* out,
               Lanes lanes = batch_lanes());
} // namespace correct

namespace stable32 {
// out[i] = stable32::intersect(shape, line i, query) for every i < lines.count: eight float
// lanes at a time.
template <class S, if_solvable<S> = 0>
void intersect(const S& shape, const LineArrays32& lines, Query query, Result* out,
               Lanes lanes = batch_lanes());
} // namespace stable32

} // namespace linequad
