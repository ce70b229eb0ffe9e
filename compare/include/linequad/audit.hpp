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
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

namespace linequad::audit {

// Distance in representable doubles (or floats: a value that is not a float is at least 1 off);
// 0 when equal; saturates for NaN.
std::uint64_t ulps_between(double a, double b, Precision p = Precision::binary64);
// Half the spacing of the format's values at x (0 for infinities).
double half_ulp_of(double x, Precision p);

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
    invented,          // more hits than the reference: a hit where there is none
    missed,            // fewer hits than the reference: a hit not found
    tangent_missed,    // the oracle has a tangent hit, the solver does not (a wrong kind)
    tangent_invented,  // the solver says tangent, the oracle does not (a wrong kind)
    on_surface_missed, // the oracle says the line lies on the surface, the solver does not
    on_surface_invented,
    nonfinite,  // NaN or infinity returned where the oracle has finite values
    refused,    // the solver returned an error the oracle does not (or the reverse)
    crashed,    // the call did not return: it crashed, exited or timed out (a library's own)
    part_wrong, // hits classified alike, but one (or the interval) on another part of the shape
    mismatch_kinds
};
const char* mismatch_name(int m);

// One of a row's worst cases: the case and both answers as `linequad solve` reads and writes
// them. Grading meets many more candidates than a row keeps, so a graded one holds what its lines
// are made from and writes them when they are first read (formatting every candidate was a tenth
// of the audit's time). Read by one thread at a time: a chunk's grader, then the merging thread.
class Worst {
  public:
    std::uint64_t ulps = 0; // t error; mismatches rank above any error
    bool mismatch = false;

    Worst() = default;
    // As a report holds it.
    Worst(std::string case_line, std::string solver_line, std::string oracle_line);
    // As grading meets it.
    // reference: how the reference line names itself ("exact", or for a solver from outside that
    // answers otherwise, "exact, nearest hit" ...).
    Worst(const Case& c, const std::string& solver, const Result& got, const Result& oracle,
          Carries carries, std::string_view reference = "exact");
    const std::string& case_line() const;
    const std::string& solver_line() const;
    const std::string& oracle_line() const;

  private:
    struct Graded;
    void write_lines() const;
    mutable std::shared_ptr<const Graded> graded_; // until the lines are written
    mutable std::string case_line_, solver_line_, oracle_line_;
};

struct Row {
    std::uint64_t cases = 0, graded_roots = 0, graded_coords = 0;
    // Cases posed in binary32 (their answers graded in float ulps): all of a float solver's, none
    // of a double solver's in a campaign.
    std::uint64_t binary32_cases = 0;
    std::array<std::uint64_t, mismatch_kinds> mismatches{};
    std::uint64_t cases_mismatched = 0;
    Histogram t_error, p_error;
    std::uint64_t t_max = 0, p_max = 0;
    // The t error as a distance in the scene: |t - t_oracle| |v| in ulps of the scene's magnitude
    // (the largest of |L0|, |t v| and the shape's coordinates). An exact zero of t, where ulps of
    // t are meaningless, reads here as what it is: how far the hit is from the true one.
    Histogram s_error;
    std::uint64_t s_max = 0;
    // Cases the solver could not be posed or could not represent (an external library's shapes
    // and semantics): not graded, not in `cases`.
    std::uint64_t unrepresented = 0;
    // Cases outside the solver's declared contract (a first exit asked of a start outside, a
    // start inside where the solver leaves it undefined), by why: never asked, not in `cases`.
    std::map<std::string, std::uint64_t> not_asked;
    // Cases whose classification differs from the exact one but is right for a surface within
    // the solver's declared tolerance: graded (in `cases`), not mismatched, no error measured.
    std::uint64_t within_tolerance = 0;
    // Roots of the wrong sign, or 0 where the exact root is not (or the reverse): counted here,
    // not as an ulp distance (which would read near 2^63 for a sign flip near 0).
    std::uint64_t t_sign_wrong = 0;
    // Of those, the ones with a reason (the library's own words, or why a case cannot be posed
    // its way), by reason.
    std::map<std::string, std::uint64_t> unrepresented_why;
    // Refusals of the solver's own (ErrorCode::foreign: another library's errors, and its crashes,
    // exits, exceptions and timeouts), by name; each is also a refused mismatch.
    std::map<std::string, std::uint64_t> foreign;
    // Calls that left the floating-point environment changed (put back before the next call), by
    // how; their answers are graded as given.
    std::map<std::string, std::uint64_t> environment;
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
    // Quantiles from the histograms, never above the largest error seen.
    double t_quantile(double q) const;
    double p_quantile(double q) const;
    double s_quantile(double q) const;
    bool timed() const { return ns.median() > 0; } // a row graded from a results file is not
};

