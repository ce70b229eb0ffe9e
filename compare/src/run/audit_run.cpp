// The campaign loop, the grading of results files, and report provenance.
#include "linequad/audit.hpp"
#include "linequad/audit_solver.hpp"

#include "io/shape_types.hpp"

#include "linequad/batch.hpp"
#include "linequad/case_io.hpp"
#include "linequad/exact.hpp"
#include "linequad/registry.hpp"

#include "grade/tolerance.hpp"
#include "io/jsonl.hpp"
#include "io/process.hpp"
#include "run/ordered_pool.hpp"
#include "run/plugin_worker.hpp"
#include "run/stop.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <map>
#include <mutex>
#include <new>
#include <optional>
#include <random>
#include <thread>
#include <unistd.h>
#include <unordered_map>

namespace linequad::audit {

namespace {
std::atomic<bool> stop_flag{false}, memory_low{false};
} // namespace

bool stop_requested() {
    return stop_flag.load(std::memory_order_relaxed);
}

void stop_for_memory() noexcept {
    memory_low = true;
    stop_flag = true;
}

std::string new_run_id() {
    std::random_device random;
    std::uint64_t id = (std::uint64_t(random()) << 32) ^ random() ^
                       std::uint64_t(std::chrono::system_clock::now().time_since_epoch().count());
    char text[20];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(id));
    return text;
}

namespace {

constexpr Range ranges[] = {Range::line, Range::ray, Range::segment};
// How much work a kill -9 may cost: a running audit saves its report this often.
constexpr double save_every_seconds = 2;

extern "C" void on_signal(int) {
    stop_flag = true;
}

} // namespace

// Without SA_RESTART: a call blocked on input (opening a FIFO no one writes, reading an endless
// file) returns EINTR, so that a stop is honoured there too; every loop on a system call retries
// on EINTR where it must.
StopOnSignal::StopOnSignal() {
    stop_flag = false, memory_low = false;
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;
    sigaction(SIGINT, &sa, &old_int_);
    sigaction(SIGTERM, &sa, &old_term_);
}
StopOnSignal::~StopOnSignal() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
}

namespace {

// What git prints of the working tree, or "" (no git, not a repository).
std::string git(const std::vector<std::string>& args) {
    std::vector<std::string> argv = {"git"};
    argv.insert(argv.end(), args.begin(), args.end());
    process::Exit e = process::run(argv);
    std::string out = e.ok() ? e.output : "";
    while (!out.empty() && (out.back() == '\n' || out.back() == '\r'))
        out.pop_back();
    return out;
}

// The shapes a campaign builds, by index in linequad::Shape.
std::vector<int> shapes_of(const Options& o) {
    std::vector<int> shapes = o.shapes;
    if (shapes.empty())
        for (int s = 0; s < int(shape_count); ++s)
            shapes.push_back(s);
    return shapes;
}

void fill_provenance(Report& r, const Options& o) {
    r.command = o.command;
    std::ifstream cpu("/proc/cpuinfo");
    std::string line, model;
    int cores = 0;
    while (std::getline(cpu, line)) {
        if (line.rfind("model name", 0) == 0 && model.empty())
            model = line.substr(line.find(':') + 2);
        if (line.rfind("processor", 0) == 0) ++cores;
    }
    r.machine = (model.empty() ? "unknown CPU" : model) + ", " + std::to_string(cores) + " cores";
    BuildInfo b = build_info();
    r.compiler = b.compiler;
    r.flags = b.fast_flags;
    r.version = b.version;
    r.commit = git({"rev-parse", "--short", "HEAD"});
    if (r.commit.empty()) r.commit = "unknown";
    if (!git({"status", "--porcelain", "--untracked-files=no"}).empty()) r.commit += "+dirty";
    char date[64];
    std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&now));
    r.date = date;
    r.run = new_run_id();
    r.seed = o.seed, r.cases_per_group = o.cases_per_group;
    r.shards = o.shards;
    r.shards_included = {o.shard};
    for (int s : shapes_of(o))
        r.shapes.emplace_back(shape_name_at(std::size_t(s)));
    r.frames = frames_name(o.frames);
    for (Range x : ranges)
        r.ranges.emplace_back(range_name(x));
}

// Counts graded cases and tells o.progress, if set.
class ProgressCount {
  public:
    ProgressCount(const Options& o, std::uint64_t total,
                  std::chrono::steady_clock::time_point start)
        : tell_(o.progress), start_(start) {
        now_.total = total;
    }
    void advance(std::uint64_t n) {
        now_.done += n;
        now_.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        if (tell_) tell_(now_);
    }

