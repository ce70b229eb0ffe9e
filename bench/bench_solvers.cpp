// ns per solve for shape x solver, on generic cases. Run:
//   build/bench/linequad_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include "generic_cases.hpp"

#include "linequad/exact.hpp"
#include "linequad/solvers.hpp"

#include <benchmark/benchmark.h>

namespace {

using namespace linequad;

const char* const shape_names[] = {"cylinder", "elliptic_cylinder", "elliptic_cone"};

void solve(benchmark::State& state, const Solver* solver, int shape, Query q) {
    auto cases = bench::generic_cases(shape, 1024);
    std::size_t i = 0;
    int hits = 0;
    for (auto _ : state) {
        const auto& c = cases[i++ & 1023];
        Result r = (*solver)(c.shape, c.line, q);
        hits += r.count;
        benchmark::DoNotOptimize(r);
    }
    state.counters["hits/solve"] = double(hits) / double(state.iterations());
    state.counters["solves/s"] =
        benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}

int register_all() {
    std::vector<const Solver*> solvers;
    for (const Solver& s : fast_solvers())
        solvers.push_back(&s);
    solvers.push_back(&exact::solver());
    for (int shape = 0; shape < 3; ++shape)
        for (const Solver* s : solvers) {
            std::string name = std::string(shape_names[shape]) + "/" + std::string(s->name);
            benchmark::RegisterBenchmark((name + "/points").c_str(), solve, s, shape,
                                         Query{Need::all, true});
            benchmark::RegisterBenchmark((name + "/no_points").c_str(), solve, s, shape,
                                         Query{Need::all, false});
        }
    return 0;
}
const int registered = register_all();

} // namespace

BENCHMARK_MAIN();
