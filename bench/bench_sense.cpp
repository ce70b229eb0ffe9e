// The sense of a point against a general quadric, per query: the textbook sign of f(p) evaluated
// in double (what transport codes do), linequad's filtered exact sign off the surface (the
// filter decides) and on it (the exact BigFloat path), and the oracle (CGAL::Mpzf). Run
// interleaved:
//   build/bench/linequad_sense_bench --benchmark_repetitions=5
//       --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true
#include "linequad/exact.hpp"
#include "linequad/surfaces.hpp"

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

namespace {

using namespace linequad;

// A one-sheet hyperboloid x^2 + y^2 - z^2 = 1 with 1024 points: near it, or exactly on it
// ((cos, sin) scaled points are not exact, so on-surface points are the rulings' integer points:
// (1, t, t) and (-1, t, -t) for integers t).
struct Points {
    Quadric q{{1, 1, -1, 0, 0, 0, 0, 0, 0, -1}};
    std::vector<Vec3> near, on;
};

const Points& points() {
    static const Points p = [] {
        Points out;
        std::mt19937_64 g(7);
        std::uniform_real_distribution<double> c(-4, 4);
        for (int i = 0; i < 1024; ++i) {
            out.near.push_back({c(g), c(g), c(g)});
            double t = double(i - 512);
            out.on.push_back(i % 2 ? Vec3{1, t, t} : Vec3{-1, t, -t});
        }
        return out;
    }();
    return p;
}

double textbook(const Quadric& s, Vec3 p) {
    const auto& q = s.q;
    return q[0] * p.x * p.x + q[1] * p.y * p.y + q[2] * p.z * p.z + q[3] * p.x * p.y +
           q[4] * p.y * p.z + q[5] * p.z * p.x + q[6] * p.x + q[7] * p.y + q[8] * p.z + q[9];
}

// Every point of `which` once per iteration through `query`.
template <class Query>
void each_point(benchmark::State& state, const std::vector<Vec3>& which, Query&& query) {
    const Points& p = points();
    for (auto _ : state)
        for (Vec3 x : which)
            benchmark::DoNotOptimize(query(p.q, x));
    state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(which.size()));
}

void textbook_near(benchmark::State& state) {
    each_point(state, points().near, [](const Quadric& q, Vec3 x) { return textbook(q, x) < 0; });
}
void sense_near(benchmark::State& state) {
    each_point(state, points().near, [](const Quadric& q, Vec3 x) { return sense(q, x); });
}
void sense_on(benchmark::State& state) {
    each_point(state, points().on, [](const Quadric& q, Vec3 x) { return sense(q, x); });
}
void oracle_near(benchmark::State& state) {
    each_point(state, points().near, [](const Quadric& q, Vec3 x) { return exact::sense(q, x); });
}

} // namespace

BENCHMARK(textbook_near)->Name("sense/textbook/near");
BENCHMARK(sense_near)->Name("sense/linequad/near");
BENCHMARK(sense_on)->Name("sense/linequad/on");
BENCHMARK(oracle_near)->Name("sense/oracle/near");
BENCHMARK_MAIN();
