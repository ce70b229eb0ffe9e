// linequad solve: every case of a file answered by the solvers named, and scenes' lines by the
// scene solvers, a result line each, in the file's order.
#include "cli/cli.hpp"

#include "linequad/case_io.hpp"
#include "linequad/exact.hpp"
#include "linequad/registry.hpp"
#include "linequad/scene.hpp"

#include "io/jsonl.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <unordered_set>

namespace linequad::cli {

namespace {

struct SolveArgs {
    std::string solvers = "stable", need = "all", file = "-", max_line_bytes = "1048576";
    std::string solver_timeout = "5", format = "hex";
    std::vector<std::string> plugins;
    bool no_points = false, summary = false;
};

// A result line for a person: its numbers (t, points, bounds, contact intervals) as JSON numbers
// in the shortest decimal that reads back to the same double, where the line has them as C99
// hex floats (exact, and what a program diffs). An infinite or NaN value stays a string, as JSON
// has no such number; the line still reads back as a result.
std::string in_decimal(const std::string& line) {
    jsonl::OrderedJson j = jsonl::OrderedJson::parse(line);
    auto number = [](jsonl::OrderedJson& v) {
        if (!v.is_string()) return;
        const std::string& text = v.get_ref<const std::string&>();
        char* end = nullptr;
        double x = std::strtod(text.c_str(), &end);
        if (end == text.c_str() + text.size() && std::isfinite(x)) v = x;
    };
    auto each = [&](jsonl::OrderedJson& v) {
        if (v.is_array())
            for (jsonl::OrderedJson& x : v)
                number(x);
        else
            number(v);
    };
    if (j.contains("on_surface")) each(j["on_surface"]);
    if (j.contains("hits"))
        for (jsonl::OrderedJson& h : j["hits"])
            for (const char* key : {"t", "p", "bound"})
                if (h.contains(key)) each(h[key]);
    return jsonl::dump(j);
}

// What the result lines said, for --summary: answers, and failures by code and message.
struct Tally {
    std::uint64_t lines = 0, answers = 0, with_hits = 0;
    std::map<std::pair<std::string, std::string>, std::uint64_t> failures; // (code, message)

    void add(const std::string& line) {
        jsonl::Json j = jsonl::Json::parse(line);
        ++lines;
        if (j.contains("code")) {
            ++failures[{j["code"].get<std::string>(), j["error"].get<std::string>()}];
        } else {
            ++answers;
            if (!j["hits"].empty() || !j["on_surface"].is_null()) ++with_hits;
        }
    }
    void print(std::FILE* to, std::size_t solvers) const {
        auto count = [](std::uint64_t n, const char* one, const char* many) {
            return std::to_string(n) + " " + (n == 1 ? one : many);
        };
        std::uint64_t failed = lines - answers;
        std::fprintf(to, "solve: %s from %s: %llu answered (%llu with a hit), %llu not%s\n",
                     count(lines, "result line", "result lines").c_str(),
                     count(solvers, "solver", "solvers").c_str(), (unsigned long long)answers,
                     (unsigned long long)with_hits, (unsigned long long)failed, failed ? ":" : "");
        for (const auto& [why, n] : failures)
            std::fprintf(to, "  %6llu  %s: %s\n", (unsigned long long)n, why.first.c_str(),
                         why.second.c_str());
    }
};

// One of linequad's solvers, or one from outside posed its way, as the audit poses it (the case
// it sees may differ from the line given: see audit::posed_for), with only what it declares.
struct NamedSolver {
    const Solver* own = nullptr;
    const audit::ExternalSolver* external = nullptr;
    std::string name() const { return own ? std::string(own->name) : external->name; }
    std::string answer_line(const Case& c, Query q) const;
};

std::string NamedSolver::answer_line(const Case& c, Query q) const {
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
                     "linequad: %s left the floating-point environment changed (%s); it was put "
                     "back\n",
                     e.name.c_str(), a.environment);
    if (!a.result) return unrepresented(a.unrepresented);
    return format_result(c.id, e.name, *a.result, carries);
}

// Scene lines are answered by Scene (stable, correct) and the oracle's scene (exact).
bool answers_scenes(std::string_view solver) {
    return solver == "stable" || solver == "correct" || solver == "exact";
}

// The scene a file has open: its shapes, and the scenes built from them when its first line is
// answered, one per solver that answers scenes.
struct OpenScene {
    SceneHeader header;
    std::vector<std::string> ids;
    std::unordered_set<std::string> known; // the ids, to refuse a repeated one in O(1)
    std::vector<Shape> shapes;
    std::string broken; // why its lines get no answer; empty if they do
    bool has_lines = false;
    std::optional<Scene> stable, correct;

