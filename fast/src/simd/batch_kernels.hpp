// What a batch kernel hands back for a block of lanes: for each lane either "solve this line with
// the scalar solver" (a branch the lanes do not take together: parallel, tangent, underflow, bad
// input, a result refused as out of range), or its hits, already in the order the scalar solver
// gives them, from which write_result() makes the Result as it would.
#pragma once

#include "forms/finish.hpp"

#include "linequad/prepared.hpp"

#include <cstddef>
#include <cstring>
#include <type_traits>

namespace linequad::detail {

// A block's hits in R: bit k of each mask is lane k. Slot 0 holds the first hit, slot 1 the
// second; a slot's values are written whether it holds a hit or not, so that writing a Result
// takes no branch.
template <class R, int N>
struct HitSlots {
    unsigned keep[2]; // slot j holds a hit (slot 1 only where slot 0 does)
    // Lane k's slot j as a Hit begins: t (the caller's units), then the point (zeros where the
    // query asks for none). The kernels transpose their lanes into these rows (store_rows).
    R tp[2][N][4];
};

// The stable kernel's block: `generic` is 0 where the scalar solver takes the line.
template <class R, int N>
struct LaneBlock : HitSlots<R, N> {
    unsigned generic;
};

// The one-byte fields that end a Result (error_code to rung) and a Hit (kind to certain), with
// the padding after them, as the bytes of one word: GCC 12 stores each such field on its own,
// which was a fifth of the batch writer's instructions.
template <class T, std::size_t First>
LINEQUAD_INLINE void store_byte_fields(T& object, const unsigned char (&bytes)[sizeof(T) - First]) {
    static_assert(std::is_trivially_copyable_v<T> && std::is_standard_layout_v<T>);
    std::memcpy(reinterpret_cast<unsigned char*>(&object) + First, bytes, sizeof(bytes));
}
static_assert(offsetof(Result, count) == offsetof(Result, error_code) + 1 &&
              offsetof(Result, on_surface) == offsetof(Result, error_code) + 2 &&
              offsetof(Result, surface_part) == offsetof(Result, error_code) + 3 &&
              offsetof(Result, certainty) == offsetof(Result, error_code) + 4 &&
              offsetof(Result, rung) == offsetof(Result, error_code) + 5 &&
              sizeof(Result) == offsetof(Result, error_code) + 8);
static_assert(offsetof(Hit, part) == offsetof(Hit, kind) + 1 &&
              offsetof(Hit, certain) == offsetof(Hit, kind) + 2 &&
              sizeof(Hit) == offsetof(Hit, kind) + 8);
template <class E>
constexpr unsigned char byte_of(E e) {
    return static_cast<unsigned char>(e);
}

// The hits of lane k of a block into r, with what the solver says of them; hits past the count
// are written too, and read by no one.
template <class R, int N, class Facts>
LINEQUAD_INLINE void write_hits(const HitSlots<R, N>& b, int k, std::uint8_t count, Facts facts,
                                Result& r) {
    r.error_field = "";
    store_byte_fields<Result, offsetof(Result, error_code)>(
        r, {byte_of(ErrorCode::none), 0, byte_of(false), byte_of(Part::lateral),
            byte_of(facts.certainty), byte_of(facts.rung), 0, 0});
    r.count = count;
    for (int j = 0; j < 2; ++j) {
        Hit& h = r.hits[j];
        const R* row = b.tp[j][k];
        if constexpr (std::is_same_v<R, double>) { // t and p at once
            static_assert(sizeof(Vec3) == 3 * sizeof(double) &&
                          offsetof(Hit, p) == offsetof(Hit, t) + sizeof(double));
            std::memcpy(reinterpret_cast<unsigned char*>(&h) + offsetof(Hit, t), row,
                        4 * sizeof(double));
        } else {
            h.t = row[0], h.p = Vec3{row[1], row[2], row[3]};
        }
        h.bound = facts.bound(j, k);
        // kind, part, certain: a crossing of the lateral surface, or a closed shape's hit as
        // the block names it
        unsigned char certain = byte_of(facts.certainty == Certainty::certain);
        if (facts.named(k))
            store_byte_fields<Hit, offsetof(Hit, kind)>(
                h, {byte_of(facts.kind(j, k)), byte_of(facts.part(j, k)), certain, 0, 0, 0, 0, 0});
        else
            store_byte_fields<Hit, offsetof(Hit, kind)>(
                h, {byte_of(HitKind::cross), byte_of(Part::lateral), certain, 0, 0, 0, 0, 0});
    }
}

// Bit k of a block's mask as byte k of a word (up to eight lanes), without a loop: the lanes'
// hit counts are then one addition for the block.
constexpr std::uint64_t bytes_of_bits(unsigned m) {
    constexpr std::uint64_t each_byte = 0x0101010101010101, bit_k_of_byte_k = 0x8040201008040201;
    std::uint64_t b = (std::uint64_t(m & 0xff) * each_byte) & bit_k_of_byte_k; // 0 or 2^k
    return ((b + 0x7f7f7f7f7f7f7f7f) >> 7) & each_byte; // 0 or 1: no byte carries
}
static_assert(bytes_of_bits(0) == 0 && bytes_of_bits(0xff) == 0x0101010101010101 &&
              bytes_of_bits(0x05) == 0x0000000000010001 && bytes_of_bits(0x80) == 0x01ull << 56);
// The count of hits in each lane of a block, lane k in byte k.
template <class R, int N>
std::uint64_t hit_counts(const HitSlots<R, N>& b) {
    static_assert(N <= 8);
    return bytes_of_bits(b.keep[0]) + bytes_of_bits(b.keep[1]);
}

// Lane k's Result, as assemble() (solve/finish.hpp) makes it: no bound, nothing certified.
template <class R, int N>
LINEQUAD_INLINE void write_result(const LaneBlock<R, N>& b, int k, std::uint8_t count, Result& r) {
    struct Stable {
        Certainty certainty = Certainty::unknown;
        Rung rung = Rung::none;
        double bound(int, int) const { return no_bound; }
        static constexpr bool named(int) { return false; }
        HitKind kind(int, int) const { return HitKind::cross; }
        Part part(int, int) const { return Part::lateral; }
    };
    write_hits(b, k, count, Stable{}, r);
}

// What the batch correct kernel hands back for a block of N lanes: the lanes the Newton rung (or
// for a hit test the quick rung) proved, the others going to the scalar ladder, and their hits
// as the rung adds them, t and the point already rounded (caller's units).
template <int N>
struct CorrectBlock : HitSlots<double, N> {
    unsigned proven;
    double bound[2][N]; // half an ulp of t; a hit test's own (its t is not rounded)
    // A closed shape's hits name their kind and part (an open shape's cross the lateral surface).
    bool closed;
    HitKind kind[2][N];
    Part part[2][N];
};

// Lane k's Result, as the scalar ladder makes it from the Newton rung's hits (a hit test's
// from its quick rung: no point, its own bound).
template <int N>
LINEQUAD_INLINE void write_result(const CorrectBlock<N>& b, int k, std::uint8_t count, Result& r) {
    struct Newton {
        const CorrectBlock<N>& b;
        Certainty certainty = Certainty::certain;
        Rung rung = Rung::newton;
        double bound(int j, int k) const { return b.bound[j][k]; }
        bool named(int) const { return b.closed; }
        HitKind kind(int j, int k) const { return b.kind[j][k]; }
        Part part(int j, int k) const { return b.part[j][k]; }
    };
    write_hits(b, k, count, Newton{b}, r);
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
