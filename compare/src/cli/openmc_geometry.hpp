// OpenMC's geometry.xml, read (with pugixml, as OpenMC reads it) into a model file's parts, each
// surface posed exactly as OpenMC defines it from its doubles, or refused by name.
#pragma once

#include "linequad/case_io.hpp"

#include <string>
#include <string_view>

namespace linequad::cli {

// Whether this linequad was built with pugixml (Debian libpugixml-dev).
bool openmc_geometry_available();

// The root universe's surfaces and cells, the universes that fill its cells flattened into them.
// Surface types plane, x-/y-/z-plane, sphere, x-/y-/z-cylinder, x-/y-/z-cone and quadric, with
// OpenMC's coefficients: the sphere and the cylinders by centre and radius (linequad/cells.hpp),
// the cones expanded into the general quadric's ten coefficients and posed only where every one
// of them is a double exactly (otherwise refused, naming the surface, its line and the
// coefficient: linequad does not round a surface). Anything else (a torus, a lattice, a universe
// placed twice, a transformed cell) is refused naming the element and its line; so is malformed
// XML. Boundary conditions are ignored: they do not change the geometry.
bool parse_openmc_geometry(std::string_view xml, ModelFile* out, std::string* why);

} // namespace linequad::cli
