// linequad replay: cases as a solver saw them in an audit (a report's worst cases), answered and
// graded again: the solver's answer and the reference its grade used. Nothing is posed again.
#include "cli/cli.hpp"

#include "linequad/case_io.hpp"
#include "linequad/registry.hpp"

#include "io/jsonl.hpp"

namespace linequad::cli {

namespace {

struct ReplayArgs {
    std::string solver, file = "-", solver_timeout = "5";
    std::vector<std::string> plugins;
};

int run_replay(const ReplayArgs& a) {
    std::vector<audit::ExternalSolver> ext =
        external_solvers(a.plugins, a.solver_timeout, {a.solver});
    const Solver* own = find_solver(a.solver);
    const audit::ExternalSolver* theirs = find_external(ext, a.solver);
    if (a.solver.find(',') != std::string::npos)
        return fail("--solver: replay takes one solver, not a list ('" + a.solver +
                    "'): a worst case is replayed as the solver that answered it saw it");
    if (!own && !theirs && a.solver != audit::batch_name)
        return fail("--solver: " + solver_error(a.solver, true, ext));
    jsonl::LineReader in(a.file, jsonl::default_max_line_bytes);
    jsonl::Output out;
    std::string line, why;
    long errors = 0;
    for (;;) {
        auto status = in.next(&line);
        if (status == jsonl::LineReader::Status::end) break;
        if (status == jsonl::LineReader::Status::error) throw std::runtime_error(in.error());
        Case c;
        if (status == jsonl::LineReader::Status::too_long) {
            why = jsonl::too_long_message(in.number(), jsonl::default_max_line_bytes);
        } else if (jsonl::blank(line)) {
            continue;
        } else if (parse_case(line, &c, &why)) {
            for (const std::string& l : audit::replay_lines(a.solver, own, theirs, c))
                out.line(l);
            continue;
        } else {
            why = "line " + std::to_string(in.number()) + ": " + why;
        }
        ++errors;
        std::fprintf(stderr, "linequad: %s\n", why.c_str());
    }
    out.finish();
    report_plugin_output(ext);
    return errors ? 1 : 0;
}

} // namespace

Command replay_command(CLI::App& app) {
    auto a = std::make_shared<ReplayArgs>();
    CLI::App* rp = app.add_subcommand(
        "replay", "Replay cases as a solver saw them in an audit (a report's worst cases): the "
                  "solver's answer and the reference its grade used, one line each per case. "
                  "Nothing is posed again.");
    rp->add_option("--solver", a->solver,
                   "the one solver to replay (linequad's, a peer's or a plugin's)")
        ->type_name("S")
        ->required();
    add_plugin_options(rp, a->plugins, a->solver_timeout);
    rp->add_option("file", a->file, "the cases (- or nothing: standard input)")->type_name("FILE");
    return {rp, [a](const std::string&) { return run_replay(*a); }, {}};
}

} // namespace linequad::cli
