// ns per solve for shape x solver, on generic cases. Run (interleaved, so that a drift of the
// machine's speed during the run does not bias the ratios between solvers):
//   build/bench/linequad_bench --benchmark_repetitions=10
//   --benchmark_enable_random_interleaving=true
//       --benchmark_report_aggregates_only=true --benchmark_min_time=0.2
#include "generic_cases.hpp"

#include "linequad/exact.hpp"
#include "linequad/linequad.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <string_view>
#include <type_traits>

namespace {

using namespace linequad;

const std::size_t shape_count = std::variant_size_v<Shape>;
std::string name_of(int shape) {
    return shape_name(bench::generic_cases(shape, 1)[0].shape);
}

void solve(benchmark::State& state, const Solver* solver, int shape, Query q) {
    auto cases = bench::generic_cases(shape, 1024, 1, solver->precision);
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

// Every alternative of Shape, prepared: what a renderer holds for many lines.
template <class Variant>
struct PreparedOf;
template <class... S>
struct PreparedOf<std::variant<S...>> {
    using type = std::variant<Prepared<S>...>;
};
using PreparedShape = PreparedOf<Shape>::type;

// The same cases, each shape prepared before the loop; solve(prepared, line, query) is one
// solver's typed call.
template <class Solve>
void solve_prepared(benchmark::State& state, int shape, Query q, Solve solve) {
    auto cases = bench::generic_cases(shape, 1024);
    std::vector<PreparedShape> shapes;
    for (const auto& c : cases)
        shapes.push_back(
            std::visit([](const auto& s) { return PreparedShape(prepare(s)); }, c.shape));
    std::size_t i = 0;
    int hits = 0;
    for (auto _ : state) {
        std::size_t k = i++ & 1023;
        Result r = std::visit([&](const auto& p) { return solve(p, cases[k].line, q); }, shapes[k]);
        hits += r.count;
        benchmark::DoNotOptimize(r);
    }
    state.counters["hits/solve"] = double(hits) / double(state.iterations());
    state.counters["solves/s"] =
        benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}

// spawn_ray from each case's nearest correct hit, on along the line (the cases without a hit
// left out): what a renderer pays per bounce for a proven origin.
void spawn(benchmark::State& state, int shape) {
    std::vector<std::pair<PreparedShape, Hit>> from;
    std::vector<Vec3> directions;
    for (const auto& c : bench::generic_cases(shape, 1024)) {
        Result r = correct::intersect(c.shape, c.line, {Need::nearest, true});
        if (r.count == 0) continue;
        from.emplace_back(
            std::visit([](const auto& x) { return PreparedShape(prepare(x)); }, c.shape),
            r.hits[0]);
        directions.push_back(c.line.v);
    }
    std::size_t i = 0, refused = 0;
    for (auto _ : state) {
        std::size_t k = i++ % from.size();
        SpawnedRay s =
            std::visit([&](const auto& p) { return spawn_ray(p, from[k].second, directions[k]); },
                       from[k].first);
        refused += !s.ok();
        benchmark::DoNotOptimize(s);
    }
    state.counters["refused/spawn"] = double(refused) / double(state.iterations());
}

template <class R>
void stable_scalar_loop(benchmark::State& state, int shape) {
    bench::OneShape<R> o = bench::one_shape<R>(shape);
    LineArraysT<R> l = o.lines();
    std::string_view name = std::is_same_v<R, float> ? "stable32" : "stable";
    const Solver& solver = *std::find_if(fast_solvers().begin(), fast_solvers().end(),
                                         [&](const Solver& f) { return f.name == name; });
    std::vector<Result> out(l.count);
    for (auto _ : state) {
        for (std::size_t i = 0; i < l.count; ++i)
            out[i] =
                solver(o.shape, Line{{l.x[i], l.y[i], l.z[i]}, {l.vx[i], l.vy[i], l.vz[i]}}, {});
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(std::int64_t(state.iterations() * l.count));
}
// The lanes a batch runs on, for the row's label: the capsule, made of patches, is the scalar
// loop on any path.
Lanes lanes_taken(const Shape& shape, Lanes asked) {
    return std::holds_alternative<Capsule>(shape) ? Lanes::scalar : std::min(asked, batch_lanes());
}

template <class R>
void stable_batch(benchmark::State& state, int shape, Lanes lanes) {
    bench::OneShape<R> o = bench::one_shape<R>(shape);
    LineArraysT<R> l = o.lines();
    std::vector<Result> out(l.count);
    for (auto _ : state) {
        std::visit(
            [&](const auto& s) {
                if constexpr (std::is_same_v<R, float>)
                    stable32::intersect(s, l, {}, out.data(), lanes);
                else
                    stable::intersect(s, l, {}, out.data(), lanes);
            },
            o.shape);
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(std::int64_t(state.iterations() * l.count));
    // Float lines run on AVX2's eight lanes on an AVX-512 machine too.
    Lanes used = lanes_taken(o.shape, lanes);
    if (std::is_same_v<R, float>) used = std::min(used, Lanes::avx2);
    state.SetLabel(lanes_name(used));
}

// correct on the same 1024 lines against the shape prepared once: one line at a time (lanes =
// scalar), or the batch on `lanes`; `closed`: the shape closed by its discs.
void correct_lines(benchmark::State& state, int shape, Lanes lanes, bool closed) {
    bench::OneShape<double> o = bench::one_shape<double>(shape);
    LineArrays l = o.lines();
    std::vector<Result> out(l.count);
    std::visit(
        [&](auto s) {
            if constexpr (has_extent_options<decltype(s)>) s.caps = closed;
            auto p = prepare(s);
            for (auto _ : state) {
                if (lanes == Lanes::scalar) {
                    for (std::size_t i = 0; i < l.count; ++i)
                        out[i] = correct::intersect(
                            p, Line{{l.x[i], l.y[i], l.z[i]}, {l.vx[i], l.vy[i], l.vz[i]}}, {});
                } else {
                    correct::intersect(p, l, {}, out.data(), lanes);
                }
                benchmark::DoNotOptimize(out.data());
            }
        },
        o.shape);
    state.SetItemsProcessed(std::int64_t(state.iterations() * l.count));
    state.SetLabel(lanes_name(lanes_taken(o.shape, lanes)));
}

int register_all() {
    for (int shape = 0; shape < int(shape_count); ++shape)
        for (bool closed : {false, true}) {
            bool has_caps = std::visit(
                [](const auto& s) { return has_extent_options<std::decay_t<decltype(s)>>; },
                bench::one_shape<double>(shape, 1).shape);
            if (closed && !has_caps) continue;
            std::string correct_name =
                name_of(shape) + (closed ? "+caps" : "") + "/correct/1024_lines/";
            benchmark::RegisterBenchmark((correct_name + "scalar_loop").c_str(), correct_lines,
                                         shape, Lanes::scalar, closed);
            for (Lanes lanes : {Lanes::avx2, Lanes::avx512})
                if (lanes <= batch_lanes())
                    benchmark::RegisterBenchmark(
                        (correct_name + "batch_" + lanes_name(lanes)).c_str(), correct_lines, shape,
                        lanes, closed);
        }
    for (int shape = 0; shape < int(shape_count); ++shape) {
        std::string name = name_of(shape) + "/stable/1024_lines/";
        benchmark::RegisterBenchmark((name + "scalar_loop").c_str(), stable_scalar_loop<double>,
                                     shape);
        // Every path this machine runs, to compare them in one (interleaved) run.
        for (Lanes lanes : {Lanes::avx2, Lanes::avx512})
            if (lanes <= batch_lanes())
                benchmark::RegisterBenchmark((name + "batch_" + lanes_name(lanes)).c_str(),
                                             stable_batch<double>, shape, lanes);
        std::string name32 = name_of(shape) + "/stable32/1024_lines/";
        benchmark::RegisterBenchmark((name32 + "scalar_loop").c_str(), stable_scalar_loop<float>,
                                     shape);
        benchmark::RegisterBenchmark((name32 + "batch").c_str(), stable_batch<float>, shape,
                                     batch_lanes());
    }
    std::vector<const Solver*> solvers;
    for (const Solver& s : fast_solvers())
        solvers.push_back(&s);
    solvers.push_back(&exact::solver());
    for (int shape = 0; shape < int(shape_count); ++shape)
        for (const Solver* s : solvers) {
            std::string name = name_of(shape) + "/" + std::string(s->name);
            benchmark::RegisterBenchmark((name + "/points").c_str(), solve, s, shape,
                                         Query{Need::all, true});
            benchmark::RegisterBenchmark((name + "/no_points").c_str(), solve, s, shape,
                                         Query{Need::all, false});
            // The nearest hit, and the hit test (no point either way).
            benchmark::RegisterBenchmark((name + "/nearest").c_str(), solve, s, shape,
                                         Query{Need::nearest, false});
            benchmark::RegisterBenchmark((name + "/any").c_str(), solve, s, shape,
                                         Query{Need::any, false});
        }
    // Prepared shapes, every fast solver, all hits with points.
    auto prepared = [&](const char* solver, auto solve) {
        for (int shape = 0; shape < int(shape_count); ++shape)
            benchmark::RegisterBenchmark(
                (name_of(shape) + "/" + solver + "/prepared/points").c_str(),
                [=](benchmark::State& st) { solve_prepared(st, shape, Query{}, solve); });
    };
    prepared("seed",
             [](const auto& p, const Line& l, Query q) { return seed::intersect(p, l, q); });
    prepared("stable",
             [](const auto& p, const Line& l, Query q) { return stable::intersect(p, l, q); });
    prepared("certified",
             [](const auto& p, const Line& l, Query q) { return certified::intersect(p, l, q); });
    prepared("correct",
             [](const auto& p, const Line& l, Query q) { return correct::intersect(p, l, q); });
    for (int shape = 0; shape < int(shape_count); ++shape)
        benchmark::RegisterBenchmark((name_of(shape) + "/spawn_ray/prepared").c_str(), spawn,
                                     shape);
    return 0;
}
const int registered = register_all();

} // namespace

BENCHMARK_MAIN();
