// What auditing a plugin out of process costs: the example plugin's solver called in this process
// (the shape and line handed over through the C ABI, the answer read back, as the audit did when
// plugins ran in its process) against the same cases answered by its worker process (the cases
// written to shared memory, one request and one reply per batch, the answers read back). Per case,
// batches of a few hundred:
//
//   build/bench/linequad_plugin_bench --benchmark_repetitions=10
//       --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true
#include "generic_cases.hpp"

#include "linequad/audit_plugin.h"
#include "run/plugin_worker.hpp"

#include <benchmark/benchmark.h>
#include <dlfcn.h>

#include <stdexcept>

using namespace linequad;

namespace {

// Generic open finite cylinders and lines through them, as cases of the audit.
std::vector<Case> cylinder_cases(std::size_t n) {
    std::vector<Case> out;
    for (const bench::GenericCase& g : bench::generic_cases(0, int(n), 7)) {
        Case c;
        c.shape = g.shape, c.line = g.line;
        out.push_back(c);
    }
    return out;
}

const lq_solver& in_process_solver() {
    static const lq_solver* solver = [] {
        void* lib = dlopen(LINEQUAD_EXAMPLE_PLUGIN, RTLD_NOW | RTLD_LOCAL);
        if (!lib) throw std::runtime_error(dlerror());
        auto entry = reinterpret_cast<lq_plugin_entry>(dlsym(lib, "linequad_audit_plugin"));
        const lq_solver* s = nullptr;
        if (!entry || entry(LQ_ABI, &s) < 1) throw std::runtime_error("no solver");
        return s;
    }();
    return *solver;
}

void in_process(benchmark::State& state) {
    std::vector<Case> cases = cylinder_cases(std::size_t(state.range(0)));
    const lq_solver& s = in_process_solver();
    std::vector<audit::ExternalAnswer> out(cases.size());
    for (auto _ : state) {
        for (std::size_t i = 0; i < cases.size(); ++i) {
            const Case& c = cases[i];
            lq_shape shape = audit::to_plugin_shape(c.shape);
            lq_line line{{c.line.L0.x, c.line.L0.y, c.line.L0.z},
                         {c.line.v.x, c.line.v.y, c.line.v.z},
                         c.line.range.t0,
                         c.line.range.t1};
            lq_answer a{};
            s.solve(s.self, &shape, &line, &a);
            audit::read_plugin_answer(a, out[i]);
        }
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(state.iterations() * state.range(0));
}

void in_worker(benchmark::State& state) {
    std::vector<Case> cases = cylinder_cases(std::size_t(state.range(0)));
    audit::PluginOptions o;
    o.program = LINEQUAD_PROGRAM;
    static audit::PluginWorker worker(LINEQUAD_EXAMPLE_PLUGIN, o);
    std::vector<audit::ExternalAnswer> out;
    double ns = 0;
    for (auto _ : state) {
        if (!worker.answer(0, cases, out, &ns)) state.SkipWithError("stopped");
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(state.iterations() * state.range(0));
}

} // namespace

BENCHMARK(in_process)->Name("plugin/in_process")->Arg(256)->Arg(512)->Arg(1024);
BENCHMARK(in_worker)->Name("plugin/in_worker")->Arg(256)->Arg(512)->Arg(1024);
BENCHMARK_MAIN();
