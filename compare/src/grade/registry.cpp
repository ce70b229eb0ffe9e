#include "linequad/registry.hpp"

#include "linequad/case_io.hpp"
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

Result answer(const Solver& s, const Case& c, Query q) {
    if (s.name == exact::solver().name) return exact::intersect(c.shape, c.line, q, c.precision);
    return s(c.shape, c.line, q);
}

} // namespace linequad
