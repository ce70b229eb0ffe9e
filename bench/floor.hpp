// The floor the instruction counts are quoted against: the textbook cylinder quadratic, as a
// renderer would write it with no guard at all. h = H - C, w = L0 - C, six dot products, A, B,
// C0, the discriminant, both roots by division, both axial coordinates, the extent test and both
// points; no validation, no special case. It is wrong near tangency and along the axis; it is
// here only as the unit of cost.
#pragma once

#include "linequad/vec3.hpp"

#include <cmath>

namespace linequad::bench {

struct FloorCase {
    Vec3 C, H;
    double r;
    Vec3 L0, v;
};

struct FloorHits {
    int count;
    double t[2];
    Vec3 p[2];
};

// Out of line: the loop that calls it must not fold the cases' arithmetic across iterations.
[[gnu::noinline]] inline FloorHits textbook_cylinder(const FloorCase& c) {
    Vec3 h = c.H - c.C, w = c.L0 - c.C;
    double hh = dot(h, h), vh = dot(c.v, h), wh = dot(w, h);
    double vv = dot(c.v, c.v), vw = dot(c.v, w), ww = dot(w, w);
    double A = vv * hh - vh * vh, B = vw * hh - vh * wh, C0 = (ww - c.r * c.r) * hh - wh * wh;
    double disc = B * B - A * C0;
    FloorHits out{0, {0, 0}, {}};
    if (disc < 0) return out;
    double sq = std::sqrt(disc);
    double t[2] = {(-B - sq) / A, (-B + sq) / A};
    for (double ti : t) {
        double z = wh + ti * vh; // (P - C) . h
        if (z >= 0 && z <= hh) {
            out.t[out.count] = ti;
            out.p[out.count] = c.L0 + ti * c.v;
            ++out.count;
        }
    }
    return out;
}

} // namespace linequad::bench
