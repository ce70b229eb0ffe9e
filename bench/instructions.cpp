// Solves N pre-built generic cases with one solver, for counting instructions under callgrind:
// bench/instructions.sh runs it with N solves and with none, and divides the difference by N.
//   linequad_instructions SOLVER SHAPE NEED POINTS HOW N
// SOLVER: floor | seed | stable | certified | correct | seed32 | stable32 | correct32 (the float
// solvers on the same cases rounded to float) | batch-LANES | batch32-LANES | batchcorrect-LANES
// (stable's, stable32's and correct's batch on LANES = scalar, avx2 or avx512: 1024 generic lines
// against one prepared shape, N lines in all, in batches of 1024); SHAPE: cylinder |
// elliptic_cylinder | elliptic_cone | frustum | sphere | ellipsoid | capsule, and SHAPE+caps for a
// shape with an axis closed by its discs (the same shapes and lines); NEED: any | nearest | all;
// POINTS: points | no_points; HOW: direct | prepared (each case's shape prepared before the solves,
// which are what is counted). floor: the textbook cylinder quadratic (bench/floor.hpp), the unit
// the ratios are quoted in.
#include "floor.hpp"
#include "generic_cases.hpp"

#include "linequad/linequad.hpp"

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

using namespace linequad;

volatile double sink;

// The solves, between linequad_stepcount's marks when it runs the program (bench/stepcount.cpp).
class Marked {
  public:
    Marked() { mark(); }
    ~Marked() { mark(); }
    Marked(const Marked&) = delete;
    Marked& operator=(const Marked&) = delete;

  private:
    static void mark() {
        static const bool on = std::getenv("LINEQUAD_STEP_MARKS") != nullptr;
        if (on) std::raise(SIGUSR1);
    }
};

// Each case's shape as given, or prepared before the solves (which are what is counted).
// Closed (SHAPE+caps): the same shapes with their discs.
bool closed = false;

template <class ShapeT, class Solve>
void run(int shape_index, long n, Query q, bool prepared, Solve solve, Precision p) {
    auto cases = bench::generic_cases(shape_index, 1024, 1, p);
    std::vector<ShapeT> shapes;
    std::vector<Prepared<ShapeT>> ready;
    std::vector<Line> lines;
    for (const auto& c : cases) {
        shapes.push_back(std::get<ShapeT>(c.shape)), lines.push_back(c.line);
        if constexpr (has_extent_options<ShapeT>) shapes.back().caps = closed;
        if (prepared) ready.push_back(prepare(shapes.back()));
    }
    double acc = 0;
    Marked solves;
    for (long i = 0; i < n; ++i) {
        std::size_t k = std::size_t(i) & 1023;
        Result r = prepared ? solve(ready[k], lines[k], q) : solve(shapes[k], lines[k], q);
        acc += r.count > 0 ? r.hits[0].t : 0;
    }
    sink = acc;
}

template <class ShapeT>
bool run_solver(const std::string& solver, int shape_index, long n, Query q, bool prepared) {
    auto with = [&](auto solve, Precision p = Precision::binary64) {
        return run<ShapeT>(shape_index, n, q, prepared, solve, p), true;
    };
    if (solver == "seed")
        return with(
            [](const auto& s, const Line& l, Query qq) { return seed::intersect(s, l, qq); });
    if (solver == "stable")
        return with(
            [](const auto& s, const Line& l, Query qq) { return stable::intersect(s, l, qq); });
    if (solver == "certified")
        return with(
            [](const auto& s, const Line& l, Query qq) { return certified::intersect(s, l, qq); });
    if (solver == "correct")
        return with(
            [](const auto& s, const Line& l, Query qq) { return correct::intersect(s, l, qq); });
    // The float solvers on the same cases rounded to float.
    if (solver == "seed32")
        return with(
            [](const auto& s, const Line& l, Query qq) { return seed32::intersect(s, l, qq); },
            Precision::binary32);
    if (solver == "stable32")
        return with(
            [](const auto& s, const Line& l, Query qq) { return stable32::intersect(s, l, qq); },
            Precision::binary32);
    if (solver == "correct32")
        return with(
            [](const auto& s, const Line& l, Query qq) { return correct32::intersect(s, l, qq); },
            Precision::binary32);
    return false;
}

