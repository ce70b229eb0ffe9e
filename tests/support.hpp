// Helpers shared by the tests: run a solver by name, describe results for failure messages.
#pragma once

#include "linequad/audit.hpp"
#include "linequad/case_io.hpp"
#include "linequad/families.hpp"
#include "linequad/registry.hpp"

#include "numeric/format.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <random>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <variant>

namespace linequad::test {

// The whole of a file ("" if it cannot be read).
inline std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// An empty directory of the test's own, under the system's temporary directory.
inline std::filesystem::path scratch(const std::string& name) {
    namespace fs = std::filesystem;
    fs::path p =
        fs::temp_directory_path() / ("linequad_test_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

// What the linequad program did when run.
struct Ran {
    int status = -1; // the exit status; 128 + N when killed by signal N
    std::string out, err;
};

// Runs `linequad ARGS` through the shell (ARGS may redirect), in dir.
inline Ran program(const std::string& args, const std::filesystem::path& dir) {
    // The captures come first, so that a redirection in args (> /dev/full, >&-) overrides them.
    std::string cmd = "cd '" + dir.string() + "' && '" + std::string(LINEQUAD_BIN) +
                      "' > stdout.txt 2> stderr.txt " + args;
    int raw = std::system(cmd.c_str());
    Ran r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    r.out = slurp(dir / "stdout.txt");
    r.err = slurp(dir / "stderr.txt");
    INFO("linequad " << args << "\nstatus " << r.status << "\nstderr: " << r.err);
    return r;
}

// The report.json an audit wrote into dir, read back strictly.
inline audit::Report read_report(const std::filesystem::path& dir) {
    audit::Report r;
    std::string why;
    INFO(why);
    REQUIRE(audit::read_json((dir / "report.json").string(), &r, &why));
    return r;
}

inline Result run(const std::string& solver, const Shape& s, const Line& l, Query q = {}) {
    const Solver* f = find_solver(solver);
    REQUIRE(f != nullptr);
    return (*f)(s, l, q);
}

inline std::string describe(const Result& r) {
    return format_result("0", "?", r);
}

// The same double, bit for bit (signed zeros and NaN payloads told apart).
inline bool same_bits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

// How many kinds of shape there are (the alternatives of Shape, indexed as the families index
// them).
inline constexpr int shape_kinds = int(std::variant_size_v<Shape>);

// The solvers that must return exact answers where the arithmetic of a case is exact. (Not
// seed32: the seeds' 4x4 inverse and textbook discriminant in float round where the double seed
// happens not to, and it invents or misses tangencies on such cases, as the audit shows.)
inline const char* const every_solver[] = {"seed",  "stable",   "certified", "correct",
                                           "exact", "stable32", "correct32"};
// The double solvers alone: for cases whose inputs are not floats, or beyond float's reach.
inline const char* const double_solvers[] = {"seed", "stable", "certified", "correct", "exact"};

// Two points on a surface: the line through them meets it exactly at t = 0 and t = 1.
inline Line through(Vec3 p, Vec3 q, Range range = Range::line) {
    return {p, q - p, range};
}

// |a - b| in units in the last place of b (0 when equal; infinite if either is not finite).
inline double ulps(double a, double b) {
    if (a == b) return 0;
    if (!std::isfinite(a) || !std::isfinite(b)) return INFINITY;
    double u = std::nextafter(std::fabs(b), INFINITY) - std::fabs(b);
    return std::fabs(a - b) / u;
}

// The oracle and the correct solvers must be exact (correctly rounded). The others round: in
// these hand-built tests every input and root is O(1..100) and the roots are well separated
// (no tangency), so each coefficient carries a few ulps and the roots at most a few dozen;
// 64 ulps of max(1, |expected|), in the solver's own format (u = 2^-53 for double, 2^-24 for
// the float solvers), bounds that with room and still fails on any real mistake (a wrong
// formula is off by O(1)).
inline bool exact_solver(const std::string& solver) {
    return solver == "exact" || solver == "correct" || solver == "correct32";
}
inline double fast_tolerance(double expected, Precision p = Precision::binary64) {
    double u = p == Precision::binary32 ? 0x1p-24 : 0x1p-53;
    return 64 * u * std::fmax(1.0, std::fabs(expected));
}
inline Precision precision_of(const std::string& solver) {
    const Solver* f = find_solver(solver);
    return f ? f->precision : Precision::binary64;
}

inline void check_t(const std::string& solver, double got, double expected) {
    INFO(solver << ": t = " << hex(got) << ", expected " << hex(expected));
    if (exact_solver(solver) || std::isinf(expected))
        CHECK(got == expected);
    else
        CHECK(std::fabs(got - expected) <= fast_tolerance(expected, precision_of(solver)));
}

inline void check_p(const std::string& solver, Vec3 got, Vec3 expected) {
    for (int i = 0; i < 3; ++i) {
        INFO("coordinate " << i);
        check_t(solver, got[i], expected[i]);
    }
}

// The line through two points on a surface crosses it at t = 0 and t = 1, exactly there.
inline void check_through_two_points(const Shape& shape, Vec3 p, Vec3 q,
                                     std::initializer_list<const char*> solvers) {
    for (const char* s : solvers) {
        Result r = run(s, shape, through(p, q));
        INFO(s << " " << describe(r));
        REQUIRE(r.count == 2);
        check_t(s, r.hits[0].t, 0);
        check_t(s, r.hits[1].t, 1);
        check_p(s, r.hits[0].p, p);
        check_p(s, r.hits[1].p, q);
    }
}

// A hit as a hand-built test expects it.
struct Want {
    double t;
    HitKind kind;
    Part part;
};

// Every solver's hits: their kinds and parts, t bit for bit from the exact solvers and within
// 4 ulps from the others (the callers' inputs are dyadic and every answer a small dyadic or a
// root of a small quadratic, so seed and stable are within 4 ulps of it; the same reason as
// fast_tolerance's, on smaller numbers).
template <class Solvers = decltype(every_solver)>
void check_hits(const Shape& s, const Line& l, std::initializer_list<Want> want,
                const Solvers& solvers = every_solver) {
    for (const char* solver : solvers) {
        Result r = run(solver, s, l);
        INFO(solver << ": " << describe(r));
        REQUIRE(r.ok());
        REQUIRE(!r.on_surface);
        REQUIRE(r.count == int(want.size()));
        int i = 0;
        for (const Want& w : want) {
            const Hit& h = r.hits[i++];
            CHECK(h.kind == w.kind);
            CHECK(h.part == w.part);
            if (exact_solver(solver))
                CHECK(h.t == w.t);
            else
                CHECK(std::fabs(h.t - w.t) <= 4 * 0x1p-52 * std::fmax(1.0, std::fabs(w.t)));
        }
    }
}

// n cases of every family, for each shape it applies to and each range, posed in p.
template <class Visit>
void for_each_family_case(std::uint64_t seed, std::uint64_t n, Precision p, Visit visit) {
    for (int fi = 0; fi < family_count; ++fi)
        for (int shape = 0; shape < shape_kinds; ++shape) {
            if (!family_applies(Family(fi), shape)) continue;
            for (Range range : {Range::line, Range::ray, Range::segment})
                for (std::uint64_t i = 0; i < n; ++i)
                    visit(make_case(Family(fi), shape, range, seed, i, Frames::any, p));
        }
}

// The same answer bit for bit (signed zeros, infinities): the classification, t, points and
// interval ends; bounds and certainty aside (the oracle gives none).
inline void check_same_answer(const Result& got, const Result& want) {
    INFO("got  " << describe(got) << "\nwant " << describe(want));
    REQUIRE(got.error_code == want.error_code);
    REQUIRE(got.count == want.count);
    REQUIRE(got.on_surface == want.on_surface);
    if (want.on_surface) {
        CHECK(same_bits(got.s0, want.s0));
        CHECK(same_bits(got.s1, want.s1));
        CHECK(got.surface_part == want.surface_part);
    }
    for (int i = 0; i < want.count; ++i) {
        CHECK(got.hits[i].kind == want.hits[i].kind);
        CHECK(got.hits[i].part == want.hits[i].part);
        CHECK(same_bits(got.hits[i].t, want.hits[i].t));
        for (int k = 0; k < 3; ++k)
            CHECK(same_bits(got.hits[i].p[k], want.hits[i].p[k]));
    }
}

// A hit test's answer (Need::any) against the oracle's full answer: a hit when the oracle has
// one, and then one of the oracle's within the hit's bound (|t - exact t| <= bound, and the
// oracle's t is within half an ulp of exact), certain when the solver says so; no hit
// otherwise; a line on the surface as the oracle has it.
inline void check_hit_test(const Result& got, const Result& all) {
    INFO("hit test " << describe(got) << "\noracle   " << describe(all));
    REQUIRE(got.error_code == all.error_code);
    REQUIRE(got.on_surface == all.on_surface);
    if (all.on_surface) return;
    REQUIRE(got.count == (all.count > 0 ? 1 : 0));
    if (all.count == 0) return;
    const Hit& h = got.hits[0];
    bool matched = false;
    for (int i = 0; i < all.count; ++i) {
        double t = all.hits[i].t;
        bool near = h.t == t || // equal infinities too
                    std::fabs(h.t - t) <= h.bound + detail::Binary64::half_ulp(t);
        matched = matched || (h.kind == all.hits[i].kind && near);
    }
    CHECK(matched);
    CHECK(h.p == Vec3{}); // a hit test computes no point
}

// Uniform doubles and vectors from a fixed seed (full 53-bit mantissas: exact inputs).
struct RandomReals {
    std::mt19937_64 rng;
    explicit RandomReals(std::uint64_t seed) : rng(seed) {}
    double real(double lo, double hi) {
        return std::uniform_real_distribution<double>(lo, hi)(rng);
    }
    Vec3 vec(double s) { return {real(-s, s), real(-s, s), real(-s, s)}; }
};

} // namespace linequad::test
