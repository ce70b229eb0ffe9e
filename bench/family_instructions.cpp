// Solves one family's audit cases with one solver, for counting instructions under callgrind:
// bench/family_instructions.sh runs it with the solves and without, and divides the difference by
// the number of cases (printed on standard error). With `by-k` it times each case warm instead
// (the fastest of 5 runs of 16 solves) and prints the times by the family's difficulty k: where
// in a family a solver's time goes, which the audit's medians over chunks of cases cannot show.
//   linequad_family_instructions SOLVER FAMILY CASES SEED SOLVE [SHAPE]
//   (SOLVE: 1, 0 for none, or by-k; SHAPE: that shape's cases only, as audit --shapes names it)
//   linequad_family_instructions --families                          (their names, one a line)
#include "linequad/audit.hpp"
#include "linequad/exact.hpp"
#include "linequad/families.hpp"
#include "linequad/linequad.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace {

volatile double sink;

int usage() {
    std::fputs("usage: linequad_family_instructions SOLVER FAMILY CASES SEED 0|1|by-k [SHAPE]\n",
               stderr);
    return 2;
}

// ns per solve of each case warm (caches and branch predictors trained on that case alone: a
// floor, below what the audit's run through mixed cases sees), grouped by k.
void print_by_k(const linequad::Solver& solver, const std::vector<linequad::Case>& cases) {
    using Clock = std::chrono::steady_clock;
    constexpr int runs = 5, solves = 16;
    std::map<int, std::vector<double>> by_k;
    double hits = 0;
    for (const linequad::Case& c : cases) {
        double fastest = 0;
        for (int run = 0; run < runs; ++run) {
            auto t0 = Clock::now();
            for (int i = 0; i < solves; ++i)
                hits += solver(c.shape, c.line).count;
            double ns = std::chrono::duration<double, std::nano>(Clock::now() - t0).count();
            fastest = run == 0 ? ns : std::min(fastest, ns);
        }
        by_k[c.k].push_back(fastest / solves);
    }
    sink = hits;
    std::printf("%4s %6s %8s %8s %8s %8s\n", "k", "cases", "mean", "median", "p90", "max");
    std::vector<double> all;
    auto row = [](const char* k, std::vector<double>& ns) {
        std::sort(ns.begin(), ns.end());
        double sum = 0;
        for (double x : ns)
            sum += x;
        std::printf("%4s %6zu %8.0f %8.0f %8.0f %8.0f\n", k, ns.size(), sum / ns.size(),
                    ns[ns.size() / 2], ns[ns.size() * 9 / 10], ns.back());
    };
    for (auto& [k, ns] : by_k) {
        all.insert(all.end(), ns.begin(), ns.end());
        row(std::to_string(k).c_str(), ns);
    }
    if (!all.empty()) row("all", all);
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
    if (std::string(argv[5]) == "by-k") {
        print_by_k(*solver, cases);
        return 0;
    }
    double hits = 0;
    if (std::atoi(argv[5]) != 0)
        for (const Case& c : cases)
            hits += (*solver)(c.shape, c.line).count;
    sink = hits;
    std::fprintf(stderr, "%zu\n", cases.size());
    return 0;
}