  private:
    const std::function<void(const Progress&)>& tell_;
    std::chrono::steady_clock::time_point start_;
    Progress now_;
};

struct Group {
    Family family;
    int shape;
    Range range;
};

std::vector<Family> families_of(const Options& o) {
    std::vector<Family> families = o.families;
    if (families.empty())
        for (int f = 0; f < family_count; ++f)
            families.push_back(Family(f));
    return families;
}

std::vector<Group> groups_of(const Options& o) {
    std::vector<Group> out;
    for (Family f : families_of(o))
        for (int shape : shapes_of(o))
            if (family_applies(f, shape))
                for (Range r : ranges)
                    out.push_back({f, shape, r});
    return out;
}

// The solvers a run grades: linequad's own (by name) and the external ones named, in the order
// named. An empty list: every fast solver, then every external one. A name that is neither is
// refused.
struct Solvers {
    std::vector<const Solver*> own;
    std::vector<const ExternalSolver*> external;
    std::vector<std::string> names; // in order, batch included where named
};

Solvers solvers_of(const Options& o, const std::vector<ExternalSolver>& external) {
    Solvers out;
    auto find_external = [&](const std::string& name) -> const ExternalSolver* {
        for (const ExternalSolver& e : external)
            if (e.name == name) return &e;
        return nullptr;
    };
    if (o.solvers.empty()) {
        for (const Solver& s : fast_solvers())
            out.own.push_back(find_solver(s.name)), out.names.emplace_back(s.name);
        for (const ExternalSolver& e : external)
            out.external.push_back(&e), out.names.push_back(e.name);
        return out;
    }
    for (const std::string& name : o.solvers) {
        if (const ExternalSolver* e = find_external(name))
            out.external.push_back(e);
        else if (const Solver* s = find_solver(name))
            out.own.push_back(s);
        else if (name != batch_name)
            throw std::invalid_argument("audit: no solver named '" + name + "'");
        if (name != batch_name) out.names.push_back(name);
    }
    return out;
}

Report::External describe(const ExternalSolver& e) {
    Report::External x;
    x.answers = answers_name(e.answers);
    x.parametrisation = parametrisation_name(e.parametrisation);
    x.surface = surface_name(e.surface);
    x.mapping = e.mapping;
    x.plugin = e.plugin;
    x.not_replayable = e.not_replayable;
    if (e.inside != StartInside::as_answers) x.inside = start_inside_name(e.inside);
    if (e.contact_as_point) x.contact = "first point";
    x.conventions = conventions_text(e);
    x.tolerance_absolute = e.tolerance.absolute;
    x.tolerance_relative = e.tolerance.relative;
    return x;
}

// What a solver from outside did while the run went on beside its answers: what it wrote of its
// own (a plugin's worker, or an in-process library's message hooks), a worker's restarts.
void note_worker(Report::External& x, const ExternalSolver& e) {
    if (e.own_output) {
        x.output = e.own_output->head();
        x.output_bytes = e.own_output->bytes();
    }
    if (!e.worker) return;
    const DeclaredSolver& d = e.worker->solvers().at(std::size_t(e.worker_index));
    x.batch = d.batch;
    x.load_environment = e.worker->load_environment();
    x.output = e.worker->output(e.worker_index);
    x.output_bytes = e.worker->output_bytes(e.worker_index);
    x.restarts = std::uint64_t(e.worker->restarts(e.worker_index));
    x.batch_fallbacks = std::uint64_t(e.worker->batch_fallbacks(e.worker_index));
}

bool batch_wanted(const Options& o) {
    return o.solvers.empty() ||
           std::find(o.solvers.begin(), o.solvers.end(), batch_name) != o.solvers.end();
}