// Error against difficulty k, per (family, solver), over all shapes and ranges.
struct CurvePoint {
    std::uint64_t cases = 0, mismatched = 0, t_max = 0;
    Histogram t_error;
};

// What a row of the report is about. Rows are kept in this order (family, shape, solver).
struct RowKey {
    std::string family, shape, solver;
    bool operator<(const RowKey& o) const {
        return std::tie(family, shape, solver) < std::tie(o.family, o.shape, o.solver);
    }
    bool operator==(const RowKey& o) const {
        return family == o.family && shape == o.shape && solver == o.solver;
    }
    std::string name() const { return family + "/" + shape + "/" + solver; } // for people
};

// A curve of error against k: one per (family, solver), over all shapes and ranges.
struct CurveKey {
    std::string family, solver;
    bool operator<(const CurveKey& o) const {
        return std::tie(family, solver) < std::tie(o.family, o.solver);
    }
    bool operator==(const CurveKey& o) const { return family == o.family && solver == o.solver; }
};

enum class Status {
    running,  // saved while the run goes on: what it holds so far
    stopped,  // ended early by a stop request: what it measured
    complete, // every case of its shards graded
};
const char* status_name(Status s);

struct Report {
    // Provenance. `run` tells one run (or merge) from another: its report.md and report.html
    // name it beside its status.
    std::string command, machine, compiler, flags, version, commit, date, run;
    double seconds = 0;
    // The campaign. Shards of one campaign agree on all of it (merge checks).
    std::uint64_t seed = 0, cases_per_group = 0;
    std::vector<std::string> families, shapes, ranges, solvers;
    std::string frames = "any"; // the frames the shapes were built on (families.hpp)
    int shards = 1;
    std::vector<int> shards_included{0}; // the shards whose cases this report holds, ascending
    // For each shard included, a mark of its own cases (shard_mark): what merge checks, so that a
    // report copied and relabelled as another shard is refused.
    std::map<int, std::uint64_t> shard_marks;
    // Set instead when the report grades a results file, or runs solvers on a cases file (not a
    // campaign: it does not merge); cases_count is then the file's number of cases.
    std::string cases_file, results_file;
    std::uint64_t cases_count = 0;
    // Solvers from outside linequad, by name: what they answer and how a case is handed over.
    struct External {
        std::string answers, parametrisation, surface, mapping, plugin;
        std::string not_replayable;  // why `linequad replay` cannot run it (empty: it can)
        std::string inside, contact; // its conventions (empty: none)
        std::string conventions;     // all of its declared conventions, in words
        double tolerance_absolute = 0, tolerance_relative = 0; // as declared
        bool batch = false;                                    // a plugin's batch entry answered it
        std::string load_environment;      // how loading the plugin changed the environment
        std::string output;                // its first lines (stdout, stderr or message hooks)
        std::uint64_t output_bytes = 0;    // how much it wrote in all
        std::uint64_t restarts = 0;        // workers started again after a crash, exit or hang
        std::uint64_t batch_fallbacks = 0; // packets asked again one case at a time
    };
    std::map<std::string, External> external;
    Status status = Status::complete;
    // Statistics.
    std::map<RowKey, Row> rows;
    std::map<CurveKey, std::map<int, CurvePoint>> curves;
    // Oracle rounding: floats its filter rounded from its intervals alone, values it rounded
    // from double-word enclosures (each 0 in a report from before it did), and the rest,
    // resolved by MPFR at 64, 128, ... bits.
    std::array<std::uint64_t, 8> oracle_steps{};
    std::uint64_t oracle_by_intervals = 0, oracle_by_filter = 0;

