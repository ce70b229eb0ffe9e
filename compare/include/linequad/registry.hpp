// Every solver the program knows, fast and exact, by name.
#pragma once

#include "linequad/solvers.hpp"

#include <string_view>
#include <vector>

namespace linequad {

const std::vector<Solver>& all_solvers();
const Solver* find_solver(std::string_view name);

} // namespace linequad