// The batch point of the Pareto plot. Its error: every case through the batch path, one line
// per call. Its time: the chunk's lines as one batch (they share the range) against the shapes
// of up to four of the chunk's cases, per line, as a renderer's packet would use it. Returns
// the ns per line; got[i] is case i's result.
double run_batch(const std::vector<Case>& cases, std::vector<Result>& got) {
    std::vector<double> soa[6];
    for (const Case& c : cases)
        for (int k = 0; k < 3; ++k)
            soa[k].push_back(c.line.L0[k]), soa[3 + k].push_back(c.line.v[k]);
    auto solve = [](const Shape& shape, const LineArrays& lines, Result* out) {
        std::visit([&](const auto& s) { stable::intersect(s, lines, Query{}, out); }, shape);
    };
    for (std::size_t i = 0; i < cases.size(); ++i) {
        LineArrays one{&soa[0][i], &soa[1][i], &soa[2][i], &soa[3][i],
                       &soa[4][i], &soa[5][i], 1,          cases[i].line.range};
        solve(cases[i].shape, one, &got[i]);
    }
    LineArrays all{soa[0].data(), soa[1].data(), soa[2].data(), soa[3].data(),
                   soa[4].data(), soa[5].data(), cases.size(),  cases[0].line.range};
    std::vector<Result> packet(cases.size());
    std::size_t shapes = std::min<std::size_t>(4, cases.size());
    auto t0 = std::chrono::steady_clock::now();
    for (std::size_t j = 0; j < shapes; ++j)
        solve(cases[j].shape, all, packet.data());
    auto t1 = std::chrono::steady_clock::now();
    return std::chrono::duration<double, std::nano>(t1 - t0).count() /
           double(shapes * cases.size());
}

// Where the run's report goes, if anywhere; saved as it goes.
class Saver {
  public:
    explicit Saver(const Options& o) {
        if (!o.out_dir.empty()) dir_.emplace(o.out_dir);
    }
    // Marks the directory as holding a run in progress, before anything is computed.
    void begin(Report& rep) {
        rep.status = Status::running;
        if (dir_) dir_->checkpoint(rep);
        last_ = std::chrono::steady_clock::now();
    }
    // Saves at most every few seconds: a kill -9 loses no more than that.
    void maybe_save(Report& rep, std::chrono::steady_clock::time_point start) {
        auto now = std::chrono::steady_clock::now();
        if (!dir_ || std::chrono::duration<double>(now - last_).count() < save_every_seconds)
            return;
        last_ = now;
        rep.seconds = std::chrono::duration<double>(now - start).count();
        dir_->checkpoint(rep);
    }
    void end(Report& rep, const Options& o, std::chrono::steady_clock::time_point start) {
        rep.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (dir_) dir_->finish(rep, o.plots, o.finish_with);
    }

  private:
    std::optional<OutputDirectory> dir_;
    std::chrono::steady_clock::time_point last_;
};

std::runtime_error out_of_memory_grading(const Options& o) {
    return std::runtime_error("out of memory while grading: the report in " +
                              (o.out_dir.empty() ? std::string("memory") : o.out_dir) +
                              " holds what was measured, marked stopped");
}

// The cases of a cases file by id, in file order; duplicate ids and malformed lines refused.
std::vector<Case> read_cases_of(const Options& o);

// Parses one line (parse() returns whether it could), running out of memory there said with the
// file and the line (the parser has let go of what it built).
template <class Parse>
bool parse_line(Parse&& parse, const std::string& file, long line) {
    try {
        return parse();
    } catch (const std::bad_alloc&) {
        throw std::runtime_error(file + ": line " + std::to_string(line) +
                                 ": out of memory while reading it");
    }
}

// The cases of a cases file; running out of memory there is said with the file.
std::vector<Case> read_cases(const Options& o) {
    try {
        return read_cases_of(o);
    } catch (const std::bad_alloc&) {
        throw std::runtime_error(o.cases_file + ": out of memory while reading its cases");
    }
}

std::vector<Case> read_cases_of(const Options& o) {
    jsonl::LineReader in(o.cases_file, o.max_line_bytes);
    in.stop_when(&stop_flag);
    std::vector<Case> cases;
    std::unordered_map<std::string, long> line_of;
    std::string line, why;
    auto fail = [&](const std::string& what) {
        return std::runtime_error(o.cases_file + ": line " + std::to_string(in.number()) + ": " +
                                  what);
    };
    auto throw_stopped = [&] {
        if (memory_low) throw fail("out of memory while reading it; nothing was graded yet");
        throw Stopped(o.cases_file + ": stopped (SIGINT or SIGTERM) while it was read, at line " +
                      std::to_string(in.number()) + "; nothing was graded yet");
    };
    for (;;) {
        if (stop_requested()) throw_stopped();
        auto status = in.next(&line);
        if (status == jsonl::LineReader::Status::end) break;
        if (status == jsonl::LineReader::Status::error) {
            if (stop_requested()) throw_stopped();
            throw std::runtime_error(in.error());
        }
        if (status == jsonl::LineReader::Status::too_long)
            throw std::runtime_error(o.cases_file + ": " +
                                     jsonl::too_long_message(in.number(), o.max_line_bytes));
        if (jsonl::blank(line)) continue;
        Case c;
        if (!parse_line([&] { return parse_case(line, &c, &why); }, o.cases_file, in.number()))
            throw fail(why);
        if (c.id == "null") throw fail("a case needs an id, to match its answers");
        auto [it, fresh] = line_of.emplace(c.id, in.number());
        if (!fresh) throw fail("id " + c.id + " repeats line " + std::to_string(it->second) + "'s");
        cases.push_back(std::move(c));
    }
    if (cases.empty()) throw std::runtime_error(o.cases_file + ": no cases to grade");
    return cases;
}

