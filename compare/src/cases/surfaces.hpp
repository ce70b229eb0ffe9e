// The families of the unbounded surfaces (plane, general quadric): exact constructions on small
// integers. A quadric of each kind is built in local coordinates y = R^T (x - O), R an integer
// rotation times N (R R^T = N I) or the identity, as f = y^T M y + g . y + k with M diagonal,
// and a point P = O + R x0 on it (k chosen so that f(P) = 0); expanded into the ten GQ
// coefficients, every one an integer (exact). Lines pass through P (or beside it by 2^-k along
// the gradient there, an integer vector), so the oracle's answers are known in advance.
#pragma once

#include "cases/case_maker.hpp"

#include <array>
#include <cmath>

namespace linequad::surfaces {

// Every kind of quadric, nondegenerate first; `plane` is a plane written in GQ form.
enum class Kind {
    ellipsoid,
    one_sheet,
    two_sheets,
    cone,
    elliptic_paraboloid,
    hyperbolic_paraboloid,
    cylinder,
    plane_pair,
    parallel_planes,
    line,
    point,
    empty,
    plane
};
constexpr int nondegenerate_kinds = 7, kind_count = 13;

// A quadric in world coordinates, its point P on the surface (O for `empty`, where none is), the
// gradient n at P (an integer vector; 0 at a singular point) and its centre or apex O.
struct Built {
    Quadric q;
    Vec3 P, n, O, axis; // axis: R e_z (a cylinder's or a paraboloid's axis, a cone's)
};

Built build(Kind kind, Rng& r, bool rotate, int thin = 0);

// A nonzero integer direction with coordinates in [-3, 3].
Vec3 direction(Rng& r);

// The quadric's cases: which families apply and each family's lines.
bool quadric_applies(Family f);
Case quadric_case(Family f, Rng& r, int k, Frames frames, Precision p);
bool plane_applies(Family f);
Case plane_case(Family f, Rng& r, int k, Precision p);

} // namespace linequad::surfaces
