// The correct solver's first rung: a double estimate of each root, refined by one Newton step
// whose residual is evaluated in double-double, with a proven enclosure of the exact root.
//
// The division-free quadratic of each shape (its exact form) is a sum of squares of linear
// functions of t, minus a constant:
//     g(t) = A t^2 + 2 B t + C0 = sum_k sigma_k u_k(t)^2 - K,   u(t) = U0 + t U1,
// each shape's line_form() (shapes/*.hpp, correct/line_form.hpp) gives U0, U1 and K in
// double-double with a bound. Then, at a point c near a root,
// g(c + x) = A x^2 + G' x + G holds exactly, with G = g(c) in double-double and G', A in double,
// each with a bound. When y = 4 A G / G'^2 is at most 1/2 in magnitude, there is a root at
// c + x* with x* = (-G / G') 2 / (1 + sqrt(1 - y)), within |x0| 0.35 |y| of x0 = -G / G':
// existence, a simple root, which of the two roots it is (the other is at -G'/A - x*), and an
// enclosure about 2^-100 |t| wide, from one evaluation (narrower about x0 phi(y) where a root
// needs it: newton_steps.hpp). The extent, the range, t and the points
// are then decided on the enclosure; whatever the bounds leave open goes to the next rung.
// The arithmetic is written once, over the number type (newton_steps.hpp): newton_rung.cpp
// branches on its proofs for one line, the batch kernels (simd/correct_lanes.hpp) combine them as
// lane masks.
#pragma once

#include "correct/ladder.hpp"
#include "correct/newton_steps.hpp"
#include "forms/line_form.hpp"

#include "linequad/result.hpp"

#include <array>
#include <optional>

namespace linequad::detail {

// How g is evaluated near each estimate: in double-double from the line form (the double
// target's rung), or in double from the quick line form, whose bounds are some 2^50 wider but
// still leave a float rounding proven nearly always (correct32's first rung).
enum class Residual { double_double, quick };

// Where the line crosses the plane of one end of the extent, Z = end, at t_E = (end - Z0) / dZ:
// what the rung asks when its bounds leave a lateral root next to that end (a rim, or a root a
// few ulps from it). The signs are exact; t_E is rational, enclosed in double-double.
struct EndCrossing {
    int q_sign;  // sgn q(t_E): -1 inside the quadric, 0 on it (t_E is a root), 1 outside
    int A_sign;  // sgn of q's leading coefficient: t_E lies between the roots iff q_sign != A_sign
    int dZ_sign; // sgn dZ
    bool open; // the end belongs to another part (a capsule side's seam): a root there is not kept
    BoundedDD t; // t_E, in the rung's units
};
// g's local quadratic at a point c, g(c + x) = A x^2 + G' x + G, from the exact form: G, G' and A
// each formed exactly, then enclosed, or enclosed by a shape's cheaper form (a multiple of the line
// form's g: the same roots).
struct ExactLocal {
    newton::Leading<double> A;
    newton::Local<double> at;
};

// The signs of g and g' (twice B + A t) at a point, exactly, and of A.
struct SignsAt {
    int g, slope, A;
};
// g = 2 B (t - t*) along the line: its root t* and B's sign (g < 0, inside the quadric, before the
// root where B > 0, after it where B < 0).
struct LinearRoot {
    BoundedDD t;
    int B_sign;
};

// The ladder's answers to what the rung's bounds leave open, exactly, from the exact form (the
// exact rung's, formed once and only when asked).
class ExtentEnds {
  public:
    // An end's crossing; no value where the end is not bounded.
    virtual std::optional<EndCrossing> at(bool top, double t_factor) const = 0;
    // Where the bounds cannot tell A from 0: when g is constant along the line (A = B = 0), the
    // sign of C0 (-1 inside the quadric, 0 on it, 1 outside); no value where it is not. `at_0`:
    // the rung's own g(0), within e_at_0 (g's scale is the rung's, its sign the same), which
    // decides that sign but on the surface.
    virtual std::optional<int> constant_sign(double at_0, double e_at_0) const = 0;
    // Where the bounds cannot tell dZ from 0 on a closed shape: when Z is constant along the line
    // (dZ = 0), Z0's level: -2 below the extent, -1 in the base's plane (the line in that disc's
    // plane), 0 strictly within, 1 in the top's plane, 2 above; no value where dZ != 0, or where
    // the line lies in the plane of an end with no disc.
    virtual std::optional<int> constant_z() const = 0;
    // Where the bounds prove no simple root and A > 0: whether g has a double root (B^2 - A C0
    // = 0 exactly: a tangency); none where it cannot be decided.
    virtual std::optional<bool> tangency() const = 0;
    // That double root -B/A (where tangency() showed one) enclosed from the exact form, in the
    // rung's units: where the rung's own enclosure of it is too wide.
    virtual std::optional<BoundedDD> double_root(double t_factor) const = 0;
    // sgn(Z(-B/A) - end), Z at the vertex against the top's or the base's level, exactly (at a
    // double root, the tangency's side of that end); none where that end is not bounded or A = 0.
    virtual std::optional<int> vertex_against(bool top) const = 0;
    // g, g' and A's signs at t = m, m = near + half exactly, in the caller's units: for a root
    // whose enclosure holds the rounding boundary m (a tie, or a few ulps beside one).
    virtual SignsAt signs_at(double near, double half) const = 0;
    // Whether that end belongs to another part (a capsule side's seam): a root there is not kept.
    virtual bool end_open(bool top) const = 0;
    // Where the bounds cannot tell A from 0 and g is not constant: when g is linear along the
    // line (A = 0, B != 0: a line parallel to a cone's generator, off the cone), its one root
    // -C0 / 2B enclosed, in the rung's units, and the sign of B.
    virtual std::optional<LinearRoot> linear_root(double t_factor) const = 0;
    // Where a root or a point's coordinate lies a few ulps from zero (a line starting on or
    // beside the surface, or a disc's plane; a hit beside a coordinate plane), the rung's bounds,
    // absolute, are wide beside it; the exact form's values are not. g's local quadratic at c,
    // and an end's crossing t_E, in the rung's units, from the exact form (a filter's bounds are
    // as wide as the rung's). g's local quadratic `exactly`, or else from the shape's cheaper
    // form of it where it has one (a sphere's: C0 exact, the rest in double-double), or none.
    virtual std::optional<ExactLocal> local_at(double c, double t_factor, bool exactly) const = 0;
    virtual std::optional<BoundedDD> crossing(bool top, double t_factor) const = 0;
    // The planes of the extent's ends in double-double (DiscPlanes, without discs) for a shape
    // whose form carries none, an open one: its Z in double leaves a root a few ulps from an end
    // open, the planes place it against that end's crossing. For the scene as given (`unit`'s
    // factors 1) only; none where the shape has no bounded end.
    virtual const DiscPlanes* end_planes(const Unit& unit) const = 0;
    // Coordinate k of the point where the line crosses an end's plane, (L0_k dZ + v_k (end - Z0))
    // / dZ formed exactly, then enclosed (an exact zero is 0), in the caller's units: for a hit
    // there whose coordinate lies a few ulps from zero, or at zero; none where the end is not
    // bounded or dZ = 0.
    virtual std::optional<BoundedDD> coordinate_at_end(bool top, int k) const = 0;
    // Whether t* = -L0_k / v_k is a root of g, exactly (g(t*) v_k^2 = A L0_k^2 - 2 B L0_k v_k +
    // C0 v_k^2 = 0): the line meets the surface on the plane of coordinate k = 0 there.
    virtual bool zero_at_root(int k) const = 0;
    // Coordinate k at either root: P = L0_k + t v_k is a root of A P^2 + 2 (B v_k - A L0_k) P +
    // (A L0_k^2 - 2 B L0_k v_k + C0 v_k^2) = 0 (t = (P - L0_k) / v_k put in g, times v_k^2), whose
    // discriminant is v_k^2 D. Its two roots from its exact coefficients, each enclosed relative
    // to itself, in the caller's units: for a lateral hit a few ulps from a coordinate plane,
    // where L0_k + t v_k cancels and t's bound cannot round it. None where A = 0, D < 0 or
    // v_k = 0.
    virtual std::optional<std::array<BoundedDD, 2>> coordinate_roots(int k) const = 0;
    // sgn(P - m), m = near + half exactly, for coordinate k at one root of its quadratic
    // (coordinate_roots), the other root P' on side sgn(m - P') = other_side of m (proven by the
    // caller); or at an end's crossing (coordinate_at_end). Where its enclosure holds a rounding
    // boundary m, the midpoint of two Target values (a tie, or a few ulps beside one), which no
    // enclosure decides.
    virtual std::optional<int> coordinate_root_against(int k, int other_side, double near,
                                                       double half) const = 0;
    virtual std::optional<int> coordinate_at_end_against(bool top, int k, double near,
                                                         double half) const = 0;

