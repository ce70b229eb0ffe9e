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
} // namespace linequad
