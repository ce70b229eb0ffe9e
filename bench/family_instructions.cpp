// Solves one family's audit cases with one solver, for counting instructions under callgrind:
// bench/family_instructions.sh runs it with the solves and without, and divides the difference by
// the number of cases (printed on standard error).
//   linequad_family_instructions SOLVER FAMILY CASES SEED SOLVE [SHAPE]
//   (SOLVE: 1, or 0 for none; SHAPE: that shape's cases only, as audit --shapes names it)
//   linequad_family_instructions --families                          (their names, one a line)
#include "linequad/audit.hpp"
#include "linequad/exact.hpp"
#include "linequad/families.hpp"
#include "linequad/linequad.hpp"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

volatile double sink;

int usage() {
    std::fputs("usage: linequad_family_instructions SOLVER FAMILY CASES SEED 0|1 [SHAPE]\n",
               stderr);
    return 2;
}

} // namespace

int main(int argc, char** argv) {
    using namespace linequad;
    if (argc == 2 && std::string(argv[1]) == "--families") {
        for (int f = 0; f < family_count; ++f)
            std::puts(family_name(Family(f)));
        return 0;
    }
    if (argc != 6 && argc != 7) return usage();
    const Solver* solver = nullptr;
    for (const Solver& s : fast_solvers())
        if (s.name == argv[1]) solver = &s;
    if (exact::solver().name == argv[1]) solver = &exact::solver(); // the oracle
    audit::Options o;
    Family family;
    if (!solver || !parse_family(argv[2], &family)) return usage();
    o.families = {family};
    if (argc == 7) {
        int shape = shape_named(argv[6]);
        if (shape < 0) return usage();
        o.shapes = {shape};
    }
    o.cases_per_group = std::strtoull(argv[3], nullptr, 10);
    o.seed = std::strtoull(argv[4], nullptr, 10);
    o.precision = solver->precision;
    std::vector<Case> cases;
    audit::for_each_case(o, [&](const Case& c) { cases.push_back(c); });
    double hits = 0;
    if (std::atoi(argv[5]) != 0)
        for (const Case& c : cases)
            hits += (*solver)(c.shape, c.line).count;
    sink = hits;
    std::fprintf(stderr, "%zu\n", cases.size());
    return 0;
}
