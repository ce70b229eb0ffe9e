// The correct solver's second and third rungs (rungs.cpp). Both take the exact form of a shape's
// derivation (shapes/exact_form.hpp), instantiated in their number types.
#pragma once

#include "correct/ladder.hpp"
#include "forms/exact_form.hpp"
#include "numeric/big_float.hpp"
#include "numeric/bounded_dd.hpp"

namespace linequad::detail {

// The quadratic of the scaled scene u in bounded double-double: the answer in r (hits, t and
// points correctly rounded to Target, Binary64 or Binary32), or false when its bounds do not
// settle it (r is then left partly written).
// given_D: an enclosure of B^2 - A C0 from its exact value (the exact rung's filter).
template <class Target>
bool double_double_rung(const exact_form::LineQuadratic<BoundedDD>& q, const Unit& u, Query query,
                        Result& r, const BoundedDD* given_D = nullptr);

// (X + Y sqrt(D)) / Den rounded to the nearest value of Target (Binary64 or Binary32, held in a
// double), ties to even, infinite beyond its range, +0 for an exact zero: decided exactly.
template <class Target>
double round_exact(const BigFloat& X, const BigFloat& Y, const BigFloat& D, const BigFloat& Den);

// The quadratic of the line as given, exactly, and its D = B^2 - A C0: always the answer,
// rounded to Target. With `filter_first` (no exact zero is known), the coefficients and D are
// first enclosed in double-double and classified there: the exact classification only where
// those bounds cannot decide.
template <class Target>
Result exact_rung(const exact_form::LineQuadratic<BigFloat>& q, const BigFloat& D, const Line& l,
                  Query query, bool filter_first);

} // namespace linequad::detail
