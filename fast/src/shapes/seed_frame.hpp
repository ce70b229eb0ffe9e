// The elliptic seeds' own construction, kept literally for the seed solvers: M = T R S with R
// built from the normalised axes and S from their lengths, inverted as a general 4x4 matrix by
// Eigen, and applied to the line by Eigen (which fuses products: another order would round
// otherwise). The only code that uses Eigen.
#pragma once

#include "linequad/shapes.hpp"

namespace linequad::detail {

// (T R S)^-1, column-major as Eigen stores it.
void seed_inverse_frame(Vec3 origin, Vec3 a, Vec3 b, Vec3 c, double (&inverse)[16]);

// The line in the unit shape's frame: the point as a point, the direction as a vector, with
// homogeneous coordinate 0 (erratum 2).
void to_seed_frame(const double (&inverse)[16], const Line& l, Vec3& w, Vec3& v);

// The same for the frame (origin, a, b, c) of a shape as a solver sees it: with the inverse
// prepare() kept, or with one built now.
template <class Src>
void to_seed_frame(const Src& src, Vec3 origin, Vec3 a, Vec3 b, Vec3 c, const Line& l, Vec3& w,
                   Vec3& v) {
    if constexpr (Src::prepared) {
        to_seed_frame(src.facts.seed_inverse, l, w, v);
    } else {
        double inverse[16];
        seed_inverse_frame(origin, a, b, c, inverse);
        to_seed_frame(inverse, l, w, v);
    }
}

} // namespace linequad::detail
