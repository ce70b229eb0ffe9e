// linequad: solve cases with any solver; audit solvers against the exact oracle.
//
// Exit status: 0 all well; 1 the data has problems (malformed case lines, a broken claim, an
// incomplete merge, a diff that got worse); 2 the command cannot run (bad options, unreadable
// input, unwritable output); 130 an audit stopped early by a signal (its report says so).
#include "linequad/audit.hpp"
#include "linequad/audit_solver.hpp"
#include "linequad/case_io.hpp"
#include "linequad/exact.hpp"
#include "linequad/registry.hpp"
#include "linequad/scene_audit.hpp"
#include "linequad/spawn_audit.hpp"

#include "history.hpp"
#include "jsonl.hpp"
#include "peers/peers.hpp"
#include "plugin_worker.hpp"
#include "process.hpp"
#include "report_html.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <new>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

namespace {

using namespace linequad;

constexpr std::uint64_t max_cases = 1000000000; // per family, shape and range
constexpr std::uint64_t max_shards = 1000000;

// A decimal whole number in [lo, hi], or why not. CLI11's own conversion reads "-5" as 2^64 - 5
// and "010" as octal, so numbers are read here.
std::string whole_number(const std::string& text, std::uint64_t lo, std::uint64_t hi,
                         std::uint64_t* out) {
    std::uint64_t x = 0;
    const char* end = text.data() + text.size();
    auto [p, ec] = std::from_chars(text.data(), end, x);
    bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
    if (!digits || ec != std::errc() || p != end || x < lo || x > hi)
        return "expected a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
               ", not '" + text + "'";
    if (out) *out = x;
    return "";
}

CLI::Validator WholeNumber(std::uint64_t lo, std::uint64_t hi) {
    return CLI::Validator(
        [=](const std::string& text) { return whole_number(text, lo, hi, nullptr); },
        std::to_string(lo) + ".." + std::to_string(hi));
}

std::uint64_t to_whole(const std::string& text) {
    std::uint64_t x = 0;
    whole_number(text, 0, UINT64_MAX, &x); // already validated
    return x;
}

// A finite number in (0, hi], or why not (CLI11's own checks let "nan" through).
std::string positive_number(const std::string& text, double hi) {
    char* end = nullptr;
    double x = std::strtod(text.c_str(), &end);
    bool ok =
        !text.empty() && end == text.c_str() + text.size() && std::isfinite(x) && x > 0 && x <= hi;
    char most[32];
    std::snprintf(most, sizeof most, "%g", hi);
    return ok ? ""
              : "expected a number above 0 and at most " + std::string(most) + ", not '" + text +
                    "'";
}

CLI::Validator PositiveNumber(double hi) {
    return CLI::Validator([=](const std::string& t) { return positive_number(t, hi); }, "");
}

// "K/N": shard K of N.
std::string shard_error(const std::string& text, int* k, int* n) {
    std::size_t slash = text.find('/');
    std::uint64_t kk = 0, nn = 0;
    if (slash == std::string::npos ||
        !whole_number(text.substr(slash + 1), 1, max_shards, &nn).empty() ||
        !whole_number(text.substr(0, slash), 0, nn - 1, &kk).empty())
        return "expected K/N with 0 <= K < N <= " + std::to_string(max_shards) + ", not '" + text +
               "'";
    if (k) *k = int(kk), *n = int(nn);
    return "";
}

// The solvers from outside linequad this run knows: the peer libraries built in, then those of
// the plugins given (--plugin), loaded once.
std::vector<audit::ExternalSolver> external_solvers(const std::vector<std::string>& plugins,
                                                    double timeout_seconds) {
    std::vector<audit::ExternalSolver> out = peers::solvers();
    audit::PluginOptions po;
    po.program = process::self(); // the worker is this program in another mode
    po.timeout_seconds = timeout_seconds;
    for (const std::string& path : plugins)
        for (audit::ExternalSolver& e : audit::load_plugin(path, po)) {
            for (const audit::ExternalSolver& x : out)
                if (x.name == e.name)
                    throw std::invalid_argument(path + ": solver '" + e.name +
                                                "' is already defined (by " +
                                                (x.plugin.empty() ? "linequad" : x.plugin) + ")");
            if (find_solver(e.name))
                throw std::invalid_argument(path + ": solver '" + e.name +
                                            "' has the name of one of linequad's");
            out.push_back(std::move(e));
        }
    return out;
}

const audit::ExternalSolver* find_external(const std::vector<audit::ExternalSolver>& ext,
                                           const std::string& name) {
    for (const audit::ExternalSolver& e : ext)
        if (e.name == name) return &e;
    return nullptr;
}

std::string solver_error(const std::string& name, bool batch_too,
                         const std::vector<audit::ExternalSolver>& ext) {
    if (find_solver(name) || find_external(ext, name) || (batch_too && name == audit::batch_name))
        return "";
    return "no solver named '" + name + "' (see: linequad solvers)";
}

// "a,b,c": the names of a list option (one argument, so that a file after it stays a file).
std::vector<std::string> split_list(const std::string& list) {
    std::vector<std::string> out;
    std::size_t start = 0;
    for (;;) {
        std::size_t comma = list.find(',', start);
        out.push_back(list.substr(start, comma - start));
        if (comma == std::string::npos) return out;
        start = comma + 1;
    }
}

// A validator of a list option: each name must pass check (which says why not). ("all" for
// solve's --solver stands alone: it is not a name in a list.)
template <class Check>
CLI::Validator each_of_list(Check check) {
    return CLI::Validator(
        [check](const std::string& list) {
            for (const std::string& name : split_list(list))
                if (std::string why = check(name); !why.empty()) return why;
            return std::string();
        },
        "");
}

std::string joined(int argc, char** argv) {
    std::string s = "linequad";
    for (int i = 1; i < argc; ++i)
        s += std::string(" ") + argv[i];
    return s;
}

int fail(const std::string& msg) {
    std::fprintf(stderr, "linequad: %s\n", msg.c_str());
    return 2;
}

// ---- solve

struct SolveArgs {
    std::string solvers = "stable", need = "all", file = "-", max_line_bytes = "1048576";
    std::string solver_timeout = "5";
    std::vector<std::string> plugins;
    bool no_points = false;
};

// One of linequad's solvers, or one from outside posed its way, as the audit poses it (the case
// it sees may differ from the line given: see audit::posed_for), with only what it declares.
struct NamedSolver {
    const Solver* own = nullptr;
    const audit::ExternalSolver* external = nullptr;
    std::string name() const { return own ? std::string(own->name) : external->name; }
    std::string answer_line(const Case& c, Query q) const {
        if (own) return format_result(c.id, own->name, answer(*own, c, q), q.points);
        const audit::ExternalSolver& e = *external;
        auto unrepresented = [&](const std::string& why) {
            return format_failure(c.id, e.name, "unrepresented",
                                  why.empty() ? "the solver cannot represent this case" : why);
        };
        if (!e.takes(c.shape)) return unrepresented("the solver takes no such shape");
        Carries carries{q.points && e.points, e.kinds, e.parts};
        // A float solver is handed floats: a case that is not is refused, naming its field.
        if (Error bad = audit::input_problem(e, c); !bad.ok())
            return format_result(c.id, e.name, Result::failure(bad), carries);
        std::string why;
        std::optional<Case> posed = audit::posed_for(e, c, &why);
        if (!posed) return unrepresented(why);
        audit::ExternalAnswer a = e.answer(posed->shape, posed->line);
        if (*a.environment)
            std::fprintf(stderr,
                         "linequad: %s left the floating-point environment changed (%s); "
                         "it was put back\n",
                         e.name.c_str(), a.environment);
        if (!a.result) return unrepresented(a.unrepresented);
        return format_result(c.id, e.name, *a.result, carries);
    }
};

// What the plugins' solvers wrote on their standard output and error, on linequad's standard
// error (never mixed into its results), a few lines each.
void report_plugin_output(const std::vector<audit::ExternalSolver>& ext) {
    for (const audit::ExternalSolver& e : ext)
        if (e.worker && e.worker->output_bytes(e.worker_index))
            std::fprintf(stderr, "linequad: %s wrote %llu bytes of its own; the first lines:\n%s\n",
                         e.name.c_str(), (unsigned long long)e.worker->output_bytes(e.worker_index),
                         e.worker->output(e.worker_index).c_str());
}

// The scene a file has open: its shapes, and the scenes built from them when its first line
// arrives, one per solver that answers scenes.
struct OpenScene {
    SceneHeader header;
    std::vector<std::string> ids;
    std::unordered_set<std::string> known; // the ids, to refuse a repeated one in O(1)
    std::vector<Shape> shapes;
    std::string broken; // why its lines get no answer; empty if they do
    bool has_lines = false;
    std::optional<Scene> stable, correct;
};

// Scene lines are answered by Scene (stable, correct) and the oracle's scene (exact).
bool answers_scenes(std::string_view solver) {
    return solver == "stable" || solver == "correct" || solver == "exact";
}

std::string scene_answer_line(const std::string& solver, OpenScene& open, const SceneLine& l,
                              Query q) {
    if (!open.broken.empty())
        return format_failure(l.id, solver, "malformed_scene",
                              "scene " + open.header.id + ": " + open.broken);
    if (!answers_scenes(solver))
        return format_failure(l.id, solver, "scene_unsupported",
                              "solver '" + solver +
                                  "' answers one shape; scenes are answered by stable, correct "
                                  "and exact");
    SceneAnswer a;
    if (solver == "exact") {
        exact::intersect(open.shapes, l.line, q, a);
    } else {
        bool stable = solver == "stable";
        std::optional<Scene>& scene = stable ? open.stable : open.correct;
        if (!scene) scene.emplace(open.shapes, stable ? SceneSolver::stable : SceneSolver::correct);
        scene->intersect(l.line, q, a);
    }
    return format_scene_answer(l.id, solver, open.header, open.ids, a,
                               q.points && q.need != Need::any);
}

int run_solve(const SolveArgs& a) {
    std::vector<audit::ExternalSolver> ext =
        external_solvers(a.plugins, std::strtod(a.solver_timeout.c_str(), nullptr));
    std::vector<NamedSolver> solvers;
    bool every_solver = a.solvers == "all";
    if (every_solver) {
        for (const Solver& s : all_solvers())
            solvers.push_back({&s, nullptr});
        for (const audit::ExternalSolver& e : ext)
            solvers.push_back({nullptr, &e});
    } else {
        for (const std::string& name : split_list(a.solvers)) {
            if (std::string why = solver_error(name, false, ext); !why.empty())
                return fail("--solver: " + why);
            solvers.push_back({find_solver(name), find_external(ext, name)});
        }
    }
    Query query;
    query.need = a.need == "any" ? Need::any : a.need == "nearest" ? Need::nearest : Need::all;
    query.points = !a.no_points;
    std::size_t max_bytes = std::size_t(to_whole(a.max_line_bytes));

    jsonl::LineReader in(a.file, max_bytes);
    jsonl::Output out;
    std::string line, why;
    long errors = 0;
    Record rec;
    // A scene is all or nothing: its lines are answered when it closes (at the next scene, a
    // single case or the end of the file), and not one of them if any record inside it was
    // malformed, whatever it was meant as (a mistyped shape reads as a broken single case). What
    // is written while it is open waits too, so that the output keeps the input's order.
    std::optional<OpenScene> open;
    struct Pending {
        std::string text;                    // a line to write as it is, or
        std::optional<SceneLine> scene_line; // a scene's line, answered when the scene closes
    };
    std::vector<Pending> pending;
    auto write = [&](std::string text) {
        if (open)
            pending.push_back({std::move(text), std::nullopt});
        else
            out.line(text);
    };
    auto close_scene = [&] {
        if (!open) return;
        for (Pending& p : pending) {
            if (!p.scene_line) {
                out.line(p.text);
                continue;
            }
            for (const NamedSolver& s : solvers)
                if (!every_solver || answers_scenes(s.name()))
                    out.line(scene_answer_line(s.name(), *open, *p.scene_line, query));
        }
        pending.clear();
        open.reset();
    };
    for (;;) {
        auto status = in.next(&line);
        if (status == jsonl::LineReader::Status::end) break;
        if (status == jsonl::LineReader::Status::error) throw std::runtime_error(in.error());
        bool parsed = false;
        std::string at = "line " + std::to_string(in.number()) + ": ";
        if (status == jsonl::LineReader::Status::too_long) {
            rec = Record{};
            why = jsonl::too_long_message(in.number(), max_bytes);
        } else {
            if (jsonl::blank(line)) continue;
            try {
                parsed = parse_record(line, &rec, &why);
                if (!parsed) why = at + why;
            } catch (const std::bad_alloc&) {
                rec = Record{};
                why = at + "out of memory while reading it";
            }
        }
        if (parsed && rec.kind == RecordKind::scene_line && !open) {
            parsed = false;
            why = at + "field \"shape\": missing (a line needs a shape, or a scene before it)";
        }
        if (parsed && rec.kind == RecordKind::scene_shape && !open) {
            parsed = false;
            why = at + "field \"shape_id\": no scene is open (a {\"scene\": id} line first)";
        }
        if (parsed && rec.kind == RecordKind::scene_shape) {
            OpenScene& o = *open;
            if (o.has_lines) {
                parsed = false;
                why = at + "shape " + rec.shape.id + " comes after the scene's lines";
            } else if (!o.known.insert(rec.shape.id).second) {
                parsed = false;
                why = at + "field \"shape_id\": " + rec.shape.id + " is already in the scene";
            }
        }
        if (!parsed) {
            // A broken scene header opens a broken scene, so that its shapes join no other.
            if (rec.kind == RecordKind::scene) {
                close_scene();
                open.emplace();
                open->header = rec.scene;
            }
            if (open && open->broken.empty()) open->broken = why;
            ++errors;
            std::fprintf(stderr, "linequad: %s\n", why.c_str());
            for (const NamedSolver& s : solvers)
                write(format_failure(rec.id(), s.name(), "malformed_case", why));
            continue;
        }
        switch (rec.kind) {
        case RecordKind::scene:
            close_scene();
            open.emplace();
            open->header = rec.scene;
            break;
        case RecordKind::scene_shape:
            open->ids.push_back(rec.shape.id);
            open->shapes.push_back(rec.shape.shape);
            break;
        case RecordKind::scene_line:
            open->has_lines = true;
            pending.push_back({"", rec.line});
            break;
        default: // a single case ends the scene before it
            close_scene();
            for (const NamedSolver& s : solvers)
                out.line(s.answer_line(rec.single, query));
        }
    }
    close_scene();
    out.finish();
    report_plugin_output(ext);
    return errors ? 1 : 0;
}

// ---- replay

struct ReplayArgs {
    std::string solver, file = "-", solver_timeout = "5";
    std::vector<std::string> plugins;
};

// Each case as a solver saw it in an audit (a worst case's first line): the solver's answer and
// the reference its grade used, as the report's worst cases show them. Nothing is posed again.
int run_replay(const ReplayArgs& a) {
    std::vector<audit::ExternalSolver> ext =
        external_solvers(a.plugins, std::strtod(a.solver_timeout.c_str(), nullptr));
    const Solver* own = find_solver(a.solver);
    const audit::ExternalSolver* theirs = find_external(ext, a.solver);
    bool batch = a.solver == audit::batch_name;
    if (!own && !theirs && !batch)
        return fail("--solver: no solver named '" + a.solver + "' (see: linequad solvers)");
    jsonl::LineReader in(a.file, jsonl::default_max_line_bytes);
    jsonl::Output out;
    std::string line, why;
    long errors = 0;
    for (;;) {
        auto status = in.next(&line);
        if (status == jsonl::LineReader::Status::end) break;
        if (status == jsonl::LineReader::Status::error) throw std::runtime_error(in.error());
        if (status == jsonl::LineReader::Status::too_long) {
            ++errors;
            std::fprintf(
                stderr, "linequad: %s\n",
                jsonl::too_long_message(in.number(), jsonl::default_max_line_bytes).c_str());
            continue;
        }
        if (jsonl::blank(line)) continue;
        Case c;
        if (!parse_case(line, &c, &why)) {
            ++errors;
            std::fprintf(stderr, "linequad: line %ld: %s\n", in.number(), why.c_str());
            continue;
        }
        for (const std::string& l : audit::replay_lines(a.solver, own, theirs, c))
            out.line(l);
    }
    out.finish();
    report_plugin_output(ext);
    return errors ? 1 : 0;
}

// ---- audit and cases

struct CampaignArgs {
    std::string cases = "100000", seed = "1", shard = "0/1", out = "reports/latest";
    std::string cases_file, results_file, max_line_bytes = "1048576", families, solvers;
    std::string shapes, frames = "any", precision = "binary64", threads = "0";
    std::vector<std::string> plugins;
    std::string solver_timeout = "5";
    bool no_plots = false, check = false;
    std::string history, commit; // the history database to append to, and under which commit

