// The inputs every solver shares: a line over a range, and the three shapes of the seeds.
#pragma once

#include "linequad/vec3.hpp"

#include <variant>

namespace linequad {

// Which part of L(t) = L0 + t v is asked about.
enum class Range { line, ray, segment }; // all t; t >= 0; 0 <= t <= 1

struct Line {
    Vec3 L0;
    Vec3 v;
    Range range = Range::line;
};

// Seed 001: the right circular cylinder of radius r around the axis from C to H.
// Finite: only the lateral surface between the planes through C and H (no caps).
struct Cylinder {
    Vec3 C, H;
    double r = 0;
    bool finite = true;
};

// Seed 000: points C + x a + y b + z c with x^2 + y^2 = 1; finite keeps 0 <= z <= 1.
// a, b, c may be any linearly independent vectors (oblique and sheared frames included).
struct EllipticCylinder {
    Vec3 C, a, b, c;
    bool finite = true;
};

// Seed 002: base centre C, apex H, c = H - C; points H + x a + y b + z c with x^2 + y^2 = z^2.
// Only the nappe z <= 0 (towards the base); finite keeps -1 <= z <= 0.
struct EllipticCone {
    Vec3 C, H, a, b;
    bool finite = true;
    Vec3 c() const { return H - C; }
};

using Shape = std::variant<Cylinder, EllipticCylinder, EllipticCone>;

const char* shape_name(const Shape& s);
const char* range_name(Range r);

} // namespace linequad