  protected:
    ~ExtentEnds() = default;
};

// The answer to `query` in r (hits, t and points correctly rounded to Target, Binary64 or
// Binary32, r.count set) when every decision and every rounding is proven; false otherwise, with
// r to be discarded. `caller` is the line as given, u the scaled scene. Where a root's bounds
// leave its side of an extent's end open, `ends` (when given) decides it exactly.
template <class Target, Residual R = Residual::double_double>
bool newton_rung(const LineForm& f, const Unit& u, const Line& caller, Query query, Result& r,
                 const ExtentEnds* ends = nullptr);

// The same proof for a surface without extent, from its own local quadratic at any point (a
// quadric's: shapes/quadric.hpp) rather than a line form; u's factors 1 (the scene as given).
// False where a bound leaves anything open (a tangency, a root at the range's end).
template <class R>
class QuadricNewtonFormT;
using QuadricNewtonForm = QuadricNewtonFormT<double>;
template <class Target>
bool surface_newton_rung(const QuadricNewtonForm& f, const Unit& u, const Line& caller, Query query,
                         Result& r, const ExtentEnds* ends);

// The hit test (Need::any) on a quick line form (the shape's quick_line_form: doubles with
// bounds) of a scene as given (u's factors 1): the same proof, from G in double. When it proves
// a root inside the extent and the range, r holds that one hit, certain, its t the enclosure's
// midpoint with the enclosure's half-width as bound (not rounded: a hit test does not pay for
// it); when it proves there is none, r holds no hit; false otherwise.
bool hit_test_rung(const LineForm& f, const Unit& u, Result& r);

// The hit test's last step on a convex shape closed by discs, for the batch lanes, which prove
// the lateral roots' enclosures exactly as the rung does (newton_steps.hpp) and close here, one
// lane at a time, a line none of whose roots they proved a hit: `f` needs only the axial line
// and the extent; A is g's leading coefficient (proven nonzero); the roots as the hit test
// estimated them. As hit_test_rung answers.
bool closed_hit_test(const LineForm& f, double A, const newton::Enclosure<double> (&roots)[2],
                     bool both_outside, const Unit& u, Result& r);

} // namespace linequad::detail
