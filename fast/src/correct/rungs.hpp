// The correct solver's second and third rungs (rungs.cpp). Both take the exact form of a shape's
// derivation (shapes/exact_form.hpp), instantiated in their number types.
#pragma once

#include "correct/ladder.hpp"
#include "numeric/big_float.hpp"
#include "numeric/bounded_dd.hpp"
#include "shapes/exact_form.hpp"

namespace linequad::detail {

// The quadratic of the scaled scene u in bounded double-double: the answer in r (hits, t and
// points correctly rounded), or false when its bounds do not settle it (r is then left partly
// written).
bool double_double_rung(const exact_form::LineQuadratic<BoundedDD>& q, const Unit& u, Query query,
                        Result& r);

// The quadratic of the line as given, exactly: always the answer.
Result exact_rung(const exact_form::LineQuadratic<BigFloat>& q, const Line& l, Query query);

} // namespace linequad::detail