    audit::Options options() const {
        audit::Options o;
        o.cases_per_group = to_whole(cases);
        o.seed = to_whole(seed);
        shard_error(shard, &o.shard, &o.shards);
        if (!families.empty())
            for (const std::string& f : split_list(families)) {
                Family x;
                parse_family(f, &x);
                o.families.push_back(x);
            }
        if (!shapes.empty()) { // in the order of linequad::Shape, once each
            for (const std::string& s : split_list(shapes))
                o.shapes.push_back(shape_named(s));
            std::sort(o.shapes.begin(), o.shapes.end());
            o.shapes.erase(std::unique(o.shapes.begin(), o.shapes.end()), o.shapes.end());
        }
        parse_frames(frames, &o.frames);
        o.precision = precision == "binary32" ? Precision::binary32 : Precision::binary64;
        if (!solvers.empty()) o.solvers = split_list(solvers);
        o.out_dir = out;
        o.plots = !no_plots;
        o.threads = int(to_whole(threads));
        o.cases_file = cases_file, o.results_file = results_file;
        o.max_line_bytes = std::size_t(to_whole(max_line_bytes));
        return o;
    }
};

void add_campaign_options(CLI::App* app, CampaignArgs& a) {
    app->add_option("--cases", a.cases, "cases per family, shape and range")
        ->type_name("N")
        ->check(WholeNumber(1, max_cases))
        ->capture_default_str();
    app->add_option("--seed", a.seed, "the campaign's seed")
        ->type_name("S")
        ->check(WholeNumber(0, UINT64_MAX))
        ->capture_default_str();
    app->add_option("--families", a.families, "families to run (default: all)")
        ->type_name("F[,F...]")
        ->check(each_of_list([](const std::string& f) {
            Family x;
            return parse_family(f, &x) ? std::string() : "no family named '" + f + "'";
        }));
    app->add_option("--shapes", a.shapes, "shapes to build (default: all)")
        ->type_name("S[,S...]")
        ->check(each_of_list([](const std::string& s) {
            return shape_named(s) >= 0 ? std::string() : "no shape named '" + s + "'";
        }));
    app->add_option("--frames", a.frames,
                    "the shapes' frames: any (oblique and sheared elliptic shapes), circular "
                    "(circular cross-sections) or axis (circular, along a coordinate axis)")
        ->type_name("any|circular|axis")
        ->check(CLI::Validator(
            [](const std::string& f) {
                Frames x;
                return parse_frames(f, &x) ? std::string() : "expected any, circular or axis";
            },
            ""))
        ->capture_default_str();
    app->add_option("--shard", a.shard, "run only shard K of N (K from 0)")
        ->type_name("K/N")
        ->check(CLI::Validator(
            [](const std::string& s) { return shard_error(s, nullptr, nullptr); }, ""))
        ->capture_default_str();
}

int run_audit(const CampaignArgs& a, const std::string& command) {
    audit::Options o = a.options();
    o.command = command;
    std::vector<audit::ExternalSolver> ext =
        external_solvers(a.plugins, std::strtod(a.solver_timeout.c_str(), nullptr));
    for (const std::string& name : o.solvers)
        if (std::string why = solver_error(name, true, ext); !why.empty())
            return fail("--solvers: " + why);
    // Without --solvers: linequad's own and the plugins' (the peer libraries when named).
    if (o.solvers.empty() && !a.plugins.empty()) {
        for (const Solver& s : fast_solvers())
            o.solvers.emplace_back(s.name);
        o.solvers.emplace_back(audit::batch_name);
        for (const audit::ExternalSolver& e : ext)
            if (!e.plugin.empty()) o.solvers.push_back(e.name);
    }
    if (o.solvers.empty()) ext.clear();
    // Opened before the run: a database it cannot use is refused before hours of work.
    std::optional<audit::History> history;
    if (!a.history.empty()) history.emplace(a.history);
    o.finish_with = audit::write_report_html;
    audit::Report r = audit::run(o, ext);
    if (history) {
        std::size_t n = history->add(r, a.commit);
        std::fprintf(stderr, "audit: %zu rows added to %s\n", n, a.history.c_str());
    }
    std::fprintf(stderr, "audit: %s/report.md and report.html (%.1f s)\n", o.out_dir.c_str(),
                 r.seconds);
    std::uint64_t graded = 0;
    for (const std::string& s : r.solvers) {
        audit::Row t = r.total(s);
        graded += t.cases;
        std::printf("%-10s cases %8llu  mismatched %6llu  t max %12s ulps  p99 %8.3g\n", s.c_str(),
                    (unsigned long long)t.cases, (unsigned long long)t.cases_mismatched,
                    t.t_max == UINT64_MAX ? "inf" : std::to_string(t.t_max).c_str(),
                    t.t_quantile(0.99));
    }
    if (std::fflush(stdout) != 0)
        throw std::runtime_error(std::string("cannot write standard output: ") +
                                 std::strerror(errno));
    if (a.check) {
        // A claim checked on nothing proves nothing.
        if (graded == 0) {
            std::fprintf(stderr, "audit --check: no case was graded, so no claim was checked\n");
            return 1;
        }
        std::vector<std::string> broken = audit::broken_claims(r);
        for (const std::string& b : broken)
            std::fprintf(stderr, "audit --check: %s\n", b.c_str());
        if (!broken.empty()) return 1;
        std::printf("audit --check: every claim holds on %llu graded results\n",
                    (unsigned long long)graded);
    }
    return r.status == audit::Status::stopped ? 130 : 0;
}

// ---- history

void add_history_options(CLI::App* app, std::string& history, std::string& commit) {
    CLI::Option* db =
        app->add_option("--history", history,
                        "append the report's summary to this SQLite database (linequad history)")
            ->type_name("DB");
    app->add_option("--commit", commit,
                    "the commit to record it under (default: linequad's own, as the report "
                    "names it): your solver's commit when you audit your solver")
        ->type_name("ID")
        ->needs(db);
}

struct HistoryArgs {
    std::string db, add, commit, solvers, family = "*", shape = "*", plot;
};

int run_history(const HistoryArgs& h) {
    if (!h.commit.empty() && h.add.empty()) return fail("history: --commit goes with --add");
    audit::History history(h.db);
    if (!h.add.empty()) {
        audit::Report r;
        std::string why;
        if (!audit::read_json(h.add, &r, &why)) return fail(why);
        std::size_t n = history.add(r, h.commit);
        std::fprintf(stderr, "history: %zu rows of %s added to %s\n", n, h.add.c_str(),
                     h.db.c_str());
    }
    std::vector<std::string> solvers =
        h.solvers.empty() ? history.solvers() : split_list(h.solvers);
    if (!h.plot.empty() && solvers.size() != 1)
        return fail("history: --plot draws one solver's trend (--solver S)");
    jsonl::Output out;
    for (const std::string& s : solvers) {
        std::vector<audit::HistoryPoint> points = history.trend(s, h.family, h.shape);
        out.line(audit::trend_markdown(points, s, h.family, h.shape));
        if (!h.plot.empty()) {
            if (points.empty()) return fail("history: no run of " + s + " to plot");
            std::string title = s + ": " + (h.family == "*" ? "every family" : h.family) + ", " +
                                (h.shape == "*" ? "every shape" : h.shape);
            if (!audit::plot_trend(points, title, h.plot)) return 1;
            std::fprintf(stderr, "history: %s\n", h.plot.c_str());
        }
    }
    out.finish();
    return 0;
}

int run_cases(const CampaignArgs& a) {
    jsonl::Output out;
    audit::for_each_case(a.options(), [&](const Case& c) { out.line(format_case(c)); });
    out.finish();
    return 0;
}

// ---- merge

int run_merge(const std::vector<std::string>& inputs, const std::string& out,
              const std::string& command, const std::string& history_path,
              const std::string& commit) {
    // merge never writes over an input: --out may not be the directory of a report it reads.
    namespace fs = std::filesystem;
    for (const std::string& input : inputs) {
        std::error_code ec;
        fs::path dir = fs::path(input).parent_path();
        if (dir.empty()) dir = ".";
        if (fs::exists(out, ec) && fs::equivalent(dir, out, ec))
            return fail("merge --out " + out + ": it holds " + input +
                        ", an input (merge never writes over an input; choose another directory)");
    }
    std::optional<audit::History> history;
    if (!history_path.empty()) history.emplace(history_path);
    audit::Report merged;
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        audit::Report r;
        std::string why;
        if (!audit::read_json(inputs[i], &r, &why)) return fail(why);
        if (i == 0) {
            if (r.from_cases_file())
                return fail(inputs[i] +
                            ": it grades a cases file; merge combines the shards of one "
                            "campaign");
            merged = std::move(r);
            continue;
        }
        if (std::string why = audit::unmergeable(merged, r); !why.empty())
            return fail(inputs[i] + ": " + why + " (merging into " + inputs[0] + ")");
        merged.merge(r);
    }
    merged.command = command;
    merged.run = audit::new_run_id();
    audit::OutputDirectory dir(out);
    dir.finish(merged, true, audit::write_report_html);
    std::fprintf(stderr, "merge: %zu reports into %s/report.md and report.html\n", inputs.size(),
                 out.c_str());
    if (history) {
        std::size_t n = history->add(merged, commit);
        std::fprintf(stderr, "merge: %zu rows added to %s\n", n, history_path.c_str());
    }
    if (merged.complete()) return 0;
    std::string missing;
    for (int k = 0; k < merged.shards; ++k)
        if (!std::binary_search(merged.shards_included.begin(), merged.shards_included.end(), k))
            missing += (missing.empty() ? "" : ", ") + std::to_string(k);
    std::fprintf(
        stderr, "merge: the campaign is incomplete:%s%s\n",
        missing.empty() ? "" : (" shards missing: " + missing + ";").c_str(),
        merged.status == audit::Status::complete
            ? ""
            : (std::string(" a shard's run is ") + audit::status_name(merged.status)).c_str());
    return 1;
}

