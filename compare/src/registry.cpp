#include "linequad/registry.hpp"

#include "linequad/exact.hpp"

namespace linequad {

const std::vector<Solver>& all_solvers() {
    static const std::vector<Solver> solvers = [] {
        std::vector<Solver> s = fast_solvers();
        s.push_back(exact::solver());
        return s;
    }();
    return solvers;
}

const Solver* find_solver(std::string_view name) {
    for (const Solver& s : all_solvers())
        if (s.name == name) return &s;
    return nullptr;
}

} // namespace linequad
