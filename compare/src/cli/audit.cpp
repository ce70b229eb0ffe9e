// linequad audit and linequad cases: a campaign's cases graded against the oracle into a report,
// or written out for someone else's solver.
#include "cli/cli.hpp"

#include "linequad/audit.hpp"
#include "linequad/case_io.hpp"

#include "io/jsonl.hpp"
#include "report/history.hpp"
#include "report/report_html.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <memory>
#include <optional>

#include <unistd.h>

namespace linequad::cli {

namespace {

struct CampaignArgs {
    std::string cases = "100000", seed = "1", shard = "0/1", out = "reports/latest";
    std::string cases_file, results_file, max_line_bytes = "1048576", families, solvers;
    std::string shapes, frames = "any", precision = "binary64", threads = "0";
    std::vector<std::string> plugins;
    std::string solver_timeout = "5";
    bool no_plots = false, check = false;
    std::string history, commit;     // the history database to append to, and under which commit
    std::vector<std::string> expect; // gates on solvers: SOLVER:METRIC<=VALUE

    audit::Options options() const;
};

audit::Options CampaignArgs::options() const {
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

void add_campaign_options(CLI::App* app, CampaignArgs& a) {
    app->add_option("--cases", a.cases, "cases per family, shape and range")
        ->type_name("N")
        ->check(WholeNumber(1, max_cases))
        ->capture_default_str();
    app->add_option("--seed", a.seed, "the campaign's seed")
        ->type_name("S")
        ->check(WholeNumber(0, UINT64_MAX))
        ->capture_default_str();
    app->add_option("--families", a.families,
                    "families to run (default: all): " + joined(family_names()))
        ->type_name("F[,F...]")
        ->check(names_in({"family", "families"}, family_names()));
    app->add_option("--shapes", a.shapes,
                    "shapes to build (default: all): " + joined(shape_names()))
        ->type_name("S[,S...]")
        ->check(names_in({"shape", "shapes"}, shape_names()));
    app->add_option("--frames", a.frames,
                    "the shapes' frames: any (oblique and sheared elliptic shapes), circular "
                    "(circular cross-sections), axis (circular, along a coordinate axis) or "
                    "aligned (along the coordinate axes, elliptic sections of distinct "
                    "semi-axes: VecGeom's and Geant4's elliptic solids)")
        ->type_name("any|circular|axis|aligned")
        ->check(CLI::Validator(
            [](const std::string& f) {
                Frames x;
                return parse_frames(f, &x) ? std::string()
                                           : "expected any, circular, axis or aligned";
            },
            ""))
        ->capture_default_str();
    app->add_option("--shard", a.shard, "run only shard K of N (K from 0)")
        ->type_name("K/N")
        ->check(CLI::Validator(
            [](const std::string& s) { return shard_error(s, nullptr, nullptr); }, ""))
        ->capture_default_str();
}

// The run's progress on standard error: a bar with the time left on a terminal, redrawn at most
// five times a second; elsewhere (a log, CI) a line at every tenth, with the time left.
void show_progress(audit::Options& o) {
    struct Shown {
        bool tty = ::isatty(STDERR_FILENO) != 0;
        int tenth = 0;
        double last = -1;
    };
    auto shown = std::make_shared<Shown>();
    o.progress = [shown](const audit::Progress& p) {
        double frac = p.total ? double(p.done) / double(p.total) : 1;
        bool last = p.done >= p.total;
        if (shown->tty) {
            if (p.seconds - shown->last < 0.2 && !last) return;
            shown->last = p.seconds;
            int width = 40, filled = int(frac * width);
            std::fprintf(stderr, "\r[%.*s%*s] %5.1f%%  %llu/%llu cases  %.0fs left ", filled,
                         "########################################", width - filled, "", 100 * frac,
                         (unsigned long long)p.done, (unsigned long long)p.total, p.seconds_left());
            if (last) std::fputc('\n', stderr);
        } else if (int(frac * 10) > shown->tenth) {
            shown->tenth = int(frac * 10);
            std::fprintf(stderr, "audit: %3d%% (%llu/%llu cases, %.1f s", shown->tenth * 10,
                         (unsigned long long)p.done, (unsigned long long)p.total, p.seconds);
            if (!last) std::fprintf(stderr, ", about %.0f s left", p.seconds_left());
            std::fprintf(stderr, ")\n");
        }
    };
    o.notice = [shown](const std::string& note) {
        std::fprintf(stderr, "%saudit: %s\n", shown->tty && shown->last >= 0 ? "\n" : "",
                     note.c_str());
    };
}

// One line per solver on standard output: cases, mismatches, t error. Returns how many results
// were graded.
std::uint64_t print_summary(const audit::Report& r) {
    std::uint64_t graded = 0;
    for (const audit::Verdict& v : audit::verdicts(r)) {
        graded += v.cases;
        std::printf("%s\n", audit::verdict_line(v).c_str());
    }
    if (std::fflush(stdout) != 0)
        throw std::runtime_error(std::string("cannot write standard output: ") +
                                 std::strerror(errno));
    return graded;
}

// The solvers that graded no case, each with why (what kept its cases from it, counted). A
// solver asked for that grades nothing is a mistake in the command (a plugin asked about shapes
// it does not take, a first-exit solver on families that never start inside), not a clean bill.
std::vector<std::string> graded_nothing(const audit::Report& r,
                                        const std::vector<audit::ExternalSolver>& ext) {
    std::vector<std::string> out;
    if (r.status == audit::Status::stopped) return out; // it may not have reached them yet
    for (const std::string& s : r.solvers) {
        audit::Row t = r.total(s);
        if (t.cases) continue;
        std::string why = "solver '" + s + "' graded no case";
        if (t.unrepresented) {
            why += ": " + std::to_string(t.unrepresented) + " could not be asked of it (";
            std::string reasons;
            for (const auto& [reason, n] : t.unrepresented_why)
                reasons += (reasons.empty() ? "" : "; ") + reason + ": " + std::to_string(n);
            why += (reasons.empty() ? std::string("no reason given") : reasons) + ")";
        } else if (const audit::ExternalSolver* e = find_external(ext, s)) {
            std::vector<std::string> names = shape_names();
            std::string takes;
            for (std::size_t i = 0; i < names.size(); ++i)
                if (e->takes_shape(i)) takes += (takes.empty() ? "" : ", ") + names[i];
            why += ": it takes none of the shapes asked for (" + joined(r.shapes) + "); it takes " +
                   (takes.empty() ? std::string("none") : takes);
        } else {
            why += ": the families, shapes and ranges asked for posed none to it";
        }
        if (const audit::ExternalSolver* e = find_external(ext, s); e && !e->plugin.empty())
            why += " (linequad solvers --plugin LIB says what a plugin's solvers take)";
        out.push_back(why);
    }
    return out;
}

// audit --check: 0 when every claim the README makes holds on what was graded.
int check_claims(const audit::Report& r, std::uint64_t graded) {
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
    return 0;
}

int run_audit(const CampaignArgs& a, const std::string& command) {
    audit::Options o = a.options();
    o.command = command;
    std::vector<audit::ExternalSolver> ext =
        external_solvers(a.plugins, a.solver_timeout, o.solvers);
    for (const std::string& name : o.solvers)
        if (std::string why = solver_error(name, true, ext); !why.empty())
            return fail("--solvers: " + why);
    // A gate on a solver the run will not grade is refused before the run, not after it.
    for (const std::string& text : a.expect) {
        audit::Expectation e;
        std::string why;
        audit::parse_expectation(text, &e, &why);
        if (std::string no = solver_error(e.solver, true, ext); !no.empty())
            return fail("--expect: " + no);
        if (!o.solvers.empty() &&
            std::find(o.solvers.begin(), o.solvers.end(), e.solver) == o.solvers.end())
            return fail("--expect: '" + e.solver + "' is not among --solvers");
    }
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
    show_progress(o);
    audit::Report r = audit::run(o, ext);
    if (history) {
        std::size_t n = history->add(r, a.commit);
        std::fprintf(stderr, "audit: %zu rows added to %s\n", n, a.history.c_str());
    }
    std::fprintf(stderr, "audit: %s/report.md and report.html (%.1f s)\n", o.out_dir.c_str(),
                 r.seconds);
    std::uint64_t graded = print_summary(r);
    // Nothing graded at all is one failure, said once (check_claims), not one per solver.
    std::vector<std::string> idle = graded ? graded_nothing(r, ext) : std::vector<std::string>{};
    for (const std::string& why : idle)
        std::fprintf(stderr, "audit: %s%s\n", a.check ? "" : "warning: ", why.c_str());
    if (a.check && !idle.empty()) return 1;
    if (a.check && check_claims(r, graded) != 0) return 1;
    if (!a.expect.empty() && r.status != audit::Status::stopped) {
        std::vector<audit::Expectation> gates;
        for (const std::string& text : a.expect) {
            audit::Expectation e;
            std::string why;
            audit::parse_expectation(text, &e, &why); // checked when the options were read
            gates.push_back(e);
        }
        std::vector<std::string> broken = audit::unmet(r, gates);
        for (const std::string& b : broken)
            std::fprintf(stderr, "audit --expect: %s\n", b.c_str());
        if (!broken.empty()) return 1;
        std::fprintf(stderr, "audit --expect: %zu held in every family\n", gates.size());
    }
    return r.status == audit::Status::stopped ? 130 : 0;
}

} // namespace

Command audit_command(CLI::App& app) {
    auto a = std::make_shared<CampaignArgs>();
    CLI::App* c = app.add_subcommand(
        "audit", "Grade solvers against the exact oracle over the case families: writes "
                 "DIR/report.json, report.md, report.html and figures. Or grade someone else's "
                 "answers (--cases-file with --results).");
    add_campaign_options(c, *a);
    c->add_option("--solvers", a->solvers,
                  "solvers: linequad's, the peer libraries built in (linequad solvers lists "
                  "them) and the plugins' (default: every fast one, batch, and the plugins')")
        ->type_name("S[,S...]");
    add_plugin_options(c, a->plugins, a->solver_timeout);
    c->add_option("--out", a->out, "the report's directory")
        ->type_name("DIR")
        ->capture_default_str();
    c->add_option("--threads", a->threads,
                  "worker threads (0: one per core); the report is the same for any number, "
                  "timings aside")
        ->type_name("N")
        ->check(WholeNumber(0, 1024))
        ->capture_default_str();
    c->add_flag("--no-plots", a->no_plots, "no figures");
    add_history_options(c, a->history, a->commit);
    c->add_flag("--check", a->check, "exit 1 if a solver breaks a claim the README makes for it");
    c->add_option("--expect", a->expect,
                  "a gate on a solver, held in every family it grades (repeatable): exit 1 "
                  "naming each family that breaks it. METRIC: misclassified (% of the cases "
                  "graded), t_bits_max or t_bits_p99 (log2(1 + ulps))")
        ->type_name("SOLVER:METRIC<=VALUE")
        ->check(CLI::Validator(
            [](const std::string& text) {
                audit::Expectation e;
                std::string why;
                return audit::parse_expectation(text, &e, &why) ? std::string() : why;
            },
            ""));
    CLI::Option* cases_file =
        c->add_option("--cases-file", a->cases_file,
                      "cases (JSON Lines) instead of the families: solved by the solvers, or "
                      "with --results, someone else's answers graded")
            ->type_name("FILE")
            ->check(CLI::ExistingFile);
    c->add_option("--results", a->results_file, "answers to those cases")
        ->type_name("FILE")
        ->check(CLI::ExistingFile)
        ->needs(cases_file);
    add_max_line_bytes(c, a->max_line_bytes, "the longest line read from those files");
    auto check = [a]() -> std::pair<std::string, std::string> {
        if (a->check && !a->results_file.empty())
            return {"--check", "checks linequad's own claims; it cannot grade a file"};
        return {};
    };
    return {c, [a](const std::string& command) { return run_audit(*a, command); }, check};
}

Command cases_command(CLI::App& app) {
    auto a = std::make_shared<CampaignArgs>();
    CLI::App* c = app.add_subcommand(
        "cases", "Write a campaign's cases (for your own solver to answer) to standard output.");
    add_campaign_options(c, *a);
    c->add_option("--precision", a->precision,
                  "the cases' format: binary64, or binary32 (every input a float, answers "
                  "graded in float ulps; the audit poses them to the float solvers)")
        ->type_name("binary64|binary32")
        ->check(CLI::IsMember({"binary64", "binary32"}))
        ->capture_default_str();
    auto run = [a](const std::string&) {
        jsonl::Output out;
        audit::for_each_case(a->options(), [&](const Case& c) { out.line(format_case(c)); });
        out.finish();
        return 0;
    };
    return {c, run, {}};
}

} // namespace linequad::cli