    std::string answer_line(const std::string& solver, const SceneLine& l, Query q);
};

std::string OpenScene::answer_line(const std::string& solver, const SceneLine& l, Query q) {
    if (!broken.empty())
        return format_failure(l.id, solver, "malformed_scene",
                              "scene " + header.id + ": " + broken);
    if (!answers_scenes(solver))
        return format_failure(l.id, solver, "scene_unsupported",
                              "solver '" + solver +
                                  "' answers one shape; scenes are answered by stable, correct "
                                  "and exact");
    SceneAnswer a;
    if (solver == "exact") {
        exact::intersect(shapes, l.line, q, a);
    } else {
        bool is_stable = solver == "stable";
        std::optional<Scene>& scene = is_stable ? stable : correct;
        if (!scene) scene.emplace(shapes, is_stable ? SceneSolver::stable : SceneSolver::correct);
        scene->intersect(l.line, q, a);
    }
    return format_scene_answer(l.id, solver, header, ids, a, q.points && q.need != Need::any);
}

// A file's records in order. A scene is all or nothing: its lines are answered when it closes
// (at the next scene, a single case or the end of the file), and not one of them if any record
// inside it was malformed, whatever it was meant as (a mistyped shape reads as a broken single
// case). What is written while a scene is open waits with it, so that the output keeps the
// input's order.
class Records {
  public:
    Records(const std::vector<NamedSolver>& solvers, bool every_solver, Query q, bool decimal,
            Tally* tally)
        : solvers_(solvers), every_solver_(every_solver), query_(q), decimal_(decimal),
          tally_(tally) {}
    long errors() const { return errors_; }
    // A line that did not read (why names it) as what it was meant as.
    void malformed(const Record& rec, const std::string& why);
    // Why a record that read cannot stand where it is, or "".
    std::string misplaced(const Record& rec, const std::string& at);
    void take(const Record& rec);
    void close_scene();
    void finish(); // the last scene closed, the output flushed (a failure throws)