// stable's (stable32's for float lines, correct's when asked) batch on `lanes`: 1024 lines against
// one prepared shape, n lines in all.
template <class R, class ShapeT>
bool run_batch(int shape_index, long n, Query q, Lanes lanes, bool correct_solver = false) {
    bench::OneShape<R> o = bench::one_shape<R>(shape_index);
    ShapeT shape = std::get<ShapeT>(o.shape);
    if constexpr (has_extent_options<ShapeT>) shape.caps = closed;
    Prepared<ShapeT> p = prepare(shape);
    LineArraysT<R> lines = o.lines();
    std::vector<Result> out(lines.count);
    double acc = 0;
    Marked solves;
    for (long done = 0; done < n; done += long(lines.count)) {
        if constexpr (std::is_same_v<R, float>)
            stable32::intersect(p, lines, q, out.data(), lanes);
        else if (correct_solver)
            correct::intersect(p, lines, q, out.data(), lanes);
        else
            stable::intersect(p, lines, q, out.data(), lanes);
        acc += out[std::size_t(done) & 1023].count;
    }
    sink = acc;
    return true;
}

// The shape named `name`, by its index in Shape.
template <std::size_t I = 0>
bool run_shape(const std::string& name, const std::string& solver, long n, Query q, bool prepared) {
    if constexpr (I < std::variant_size_v<Shape>) {
        using S = std::variant_alternative_t<I, Shape>;
        if (name != shape_name<S>()) return run_shape<I + 1>(name, solver, n, q, prepared);
        for (Lanes lanes : {Lanes::scalar, Lanes::avx2, Lanes::avx512}) {
            std::string suffix = std::string("-") + lanes_name(lanes);
            if (solver == "batch" + suffix) return run_batch<double, S>(int(I), n, q, lanes);
            if (solver == "batch32" + suffix) return run_batch<float, S>(int(I), n, q, lanes);
            if (solver == "batchcorrect" + suffix)
                return run_batch<double, S>(int(I), n, q, lanes, true);
        }
        return run_solver<S>(solver, int(I), n, q, prepared);
    }
    return false;
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 7) {
        std::fprintf(stderr,
                     "usage: %s SOLVER SHAPE any|nearest|all points|no_points direct|prepared N\n",
                     argv[0]);
        return 2;
    }
    std::string solver = argv[1], shape = argv[2], need = argv[3];
    if (std::string caps = "+caps";
        shape.size() > caps.size() &&
        shape.compare(shape.size() - caps.size(), caps.size(), caps) == 0) {
        shape.resize(shape.size() - caps.size());
        closed = true;
    }
    Query q{need == "any"       ? Need::any
            : need == "nearest" ? Need::nearest
                                : Need::all,
            std::strcmp(argv[4], "points") == 0};
    long n = std::atol(argv[6]);
    if (solver == "floor") {
        auto cases = bench::generic_cases(0, 1024);
        std::vector<bench::FloorCase> fc;
        for (const auto& c : cases) {
            const Cylinder& s = std::get<Cylinder>(c.shape);
            fc.push_back({s.C, s.H, s.r, c.line.L0, c.line.v});
        }
        double acc = 0;
        Marked solves;
        for (long i = 0; i < n; ++i)
            acc += bench::textbook_cylinder(fc[std::size_t(i) & 1023]).t[0];
        sink = acc;
        return 0;
    }
    bool prepared = std::strcmp(argv[5], "prepared") == 0;
    if (!run_shape(shape, solver, n, q, prepared)) {
        std::fprintf(stderr, "unknown solver or shape\n");
        return 2;
    }
    return 0;
}
