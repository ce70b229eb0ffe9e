#include "simd/batch_kernels.hpp"
#include "solve/api.hpp"
#include "solve/solve.hpp"

#include "linequad/batch.hpp"

namespace linequad {

bool batch_uses_avx2() {
#if defined(__x86_64__) && defined(LINEQUAD_HAVE_AVX2_KERNELS)
    static const bool yes = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    return yes;
#else
    return false;
#endif
}

namespace {

// The scalar solver for lines in R.
template <class R, class S>
Result solve_one(const S& shape, const Line& l, Query q) {
    if constexpr (std::is_same_v<R, float>)
        return stable32::intersect(shape, l, q);
    else
        return stable::intersect(shape, l, q);
}

// Lanes of lines at a time through the kernel; the lanes it does not take, bad lines, a bad
// shape and the tail through the scalar solver, which names any problem.
template <class R, class S>
void solve_batch(const S& shape, const LineArraysT<R>& lines, Query q, Result* out) {
    auto src = detail::source(shape);
    auto line_at = [&](std::size_t i) {
        return Line{{lines.x[i], lines.y[i], lines.z[i]},
                    {lines.vx[i], lines.vy[i], lines.vz[i]},
                    lines.range};
    };
    std::size_t i = 0;
#if defined(LINEQUAD_HAVE_AVX2_KERNELS)
    // The shape is checked once, and the range (for float lines: that they are floats); a bad
    // line goes to the scalar solver, which names it. A closed shape's discs are the scalar
    // solver's too.
    Line probe{{0, 0, 0}, {1, 0, 0}, lines.range};
    bool shape_ok = src.validity().error.ok() && !detail::closed(src.shape) &&
                    detail::check_line(probe).ok() && detail::real_error<R>(src, probe).ok();
    if (batch_uses_avx2() && shape_ok) {
        using Kernel = detail::BatchKernel<R>;
        constexpr int N = Kernel::lanes;
        const R* const soa[6] = {lines.x, lines.y, lines.z, lines.vx, lines.vy, lines.vz};
        double shape_extent = src.magnitude();
        detail::LaneResult lane[N];
        for (; i + N <= lines.count; i += N) {
            Kernel::run(src.shape, shape_extent, soa, i, lines.range, lane);
            for (int k = 0; k < N; ++k) {
                Line l = line_at(i + k);
                bool line_ok = is_finite(l.L0) && is_finite(l.v) && l.v != Vec3{};
                if (lane[k].generic && line_ok) {
                    detail::reset(out[i + k]);
                    detail::assemble(lane[k], lane[k].count, q, out[i + k]);
                } else
                    out[i + k] = solve_one<R>(shape, l, q);
            }
        }
    }
#endif
    for (; i < lines.count; ++i)
        out[i] = solve_one<R>(shape, line_at(i), q);
}

} // namespace

template <class S, if_solvable<S>>
void stable::intersect(const S& shape, const LineArrays& lines, Query q, Result* out) {
    solve_batch(shape, lines, q, out);
}
template <class S, if_solvable<S>>
void stable32::intersect(const S& shape, const LineArrays32& lines, Query q, Result* out) {
    solve_batch(shape, lines, q, out);
}

#define LINEQUAD_INSTANTIATE_BATCH(S)                                                              \
    template void stable::intersect(const S&, const LineArrays&, Query, Result*);                  \
    template void stable::intersect(const Prepared<S>&, const LineArrays&, Query, Result*);        \
    template void stable32::intersect(const S&, const LineArrays32&, Query, Result*);              \
    template void stable32::intersect(const Prepared<S>&, const LineArrays32&, Query, Result*);
LINEQUAD_FOR_EACH_SHAPE(LINEQUAD_INSTANTIATE_BATCH)

} // namespace linequad