    // Every case of the campaign graded: each shard present and complete.
    bool complete() const {
        return status == Status::complete && int(shards_included.size()) == shards;
    }
    bool grades_results() const { return !results_file.empty(); }
    bool from_cases_file() const { return !cases_file.empty(); }
    // Adds another shard of the same campaign (see mergeable()).
    void merge(const Report& o);
    // Adds another report's statistics (rows, curves, oracle steps) and nothing else: how the
    // audit's worker threads' chunks join the report, in chunk order.
    void merge_statistics(const Report& o);
    Row total(const std::string& solver) const; // all rows of one solver
};

// How many cases a row did not ask (Row::not_asked, summed).
std::uint64_t not_asked_count(const Row& r);

// A fresh run identity (Report::run): 16 hex digits.
std::string new_run_id();

// Why b cannot be merged into a (another campaign, a shard twice, a results grading), naming
// the difference; empty when it can.
std::string unmergeable(const Report& a, const Report& b);

// What a solver's answers carry, and so are graded on (linequad/case_io.hpp).
using Grading = Carries;

// One answer to grade: the case, the solver's answer and the reference (the oracle's, or for a
// solver from outside the reference for what it declares), what of the answer is graded, and how
// the reference names itself in the row's worst cases (see Worst).
struct Answered {
    const Case& c;
    const std::string& solver;
    const Result& got;
    const Result& reference;
    Grading what = {};
    std::string_view reference_name = "exact";
    // For a solver with a declared tolerance: whether an answer whose classification differs is
    // right for some surface within it (asked only of such answers).
    const std::function<bool(const Result&)>* tolerated = nullptr;
};

// Grades one answer into a row and a curve point (if given), in ulps of the case's precision
// (the reference rounded to it). A mismatched classification measures no error: the roots it
// would compare are not the same roots.
void grade(const Answered& a, Row& row, CurvePoint* curve);

// The audit's name for stable's batch path (many lines against one shape): not a Solver, since
// it takes lines in arrays. Graded like stable, whose results it equals bit for bit.
inline constexpr const char* batch_name = "batch";
// Cases graded as one unit: by one worker, into statistics of their own, timed together. Large
// enough that merging a chunk's statistics (its rows' and curves' histograms) costs little
// beside grading it, and that batch's packet is the benchmarks' 1024 lines.
inline constexpr std::uint64_t chunk_size = 1024;

// How far a run has come: cases graded of those it will grade, and the time it took so far.
struct Progress {
    std::uint64_t done = 0, total = 0;
    double seconds = 0;
    // The time left at the pace so far (0 before any case is graded, or once all are).
    double seconds_left() const {
        return done && done < total ? seconds * double(total - done) / double(done) : 0;
    }
};

struct Options {
    std::uint64_t seed = 1, cases_per_group = 100000;
    std::vector<Family> families; // empty: all
    std::vector<int> shapes;      // indices in linequad::Shape; empty: all
    Frames frames = Frames::any;
    // The cases' precision for for_each_case (the cases command); a campaign poses each family's
    // cases in each solver's own precision.
    Precision precision = Precision::binary64;
    std::vector<std::string> solvers; // empty: every fast solver, and batch
    int shard = 0, shards = 1;
    std::string out_dir; // reports/<run>; empty: nothing written
    // A cases file instead of the families: graded with results_file (someone else's answers),
    // or without it, solved by the solvers.
    std::string results_file, cases_file;
    std::string command; // how it was invoked, for the report
    bool plots = true;
    // Worker threads grading chunks of cases; 0: one per core. The report is the same for any
    // number (timings aside): each chunk is graded on its own and merged in order.
    int threads = 0;
    std::size_t max_line_bytes = std::size_t(1) << 20; // per line of a cases or results file
    // Written into out_dir at the end, from report.md and the figures, before report.json says
    // the run ended (the linequad program's report.html); nothing when empty.
    std::function<void(const std::string& dir)> finish_with;
    // The library writes nothing on the terminal: how far the run has come (called on run's own
    // thread after each chunk of cases is graded) and notes on it (a result line graded as
    // refused, an early stop) go to these, which the linequad program draws; empty ones drop them.
    std::function<void(const Progress&)> progress;
    std::function<void(const std::string&)> notice;
};