// A results file's answers, by solver and then by the index of their case; each (case, solver)
// at most once, each naming a case of the file.
struct Answer {
    ParsedResult result;
    long line = 0;
    bool malformed = false;
};
using ResultsByCase = std::map<std::string, std::unordered_map<std::size_t, Answer>>;
ResultsByCase read_answers(const Options& o,
                           const std::unordered_map<std::string, std::size_t>& index) {
    ResultsByCase answers;
    jsonl::LineReader res(o.results_file, o.max_line_bytes);
    std::string line, why;
    for (;;) {
        auto status = res.next(&line);
        if (status == jsonl::LineReader::Status::end) break;
        if (status == jsonl::LineReader::Status::error) throw std::runtime_error(res.error());
        std::string where = o.results_file + ": line " + std::to_string(res.number());
        if (status == jsonl::LineReader::Status::too_long)
            throw std::runtime_error(o.results_file + ": " +
                                     jsonl::too_long_message(res.number(), o.max_line_bytes));
        if (jsonl::blank(line)) continue;
        Answer a;
        a.line = res.number();
        if (!parse_line([&] { return parse_result(line, &a.result, &why); }, o.results_file,
                        res.number())) {
            // An answer that names its case is graded as refused; one that does not cannot be
            // attributed to any case.
            if (!a.result.has_id) throw std::runtime_error(where + ": " + why);
            if (o.notice) o.notice(where + ": " + why + " (graded as refused)");
            a.malformed = true;
        }
        auto it = index.find(a.result.id);
        if (it == index.end())
            throw std::runtime_error(where + ": no case in " + o.cases_file + " has id " +
                                     a.result.id);
        std::string solver = a.result.solver.empty() ? "results" : a.result.solver;
        auto [prev, fresh] = answers[solver].emplace(it->second, a);
        if (!fresh)
            throw std::runtime_error(where + ": a second answer from " + solver + " to case " +
                                     a.result.id + " (the first is on line " +
                                     std::to_string(prev->second.line) + ")");
    }
    // What a solver's answers carry (points, kinds, parts) is what any of its lines shows: a line
    // without hits shows none of them, yet a solver that reports kinds has said "no tangent" there.
    for (auto& [solver, by_case] : answers) {
        bool points = false, kinds = false, parts = false;
        for (const auto& [i, a] : by_case)
            points |= a.result.has_points, kinds |= a.result.has_kinds, parts |= a.result.has_parts;
        for (auto& [i, a] : by_case)
            a.result.has_points |= points, a.result.has_kinds |= kinds, a.result.has_parts |= parts;
    }
    // An empty results file still grades one solver: every case unanswered.
    if (answers.empty()) answers["results"];
    return answers;
}

// One case's answers from every solver of a results file, graded into rep.
void grade_answers(const Case& c, std::size_t i, const ResultsByCase& answers, Report& rep) {
    Result oracle = exact::intersect(c.shape, c.line, {}, c.precision);
    std::string family = c.family.empty() ? "cases" : c.family;
    for (const auto& [solver, by_case] : answers) {
        Row& row = rep.rows[{family, shape_name(c.shape), solver}];
        auto a = by_case.find(i);
        if (a == by_case.end() || a->second.malformed) {
            // No answer, or none we can read: a refusal the oracle never makes.
            Result none = Result::failure(ErrorCode::out_of_range,
                                          a == by_case.end() ? "no answer" : "malformed");
            grade({c, solver, none, oracle, Grading{false}}, row, nullptr);
        } else if (a->second.result.error_code == "unrepresented") {
            // What `linequad solve` writes for a case an external solver cannot take.
            ++row.unrepresented;
        } else {
            const ParsedResult& pr = a->second.result;
            grade(
                {c, solver, pr.result, oracle, Grading{pr.has_points, pr.has_kinds, pr.has_parts}},
                row, &rep.curves[{family, solver}][c.k]);
        }
    }
}

void note_oracle_steps(Report& rep) {
    const auto& steps = exact::rounding_stats().by_steps;
    std::copy(std::begin(steps), std::end(steps), rep.oracle_steps.begin());
    rep.oracle_by_intervals = exact::rounding_stats().by_intervals;
    rep.oracle_by_filter = exact::rounding_stats().by_filter;
}

