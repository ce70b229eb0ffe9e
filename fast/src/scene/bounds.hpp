// A scene's culling: whether a line may come within a shape's box or capsule (each shape's own
// bounds are in its traits, shapes/*.hpp, built from forms/bounds.hpp).
#pragma once

#include "forms/bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace linequad::detail {

// Whether the line may come within the capsule: false only when it is proven not to. With v
// scaled by a power of two to |v| near 1 (exactly), the squared distance from the line to
// P + s h is |w + s u|^2 / |v|^2 for w = (P - L0) x v and u = h x v; any s in [0, 1] gives at
// least the least distance, and s near the minimiser gives it to within the rounding. The slack,
// 2^-40 of the magnitudes squared, covers that, the errors of P - L0, of the cross products and
// sums (some 2^-48), and those of h and r as the shape's doubles round them. Overflow, and
// magnitudes where underflow could eat the slack, answer "may".
inline bool may_cross(const BoundingCapsule& c, const Line& line) {
    double vmax = std::max({std::fabs(line.v.x), std::fabs(line.v.y), std::fabs(line.v.z)});
    Vec3 v = std::ldexp(1.0, -std::ilogb(vmax)) * line.v;
    Vec3 d = c.P - line.L0;
    Vec3 w = cross(d, v), u = cross(c.h, v);
    double uu = dot(u, u), wu = dot(w, u);
    double s = uu > 0 ? std::clamp(-wu / uu, 0.0, 1.0) : 0.0;
    Vec3 q = w + s * u;
    double vv = dot(v, v);
    double reach = norm(d) + norm(c.h) + c.r;
    double least = dot(q, q);
    double limit = c.r * c.r * vv * (1 + 0x1p-40) + reach * reach * vv * 0x1p-40;
    if (!std::isfinite(least) || !std::isfinite(limit) || reach < 0x1p-400) return true;
    return least <= limit;
}

inline bool bounded(const Box& b) {
    return std::isfinite(b.lo.x) && std::isfinite(b.lo.y) && std::isfinite(b.lo.z) &&
           std::isfinite(b.hi.x) && std::isfinite(b.hi.y) && std::isfinite(b.hi.z);
}

} // namespace linequad::detail
