#include "linequad/batch.hpp"

#include "batch_kernels.hpp"
#include "linequad/cylinder.hpp"
#include "linequad/validate.hpp"
#include "support.hpp"

namespace linequad {

bool batch_uses_avx2() {
#if defined(__x86_64__) && defined(LINEQUAD_HAVE_AVX2_KERNELS)
    static const bool yes = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    return yes;
#else
    return false;
#endif
}

void stable::intersect(const Cylinder& s, const LineArrays& lines, Query q, Result* out) {
    auto line_at = [&](std::size_t i) {
        return Line{{lines.x[i], lines.y[i], lines.z[i]},
                    {lines.vx[i], lines.vy[i], lines.vz[i]},
                    lines.range};
    };
    std::size_t i = 0;
#if defined(LINEQUAD_HAVE_AVX2_KERNELS)
    // The shape is checked once (with a valid line, so that only the shape's checks can fail);
    // a bad shape, or a bad line, goes through the scalar solver, which names the problem.
    bool shape_ok = validate(s, Line{{0, 0, 0}, {1, 0, 0}}).code == ErrorCode::none;
    if (batch_uses_avx2() && shape_ok) {
        const double* const soa[6] = {lines.x, lines.y, lines.z, lines.vx, lines.vy, lines.vz};
        double shape_extent = std::max({max_abs(s.C), max_abs(s.H), s.r});
        detail::LaneResult lane[4];
        for (; i + 4 <= lines.count; i += 4) {
            detail::cylinder_stable_x4(s, shape_extent, soa, i, lines.range, lane);
            for (int k = 0; k < 4; ++k) {
                Line l = line_at(i + k);
                bool line_ok = is_finite(l.L0) && is_finite(l.v) && l.v != Vec3{};
                if (!lane[k].generic || !line_ok) {
                    out[i + k] = stable::intersect(s, l, q);
                    continue;
                }
                detail::assemble(lane[k].root, lane[k].count, q, out[i + k]);
            }
        }
    }
#endif
    for (; i < lines.count; ++i)
        out[i] = stable::intersect(s, line_at(i), q);
}

} // namespace linequad