// Memory runs low (a program's reserve was just given up to the allocation that failed): the
// running audit stops as a stop request would, at its next chunk, and ends in a
// std::runtime_error saying so, its report saved and marked stopped. Stopping between chunks
// rather than by a std::bad_alloc in the middle of one matters: CGAL's Mpzf, which the exact
// oracle computes in, does not survive one thrown inside it (seen: a SIGSEGV in Mpzf::clear and
// glibc's "munmap_chunk(): invalid pointer" under an address-space limit).
void stop_for_memory() noexcept;

// A stop request (SIGINT, SIGTERM) that came before any case was graded (while a cases file was
// read): there is no report to keep. The linequad program exits 130 with its message.
struct Stopped : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Runs the campaign (or grades a results file) and writes the report; returns it. The output
// directory is locked and marked in progress first, and saved every few seconds: a run that is
// killed loses at most those seconds. A stop request (SIGINT, SIGTERM) ends the run early with
// what it has, marked stopped. Throws std::runtime_error on input it must refuse (a malformed
// cases file, duplicate ids) and on output it cannot write.
Report run(const Options& o);

// A mark of one campaign shard's cases (o.shard of o.shards): a hash of the id of each group's
// first case in that shard. The shard's cases are a function of the campaign and the shard, so a
// report of another shard's cases, relabelled, carries another mark.
std::uint64_t shard_mark(const Options& o);
// The mark of shard k of the campaign a report describes (0 if the report names a family, shape
// or frames linequad does not know).
std::uint64_t shard_mark(const Report& r, int k);
// Why a campaign report's cases are not those of the shards it names (its marks differ from the
// marks of its campaign's shards, or it has none); empty when they are (or it grades a file).
std::string shard_problem(const Report& r);

// Every case of a campaign, in order (the shard's share only).
void for_each_case(const Options& o, const std::function<void(const Case&)>& f);

// The claims the README makes for each solver, checked against a report; each broken claim
// is described in one line. Empty: every claim holds.
std::vector<std::string> broken_claims(const Report& r);

// A solver's verdict, as the report's first screen and the audit's closing summary say it: of the
// cases it was asked, the share classified as the exact oracle does; the families where it
// misclassifies most, each with the difficulty k from which it breaks (at least 1 % misclassified
// at that k; -1 when no k reaches it); its t error in bits, log2(1 + ulps) (Herbie's measure).
struct FamilyShare {
    std::string family;
    std::uint64_t misclassified = 0, cases = 0;
    int breaks_at = -1;
};
struct Verdict {
    std::string solver;
    std::uint64_t cases = 0, misclassified = 0, within_tolerance = 0, not_asked = 0,
                  unrepresented = 0, sign_wrong = 0;
    std::vector<FamilyShare> worst_families; // at most three, the largest share first
    bool errors = false;                     // any root graded
    double t_max_ulps = 0, t_p99_ulps = 0;
    double t_max_bits() const;
    double t_p99_bits() const;
};
std::vector<Verdict> verdicts(const Report& r);
// One solver's rows of one family, merged.
Row family_total(const Report& r, const std::string& family, const std::string& solver);
// The smallest difficulty k at which the solver misclassifies at least 1 % of the family's cases
// (its curve's point), or -1.
int breaks_at(const Report& r, const std::string& family, const std::string& solver);
// Text for people: "0.12 %", "< 0.01 %", "100 %"; "-" of nothing.
std::string percent_of(std::uint64_t part, std::uint64_t whole);
// A count as people read it: 21,600,000.
std::string grouped(std::uint64_t n);
// An error of t in bits, log2(1 + ulps), one decimal ("0" when there is none).
std::string bits_text(double ulps);
// The verdict in one line of words (the audit's closing summary).
std::string verdict_line(const Verdict& v);

