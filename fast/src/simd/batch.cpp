#include "simd/batch_kernels.hpp"
#include "solve/api.hpp"
#include "solve/solve.hpp"

#include "linequad/batch.hpp"
#include "linequad/prepared.hpp"

namespace linequad {

const char* lanes_name(Lanes l) {
    switch (l) {
    case Lanes::avx512:
        return "avx512";
    case Lanes::avx2:
        return "avx2";
    default:
        return "scalar";
    }
}

Lanes batch_lanes() {
#if defined(__x86_64__) && defined(LINEQUAD_HAVE_AVX2_KERNELS)
    static const Lanes widest = [] {
#if defined(LINEQUAD_HAVE_AVX512_KERNELS)
        if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq"))
            return Lanes::avx512;
#endif
        if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return Lanes::avx2;
        return Lanes::scalar;
    }();
    return widest;
#else
    return Lanes::scalar;
#endif
}

namespace {

// Line i of the arrays, in double (a float line's coordinates are exact in double).
template <class R>
Line line_at(const LineArraysT<R>& lines, std::size_t i) {
    return Line{
        {lines.x[i], lines.y[i], lines.z[i]}, {lines.vx[i], lines.vy[i], lines.vz[i]}, lines.range};
}

// A block's Results: the lanes in `answered` from the block, the others by `scalar(k)`. A block
// the lanes answer whole (the usual case) is written without a test per lane.
template <class Block, class Scalar>
void write_results(const Block& block, unsigned answered, Result* out, Scalar scalar) {
    constexpr int n = int(sizeof(block.tp[0]) / sizeof(block.tp[0][0]));
    std::uint64_t counts = detail::hit_counts(block);
    auto count = [counts](int k) { return std::uint8_t(counts >> (8 * k)); };
    if (answered == (1u << n) - 1) {
#pragma GCC unroll 8
        for (int k = 0; k < n; ++k)
            detail::write_result(block, k, count(k), out[k]);
        return;
    }
    for (int k = 0; k < n; ++k) {
        if ((answered >> k) & 1)
            detail::write_result(block, k, count(k), out[k]);
        else
            scalar(k);
    }
}

// The scalar solver for lines in R.
template <class R, class S>
Result solve_one(const S& shape, const Line& l, Query q) {
    if constexpr (std::is_same_v<R, float>)
        return stable32::intersect(shape, l, q);
    else
        return stable::intersect(shape, l, q);
}

// The kernel for lines in R on N lanes: stable_x8 or stable_x4 for double, stable32_x8 for float.
template <class R, int N>
struct Kernel {
    template <class S>
    static void run(const S& s, double extent, const R* const soa[6], std::size_t i, Interval range,
                    Query q, detail::LaneBlock<R, N>& out) {
        if constexpr (std::is_same_v<R, float>)
            detail::stable32_x8(s, extent, soa, i, range, q, out);
        else if constexpr (N == 8)
            detail::stable_x8(s, extent, soa, i, range, q, out);
        else
            detail::stable_x4(s, extent, soa, i, range, q, out);
    }
};

// Lines [i, i + N) of the batch that the kernel takes: their results, assembled from the lanes;
// the lanes it does not take (bad lines, the branches of the scalar solver) by the scalar
// solver, which names any problem. Returns the first line it has not done.
template <class R, int N, class S>
std::size_t run_lanes(const S& shape, const LineArraysT<R>& lines, Query q, Result* out) {
    auto src = detail::source(shape);
    const R* const soa[6] = {lines.x, lines.y, lines.z, lines.vx, lines.vy, lines.vz};
    double shape_extent = src.magnitude();
    detail::LaneBlock<R, N> block;
    std::size_t i = 0;
    for (; i + N <= lines.count; i += N) {
        Kernel<R, N>::run(src.shape, shape_extent, soa, i, lines.range, q, block);
        write_results(block, block.generic, out + i,
                      [&](int k) { out[i + k] = solve_one<R>(shape, line_at(lines, i + k), q); });
    }
    return i;
}

template <class R, class S>
void solve_batch(const S& shape, const LineArraysT<R>& lines, Query q, Result* out, Lanes lanes) {
    std::size_t i = 0;
#if defined(LINEQUAD_HAVE_AVX2_KERNELS)
    // The shape is checked once, and the range (for float lines: that they are floats). A closed
    // shape's discs, a shape made of patches, and a shape without a lane kernel are the scalar
    // solver's.
    auto src = detail::source(shape);
    if constexpr (detail::stable_in_lanes<typename decltype(src)::Shape>) {
        Line probe{{0, 0, 0}, {1, 0, 0}, lines.range};
        bool shape_ok = src.validity().error.ok() && !detail::has_discs(src.shape) &&
                        detail::check_line(probe).ok() && detail::real_error<R>(src, probe).ok();
        lanes = std::min(lanes, batch_lanes());
        if (shape_ok && lanes != Lanes::scalar) {
#if defined(LINEQUAD_HAVE_AVX512_KERNELS)
            if (lanes == Lanes::avx512 && std::is_same_v<R, double>)
                i = run_lanes<R, 8>(shape, lines, q, out);
            else
#endif
                i = run_lanes < R, std::is_same_v<R, float> ? 8 : 4 > (shape, lines, q, out);
        }
    }
#endif
    for (; i < lines.count; ++i)
        out[i] = solve_one<R>(shape, line_at(lines, i), q);
}

// correct's batch: the Newton rung on N lanes (correct_x4, correct_x8), the lanes it does not
// prove by the scalar ladder.
template <int N, class S>
std::size_t run_correct_lanes(const Prepared<S>& shape, const LineArrays& lines, Query q,
                              Result* out) {
    int orientation = detail::source(shape).validity().orientation;
    const double* const soa[6] = {lines.x, lines.y, lines.z, lines.vx, lines.vy, lines.vz};
    detail::CorrectBlock<N> block;
    std::size_t i = 0;
    for (; i + N <= lines.count; i += N) {
        if constexpr (N == 8)
            detail::correct_x8(shape, orientation, soa, i, lines.range, q, block);
        else
            detail::correct_x4(shape, orientation, soa, i, lines.range, q, block);
        write_results(block, block.proven, out + i, [&](int k) {
            out[i + k] = correct::intersect(shape, line_at(lines, i + k), q);
        });
    }
    return i;
}

template <class S>
void correct_batch(const Prepared<S>& shape, const LineArrays& lines, Query q, Result* out,
                   Lanes lanes) {
    std::size_t i = 0;
#if defined(LINEQUAD_HAVE_AVX2_KERNELS)
    // The ladder's Newton rung as given (a hit test's quick rung) covers a valid shape with a
    // line form (open, or closed by discs) or its own local quadratic (a plane, a quadric) and a
    // valid range.
    if constexpr (detail::correct_in_lanes<S>) {
        Line probe{{0, 0, 0}, {1, 0, 0}, lines.range};
        bool rung_applies = shape.ok() && detail::check_line(probe).ok();
        lanes = std::min(lanes, batch_lanes());
        if (rung_applies && lanes != Lanes::scalar) {
#if defined(LINEQUAD_HAVE_AVX512_KERNELS)
            if (lanes == Lanes::avx512)
                i = run_correct_lanes<8>(shape, lines, q, out);
            else
#endif
                i = run_correct_lanes<4>(shape, lines, q, out);
        }
    }
#endif
    for (; i < lines.count; ++i)
        out[i] = correct::intersect(shape, line_at(lines, i), q);
}
// A plain shape is prepared once for the batch: the rung's frame rows and orientation.
template <class S>
void correct_batch(const S& shape, const LineArrays& lines, Query q, Result* out, Lanes lanes) {
    correct_batch(prepare(shape), lines, q, out, lanes);
}

} // namespace

template <class S, if_solvable<S>>
void correct::intersect(const S& shape, const LineArrays& lines, Query q, Result* out,
                        Lanes lanes) {
    numeric::StandardEnvironment standard;
    correct_batch(shape, lines, q, out, lanes);
}

template <class S, if_solvable<S>>
void stable::intersect(const S& shape, const LineArrays& lines, Query q, Result* out, Lanes lanes) {
    numeric::StandardEnvironment standard;
    solve_batch(shape, lines, q, out, lanes);
}
template <class S, if_solvable<S>>
void stable32::intersect(const S& shape, const LineArrays32& lines, Query q, Result* out,
                         Lanes lanes) {
    numeric::StandardEnvironment standard;
    solve_batch(shape, lines, q, out, lanes);
}

#define LINEQUAD_INSTANTIATE_BATCH(S)                                                              \
    template void stable::intersect(const S&, const LineArrays&, Query, Result*, Lanes);           \
    template void correct::intersect(const S&, const LineArrays&, Query, Result*, Lanes);          \
    template void correct::intersect(const Prepared<S>&, const LineArrays&, Query, Result*,        \
                                     Lanes);                                                       \
    template void stable::intersect(const Prepared<S>&, const LineArrays&, Query, Result*, Lanes); \
    template void stable32::intersect(const S&, const LineArrays32&, Query, Result*, Lanes);       \
    template void stable32::intersect(const Prepared<S>&, const LineArrays32&, Query, Result*,     \
                                      Lanes);
LINEQUAD_FOR_EACH_SHAPE(LINEQUAD_INSTANTIATE_BATCH)

} // namespace linequad
