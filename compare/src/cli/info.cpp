// linequad solvers, version, and the plugin worker (the mode a plugin's worker process runs in).
#include "cli/cli.hpp"

#include "linequad/registry.hpp"

#include "io/jsonl.hpp"
#include "peers/peers.hpp"

#include <cstring>

namespace linequad::cli {

int print_version() {
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

Command version_command(CLI::App& app) {
    CLI::App* c = app.add_subcommand("version", "Version, compiler and floating-point flags.");
    return {c, [](const std::string&) { return print_version(); }, {}};
}

Command solvers_command(CLI::App& app) {
    CLI::App* c = app.add_subcommand("solvers", "List the solver names.");
    auto run = [](const std::string&) {
        jsonl::Output out;
        auto line = [&](std::string name, const std::string& summary) {
            out.line(name + std::string(name.size() < 9 ? 9 - name.size() : 0, ' ') + " " +
                     summary);
        };
        for (const Solver& s : all_solvers())
            line(std::string(s.name), std::string(s.summary));
        for (const audit::ExternalSolver& e : peers::solvers())
            line(e.name, std::string("(peer library) ") + audit::answers_name(e.answers) + ", " +
                             audit::parametrisation_name(e.parametrisation) + ", " +
                             audit::surface_name(e.surface) + ": " + e.mapping);
        out.finish();
        return 0;
    };
    return {c, run, {}};
}

Command worker_command(CLI::App& app) {
    // The worker that runs a plugin's solvers for the process that started it (not for people:
    // no description, so --help leaves it out).
    auto plugin = std::make_shared<std::string>();
    CLI::App* c = app.add_subcommand("plugin-worker", "");
    c->group("");
    c->add_option("plugin", *plugin)->required();
    return {c, [plugin](const std::string&) { return audit::plugin_worker_main(*plugin); }, {}};
}

} // namespace linequad::cli
