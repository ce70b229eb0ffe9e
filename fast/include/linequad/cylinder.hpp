// Line against a finite or infinite right circular cylinder (seed 001).
#pragma once

#include "linequad/result.hpp"
#include "linequad/shapes.hpp"

namespace linequad {
namespace seed {
// As seed 001 writes it: normalised axis, the textbook roots; errata fixed, nothing improved.
Result intersect(const Cylinder& s, const Line& l, Query q = {});
} // namespace seed
namespace stable {
// Same geometry without cancellation: see the derivation at the top of src/cylinder.cpp.
Result intersect(const Cylinder& s, const Line& l, Query q = {});
} // namespace stable
namespace certified {
// Stable's geometry with a rigorous bound on every quantity: each hit carries a bound on its t
// error and is certain or marked uncertain; the classification is never wrong when certain.
Result intersect(const Cylinder& s, const Line& l, Query q = {});
} // namespace certified
namespace correct {
// The exact classification, with t and points correctly rounded (the oracle's answer, bit for
// bit): double-double with proven bounds, exact arithmetic when they do not settle it.
Result intersect(const Cylinder& s, const Line& l, Query q = {});
} // namespace correct
} // namespace linequad
