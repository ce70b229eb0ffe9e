// The elliptic seeds' own construction, kept literally for the seed solvers: M = T R S with R
// built from the normalised axes and S from their lengths, inverted as a general 4x4 matrix by
// Eigen, and applied to the line by Eigen (which fuses products: another order would round
// otherwise), in double (seed) or float (seed32). The only code that uses Eigen.
#pragma once

#include "forms/prescale.hpp"

#include "linequad/shapes.hpp"

namespace linequad::detail {

// (T R S)^-1 in R, column-major as Eigen stores it; the frame's coordinates are R's values.
template <class R>
void seed_inverse_frame(Vec3 origin, Vec3 a, Vec3 b, Vec3 c, R (&inverse)[16]);

// The line in the unit shape's frame: the point as a point, the direction as a vector, with
// homogeneous coordinate 0 (erratum 2).
template <class R>
void to_seed_frame(const R (&inverse)[16], const Line& l, Vec3T<R>& w, Vec3T<R>& v);

// The same for the frame (origin, a, b, c) of a shape as a solver sees it: with the inverse
// prepare() kept (in double), or with one built now.
template <class R, class Source>
void to_seed_frame(const Source& src, Vec3 origin, Vec3 a, Vec3 b, Vec3 c, const Line& l,
                   Vec3T<R>& w, Vec3T<R>& v) {
    if constexpr (Source::prepared && in_double<R>) {
        to_seed_frame(src.facts.seed_inverse, l, w, v);
    } else {
        R inverse[16];
        seed_inverse_frame(origin, a, b, c, inverse);
        to_seed_frame(inverse, l, w, v);
    }
}

} // namespace linequad::detail
