// Each shape's axis-aligned bounding box, rounded outward: it holds every point of the surface
// (caps included) however the doubles below round.
//
// Every bound is a coordinate of the form P + z c ± |z| s with s = |a| + |b| per axis (the
// largest |x a + y b| over x^2 + y^2 <= z^2), linear in z on each side of 0, so its extremes lie
// at z in {-1, 0, 1} (the circular shapes: the two end centres ± the largest radius). Each is a
// few roundings of numbers no larger than the sum m of the magnitudes involved, so widening by
// m 2^-48 (64 unit roundoffs of m) and then one ulp covers them.
#pragma once

#include "linequad/scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace linequad::detail {

struct BoxBuilder {
    double lo[3], hi[3];
    BoxBuilder() {
        for (int i = 0; i < 3; ++i)
            lo[i] = std::numeric_limits<double>::infinity(), hi[i] = -lo[i];
    }
    // Coordinate i may reach value, computed with roundings of numbers below magnitude.
    void reach(int i, double value, double magnitude) {
        double slack = magnitude * 0x1p-48;
        lo[i] = std::min(lo[i],
                         std::nextafter(value - slack, -std::numeric_limits<double>::infinity()));
        hi[i] =
            std::max(hi[i], std::nextafter(value + slack, std::numeric_limits<double>::infinity()));
    }
    Box box() const { return {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}}; }
};

inline Box everything() {
    double inf = std::numeric_limits<double>::infinity();
    return {{-inf, -inf, -inf}, {inf, inf, inf}};
}

// The circular shapes: the discs of radius r0 at P0 and r1 at P1, and the surface between them.
inline Box circular_box(Vec3 P0, double r0, Vec3 P1, double r1) {
    BoxBuilder b;
    double r = std::max(r0, r1);
    for (int i = 0; i < 3; ++i) {
        double m = std::max(std::fabs(P0[i]), std::fabs(P1[i])) + r;
        for (double p : {P0[i], P1[i]}) {
            b.reach(i, p - r, m);
            b.reach(i, p + r, m);
        }
    }
    return b.box();
}

// P + z c + (x a + y b), x^2 + y^2 <= z^2 (cone) or <= 1 (cylinder: pass unit = true), for z in
// [z0, z1] with z0, z1 in {-1, 0, 1}.
inline Box frame_box(Vec3 P, Vec3 a, Vec3 b, Vec3 c, int z0, int z1, bool unit) {
    BoxBuilder box;
    for (int i = 0; i < 3; ++i) {
        double s = std::fabs(a[i]) + std::fabs(b[i]);
        double m = std::fabs(P[i]) + std::fabs(c[i]) + s;
        for (int z = z0; z <= z1; ++z) {
            double centre = P[i] + z * c[i];
            double spread = unit ? s : std::abs(z) * s;
            box.reach(i, centre - spread, m);
            box.reach(i, centre + spread, m);
        }
    }
    return box.box();
}

inline Box bounds_of(const Cylinder& s) {
    return s.finite ? circular_box(s.C, s.r, s.H, s.r) : everything();
}
inline Box bounds_of(const Frustum& s) {
    return s.finite ? circular_box(s.C0, s.r0, s.C1, s.r1) : everything();
}
inline Box bounds_of(const EllipticCylinder& s) {
    return s.finite ? frame_box(s.C, s.a, s.b, s.c, 0, 1, true) : everything();
}
// c = H - C is rounded here, by at most 2^-53 |c|: the slack, which counts |c|, covers it.
inline Box bounds_of(const EllipticCone& s) {
    if (!s.finite) return everything();
    return frame_box(s.H, s.a, s.b, s.H - s.C, -1, s.nappes == 2 ? 1 : 0, false);
}

// A capsule around a bounded shape: the points within r of the segment from P to P + h. For a
// thin shape across its box (a rod on a diagonal) it is much tighter than the box.
struct Capsule {
    Vec3 P, h;
    double r = 0;
};

// r from |x a + y b| <= |a| + |b| on the unit disc, rounded up (sums of doubles: half an ulp each).
inline double spread_of(Vec3 a, Vec3 b) {
    double up = std::numeric_limits<double>::infinity();
    return std::nextafter(std::nextafter(norm(a), up) + std::nextafter(norm(b), up), up);
}

inline Capsule capsule_of(const Cylinder& s) {
    return {s.C, s.H - s.C, s.r};
}
inline Capsule capsule_of(const Frustum& s) {
    return {s.C0, s.C1 - s.C0, std::max(s.r0, s.r1)};
}
inline Capsule capsule_of(const EllipticCylinder& s) {
    return {s.C, s.c, spread_of(s.a, s.b)};
}
// The cone's nappes reach from H - c (z = -1) to H + c (z = 1) with |z| (|a| + |b|) around the
// axis: within |a| + |b| of the segment.
inline Capsule capsule_of(const EllipticCone& s) {
    Vec3 c = s.H - s.C;
    return s.nappes == 2 ? Capsule{s.H - c, 2 * c, spread_of(s.a, s.b)}
                         : Capsule{s.H - c, c, spread_of(s.a, s.b)};
}

// Whether the line may come within the capsule: false only when it is proven not to. With v
// scaled by a power of two to |v| near 1 (exactly), the squared distance from the line to
// P + s h is |w + s u|^2 / |v|^2 for w = (P - L0) x v and u = h x v; any s in [0, 1] gives at
// least the least distance, and s near the minimiser gives it to within the rounding. The slack,
// 2^-40 of the magnitudes squared, covers that, the errors of P - L0, of the cross products and
// sums (some 2^-48), and those of h and r as the shape's doubles round them. Overflow, and
// magnitudes where underflow could eat the slack, answer "may".
inline bool may_cross(const Capsule& c, const Line& line) {
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
