// The accuracy audit: solvers graded against the exact oracle, family by family.
//
// Statistics are kept in forms that merge exactly (counts, maxima, sums, histograms), so that
// shards of one campaign run on many machines combine into the report one machine would write.
#pragma once

#include "linequad/families.hpp"
#include "linequad/result.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace linequad::audit {

// Distance in representable doubles: 0 when equal; saturates for NaN and opposite infinities.
std::uint64_t ulps_between(double a, double b);

// Error histogram: exact buckets for 0..16 ulps, then quarter octaves up to 2^64.
struct Histogram {
    static constexpr int exact = 17, bins = exact + 4 * 60 + 1;
    std::array<std::uint64_t, bins> count{};
    static int bucket(std::uint64_t ulps);
    static double upper_edge(int bucket); // the largest error a bucket may hold
    void add(std::uint64_t ulps) { ++count[bucket(ulps)]; }
    std::uint64_t total() const;
    double quantile(double q) const; // upper edge of the bucket holding the q-quantile
    void merge(const Histogram& o);
};

// ns per solve, per chunk of cases; medians come from here. Buckets of 1/16 octave from 0.25 ns.
struct TimeHistogram {
    static constexpr int bins = 16 * 24;
    std::array<std::uint64_t, bins> count{};
    void add(double ns);
    double median() const; // 0 when empty
    void merge(const TimeHistogram& o);
};

enum Mismatch {
    hit_count,         // a different number of hits (or an interval instead of hits)
    tangent_missed,    // the oracle has a tangent hit, the solver does not
    tangent_invented,  // the solver says tangent, the oracle does not
    on_surface_missed, // the oracle says the line lies on the surface, the solver does not
    on_surface_invented,
    nonfinite, // NaN or infinity returned where the oracle has finite values
    refused,   // the solver returned an error the oracle does not (or the reverse)
    mismatch_kinds
};
const char* mismatch_name(int m);

struct Worst {
    std::uint64_t ulps = 0; // t error; mismatches rank above any error
    bool mismatch = false;
    std::string case_line, solver_line, oracle_line;
};

struct Row {
    std::uint64_t cases = 0, graded_roots = 0, graded_coords = 0;
    std::array<std::uint64_t, mismatch_kinds> mismatches{};
    std::uint64_t cases_mismatched = 0;
    Histogram t_error, p_error;
    std::uint64_t t_max = 0, p_max = 0;
    double t_sum = 0, t_bits_sum = 0; // for the mean in ulps and in bits (Herbie)
    TimeHistogram ns;
    // Certified results: classifications the solver called uncertain (not counted as
    // mismatches), certain ones that were wrong, roots whose bound did not hold, and how loose
    // the bounds are (bound / actual error, rounded up).
    std::uint64_t uncertain = 0, certain_wrong = 0, bounded_roots = 0, bound_violations = 0;
    Histogram tightness;
    // Bounded roots whose bound is below half an ulp of t: the most that the bound alone could
    // prove correctly rounded (Ziv's first test).
    std::uint64_t bound_below_half_ulp = 0;
    // The correct solver: results by the rung that settled them (indexed by Rung).
    std::array<std::uint64_t, 4> rungs{};
    std::vector<Worst> worst; // at most keep_worst, worst first
    static constexpr std::size_t keep_worst = 3;
    void merge(const Row& o);
};

// Error against difficulty k, per (family, solver), over all shapes and ranges.
struct CurvePoint {
    std::uint64_t cases = 0, mismatched = 0, t_max = 0;
    Histogram t_error;
};

struct Report {
    // Provenance.
    std::string command, machine, compiler, flags, commit, date;
    std::uint64_t seed = 0, cases_per_group = 0;
    int shard = 0, shards = 1;
    bool complete = true;
    double seconds = 0;
    std::vector<std::string> solvers;
    // "family/shape/solver" -> statistics.
    std::map<std::string, Row> rows;
    // "family/solver" -> k -> point.
    std::map<std::string, std::map<int, CurvePoint>> curves;
    // Oracle rounding: values resolved at 64, 128, ... bits.
    std::array<std::uint64_t, 8> oracle_steps{};

    void merge(const Report& o);
    Row total(const std::string& solver) const; // all rows of one solver
};

// Grades one solver result against the oracle's for one case, into a row and a curve point.
// points: whether the solver's result carries hit points to grade.
void grade(const Case& c, const std::string& solver, const Result& got, const Result& oracle,
           Row& row, CurvePoint* curve, bool points = true);

// The audit's name for stable's batch path (many lines against one shape): not a Solver, since
// it takes lines in arrays. Graded like stable, whose results it equals bit for bit.
inline constexpr const char* batch_name = "batch";

struct Options {
    std::uint64_t seed = 1, cases_per_group = 100000;
    std::vector<Family> families;     // empty: all
    std::vector<std::string> solvers; // empty: every fast solver, and batch
    int shard = 0, shards = 1;
    std::string out_dir;                  // reports/<run>
    std::string results_file, cases_file; // grade someone else's answers
    std::string command;                  // how it was invoked, for the report
    bool plots = true;
};

// Runs the campaign (or grades a results file) and writes the report; returns it.
// A stop request (SIGINT, SIGTERM) ends the run early with what it has, marked incomplete.
Report run(const Options& o);

// Every case of a campaign, in order (the shard's share only).
void for_each_case(const Options& o, const std::function<void(const Case&)>& f);

// The claims the README makes for each solver, checked against a report; each broken claim
// is described in one line. Empty: every claim holds.
std::vector<std::string> broken_claims(const Report& r);

void write_json(const Report& r, const std::string& path);
bool read_json(const std::string& path, Report* r, std::string* why);
void write_markdown(const Report& r, const std::string& dir);
void write_plots(const Report& r, const std::string& dir); // gnuplot: SVG and PNG

} // namespace linequad::audit
