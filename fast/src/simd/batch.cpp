#include "simd/batch_kernels.hpp"
#include "solve/api.hpp"

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

// Four lines at a time through the kernel; the lanes it does not take, bad lines, a bad shape
// and the tail through the scalar solver, which names any problem.
template <class S>
void solve_batch(const S& shape, const LineArrays& lines, Query q, Result* out) {
    auto src = detail::source(shape);
    using Shape = typename decltype(src)::Shape;
    auto line_at = [&](std::size_t i) {
        return Line{{lines.x[i], lines.y[i], lines.z[i]},
                    {lines.vx[i], lines.vy[i], lines.vz[i]},
                    lines.range};
    };
    std::size_t i = 0;
#if defined(LINEQUAD_HAVE_AVX2_KERNELS)
    // The shape is checked once, and the range; a bad line goes to the scalar solver, which
    // names it. A closed shape's discs are the scalar solver's too.
    bool shape_ok = src.validity().error.ok() && !detail::closed(src.shape) &&
                    detail::check_line(Line{{0, 0, 0}, {1, 0, 0}, lines.range}).ok();
    if (batch_uses_avx2() && shape_ok) {
        const double* const soa[6] = {lines.x, lines.y, lines.z, lines.vx, lines.vy, lines.vz};
        double shape_extent = src.magnitude();
        detail::LaneResult lane[4];
        for (; i + 4 <= lines.count; i += 4) {
            detail::stable_x4<Shape>(src.shape, shape_extent, soa, i, lines.range, lane);
            for (int k = 0; k < 4; ++k) {
                Line l = line_at(i + k);
                bool line_ok = is_finite(l.L0) && is_finite(l.v) && l.v != Vec3{};
                if (lane[k].generic && line_ok) {
                    detail::reset(out[i + k]);
                    detail::assemble(lane[k], lane[k].count, q, out[i + k]);
                } else
                    out[i + k] = stable::intersect(shape, l, q);
            }
        }
    }
#endif
    for (; i < lines.count; ++i)
        out[i] = stable::intersect(shape, line_at(i), q);
}

} // namespace

template <class S, if_solvable<S>>
void stable::intersect(const S& shape, const LineArrays& lines, Query q, Result* out) {
    solve_batch(shape, lines, q, out);
}

#define LINEQUAD_INSTANTIATE_BATCH(S)                                                              \
    template void stable::intersect(const S&, const LineArrays&, Query, Result*);                  \
    template void stable::intersect(const Prepared<S>&, const LineArrays&, Query, Result*);
LINEQUAD_FOR_EACH_SHAPE(LINEQUAD_INSTANTIATE_BATCH)

} // namespace linequad