// A gate on a solver: `SOLVER:METRIC<=VALUE`, with METRIC misclassified (% of the cases graded),
// t_bits_max or t_bits_p99, held in every family the solver graded.
struct Expectation {
    std::string solver, metric;
    double at_most = 0;
};
// Reads one; false with *why naming what is wrong.
bool parse_expectation(std::string_view text, Expectation* e, std::string* why);
// Every family and metric that breaks an expectation, in words (a solver that graded nothing
// breaks every expectation on it); empty when all hold.
std::vector<std::string> unmet(const Report& r, const std::vector<Expectation>& expectations);

// What changed from one report to another, family by family and solver by solver (each
// solver's rows of a family merged over shapes and ranges), and whether it got worse beyond the
// thresholds: a regression gate for CI that asks "not made worse", not a fixed tolerance.
struct DiffThresholds {
    // How much larger the new max and p99 errors (in ulps) may be: new <= old * (1 + growth).
    double max_growth = 0, p99_growth = 0;
    // How much slower the median may be, as a fraction; negative: times are shown, never fail
    // (the default, since a noisy machine would fail a gate on them at random).
    double time_growth = -1;
};

struct Change {
    std::string family, solver, measure; // measure: "mismatched", "t max ulps", ...
    std::string old_value, new_value;
    enum Verdict { better, worse, worse_within_threshold, changed } verdict = changed;
};

struct Diff {
    std::vector<Change> changes;
    std::vector<std::pair<std::string, std::string>> compared; // (family, solver), in order
    std::string campaigns;  // how the two campaigns differ, if they do (their cases then differ)
    std::string incomplete; // which report did not grade its whole campaign, if one did not
    bool worse() const;     // anything worse beyond its threshold
    // The same campaign, both complete: a change is then the solvers' own.
    bool comparable() const { return campaigns.empty() && incomplete.empty(); }
};

Diff diff(const Report& old_report, const Report& new_report, const DiffThresholds& t);
std::string diff_markdown(const Diff& d, const std::string& old_name, const std::string& new_name);
std::string diff_junit(const Diff& d, const std::string& old_name, const std::string& new_name);

// report.json: the exact, mergeable record (format "linequad-audit-2").
std::string to_json(const Report& r);
// Reads report.json text, checking the schema and every value's range; on failure returns false
// with *why naming the field by its path (rows[3].t_ulps.max) and what is wrong with it.
bool from_json(std::string_view text, Report* r, std::string* why);
bool read_json(const std::string& path, Report* r, std::string* why); // why names the file too
void write_json(const Report& r, const std::string& path);            // atomic; throws
std::string markdown(const Report& r);
// The command that replays one of a row's worst cases of solver `solver`, every word quoted for
// the shell: `echo '<case>' | linequad replay [--plugin '<path>'] --solver '<name>'`.
std::string replay_command(const Report& r, const Worst& w, const std::string& solver);
// The figures beside the report, as SVG: pareto.svg, difficulty_<family>.svg (the family's name
// made a file name: difficulty_figure) and distance.svg. Returns whether it drew; throws if it
// cannot write its files.
bool write_plots(const Report& r, const std::string& dir);
std::string difficulty_figure(const std::string& family);

// An output directory held by one run: locked (a second run into it is refused, naming the lock),
// emptied of an earlier run's report.md, report.html and figures before anything is written (so
// that no file of another run is ever presented as this one's), marked as running, and saved as
// it goes. Every file is written to a temporary name and renamed; report.json, the record, is
// written last at the end, so that a run killed while finishing still says "running" there.
class OutputDirectory {
  public:
    explicit OutputDirectory(const std::string& dir); // throws, naming the path and the reason
    ~OutputDirectory();
    OutputDirectory(const OutputDirectory&) = delete;
    OutputDirectory& operator=(const OutputDirectory&) = delete;
    // A running report's save: report.json, then report.md from the same report.
    void checkpoint(const Report& r);
    // The end of a run: the report checked by reading its JSON back, then the figures (when
    // `plots`), report.md, whatever `also` writes from them (report.html), and report.json last.
    // Memory that runs out there is a std::runtime_error saying what report.json then holds.
    void finish(const Report& r, bool plots,
                const std::function<void(const std::string& dir)>& also = {});
    const std::string& path() const { return dir_; }

  private:
    std::string saved_out_of_memory(const std::string& json_text, Status status);
    std::string dir_;
    int lock_fd_ = -1;
};

} // namespace linequad::audit
