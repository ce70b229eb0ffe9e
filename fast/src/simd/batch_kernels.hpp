// What a batch kernel hands back for a block of lanes: for each lane either "solve this line with
// the scalar solver" (a branch the lanes do not take together: parallel, tangent, underflow, bad
// input), or the two roots' facts, already in the order assemble() (solve/finish.hpp) takes them,
// from which write_result() makes the Result as the scalar solver would.
#pragma once

#include "solve/finish.hpp"

#include "linequad/prepared.hpp"

#include <cstddef>
#include <type_traits>

namespace linequad::detail {

// N lanes of lines in R; bit k of each mask is lane k. Root 0 is the one assemble() looks at first
// (the smaller t, except for a hit test, which takes them as found).
template <class R, int N>
struct LaneBlock {
    unsigned generic; // 0: the scalar solver takes the line
    unsigned two;     // two real roots (else none)
    unsigned bad;     // a root's t or z not finite
    unsigned keep[2]; // the root inside the extent and the range
    unsigned finite_point[2];
    R t[2][N];    // in the caller's units
    R p[2][3][N]; // fma(t, v, L0)
};

// Lane k's Result, as assemble() makes it from the same facts.
template <class R, int N>
LINEQUAD_INLINE void write_result(const LaneBlock<R, N>& b, int k, Query q, Result& r) {
    reset(r);
    if (!((b.two >> k) & 1)) return;
    if ((b.bad >> k) & 1) return fail(r, ErrorCode::out_of_range, "t");
    bool points = q.points && q.need != Need::any;
    int count = 0;
    for (int j = 0; j < 2; ++j) {
        if (!((b.keep[j] >> k) & 1)) continue;
        if (points && !((b.finite_point[j] >> k) & 1)) return fail(r, ErrorCode::out_of_range, "p");
        Hit& h = r.hits[count++];
        h.t = b.t[j][k], h.kind = HitKind::cross, h.part = Part::lateral; // closed: scalar
        h.bound = no_bound, h.certain = false;
        h.p = points ? Vec3{b.p[j][0][k], b.p[j][1][k], b.p[j][2][k]} : Vec3{};
        if (q.need != Need::all) break; // the first kept is the nearest
    }
    r.count = std::uint8_t(count);
}

// What the batch correct kernel hands back for a block of N lanes: the lanes the Newton rung (or
// for a hit test the quick rung) proved, the others going to the scalar ladder, and their hits
// as the rung adds them: root j is a hit where bit k of keep[j] is set, t and the point already
// rounded (caller's units).
template <int N>
struct CorrectBlock {
    unsigned proven;
    unsigned keep[2];
    double t[2][N];
    double p[2][3][N];
    double bound[2][N]; // half an ulp of t; a hit test's own (its t is not rounded)
};

// Lane k's Result, as the scalar ladder makes it from the Newton rung's hits (a hit test's
// from its quick rung: no point, its own bound).
template <int N>
LINEQUAD_INLINE void write_result(const CorrectBlock<N>& b, int k, Query q, Result& r) {
    reset(r);
    bool points = q.points && q.need != Need::any;
    for (int j = 0; j < 2; ++j) {
        if (!((b.keep[j] >> k) & 1)) continue;
        Hit& h = r.hits[r.count++];
        h.t = b.t[j][k], h.kind = HitKind::cross, h.part = Part::lateral;
        h.p = points ? Vec3{b.p[j][0][k], b.p[j][1][k], b.p[j][2][k]} : Vec3{};
        h.bound = b.bound[j][k], h.certain = true;
    }
    r.certainty = Certainty::certain;
    r.rung = Rung::newton;
}

// Lines [i, i + 4) of the arrays (x, y, z, vx, vy, vz) against the shape, in double lanes;
// AVX2 and FMA. shape_extent: the largest magnitude among the shape's points and vectors
// (prescaling).
template <class S>
void stable_x4(const S& s, double shape_extent, const double* const soa[6], std::size_t i,
               Interval range, Query q, LaneBlock<double, 4>& out);
// Lines [i, i + 8) in double lanes; AVX-512F and DQ.
template <class S>
void stable_x8(const S& s, double shape_extent, const double* const soa[6], std::size_t i,
               Interval range, Query q, LaneBlock<double, 8>& out);
// Lines [i, i + 8) in float lanes (stable32); AVX2 and FMA.
template <class S>
void stable32_x8(const S& s, double shape_extent, const float* const soa[6], std::size_t i,
                 Interval range, Query q, LaneBlock<float, 8>& out);

// The Newton rung of correct on lines [i, i + 4) (AVX2 and FMA) or [i, i + 8) (AVX-512F and DQ)
// against a prepared shape with a line form; orientation: its frame's, as validation decides it.
template <class S>
void correct_x4(const Prepared<S>& s, int orientation, const double* const soa[6], std::size_t i,
                Interval range, Query q, CorrectBlock<4>& out);
template <class S>
void correct_x8(const Prepared<S>& s, int orientation, const double* const soa[6], std::size_t i,
                Interval range, Query q, CorrectBlock<8>& out);

} // namespace linequad::detail
