// The slab test of a line against an axis-aligned box, widened by its own rounding error: what
// the scene's hierarchy and its Embree traversal both clip lines with.
#pragma once

#include "linequad/scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace linequad::detail {

inline Box merged(const Box& a, const Box& b) {
    return {{std::min(a.lo.x, b.lo.x), std::min(a.lo.y, b.lo.y), std::min(a.lo.z, b.lo.z)},
            {std::max(a.hi.x, b.hi.x), std::max(a.hi.y, b.hi.y), std::max(a.hi.z, b.hi.z)}};
}

// The line as the slab test takes it: 1 / v_i per axis, where that is a normal double.
struct SlabLine {
    Vec3 L0, inv;
    bool exact_axis[3]; // v_i = 0: the line stays in the slab's plane or never meets it
    bool divide[3];     // 1 / v_i overflowed or is subnormal: divide by v_i instead
    Vec3 v;
    explicit SlabLine(const Line& l) : L0(l.L0), inv{1 / l.v.x, 1 / l.v.y, 1 / l.v.z}, v(l.v) {
        for (int i = 0; i < 3; ++i) {
            exact_axis[i] = v[i] == 0;
            // Overflowed or subnormal: its relative error would not hold.
            double inv_i = inv[i];
            divide[i] =
                !(std::fabs(inv_i) >= std::numeric_limits<double>::min() && std::isfinite(inv_i));
        }
    }
};

// The part [t0, t1] of the line's range where it may be inside the box, or false when it cannot
// be. Each slab's t = (bound - L0_i) / v_i, as three roundings ((bound - L0_i), 1 / v_i and
// their product), lies within 2^-51 |t| of the exact quotient (or is 0, or has overflowed); it is
// widened by 2^-50 |t| and the smallest subnormal, or not used at all when it overflowed from
// finite numbers (the box's bounds are finite).
inline bool slab(const Box& box, const SlabLine& line, double& t0, double& t1) {
    constexpr double tiny = 0x1p-1074;
    for (int i = 0; i < 3; ++i) {
        double L = line.L0[i];
        double lo = box.lo[i], hi = box.hi[i];
        if (line.exact_axis[i]) {
            if (L < lo || L > hi) return false;
            continue;
        }
        double ta, tb;
        if (line.divide[i]) {
            double vi = line.v[i];
            ta = (lo - L) / vi, tb = (hi - L) / vi;
        } else {
            double inv = line.inv[i];
            ta = (lo - L) * inv, tb = (hi - L) * inv;
        }
        if (ta > tb) std::swap(ta, tb);
        if (std::isfinite(ta)) t0 = std::max(t0, ta - (std::fabs(ta) * 0x1p-50 + tiny));
        if (std::isfinite(tb)) t1 = std::min(t1, tb + (std::fabs(tb) * 0x1p-50 + tiny));
        if (t0 > t1) return false;
    }
    return true;
}

} // namespace linequad::detail
