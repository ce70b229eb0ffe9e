// Line against an elliptic cone, apex H, base centre C, x^2 + y^2 = z^2, z <= 0 (seed 002).
#pragma once

#include "linequad/result.hpp"
#include "linequad/shapes.hpp"

namespace linequad {
namespace seed {
// As seed 002 writes it, with its own equation (erratum 1): M = T R S inverted, the textbook roots;
// errata fixed, nothing improved.
Result intersect(const EllipticCone& s, const Line& l, Query q = {});
} // namespace seed
namespace stable {
// Same geometry without cancellation: see the derivation at the top of src/elliptic_cone.cpp.
Result intersect(const EllipticCone& s, const Line& l, Query q = {});
} // namespace stable
namespace certified {
// Stable's geometry with a rigorous bound on every quantity: each hit carries a bound on its t
// error and is certain or marked uncertain; the classification is never wrong when certain.
Result intersect(const EllipticCone& s, const Line& l, Query q = {});
} // namespace certified
namespace correct {
// The exact classification, with t and points correctly rounded (the oracle's answer, bit for
// bit): double-double with proven bounds, exact arithmetic when they do not settle it.
Result intersect(const EllipticCone& s, const Line& l, Query q = {});
} // namespace correct
} // namespace linequad