// ---- diff

struct DiffArgs {
    std::string old_report, new_report, markdown_file = "-", junit_file;
    std::string max_growth = "0", p99_growth = "0", time_growth;
    bool any_campaign = false;
};

double to_real(const std::string& text) {
    return std::strtod(text.c_str(), nullptr); // already validated
}

int run_diff(const DiffArgs& a) {
    audit::Report old_report, new_report;
    std::string why;
    if (!audit::read_json(a.old_report, &old_report, &why)) return fail(why);
    if (!audit::read_json(a.new_report, &new_report, &why)) return fail(why);
    audit::DiffThresholds t;
    t.max_growth = to_real(a.max_growth);
    t.p99_growth = to_real(a.p99_growth);
    if (!a.time_growth.empty()) t.time_growth = to_real(a.time_growth);
    audit::Diff d = audit::diff(old_report, new_report, t);
    std::string md = audit::diff_markdown(d, a.old_report, a.new_report);
    if (a.markdown_file == "-") {
        jsonl::Output out;
        out.text(md);
        out.finish();
    } else {
        jsonl::write_file(a.markdown_file, md);
    }
    if (!a.junit_file.empty())
        jsonl::write_file(a.junit_file, audit::diff_junit(d, a.old_report, a.new_report));
    // A gate that compared other cases, or fewer, would pass on what it did not measure.
    if (!d.comparable() && !a.any_campaign) {
        std::fprintf(stderr,
                     "linequad: diff: %s%s%s; not a comparison of the same cases "
                     "(--any-campaign compares them anyway)\n",
                     d.campaigns.empty() ? "" : ("not the same campaign: " + d.campaigns).c_str(),
                     !d.campaigns.empty() && !d.incomplete.empty() ? "; " : "",
                     d.incomplete.c_str());
        return 1;
    }
    return d.worse() ? 1 : 0;
}