  private:
    void write(std::string text);
    void emit(const std::string& text); // a line out, now
    struct Pending {
        std::string text;                    // a line to write as it is, or
        std::optional<SceneLine> scene_line; // a scene's line, answered when the scene closes
    };
    const std::vector<NamedSolver>& solvers_;
    bool every_solver_;
    Query query_;
    bool decimal_;
    Tally* tally_; // or none
    std::optional<OpenScene> open_;
    std::vector<Pending> pending_;
    jsonl::Output out_;
    long errors_ = 0;
};

void Records::write(std::string text) {
    if (open_)
        pending_.push_back({std::move(text), std::nullopt});
    else
        emit(text);
}

void Records::emit(const std::string& text) {
    if (tally_) tally_->add(text);
    out_.line(decimal_ ? in_decimal(text) : text);
}

void Records::close_scene() {
    if (open_) {
        for (Pending& p : pending_) {
            if (!p.scene_line) {
                emit(p.text);
                continue;
            }
            for (const NamedSolver& s : solvers_)
                if (!every_solver_ || answers_scenes(s.name()))
                    emit(open_->answer_line(s.name(), *p.scene_line, query_));
        }
        pending_.clear();
        open_.reset();
    }
}

void Records::finish() {
    close_scene();
    out_.finish();
}

std::string Records::misplaced(const Record& rec, const std::string& at) {
    if (rec.kind == RecordKind::scene_line && !open_)
        return at + "field \"shape\": missing (a line needs a shape, or a scene before it)";
    if (rec.kind == RecordKind::scene_shape && !open_)
        return at + "field \"shape_id\": no scene is open (a {\"scene\": id} line first)";
    if (rec.kind == RecordKind::scene_shape && open_->has_lines)
        return at + "shape " + rec.shape.id + " comes after the scene's lines";
    if (rec.kind == RecordKind::scene_shape && !open_->known.insert(rec.shape.id).second)
        return at + "field \"shape_id\": " + rec.shape.id + " is already in the scene";
    return "";
}

void Records::malformed(const Record& rec, const std::string& why) {
    // A broken scene header opens a broken scene, so that its shapes join no other.
    if (rec.kind == RecordKind::scene) {
        close_scene();
        open_.emplace();
        open_->header = rec.scene;
    }
    if (open_ && open_->broken.empty()) open_->broken = why;
    ++errors_;
    std::fprintf(stderr, "linequad: %s\n", why.c_str());
    for (const NamedSolver& s : solvers_)
        write(format_failure(rec.id(), s.name(), "malformed_case", why));
}

void Records::take(const Record& rec) {
    switch (rec.kind) {
    case RecordKind::scene:
        close_scene();
        open_.emplace();
        open_->header = rec.scene;
        break;
    case RecordKind::scene_shape:
        open_->ids.push_back(rec.shape.id);
        open_->shapes.push_back(rec.shape.shape);
        break;
    case RecordKind::scene_line:
        open_->has_lines = true;
        pending_.push_back({"", rec.line});
        break;
    default: // a single case ends the scene before it
        close_scene();
        for (const NamedSolver& s : solvers_)
            emit(s.answer_line(rec.single, query_));
    }
}

int run_solve(const SolveArgs& a) {
    bool every_solver = a.solvers == "all";
    std::vector<audit::ExternalSolver> ext =
        external_solvers(a.plugins, a.solver_timeout,
                         every_solver ? std::vector<std::string>{"*"} : split_list(a.solvers));
    std::vector<NamedSolver> solvers;
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
    Tally tally;
    Records records(solvers, every_solver, query, a.format == "decimal",
                    a.summary ? &tally : nullptr);
    std::string why;
    Record rec;
    jsonl::each_line(
        in, max_bytes, &why,
        [&](const std::string& line, auto&& parse) {
            std::string at = "line " + std::to_string(in.number()) + ": ";
            bool parsed = parse([&] { return parse_record(line, &rec, &why); });
            why = parsed ? records.misplaced(rec, at) : at + why;
            if (!why.empty())
                records.malformed(rec, why);
            else
                records.take(rec);
        },
        [&](const std::string& too_long) { records.malformed(Record{}, too_long); });
    records.finish();
    report_plugin_output(ext);
    if (a.summary) tally.print(stderr, solvers.size());
    return records.errors() ? 1 : 0;
}

} // namespace

Command solve_command(CLI::App& app) {
    auto a = std::make_shared<SolveArgs>();
    CLI::App* s = app.add_subcommand(
        "solve", "Solve every case of a JSON Lines file (or standard input): one result line per "
                 "case and solver. A malformed line gets an error result naming the line and the "
                 "field.");
    s->add_option("--solver", a->solvers, "solvers, or all")
        ->type_name("S[,S...]")
        ->capture_default_str();
    add_plugin_options(s, a->plugins, a->solver_timeout);
    s->add_option("--need", a->need, "what to find: any, nearest or all")
        ->type_name("WHAT")
        ->check(CLI::IsMember({"any", "nearest", "all"}))
        ->capture_default_str();
    s->add_flag("--no-points", a->no_points, "leave the hit points out");
    s->add_option("--format", a->format,
                  "numbers as hex (C99 hex floats: exact, for programs) or decimal (JSON "
                  "numbers, the shortest decimal that reads back to the same double: for a "
                  "person)")
        ->type_name("hex|decimal")
        ->check(CLI::IsMember({"hex", "decimal"}))
        ->capture_default_str();
    s->add_flag("--summary", a->summary,
                "at the end, on standard error: how many answers, and the failures by reason");
    add_max_line_bytes(s, a->max_line_bytes);
    s->add_option("file", a->file, "the cases (- or nothing: standard input)")->type_name("FILE");
    return {s, [a](const std::string&) { return run_solve(*a); }, {}};
}

} // namespace linequad::cli
