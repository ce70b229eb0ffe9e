// The campaign loop, the grading of results files, and report provenance.
#include "linequad/audit.hpp"

#include "shape_types.hpp"

#include "linequad/batch.hpp"
#include "linequad/case_io.hpp"
#include "linequad/exact.hpp"
#include "linequad/registry.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <unordered_map>

namespace linequad::audit {

namespace {

std::atomic<bool> stop_requested{false};
extern "C" void on_signal(int) {
    stop_requested = true;
}

std::string run_command(const char* cmd) {
    std::string out;
    if (FILE* p = popen(cmd, "r")) {
        char buf[256];
        while (std::fgets(buf, sizeof buf, p))
            out += buf;
        pclose(p);
    }
    while (!out.empty() && (out.back() == '\n' || out.back() == '\r'))
        out.pop_back();
    return out;
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
    r.commit = run_command("git rev-parse --short HEAD 2>/dev/null");
    if (r.commit.empty()) r.commit = "unknown";
    if (!run_command("git status --porcelain --untracked-files=no 2>/dev/null").empty())
        r.commit += "+dirty";
    char date[64];
    std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&now));
    r.date = date;
    r.seed = o.seed, r.cases_per_group = o.cases_per_group;
    r.shard = o.shard, r.shards = o.shards;
}

// A progress bar with time left on a terminal; a plain line every tenth otherwise.
class Progress {
  public:
    explicit Progress(std::uint64_t total) : total_(total), tty_(isatty(STDERR_FILENO)) {}
    void advance(std::uint64_t n) {
        done_ += n;
        auto now = std::chrono::steady_clock::now();
        double elapsed = std::chrono::duration<double>(now - start_).count();
        double frac = total_ ? double(done_) / double(total_) : 1;
        if (tty_) {
            if (std::chrono::duration<double>(now - last_).count() < 0.2 && done_ < total_) return;
            last_ = now;
            int width = 40, filled = int(frac * width);
            double left = frac > 0 ? elapsed * (1 - frac) / frac : 0;
            std::fprintf(stderr, "\r[%.*s%*s] %5.1f%%  %llu/%llu cases  %.0fs left ", filled,
                         "########################################", width - filled, "", 100 * frac,
                         (unsigned long long)done_, (unsigned long long)total_, left);
            if (done_ >= total_) std::fputc('\n', stderr);
        } else if (int(frac * 10) > tenth_) {
            tenth_ = int(frac * 10);
            std::fprintf(stderr, "audit: %d%% (%llu/%llu cases, %.1fs)\n", tenth_ * 10,
                         (unsigned long long)done_, (unsigned long long)total_, elapsed);
        }
    }

  private:
    std::uint64_t total_, done_ = 0;
    bool tty_;
    int tenth_ = 0;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_ = start_;
};

struct Group {
    Family family;
    int shape;
    Range range;
};

std::vector<Group> groups_of(const Options& o) {
    std::vector<Family> families = o.families;
    if (families.empty())
        for (int f = 0; f < family_count; ++f)
            families.push_back(Family(f));
    std::vector<Group> out;
    for (Family f : families)
        for (int shape = 0; shape < int(shape_count); ++shape)
            if (family_applies(f, shape))
                for (Range r : {Range::line, Range::ray, Range::segment})
                    out.push_back({f, shape, r});
    return out;
}

std::vector<const Solver*> solvers_of(const Options& o) {
    std::vector<const Solver*> out;
    if (o.solvers.empty()) {
        for (const Solver& s : fast_solvers())
            out.push_back(find_solver(s.name));
        return out;
    }
    for (const std::string& name : o.solvers)
        if (const Solver* s = find_solver(name)) out.push_back(s);
    return out;
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

void finish(Report& rep, const Options& o, std::chrono::steady_clock::time_point start) {
    rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto& st = exact::rounding_stats();
    for (int i = 0; i < 8; ++i)
        rep.oracle_steps[i] = st.by_steps[i];
    if (o.out_dir.empty()) return;
    std::filesystem::create_directories(o.out_dir);
    write_json(rep, o.out_dir + "/report.json");
    write_markdown(rep, o.out_dir);
    if (o.plots) write_plots(rep, o.out_dir);
}

Report grade_results(const Options& o) {
    Report rep;
    fill_provenance(rep, o);
    auto start = std::chrono::steady_clock::now();
    std::unordered_map<std::string, Case> cases;
    std::unordered_map<std::string, bool> answered;
    std::ifstream in(o.cases_file);
    if (!in) throw std::runtime_error("cannot open cases file '" + o.cases_file + "'");
    std::string line, why;
    long n = 0;
    while (std::getline(in, line)) {
        ++n;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        Case c;
        if (!parse_case(line, &c, &why))
            throw std::runtime_error(o.cases_file + ": line " + std::to_string(n) + ": " + why);
        cases[c.id] = c;
    }
    std::ifstream res(o.results_file);
    if (!res) throw std::runtime_error("cannot open results file '" + o.results_file + "'");
    n = 0;
    while (std::getline(res, line)) {
        ++n;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        ParsedResult pr;
        if (!parse_result(line, &pr, &why)) {
            std::fprintf(stderr, "linequad: %s: line %ld: %s (skipped)\n", o.results_file.c_str(),
                         n, why.c_str());
            continue;
        }
        auto it = cases.find(pr.id);
        if (it == cases.end()) {
            std::fprintf(stderr, "linequad: %s: line %ld: no case with id %s (skipped)\n",
                         o.results_file.c_str(), n, pr.id.c_str());
            continue;
        }
        const Case& c = it->second;
        std::string solver = pr.solver.empty() ? "results" : pr.solver;
        if (std::find(rep.solvers.begin(), rep.solvers.end(), solver) == rep.solvers.end())
            rep.solvers.push_back(solver);
        answered[c.id + "/" + solver] = true;
        Result oracle = exact::intersect(c.shape, c.line);
        std::string family = c.family.empty() ? "cases" : c.family;
        Row& row = rep.rows[family + "/" + shape_name(c.shape) + "/" + solver];
        grade(c, solver, pr.result, oracle, row, &rep.curves[family + "/" + solver][c.k],
              pr.has_points);
    }
    // A case without an answer is a refusal.
    for (const std::string& solver : rep.solvers)
        for (const auto& [id, c] : cases)
            if (!answered.count(id + "/" + solver)) {
                std::string family = c.family.empty() ? "cases" : c.family;
                Row& row = rep.rows[family + "/" + shape_name(c.shape) + "/" + solver];
                // A refusal the oracle never makes (see parse_result).
                Result missing = Result::failure(ErrorCode::out_of_range, "no answer");
                grade(c, solver, missing, exact::intersect(c.shape, c.line), row, nullptr, false);
            }
    finish(rep, o, start);
    return rep;
}

} // namespace