int run_version() {
    BuildInfo b = build_info();
    jsonl::Output out;
    out.line(std::string("linequad ") + b.version);
    out.line(std::string("compiler: ") + b.compiler);
    out.line(std::string("fast/ flags: ") + b.fast_flags);
    out.line(std::string("FP contraction in fast/: ") +
             (std::strstr(b.fast_flags, "-ffp-contract=off") ? "off" : "compiler default"));
    out.finish();
    return 0;
}

// A report to out_file, or standard output when none is given.
int write_markdown(const std::string& md, const std::string& out_file, const char* what) {
    if (out_file.empty()) {
        jsonl::Output out;
        out.text(md);
        out.finish();
    } else {
        jsonl::write_file(out_file, md);
        std::fprintf(stderr, "%s: %s\n", what, out_file.c_str());
    }
    return 0;
}

int run_spawn(const audit::SpawnAuditOptions& o, const std::string& out_file,
              const std::string& command) {
    return write_markdown(audit::spawn_report_markdown(audit::run_spawn_audit(o), o, command),
                          out_file, "spawn");
}

int run_scenes(const audit::SceneAuditOptions& o, const std::string& out_file,
               const std::string& command) {
    return write_markdown(audit::scene_report_markdown(audit::run_scene_audit(o), o, command),
                          out_file, "scenes");
}

