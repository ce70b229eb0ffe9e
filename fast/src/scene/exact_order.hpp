// The exact order of hits on different shapes along one line: each hit's root as the correct
// solver's exact rung finds it, t = (N + S sqrt(D)) / Den in exact big-float arithmetic, and two
// such roots compared exactly. A correct scene decides with it only the hits whose correctly
// rounded t is the same double; any others are ordered by their t already.
#pragma once

#include "forms/exact_form.hpp"
#include "numeric/big_float.hpp"

#include "linequad/prepared.hpp"

namespace linequad::detail {

// Every root of the shape on the line within its range, in increasing t, as the exact rung finds
// them (a shape's correct hits for Need::all are these, rounded, in this order), each with the D
// of its quadratic (a shape made of patches has one per patch); or the on-surface interval.
struct ExactRoots {
    exact_form::Outcome outcome = exact_form::Outcome::none;
    int count = 0;
    exact_form::SurdRoot<BigFloat> roots[max_hits];
    BigFloat D[max_hits];
    exact_form::Fraction<BigFloat> s0; // on_surface: the interval's first end
    BigFloat s0_D;
};
template <class S>
ExactRoots exact_roots(const Prepared<S>& p, const Line& l);

// sign(t_a - t_b) for t_a = (a.N + a.S sqrt(Da)) / a.Den and t_b likewise.
int compare_roots(const exact_form::SurdRoot<BigFloat>& a, const BigFloat& Da,
                  const exact_form::SurdRoot<BigFloat>& b, const BigFloat& Db);

} // namespace linequad::detail
