// The invariants every solver's result must satisfy on any input, checked against the oracle.
// Shared by the libFuzzer target and the regression tests of what it found.
#pragma once

#include "linequad/case_io.hpp"

#include <string>

namespace linequad {

// "" when every invariant holds; otherwise what broke, for which solver, with the case and
// result lines. See the list at the top of src/invariants.cpp.
std::string broken_invariant(const Case& c);

// Whether every t, point and interval end of r is a float (what a float solver must answer).
bool answered_in_floats(const Result& r);

} // namespace linequad
