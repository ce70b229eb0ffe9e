// What a shape's bounds are made of (each shape's ShapeTraits<S>::bounds and ::bounding_capsule,
// shapes/*.hpp): an axis-aligned box rounded outward, which holds every point of the surface
// (caps included) however the doubles below round, and a capsule around a thin shape.
//
// Every bound is a coordinate of the form P + z c +- |z| s with s = |a| + |b| per axis (the
// largest |x a + y b| over x^2 + y^2 <= z^2), linear in z on each side of 0, so its extremes lie
// at z in {-1, 0, 1} (the circular shapes: the two end centres +- the largest radius). Each is a
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

// A capsule around a bounded shape, for culling: the points within r of the segment from P to
// P + h. For a thin shape across its box (a rod on a diagonal) it is much tighter than the box.
struct BoundingCapsule {
    Vec3 P, h;
    double r = 0;
};

// r from |x a + y b| <= |a| + |b| on the unit disc, rounded up (sums of doubles: half an ulp each).
inline double spread_of(Vec3 a, Vec3 b) {
    double up = std::numeric_limits<double>::infinity();
    return std::nextafter(std::nextafter(norm(a), up) + std::nextafter(norm(b), up), up);
}

} // namespace linequad::detail
