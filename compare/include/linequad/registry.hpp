// Every solver the program knows, fast and exact, by name.
#pragma once

#include "linequad/solvers.hpp"

#include <string_view>
#include <vector>

namespace linequad {

const std::vector<Solver>& all_solvers();
const Solver* find_solver(std::string_view name);

struct Case;
// s's answer to a case. The oracle answers in the case's precision (a binary32 case in floats);
// every other solver in its own.
Result answer(const Solver& s, const Case& c, Query q = {});

} // namespace linequad
