// The input checks every solver applies first (fast and exact alike): NaN and infinite
// coordinates, v = 0, r <= 0, H = C, and singular frames (decided exactly, by expansions).
#pragma once

#include "linequad/result.hpp"
#include "linequad/shapes.hpp"

namespace linequad {

Error validate(const Cylinder& s, const Line& l);
Error validate(const EllipticCylinder& s, const Line& l);
Error validate(const EllipticCone& s, const Line& l);
Error validate(const Shape& s, const Line& l);

} // namespace linequad
