// The correct solver's first rung: a double estimate of each root, refined by one Newton step
// whose residual is evaluated in double-double, with a proven enclosure of the exact root.
//
// The division-free quadratic of each shape (line_quadratic.hpp) is a sum of squares of linear
// functions of t, minus a constant:
//     g(t) = A t^2 + 2 B t + C0 = sum_k sigma_k u_k(t)^2 - K,   u(t) = U0 + t U1,
//   circular cylinder (seed 001): U0 = w x h, U1 = v x h, sigma = (1, 1, 1), K = r^2 (h.h),
//       by Lagrange's identity (cylinder.cpp); w = L0 - C, h = H - C;
//   elliptic cylinder (seed 000): U0 = adj(M) (L0 - C), U1 = adj(M) v, sigma = (1, 1, 0),
//       K = det(M)^2: the exact form's W and V;
//   elliptic cone (seed 002): U0 = adj(M) (L0 - H), U1 = adj(M) v, sigma = (1, 1, -1), K = 0.
// U0, U1 and K are computed once in double-double with a bound. Then, at a point c near a root,
// g(c + x) = A x^2 + G' x + G holds exactly, with G = g(c) in double-double and G', A in double,
// each with a bound. When y = 4 A G / G'^2 is at most 1/2 in magnitude, there is a root at
// c + x* with x* = (-G / G') 2 / (1 + sqrt(1 - y)), within |x0| 0.35 |y| of x0 = -G / G':
// existence, a simple root, which of the two roots it is (the other is at -G'/A - x*), and an
// enclosure about 2^-100 |t| wide, from one evaluation. The extent, the range, t and the points
// are then decided on the enclosure; whatever the bounds leave open goes to the next rung.
#pragma once

#include "bounded_dd.hpp"
#include "ladder.hpp"

#include "linequad/result.hpp"
#include "linequad/shapes.hpp"

namespace linequad::detail {

// g(t) = sum_k sigma_k (U0_k + t U1_k)^2 - K, and the axial coordinate Z(t) = Z0 + t dZ that the
// extent lo <= Z <= hi bounds (the exact form's Z0, dZ, lo, hi). Every value carries a bound:
// the BoundedDD ones in e, the doubles in the e_ fields.
struct LineForm {
    BoundedDD U0[3], U1[3], K;
    int sigma_z; // sigma = (1, 1, sigma_z)
    double Z0, e_Z0, dZ, e_dZ;
    double lo, e_lo, hi, e_hi;
    bool lo_bounded, hi_bounded;
};

// Each for the scene the ladder gives (correct.cpp): as given when of moderate size, else scaled
// to unit size (ladder.hpp). negative_det: det(M) < 0, decided exactly by validation.
LineForm line_form(const Cylinder& s, const Line& l);
LineForm line_form(const EllipticCylinder& s, const Line& l, bool negative_det);
LineForm line_form(const EllipticCone& s, const Line& l, bool negative_det);

// The answer to `query` in r (hits, t and points correctly rounded, r.count set) when every
// decision and every rounding is proven; false otherwise, with r to be discarded. `caller` is
// the line as given, u the scaled scene.
bool newton_rung(const LineForm& f, const Unit& u, const Line& caller, Query query, Result& r);

} // namespace linequad::detail