Report grade_results(const Options& o) {
    Report rep;
    fill_provenance(rep, o);
    rep.cases_file = o.cases_file, rep.results_file = o.results_file;
    rep.seed = 0, rep.cases_per_group = 0;
    rep.families.clear();
    exact::rounding_stats() = {};
    auto start = std::chrono::steady_clock::now();
    std::vector<Case> cases = read_cases(o);
    rep.cases_count = cases.size();
    std::unordered_map<std::string, std::size_t> index;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        index[cases[i].id] = i;
        std::string family = cases[i].family.empty() ? "cases" : cases[i].family;
        if (std::find(rep.families.begin(), rep.families.end(), family) == rep.families.end())
            rep.families.push_back(family);
    }
    Saver saver(o);
    saver.begin(rep);
    ResultsByCase answers = read_answers(o, index);
    for (const auto& [solver, by_case] : answers)
        rep.solvers.push_back(solver);
    for (std::size_t i = 0; i < cases.size(); ++i) {
        grade_answers(cases[i], i, answers, rep);
        saver.maybe_save(rep, start);
    }
    rep.status = Status::complete;
    note_oracle_steps(rep);
    saver.end(rep, o, start);
    return rep;
}

void check_shard(const Options& o) {
    if (o.shards < 1 || o.shard < 0 || o.shard >= o.shards)
        throw std::invalid_argument("audit: shard " + std::to_string(o.shard) + " of " +
                                    std::to_string(o.shards) + " does not exist");
}

} // namespace

std::uint64_t shard_mark(const Options& o) {
    check_shard(o);
    std::uint64_t k = std::uint64_t(o.shards), r = std::uint64_t(o.shard), first = 0;
    std::uint64_t mark = 0xcbf29ce484222325ull; // FNV-1a over the ids, each ended by a newline
    for (const Group& grp : groups_of(o)) {
        std::uint64_t i = (r + k - first % k) % k;
        first += o.cases_per_group;
        if (i >= o.cases_per_group) continue;
        Case c = make_case(grp.family, grp.shape, grp.range, o.seed, i, o.frames);
        for (char ch : c.id + "\n")
            mark = (mark ^ static_cast<unsigned char>(ch)) * 0x100000001b3ull;
    }
    return mark;
}

std::uint64_t shard_mark(const Report& r, int k) {
    Options o;
    o.seed = r.seed, o.cases_per_group = r.cases_per_group, o.shards = r.shards, o.shard = k;
    for (const std::string& name : r.families) {
        Family f;
        if (!parse_family(name, &f)) return 0;
        o.families.push_back(f);
    }
    for (const std::string& name : r.shapes) {
        int shape = shape_named(name);
        if (shape < 0) return 0;
        o.shapes.push_back(shape);
    }
    if (!parse_frames(r.frames, &o.frames)) return 0;
    return shard_mark(o);
}

std::string shard_problem(const Report& r) {
    if (r.from_cases_file() || r.grades_results()) return "";
    for (int k : r.shards_included) {
        auto mark = r.shard_marks.find(k);
        if (mark == r.shard_marks.end())
            return "holds no mark of shard " + std::to_string(k) + "'s cases";
        if (mark->second != shard_mark(r, k))
            return "its cases are not shard " + std::to_string(k) +
                   "'s (a report copied from another shard and relabelled?)";
    }
    return "";
}

void for_each_case(const Options& o, const std::function<void(const Case&)>& f) {
    check_shard(o);
    // Case i of group g is the shard's when (g N + i) mod shards is: walked as i = offset + j
    // shards, so that a shard costs its own cases only.
    std::uint64_t k = std::uint64_t(o.shards), r = std::uint64_t(o.shard), first = 0;
    for (const Group& grp : groups_of(o)) {
        for (std::uint64_t i = (r + k - first % k) % k; i < o.cases_per_group; i += k)
            f(make_case(grp.family, grp.shape, grp.range, o.seed, i, o.frames, o.precision));
        first += o.cases_per_group;
    }
}

namespace {

// Grades one chunk of cases (one family and shape, one precision) with every solver that answers
// in that precision, into a report of the chunk's own. One per worker thread (its scratch space).
class ChunkGrader {
  public:
    ChunkGrader(const Solvers& solvers, bool batch) : solvers_(solvers), batch_(batch) {}

    // Whether any solver answers cases posed in p.
    bool wanted(Precision p) const {
        if (p == Precision::binary64 && batch_) return true;
        for (const Solver* s : solvers_.own)
            if (s->precision == p) return true;
        for (const ExternalSolver* e : solvers_.external)
            if (e->precision == p) return true;
        return false;
    }

