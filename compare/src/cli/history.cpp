// linequad history: the audit's trend across commits, from the SQLite history.
#include "cli/cli.hpp"

#include "linequad/audit.hpp"

#include "io/jsonl.hpp"
#include "report/history.hpp"

namespace linequad::cli {

namespace {

struct HistoryArgs {
    std::string db, add, commit, solvers, family = "*", shape = "*", plot, format = "auto";
};

int run_history(const HistoryArgs& h) {
    if (!h.commit.empty() && h.add.empty()) return fail("history: --commit goes with --add");
    if (std::string no = output_is_input(h.plot, {h.db, h.add}); !no.empty())
        return fail("history: --plot: " + no);
    // Reading a trend needs no write access: a shared, read-only history can be read.
    audit::History history(h.db, h.add.empty() ? audit::History::Access::read_only
                                               : audit::History::Access::read_write);
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
        out.line(
            for_standard_output(audit::trend_markdown(points, s, h.family, h.shape), h.format));
        if (!h.plot.empty()) {
            if (points.empty()) return fail("history: no run of " + s + " to plot");
            std::string title = s + ": " + (h.family == "*" ? "every family" : h.family) + ", " +
                                (h.shape == "*" ? "every shape" : h.shape);
            audit::plot_trend(points, title, h.plot);
            std::fprintf(stderr, "history: %s\n", h.plot.c_str());
        }
    }
    out.finish();
    return 0;
}

} // namespace

Command history_command(CLI::App& app) {
    auto h = std::make_shared<HistoryArgs>();
    CLI::App* c = app.add_subcommand(
        "history", "The audit's history across commits (a SQLite database that audit --history "
                   "and merge --history append to): add a report to it, print a solver's trend "
                   "as markdown, plot it.");
    c->add_option("db", h->db, "the history database")->type_name("DB")->required();
    c->add_option("--add", h->add, "append this report first")
        ->type_name("REPORT.json")
        ->check(CLI::ExistingFile);
    c->add_option("--commit", h->commit,
                  "with --add: the commit to record it under (default: the report's)")
        ->type_name("ID");
    c->add_option("--solver", h->solvers, "the solvers to show (default: every one)")
        ->type_name("S[,S...]");
    c->add_option("--family", h->family, "one family (default: every family)")->type_name("F");
    c->add_option("--shape", h->shape, "one shape (default: every shape)")->type_name("SHAPE");
    c->add_option("--plot", h->plot, "draw the trend (one solver) as an SVG file")
        ->type_name("FILE.svg");
    add_format_option(c, h->format);
    return {c, [h](const std::string&) { return run_history(*h); }, {}};
}

} // namespace linequad::cli
