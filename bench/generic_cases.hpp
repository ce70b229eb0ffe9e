// Generic benchmark cases: random well-shaped shapes, lines aimed through their middle (so
// most cross twice), reproducible from a seed.
#pragma once

#include "linequad/shapes.hpp"

#include <random>
#include <vector>

namespace linequad::bench {

struct GenericCase {
    Shape shape;
    Line line;
};

inline std::vector<GenericCase> generic_cases(int shape_index, int n, unsigned seed = 1) {
    std::mt19937_64 rng(seed);
    auto real = [&](double lo, double hi) {
        return std::uniform_real_distribution<double>(lo, hi)(rng);
    };
    auto vec = [&](double s) { return Vec3{real(-s, s), real(-s, s), real(-s, s)}; };
    std::vector<GenericCase> out;
    while (int(out.size()) < n) {
        Vec3 C = vec(2), a = vec(2), b = vec(2), c = vec(2);
        if (std::fabs(dot(a, cross(b, c))) < 0.25 * norm(a) * norm(b) * norm(c)) continue;
        Shape s;
        Vec3 middle;
        switch (shape_index) {
        case 0:
            s = Cylinder{C, C + c, real(0.5, 2)}, middle = C + 0.5 * c;
            break;
        case 1:
            s = EllipticCylinder{C, a, b, c}, middle = C + 0.5 * c;
            break;
        default:
            s = EllipticCone{C, C + c, a, b}, middle = C + 0.5 * c;
            break;
        }
        Vec3 from = vec(4);
        out.push_back({s, {from, middle + vec(0.3) - from, Range::line}});
    }
    return out;
}

} // namespace linequad::bench
