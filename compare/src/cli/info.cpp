// linequad solvers, version, and the plugin worker (the mode a plugin's worker process runs in).
#include "cli/cli.hpp"

#include "linequad/families.hpp"
#include "linequad/registry.hpp"

#include "io/escape.hpp"
#include "io/jsonl.hpp"
#include "peers/peers.hpp"

#include <algorithm>

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

namespace {

// What a solver from outside declares, in words: how it is asked, and the shapes it takes.
std::string declared(const audit::ExternalSolver& e) {
    std::string shapes;
    std::vector<std::string> names = shape_names();
    for (std::size_t i = 0; i < names.size(); ++i)
        if (e.takes_shape(i)) shapes += (shapes.empty() ? "" : ",") + names[i];
    std::string out =
        std::string(audit::answers_name(e.answers)) + ", " +
        audit::parametrisation_name(e.parametrisation) + ", " + audit::surface_name(e.surface) +
        ", " + (e.precision == Precision::binary32 ? "binary32" : "binary64") +
        ", start inside: " + audit::start_inside_name(e.inside) +
        (e.contact_as_point ? ", a contact as its first point" : "") +
        (audit::conventions_text(e).empty() ? "" : ", " + audit::conventions_text(e)) +
        "; answers carry" + (e.points ? " points" : "") + (e.kinds ? " kinds" : "") +
        (e.parts ? " parts" : "") + (!e.points && !e.kinds && !e.parts ? " t alone" : "") +
        "; shapes " + (shapes.empty() ? "none" : shapes);
    return e.mapping.empty() ? out : out + ": " + e.mapping;
}

struct SolversArgs {
    std::vector<std::string> plugins;
    std::string solver_timeout = "5";
};

} // namespace

Command solvers_command(CLI::App& app) {
    auto a = std::make_shared<SolversArgs>();
    CLI::App* c = app.add_subcommand(
        "solvers", "List the solvers: linequad's, the peer libraries built in, and those of the "
                   "plugins given, each with what it declares.");
    add_plugin_options(c, a->plugins, a->solver_timeout);
    auto run = [a](const std::string&) {
        std::vector<audit::ExternalSolver> ext =
            external_solvers(a->plugins, a->solver_timeout, {"*"});
        jsonl::Output out;
        auto line = [&](std::string name, const std::string& summary) {
            out.line(name + std::string(name.size() < 9 ? 9 - name.size() : 0, ' ') + " " +
                     summary);
        };
        for (const Solver& s : all_solvers())
            line(std::string(s.name), std::string(s.summary));
        std::vector<std::string> peer_plugins;
        for (const peers::PluginPeer& p : peers::plugin_peers())
            peer_plugins.push_back(p.path);
        auto from = [&](const audit::ExternalSolver& e) {
            if (e.plugin.empty()) return std::string("(peer library) ");
            if (std::find(peer_plugins.begin(), peer_plugins.end(), e.plugin) != peer_plugins.end())
                return "(peer library, out of process: " + escape::shell_word(e.plugin) + ") ";
            return "(plugin " + escape::shell_word(e.plugin) + ") ";
        };
        for (const audit::ExternalSolver& e : ext)
            line(e.name, from(e) + declared(e));
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