    // The chunk's statistics, its oracle's rounding steps among them.
    Report grade_chunk(const std::vector<Case>& cases, Precision precision,
                       const std::string& family, const std::string& shape) {
        Report out;
        exact::rounding_stats() = {};
        oracle_.resize(cases.size());
        got_.resize(cases.size());
        for (std::size_t i = 0; i < cases.size(); ++i)
            oracle_[i] = exact::intersect(cases[i].shape, cases[i].line, {}, precision);
        for (const Solver* s : solvers_.own) {
            if (s->precision != precision) continue;
            std::string name(s->name);
            Row& row = out.rows[{family, shape, name}];
            auto t0 = std::chrono::steady_clock::now();
            for (std::size_t i = 0; i < cases.size(); ++i)
                got_[i] = (*s)(cases[i].shape, cases[i].line);
            auto t1 = std::chrono::steady_clock::now();
            row.ns.add(std::chrono::duration<double, std::nano>(t1 - t0).count() /
                       double(cases.size()));
            auto& curve = out.curves[{family, name}];
            for (std::size_t i = 0; i < cases.size(); ++i)
                grade({cases[i], name, got_[i], oracle_[i]}, row, &curve[cases[i].k]);
        }
        if (batch_ && precision == Precision::binary64) {
            const std::string batch = batch_name;
            Row& row = out.rows[{family, shape, batch_name}];
            row.ns.add(run_batch(cases, got_));
            auto& curve = out.curves[{family, batch_name}];
            for (std::size_t i = 0; i < cases.size(); ++i)
                grade({cases[i], batch, got_[i], oracle_[i]}, row, &curve[cases[i].k]);
        }
        for (const ExternalSolver* e : solvers_.external)
            if (e->precision == precision && e->takes(cases[0].shape))
                grade_external(*e, cases, family, shape, out);
        note_oracle_steps(out);
        return out;
    }

  private:
    // The library's cases are posed its way, its reference solved for what it saw (under its
    // declared conventions), and it is asked only what its contract defines.
    void grade_external(const ExternalSolver& e, const std::vector<Case>& cases,
                        const std::string& family, const std::string& shape, Report& out) {
        Row& row = out.rows[{family, shape, e.name}];
        auto unrepresented = [&](const std::string& why) {
            ++row.unrepresented;
            if (!why.empty()) ++row.unrepresented_why[why];
        };
        // The oracle's answer stands when the library saw the case as it is and answers all.
        bool as_is = answers_as_oracle(e);
        posed_.clear();
        from_.clear();
        references_.clear();
        std::string why;
        for (std::size_t i = 0; i < cases.size(); ++i) {
            std::optional<Case> p = posed_for(e, cases[i], &why);
            if (!p) {
                unrepresented(why);
                continue;
            }
            Reference ref;
            if (as_is)
                ref.result = oracle_[i];
            else
                ref = reference_for(e, *p);
            if (!ref.unrepresented.empty()) {
                unrepresented(ref.unrepresented);
            } else if (!ref.not_asked.empty()) {
                ++row.not_asked[ref.not_asked];
            } else {
                posed_.push_back(std::move(*p));
                from_.push_back(i);
                references_.push_back(std::move(ref));
            }
        }
        if (posed_.empty()) return;
        double ns = 0;
        {
            // Another library's thread safety is not known (nor declared by the plugin ABI), and
            // a plugin's worker answers one request at a time: one thread calls them at a time.
            static std::mutex one_at_a_time;
            std::lock_guard<std::mutex> lock(one_at_a_time);
            // A stop request while the library answers: none of its answers here are graded.
            if (!e.answer_all(posed_, answers_, &ns)) return;
        }
        if (ns > 0) row.ns.add(ns / double(posed_.size()));
        std::string label = reference_label(e);
        auto& curve = out.curves[{family, e.name}];
        for (std::size_t j = 0; j < posed_.size(); ++j) {
            ExternalAnswer& a = answers_[j];
            if (*a.environment) ++row.environment[a.environment];
            if (!a.result) {
                unrepresented(a.unrepresented);
                continue;
            }
            read_conventions(e, posed_[j], *a.result);
            const Reference& ref = references_[j];
            Grading what{e.points && ref.points, e.kinds && ref.kinds, e.parts && ref.parts};
            std::function<bool(const Result&)> tolerated = [&](const Result& got) {
                return within_tolerance(e, posed_[j], got);
            };
            grade({posed_[j], e.name, *a.result, ref.result, what, label,
                   e.tolerance.none() ? nullptr : &tolerated},
                  row, &curve[posed_[j].k]);
        }
    }

