#include "linequad/batch.hpp"

#include "batch_kernels.hpp"
#include "linequad/cylinder.hpp"
#include "linequad/elliptic_cone.hpp"
#include "linequad/elliptic_cylinder.hpp"
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

namespace {

double extent_of(const Cylinder& s) {
    return std::max({max_abs(s.C), max_abs(s.H), s.r});
}
double extent_of(const EllipticCylinder& s) {
    return std::max({max_abs(s.C), max_abs(s.a), max_abs(s.b), max_abs(s.c)});
}
double extent_of(const EllipticCone& s) {
    return std::max({max_abs(s.C), max_abs(s.H), max_abs(s.a), max_abs(s.b)});
}

// Four lines at a time through the kernel; the lanes it does not take, bad lines, a bad shape
// and the tail through the scalar solver, which names any problem.
template <class ShapeT, class Kernel>
void solve_batch(const ShapeT& s, const LineArrays& lines, Query q, Result* out, Kernel kernel) {
    auto line_at = [&](std::size_t i) {
        return Line{{lines.x[i], lines.y[i], lines.z[i]},
                    {lines.vx[i], lines.vy[i], lines.vz[i]},
                    lines.range};
    };
    std::size_t i = 0;
    // The shape is checked once, with a valid line, so that only the shape's checks can fail.
    bool shape_ok = validate(s, Line{{0, 0, 0}, {1, 0, 0}}).code == ErrorCode::none;
    if (batch_uses_avx2() && shape_ok) {
        const double* const soa[6] = {lines.x, lines.y, lines.z, lines.vx, lines.vy, lines.vz};
        double shape_extent = extent_of(s);
        detail::LaneResult lane[4];
        for (; i + 4 <= lines.count; i += 4) {
            kernel(s, shape_extent, soa, i, lines.range, lane);
            for (int k = 0; k < 4; ++k) {
                Line l = line_at(i + k);
                bool line_ok = is_finite(l.L0) && is_finite(l.v) && l.v != Vec3{};
                if (lane[k].generic && line_ok)
                    detail::assemble(lane[k].root, lane[k].count, q, out[i + k]);
                else
                    out[i + k] = stable::intersect(s, l, q);
            }
        }
    }
    for (; i < lines.count; ++i)
        out[i] = stable::intersect(s, line_at(i), q);
}

#if defined(LINEQUAD_HAVE_AVX2_KERNELS)
#define LINEQUAD_KERNEL(name) detail::name
#else
// Never called: batch_uses_avx2() is false without the kernels.
#define LINEQUAD_KERNEL(name) [](auto&&...) {}
#endif

} // namespace

void stable::intersect(const Cylinder& s, const LineArrays& lines, Query q, Result* out) {
    solve_batch(s, lines, q, out, LINEQUAD_KERNEL(cylinder_stable_x4));
}
void stable::intersect(const EllipticCylinder& s, const LineArrays& lines, Query q, Result* out) {
    solve_batch(s, lines, q, out, LINEQUAD_KERNEL(elliptic_cylinder_stable_x4));
}
void stable::intersect(const EllipticCone& s, const LineArrays& lines, Query q, Result* out) {
    solve_batch(s, lines, q, out, LINEQUAD_KERNEL(elliptic_cone_stable_x4));
}

} // namespace linequad