int run_solvers() {
    jsonl::Output out;
    auto line = [&](std::string name, const std::string& summary) {
        out.line(name + std::string(name.size() < 9 ? 9 - name.size() : 0, ' ') + " " + summary);
    };
    for (const Solver& s : all_solvers())
        line(std::string(s.name), std::string(s.summary));
    for (const audit::ExternalSolver& e : peers::solvers())
        line(e.name, std::string("(peer library) ") + audit::answers_name(e.answers) + ", " +
                         audit::parametrisation_name(e.parametrisation) + ", " +
                         audit::surface_name(e.surface) + ": " + e.mapping);
    out.finish();
    return 0;
}

int main_checked(int argc, char** argv) {
    CLI::App app{"linequad: line-quadric intersection solvers, graded against an exact oracle"};
    app.require_subcommand(0, 1);
    bool version = false;
    app.add_flag("--version", version, "version, compiler and floating-point flags");

    SolveArgs solve;
    CLI::App* s = app.add_subcommand(
        "solve", "Solve every case of a JSON Lines file (or standard input): one result line per "
                 "case and solver. A malformed line gets an error result naming the line and the "
                 "field.");
    s->add_option("--solver", solve.solvers, "solvers, or all")
        ->type_name("S[,S...]")
        ->capture_default_str();
    s->add_option("--plugin", solve.plugins,
                  "a shared library of solvers (the C ABI of linequad/audit_plugin.h)")
        ->type_name("LIB.so")
        ->check(CLI::ExistingFile);
    s->add_option("--solver-timeout", solve.solver_timeout,
                  "seconds a plugin's call may take before it is stopped and answered as timed out")
        ->type_name("S")
        ->check(PositiveNumber(3600))
        ->capture_default_str();
    s->add_option("--need", solve.need, "what to find: any, nearest or all")
        ->type_name("WHAT")
        ->check(CLI::IsMember({"any", "nearest", "all"}))
        ->capture_default_str();
    s->add_flag("--no-points", solve.no_points, "leave the hit points out");
    s->add_option("--max-line-bytes", solve.max_line_bytes, "the longest line read")
        ->type_name("N")
        ->check(WholeNumber(64, std::uint64_t(1) << 30))
        ->capture_default_str();
    s->add_option("file", solve.file, "the cases (- or nothing: standard input)")
        ->type_name("FILE");

    CampaignArgs audit_args;
    CLI::App* a = app.add_subcommand(
        "audit", "Grade solvers against the exact oracle over the case families: writes "
                 "DIR/report.json, report.md and plots. Or grade someone else's answers "
                 "(--cases-file with --results).");
    add_campaign_options(a, audit_args);
    a->add_option("--solvers", audit_args.solvers,
                  "solvers: linequad's, the peer libraries built in (linequad solvers lists "
                  "them) and the plugins' (default: every fast one, batch, and the plugins')")
        ->type_name("S[,S...]");
    a->add_option("--plugin", audit_args.plugins,
                  "audit the solvers of a shared library (the C ABI of linequad/audit_plugin.h)")
        ->type_name("LIB.so")
        ->check(CLI::ExistingFile);
    a->add_option("--solver-timeout", audit_args.solver_timeout,
                  "seconds a plugin's call may take before it is stopped and counted as timed out")
        ->type_name("S")
        ->check(PositiveNumber(3600))
        ->capture_default_str();
    a->add_option("--out", audit_args.out, "the report's directory")
        ->type_name("DIR")
        ->capture_default_str();
    a->add_option("--threads", audit_args.threads,
                  "worker threads (0: one per core); the report is the same for any number, "
                  "timings aside")
        ->type_name("N")
        ->check(WholeNumber(0, 1024))
        ->capture_default_str();
    a->add_flag("--no-plots", audit_args.no_plots, "no figures");
    add_history_options(a, audit_args.history, audit_args.commit);
    a->add_flag("--check", audit_args.check,
                "exit 1 if a solver breaks a claim the README makes for it");
    CLI::Option* cases_file =
        a->add_option("--cases-file", audit_args.cases_file,
                      "cases (JSON Lines) instead of the families: solved by the solvers, or "
                      "with --results, someone else's answers graded")
            ->type_name("FILE")
            ->check(CLI::ExistingFile);
    CLI::Option* results =
        a->add_option("--results", audit_args.results_file, "answers to those cases")
            ->type_name("FILE")
            ->check(CLI::ExistingFile);
    results->needs(cases_file);
    a->add_option("--max-line-bytes", audit_args.max_line_bytes,
                  "the longest line read from those files")
        ->type_name("N")
        ->check(WholeNumber(64, std::uint64_t(1) << 30))
        ->capture_default_str();

    CampaignArgs cases_args;
    CLI::App* c = app.add_subcommand(
        "cases", "Write a campaign's cases (for your own solver to answer) to standard output.");
    add_campaign_options(c, cases_args);
    c->add_option("--precision", cases_args.precision,
                  "the cases' format: binary64, or binary32 (every input a float, answers "
                  "graded in float ulps; the audit poses them to the float solvers)")
        ->type_name("binary64|binary32")
        ->check(CLI::IsMember({"binary64", "binary32"}))
        ->capture_default_str();

    std::vector<std::string> inputs;
    std::string merge_out;
    CLI::App* m = app.add_subcommand(
        "merge", "Combine the shard reports of one campaign exactly (counts, maxima, "
                 "histograms); refuses reports of another campaign or a shard twice, and exits 1 "
                 "when shards are missing.");
    m->add_option("--out", merge_out, "the merged report's directory")
        ->type_name("DIR")
        ->required();
    std::string merge_history, merge_commit;
    add_history_options(m, merge_history, merge_commit);
    m->add_option("reports", inputs, "report.json files")
        ->type_name("REPORT.json")
        ->required()
        ->check(CLI::ExistingFile);

    DiffArgs diff;
    CLI::App* dcmd = app.add_subcommand(
        "diff", "Compare two reports family by family and solver by solver: what got worse (new "
                "misclassifications or bound violations, a larger max or p99 error, a slower "
                "median when --time-growth is given) and what got better. Exits 1 when anything "
                "got worse beyond the thresholds.");
    dcmd->add_option("old", diff.old_report, "the earlier report.json")
        ->type_name("OLD.json")
        ->required()
        ->check(CLI::ExistingFile);
    dcmd->add_option("new", diff.new_report, "the later report.json")
        ->type_name("NEW.json")
        ->required()
        ->check(CLI::ExistingFile);
    auto growth = CLI::Validator(
        [](const std::string& text) {
            char* end = nullptr;
            double x = std::strtod(text.c_str(), &end);
            bool ok =
                !text.empty() && end == text.c_str() + text.size() && std::isfinite(x) && x >= 0;
            return ok ? std::string() : "expected a fraction >= 0, not '" + text + "'";
        },
        "");
    dcmd->add_option("--max-growth", diff.max_growth,
                     "how much larger a max error may get: new <= old * (1 + F)")
        ->type_name("F")
        ->check(growth)
        ->capture_default_str();
    dcmd->add_option("--p99-growth", diff.p99_growth, "the same for the p99 error")
        ->type_name("F")
        ->check(growth)
        ->capture_default_str();
    dcmd->add_option("--time-growth", diff.time_growth,
                     "how much slower a median may get (default: times are shown, never fail)")
        ->type_name("F")
        ->check(growth);
    dcmd->add_flag("--any-campaign", diff.any_campaign,
                   "compare reports of different campaigns, or incomplete ones (said at the top "
                   "of the markdown); without it such a diff exits 1");
    dcmd->add_option("--markdown", diff.markdown_file, "where the markdown goes (- : stdout)")
        ->type_name("FILE")
        ->capture_default_str();
    dcmd->add_option("--junit", diff.junit_file, "also write JUnit XML here")->type_name("FILE");

    std::string html_dir;
    CLI::App* html = app.add_subcommand(
        "html", "Write DIR/report.html again from DIR/report.md and its figures (the audit and "
                "merge write it themselves).");
    html->add_option("dir", html_dir, "a report's directory")
        ->type_name("DIR")
        ->required()
        ->check(CLI::ExistingDirectory);

    HistoryArgs history_args;
    CLI::App* hist = app.add_subcommand(
        "history", "The audit's history across commits (a SQLite database that audit --history "
                   "and merge --history append to): add a report to it, print a solver's trend "
                   "as markdown, plot it.");
    hist->add_option("db", history_args.db, "the history database")->type_name("DB")->required();
    hist->add_option("--add", history_args.add, "append this report first")
        ->type_name("REPORT.json")
        ->check(CLI::ExistingFile);
    hist->add_option("--commit", history_args.commit,
                     "with --add: the commit to record it under (default: the report's)")
        ->type_name("ID");
    hist->add_option("--solver", history_args.solvers, "the solvers to show (default: every one)")
        ->type_name("S[,S...]");
    hist->add_option("--family", history_args.family, "one family (default: every family)")
        ->type_name("F");
    hist->add_option("--shape", history_args.shape, "one shape (default: every shape)")
        ->type_name("SHAPE");
    hist->add_option("--plot", history_args.plot, "draw the trend (one solver) as an SVG file")
        ->type_name("FILE.svg");

    // Read as text and checked here, as the audit's are (CLI11 reads "-1" as 2^64 - 1, "010" as
    // octal, and takes "nan" for a positive number).
    struct {
        std::string cases = "500", seed = "1", epsilon = "1e-4";
    } spawn_text;
    std::string spawn_out;
    CLI::App* sp = app.add_subcommand(
        "spawn", "Audit rays spawned from hits: how often each way of starting them (stable with "
                 "the usual epsilon, correct from the hit, spawn_ray's proven offset) finds the "
                 "surface it left again, graded against the oracle. Writes markdown.");
    sp->add_option("--cases", spawn_text.cases, "cases per family and shape")
        ->type_name("N")
        ->check(WholeNumber(1, std::uint64_t(1) << 32))
        ->capture_default_str();
    sp->add_option("--seed", spawn_text.seed, "the families' seed")
        ->type_name("S")
        ->check(WholeNumber(0, UINT64_MAX))
        ->capture_default_str();
    sp->add_option("--epsilon", spawn_text.epsilon, "the distance stable's rays skip")
        ->type_name("E")
        ->check(PositiveNumber(1e300))
        ->capture_default_str();
    sp->add_option("--out", spawn_out, "write the report here (default: standard output)")
        ->type_name("FILE.md");

    struct {
        std::string scenes = "40", lines = "25", seed = "1", families, cases_file, write_cases, out,
                    max_line_bytes = "16777216";
    } scene_args;
    CLI::App* sc = app.add_subcommand(
        "scenes", "Audit scenes (touching, nested, coaxial and stacked shapes, grids of thin rods "
                  "far out, rays spawned from hits): stable and correct scenes against the "
                  "oracle's exact order of hits. Writes markdown.");
    sc->add_option("--scenes", scene_args.scenes, "scenes per family")
        ->type_name("N")
        ->check(WholeNumber(1, 1000000))
        ->capture_default_str();
    sc->add_option("--lines", scene_args.lines, "lines per scene")
        ->type_name("N")
        ->check(WholeNumber(1, 100000))
        ->capture_default_str();
    sc->add_option("--seed", scene_args.seed, "the families' seed")
        ->type_name("S")
        ->check(WholeNumber(0, ~std::uint64_t(0)))
        ->capture_default_str();
    sc->add_option("--families", scene_args.families,
                   "families, comma separated (default: all): touching, nested, coaxial, "
                   "shared_rim, far_grid, spawned, from_hit")
        ->type_name("F[,F...]");
    sc->add_option("--cases-file", scene_args.cases_file,
                   "grade the scenes of this file (the case format) instead")
        ->type_name("FILE")
        ->check(CLI::ExistingFile);
    sc->add_option("--write-cases", scene_args.write_cases,
                   "write the scenes graded, in the case format (linequad solve reads them)")
        ->type_name("FILE");
    sc->add_option("--max-line-bytes", scene_args.max_line_bytes, "the longest line read")
        ->type_name("N")
        ->check(WholeNumber(64, std::uint64_t(1) << 30))
        ->capture_default_str();
    sc->add_option("--out", scene_args.out, "write the report here (default: standard output)")
        ->type_name("FILE.md");

    ReplayArgs replay;
    CLI::App* rp = app.add_subcommand(
        "replay", "Replay cases as a solver saw them in an audit (a report's worst cases): the "
                  "solver's answer and the reference its grade used, one line each per case. "
                  "Nothing is posed again.");
    rp->add_option("--solver", replay.solver, "the solver (linequad's, a peer's or a plugin's)")
        ->type_name("S")
        ->required();
    rp->add_option("--plugin", replay.plugins,
                   "a shared library of solvers (the C ABI of linequad/audit_plugin.h)")
        ->type_name("LIB.so")
        ->check(CLI::ExistingFile);
    rp->add_option("--solver-timeout", replay.solver_timeout, "seconds a plugin's call may take")
        ->type_name("S")
        ->check(PositiveNumber(3600))
        ->capture_default_str();
    rp->add_option("file", replay.file, "the cases (- or nothing: standard input)")
        ->type_name("FILE");

    // The worker that runs a plugin's solvers for the process that started it (not for people).
    std::string worker_plugin;
    CLI::App* worker = app.add_subcommand("plugin-worker", "");
    worker->group("");
    worker->add_option("plugin", worker_plugin)->required();

    CLI::App* list = app.add_subcommand("solvers", "List the solver names.");
    CLI::App* v = app.add_subcommand("version", "Version, compiler and floating-point flags.");

    try {
        app.parse(argc, argv);
        if (audit_args.check && !audit_args.results_file.empty())
            throw CLI::ValidationError("--check",
                                       "checks linequad's own claims; it cannot grade a file");
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) { // --help, on standard output
            app.exit(e);
            std::cout.flush();
            if (!std::cout) throw std::runtime_error("cannot write standard output");
            return 0;
        }
        std::fprintf(stderr, "linequad: %s\nrun 'linequad --help' for the commands and options\n",
                     e.what());
        return 2;
    }
    std::string command = joined(argc, argv);
    if (version || v->parsed()) return run_version();
    if (list->parsed()) return run_solvers();
    if (worker->parsed()) return audit::plugin_worker_main(worker_plugin);
    if (s->parsed()) return run_solve(solve);
    if (rp->parsed()) return run_replay(replay);
    if (a->parsed()) return run_audit(audit_args, command);
    if (c->parsed()) return run_cases(cases_args);
    if (m->parsed()) return run_merge(inputs, merge_out, command, merge_history, merge_commit);
    if (hist->parsed()) return run_history(history_args);
    if (sp->parsed()) {
        audit::SpawnAuditOptions o;
        o.cases = to_whole(spawn_text.cases);
        o.seed = to_whole(spawn_text.seed);
        o.epsilon = std::strtod(spawn_text.epsilon.c_str(), nullptr);
        return run_spawn(o, spawn_out, command);
    }
    if (sc->parsed()) {
        audit::SceneAuditOptions o;
        o.scenes = to_whole(scene_args.scenes);
        o.lines = int(to_whole(scene_args.lines));
        o.seed = to_whole(scene_args.seed);
        std::vector<std::string> families;
        if (!scene_args.families.empty()) families = split_list(scene_args.families);
        for (const std::string& name : families) {
            audit::SceneFamily f;
            if (!audit::parse_scene_family(name, &f))
                return fail(
                    "--families: no scene family named '" + name +
                    "' (touching, nested, coaxial, shared_rim, far_grid, spawned, from_hit)");
            o.families.push_back(f);
        }
        o.cases_file = scene_args.cases_file, o.write_cases = scene_args.write_cases;
        o.max_line_bytes = std::size_t(to_whole(scene_args.max_line_bytes));
        return run_scenes(o, scene_args.out, command);
    }
    if (dcmd->parsed()) return run_diff(diff);
    if (html->parsed()) {
        audit::write_report_html(html_dir);
        std::fprintf(stderr, "html: %s/report.html\n", html_dir.c_str());
        return 0;
    }
    std::fputs(app.help().c_str(), stderr);
    return 2;
}

} // namespace

int main(int argc, char** argv) {
    jsonl::guard_standard_descriptors();
    // A file-size limit makes a write fail (EFBIG, named like any write error, its temporary
    // file removed) instead of killing the process with nothing said.
    std::signal(SIGXFSZ, SIG_IGN);
    try {
        return main_checked(argc, argv);
    } catch (const std::bad_alloc&) {
        return fail("out of memory");
    } catch (const std::exception& e) {
        return fail(e.what());
    }
}