void for_each_case(const Options& o, const std::function<void(const Case&)>& f) {
    std::uint64_t g = 0;
    for (const Group& grp : groups_of(o))
        for (std::uint64_t i = 0; i < o.cases_per_group; ++i, ++g)
            if (g % std::uint64_t(o.shards) == std::uint64_t(o.shard))
                f(make_case(grp.family, grp.shape, grp.range, o.seed, i));
}

Report run(const Options& o) {
    if (!o.results_file.empty()) return grade_results(o);
    Report rep;
    fill_provenance(rep, o);
    std::vector<const Solver*> solvers = solvers_of(o);
    for (const Solver* s : solvers)
        rep.solvers.emplace_back(s->name);
    bool batch = batch_wanted(o);
    if (batch) rep.solvers.emplace_back(batch_name);
    std::vector<Group> groups = groups_of(o);
    exact::rounding_stats() = {};
    stop_requested = false;
    auto old_int = std::signal(SIGINT, on_signal), old_term = std::signal(SIGTERM, on_signal);
    auto start = std::chrono::steady_clock::now(), last_save = start;

    Progress progress(groups.size() * o.cases_per_group / std::uint64_t(o.shards));
    constexpr std::uint64_t chunk = 256;
    std::vector<Case> cases;
    std::vector<Result> oracle, got;
    std::uint64_t g_base = 0;
    for (const Group& grp : groups) {
        for (std::uint64_t begin = 0; begin < o.cases_per_group && !stop_requested;
             begin += chunk) {
            std::uint64_t end = std::min(o.cases_per_group, begin + chunk);
            cases.clear();
            for (std::uint64_t i = begin; i < end; ++i)
                if ((g_base + i) % std::uint64_t(o.shards) == std::uint64_t(o.shard))
                    cases.push_back(make_case(grp.family, grp.shape, grp.range, o.seed, i));
            if (cases.empty()) continue;
            oracle.resize(cases.size());
            got.resize(cases.size());
            for (std::size_t i = 0; i < cases.size(); ++i)
                oracle[i] = exact::intersect(cases[i].shape, cases[i].line);
            for (const Solver* s : solvers) {
                Row& row =
                    rep.rows[std::string(family_name(grp.family)) + "/" +
                             shape_name_at(std::size_t(grp.shape)) + "/" + std::string(s->name)];
                auto t0 = std::chrono::steady_clock::now();
                for (std::size_t i = 0; i < cases.size(); ++i)
                    got[i] = (*s)(cases[i].shape, cases[i].line);
                auto t1 = std::chrono::steady_clock::now();
                row.ns.add(std::chrono::duration<double, std::nano>(t1 - t0).count() /
                           double(cases.size()));
                auto& curve =
                    rep.curves[std::string(family_name(grp.family)) + "/" + std::string(s->name)];
                for (std::size_t i = 0; i < cases.size(); ++i)
                    grade(cases[i], std::string(s->name), got[i], oracle[i], row,
                          &curve[cases[i].k]);
            }
            if (batch) {
                std::string family = family_name(grp.family);
                Row& row = rep.rows[family + "/" + shape_name_at(std::size_t(grp.shape)) + "/" +
                                    batch_name];
                row.ns.add(run_batch(cases, got));
                auto& curve = rep.curves[family + "/" + batch_name];
                for (std::size_t i = 0; i < cases.size(); ++i)
                    grade(cases[i], batch_name, got[i], oracle[i], row, &curve[cases[i].k]);
            }
            progress.advance(cases.size());
        }
        g_base += o.cases_per_group;
        if (stop_requested) break;
        // A long run never loses what it has: the JSON is rewritten every few seconds.
        auto now = std::chrono::steady_clock::now();
        if (!o.out_dir.empty() && std::chrono::duration<double>(now - last_save).count() > 5) {
            last_save = now;
            std::filesystem::create_directories(o.out_dir);
            rep.complete = false;
            write_json(rep, o.out_dir + "/report.json");
        }
    }
    rep.complete = !stop_requested;
    if (stop_requested) std::fprintf(stderr, "\naudit: stopped early; writing what was measured\n");
    std::signal(SIGINT, old_int), std::signal(SIGTERM, old_term);
    finish(rep, o, start);
    return rep;
}

} // namespace linequad::audit