    const Solvers& solvers_;
    bool batch_;
    std::vector<Result> oracle_, got_;
    std::vector<Case> posed_;
    std::vector<std::size_t> from_;
    std::vector<Reference> references_;
    std::vector<ExternalAnswer> answers_;
};

// A chunk of a run: cases [begin, end) of one source of cases (a campaign group's cases of this
// shard, a cases file's group), posed in one precision. The cases are made by the worker that
// grades it.
struct Chunk {
    std::size_t source;
    std::uint64_t begin, end;
    Precision precision;
};

// Where chunks come from: the cases of chunk c, and the family and shape its rows are under.
struct ChunkSource {
    std::function<std::vector<Case>(const Chunk&)> cases;
    std::function<std::pair<std::string, std::string>(std::size_t)> names;
};

// Grades the chunks on o.threads workers, each with a grader of its own, and merges their
// statistics into rep in chunk order (so the report does not depend on the number of threads),
// saving as it goes; marks rep complete or stopped.
void grade_chunks(const Options& o, const Solvers& solvers, bool batch,
                  const std::vector<Chunk>& chunks, const ChunkSource& source,
                  std::uint64_t total_cases, Report& rep) {
    auto start = std::chrono::steady_clock::now();
    Saver saver(o);
    saver.begin(rep);
    for (const ExternalSolver* e : solvers.external)
        if (e->own_output) e->own_output->clear();
    ProgressCount progress(o, total_cases, start);
    struct Graded {
        Report stats;
        std::uint64_t cases = 0;
    };
    std::mutex graders_lock;
    std::map<std::thread::id, ChunkGrader> graders;
    auto grader = [&]() -> ChunkGrader& {
        std::lock_guard<std::mutex> lock(graders_lock);
        return graders.try_emplace(std::this_thread::get_id(), solvers, batch).first->second;
    };
    // Memory that runs out while grading ends the run with what it measured, saved and marked
    // stopped, and a named error: never a report left saying "running".
    try {
        in_order<Graded>(
            chunks.size(), threads_for(o.threads),
            [&](std::size_t i) {
                const Chunk& c = chunks[i];
                std::vector<Case> cases = source.cases(c);
                Graded g;
                g.cases = cases.size();
                if (!cases.empty()) {
                    auto [family, shape] = source.names(c.source);
                    g.stats = grader().grade_chunk(cases, c.precision, family, shape);
                }
                return g;
            },
            [&](std::size_t, Graded&& g) {
                rep.merge_statistics(g.stats);
                progress.advance(g.cases);
                saver.maybe_save(rep, start);
            },
            [] { return stop_requested(); });
    } catch (const std::bad_alloc&) {
        graders.clear(); // their scratch space, for the save
        rep.status = Status::stopped;
        saver.end(rep, o, start);
        throw out_of_memory_grading(o);
    }
    for (const ExternalSolver* e : solvers.external)
        note_worker(rep.external[e->name], *e);
    rep.status = stop_requested() ? Status::stopped : Status::complete;
    bool out_of_memory = memory_low; // while grading (the report's writing says its own)
    if (stop_requested() && !out_of_memory && o.notice)
        o.notice("stopped early; writing what was measured");
    saver.end(rep, o, start);
    if (out_of_memory) throw out_of_memory_grading(o);
}

// Every solver on the cases of a cases file, grouped by family, shape and precision (in the
// order the file first names them), in chunks.
Report solve_cases_file(const Options& o, const Solvers& solvers, Report rep) {
    std::vector<Case> all = read_cases(o);
    rep.cases_file = o.cases_file, rep.cases_count = all.size();
    rep.seed = 0, rep.cases_per_group = 0;
    rep.families.clear(), rep.shapes.clear();
    std::vector<std::tuple<std::string, std::string, Precision>> order;
    std::map<std::tuple<std::string, std::string, Precision>, std::vector<Case>> groups;
    for (Case& c : all) {
        std::string family = c.family.empty() ? "cases" : c.family;
        std::string shape = shape_name(c.shape);
        if (std::find(rep.families.begin(), rep.families.end(), family) == rep.families.end())
            rep.families.push_back(family);
        if (std::find(rep.shapes.begin(), rep.shapes.end(), shape) == rep.shapes.end())
            rep.shapes.push_back(shape);
        auto key = std::make_tuple(family, shape, c.precision);
        auto [it, fresh] = groups.try_emplace(key);
        if (fresh) order.push_back(key);
        it->second.push_back(std::move(c));
    }
    bool batch = batch_wanted(o);
    ChunkGrader probe(solvers, batch);
    std::vector<Chunk> chunks;
    std::uint64_t total = 0;
    for (std::size_t g = 0; g < order.size(); ++g) {
        const std::vector<Case>& group = groups[order[g]];
        total += group.size();
        for (std::uint64_t begin = 0; begin < group.size(); begin += chunk_size)
            chunks.push_back({g, begin, std::min<std::uint64_t>(group.size(), begin + chunk_size),
                              std::get<2>(order[g])});
    }
    ChunkSource source{[&](const Chunk& c) {
                           const std::vector<Case>& group = groups.at(order[c.source]);
                           if (!probe.wanted(c.precision)) return std::vector<Case>();
                           return std::vector<Case>(group.begin() + long(c.begin),
                                                    group.begin() + long(c.end));
                       },
                       [&](std::size_t g) {
                           return std::pair{std::get<0>(order[g]), std::get<1>(order[g])};
                       }};
    grade_chunks(o, solvers, batch, chunks, source, total, rep);
    return rep;
}

} // namespace

