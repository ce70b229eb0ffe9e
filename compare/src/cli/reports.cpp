// linequad html, spawn and scenes: report.html written again, and the spawned-ray and scene
// audits, each written as markdown.
#include "cli/cli.hpp"

#include "linequad/scene_audit.hpp"
#include "linequad/spawn_audit.hpp"

#include "report/report_html.hpp"

namespace linequad::cli {

Command html_command(CLI::App& app) {
    auto dir = std::make_shared<std::string>();
    CLI::App* c = app.add_subcommand(
        "html", "Write DIR/report.html again from DIR/report.md and its figures (the audit and "
                "merge write it themselves).");
    c->add_option("dir", *dir, "a report's directory")
        ->type_name("DIR")
        ->required()
        ->check(CLI::ExistingDirectory);
    auto run = [dir](const std::string&) {
        audit::write_report_html(*dir);
        std::fprintf(stderr, "html: %s/report.html\n", dir->c_str());
        return 0;
    };
    return {c, run, {}};
}

Command spawn_command(CLI::App& app) {
    struct Args {
        std::string cases = "500", seed = "1", epsilon = "1e-4", out;
    };
    auto a = std::make_shared<Args>();
    CLI::App* c = app.add_subcommand(
        "spawn", "Audit rays spawned from hits: how often each way of starting them (stable with "
                 "the usual epsilon, correct from the hit, spawn_ray's proven offset) finds the "
                 "surface it left again, graded against the oracle. Writes markdown.");
    c->add_option("--cases", a->cases, "cases per family and shape")
        ->type_name("N")
        ->check(WholeNumber(1, std::uint64_t(1) << 32))
        ->capture_default_str();
    c->add_option("--seed", a->seed, "the families' seed")
        ->type_name("S")
        ->check(WholeNumber(0, UINT64_MAX))
        ->capture_default_str();
    c->add_option("--epsilon", a->epsilon, "the distance stable's rays skip")
        ->type_name("E")
        ->check(PositiveNumber(1e300))
        ->capture_default_str();
    c->add_option("--out", a->out, "write the report here (default: standard output)")
        ->type_name("FILE.md");
    auto run = [a](const std::string& command) {
        audit::SpawnAuditOptions o;
        o.cases = to_whole(a->cases);
        o.seed = to_whole(a->seed);
        o.epsilon = to_real(a->epsilon);
        return write_markdown(audit::spawn_report_markdown(audit::run_spawn_audit(o), o, command),
                              a->out, "spawn");
    };
    return {c, run, {}};
}

namespace {

struct SceneArgs {
    std::string scenes = "40", lines = "25", seed = "1", families, cases_file, write_cases, out,
                max_line_bytes = "16777216";
};

int run_scenes(const SceneArgs& a, const std::string& command) {
    audit::SceneAuditOptions o;
    o.scenes = to_whole(a.scenes);
    o.lines = int(to_whole(a.lines));
    o.seed = to_whole(a.seed);
    if (!a.families.empty())
        for (const std::string& name : split_list(a.families)) {
            audit::SceneFamily f;
            audit::parse_scene_family(name, &f); // validated
            o.families.push_back(f);
        }
    o.cases_file = a.cases_file, o.write_cases = a.write_cases;
    o.max_line_bytes = std::size_t(to_whole(a.max_line_bytes));
    return write_markdown(audit::scene_report_markdown(audit::run_scene_audit(o), o, command),
                          a.out, "scenes");
}

} // namespace

Command scenes_command(CLI::App& app) {
    auto a = std::make_shared<SceneArgs>();
    CLI::App* c = app.add_subcommand(
        "scenes", "Audit scenes (touching, nested, coaxial and stacked shapes, grids of thin rods "
                  "far out, rays spawned from hits): stable and correct scenes against the "
                  "oracle's exact order of hits. Writes markdown.");
    c->add_option("--scenes", a->scenes, "scenes per family")
        ->type_name("N")
        ->check(WholeNumber(1, 1000000))
        ->capture_default_str();
    c->add_option("--lines", a->lines, "lines per scene")
        ->type_name("N")
        ->check(WholeNumber(1, 100000))
        ->capture_default_str();
    c->add_option("--seed", a->seed, "the families' seed")
        ->type_name("S")
        ->check(WholeNumber(0, UINT64_MAX))
        ->capture_default_str();
    std::vector<std::string> scene_families;
    for (int f = 0; f < audit::scene_family_count; ++f)
        scene_families.emplace_back(audit::scene_family_name(audit::SceneFamily(f)));
    c->add_option("--families", a->families,
                  "families, comma separated (default: all): " + joined(scene_families))
        ->type_name("F[,F...]")
        ->check(names_in({"scene family", "scene families"}, scene_families));
    c->add_option("--cases-file", a->cases_file,
                  "grade the scenes of this file (the case format) instead")
        ->type_name("FILE")
        ->check(CLI::ExistingFile);
    c->add_option("--write-cases", a->write_cases,
                  "write the scenes graded, in the case format (linequad solve reads them)")
        ->type_name("FILE");
    add_max_line_bytes(c, a->max_line_bytes);
    c->add_option("--out", a->out, "write the report here (default: standard output)")
        ->type_name("FILE.md");
    return {c, [a](const std::string& command) { return run_scenes(*a, command); }, {}};
}

} // namespace linequad::cli