Report run(const Options& o) {
    return run(o, {});
}

Report run(const Options& o, const std::vector<ExternalSolver>& external) {
    check_shard(o);
    if (!o.results_file.empty() && o.cases_file.empty())
        throw std::invalid_argument("audit: a results file is graded against its cases file");
    if (!o.results_file.empty()) return grade_results(o);
    StopOnSignal stop; // before any work: a stop while the chunks are laid out ends the run too
    Report rep;
    fill_provenance(rep, o);
    Solvers solvers = solvers_of(o, external);
    rep.solvers = solvers.names;
    bool batch = batch_wanted(o);
    if (batch) rep.solvers.emplace_back(batch_name);
    for (const ExternalSolver* e : solvers.external) {
        if (std::string p = declaration_problem(*e); !p.empty()) throw std::invalid_argument(p);
        rep.external[e->name] = describe(*e);
    }
    if (!o.cases_file.empty()) return solve_cases_file(o, solvers, rep);
    for (Family f : families_of(o))
        rep.families.emplace_back(family_name(f));
    rep.shard_marks[o.shard] = shard_mark(o);

    // Each solver answers the family's cases posed in its own precision: the double solvers (and
    // batch) binary64 cases, the float solvers binary32 cases, each graded in its own ulps.
    ChunkGrader probe(solvers, batch);
    std::vector<Group> groups = groups_of(o);
    // Case i of group g belongs to shard (g N + i) mod shards. A shard lays out its own cases
    // only, as j = 0, 1, ... for i = offset + j shards: its time and memory are its cases', not
    // the campaign's (a shard of a 10^9-case campaign walks no index it does not grade).
    std::uint64_t k = std::uint64_t(o.shards), r = std::uint64_t(o.shard);
    auto offset_of = [&](std::size_t g) { // the group's first index of this shard
        std::uint64_t first = std::uint64_t(g) * o.cases_per_group;
        return (r + k - first % k) % k;
    };
    std::vector<Chunk> chunks;
    std::uint64_t total = 0;
    for (std::size_t g = 0; g < groups.size(); ++g) {
        std::uint64_t offset = offset_of(g);
        std::uint64_t count =
            o.cases_per_group > offset ? (o.cases_per_group - offset + k - 1) / k : 0;
        for (std::uint64_t begin = 0; begin < count; begin += chunk_size)
            for (Precision precision : {Precision::binary64, Precision::binary32}) {
                if (!probe.wanted(precision)) continue;
                std::uint64_t end = std::min(count, begin + chunk_size);
                total += end - begin;
                chunks.push_back({g, begin, end, precision});
            }
    }
    ChunkSource source{[&](const Chunk& c) {
                           const Group& grp = groups[c.source];
                           std::uint64_t offset = offset_of(c.source);
                           std::vector<Case> out;
                           out.reserve(c.end - c.begin);
                           for (std::uint64_t j = c.begin; j < c.end; ++j)
                               out.push_back(make_case(grp.family, grp.shape, grp.range, o.seed,
                                                       offset + j * k, o.frames, c.precision));
                           return out;
                       },
                       [&](std::size_t g) {
                           return std::pair{std::string(family_name(groups[g].family)),
                                            shape_name_at(groups[g].shape)};
                       }};
    grade_chunks(o, solvers, batch, chunks, source, total, rep);
    return rep;
}

} // namespace linequad::audit
