// linequad merge: the shard reports of one campaign combined exactly.
#include "cli/cli.hpp"

#include "linequad/audit.hpp"

#include "report/history.hpp"
#include "report/report_html.hpp"

#include <algorithm>
#include <filesystem>
#include <optional>

namespace linequad::cli {

namespace {

struct MergeArgs {
    std::vector<std::string> inputs;
    std::string out, history, commit;
};

// "" when --out is none of the inputs' directories (merge never writes over an input).
std::string over_an_input(const MergeArgs& a) {
    namespace fs = std::filesystem;
    for (const std::string& input : a.inputs) {
        std::error_code ec;
        fs::path dir = fs::path(input).parent_path();
        if (dir.empty()) dir = ".";
        if (fs::exists(a.out, ec) && fs::equivalent(dir, a.out, ec))
            return "merge --out " + a.out + ": it holds " + input +
                   ", an input (merge never writes over an input; choose another directory)";
    }
    return "";
}

// Says which shards are missing, or which shard did not complete; 1.
int incomplete(const audit::Report& merged) {
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

int run_merge(const MergeArgs& a, const std::string& command) {
    if (std::string why = over_an_input(a); !why.empty()) return fail(why);
    std::optional<audit::History> history;
    if (!a.history.empty()) history.emplace(a.history);
    audit::Report merged;
    for (std::size_t i = 0; i < a.inputs.size(); ++i) {
        audit::Report r;
        std::string why;
        if (!audit::read_json(a.inputs[i], &r, &why)) return fail(why);
        // Its cases must be the shards' it names (checked after what it differs in, which says
        // more): a copy relabelled as another shard is not.
        auto shards_own = [&]() -> std::string {
            std::string no = audit::shard_problem(r);
            return no.empty() ? "" : a.inputs[i] + ": " + no;
        };
        if (i == 0) {
            if (r.from_cases_file())
                return fail(a.inputs[i] +
                            ": it grades a cases file; merge combines the shards of one campaign");
            if (std::string no = shards_own(); !no.empty()) return fail(no);
            merged = std::move(r);
            continue;
        }
        if (std::string why = audit::unmergeable(merged, r); !why.empty())
            return fail(a.inputs[i] + ": " + why + " (merging into " + a.inputs[0] + ")");
        if (std::string no = shards_own(); !no.empty()) return fail(no);
        merged.merge(r);
    }
    merged.command = command;
    merged.run = audit::new_run_id();
    audit::OutputDirectory dir(a.out);
    dir.finish(merged, true, audit::write_report_html);
    std::fprintf(stderr, "merge: %zu reports into %s/report.md and report.html\n", a.inputs.size(),
                 a.out.c_str());
    if (history) {
        std::size_t n = history->add(merged, a.commit);
        std::fprintf(stderr, "merge: %zu rows added to %s\n", n, a.history.c_str());
    }
    return merged.complete() ? 0 : incomplete(merged);
}

} // namespace

Command merge_command(CLI::App& app) {
    auto a = std::make_shared<MergeArgs>();
    CLI::App* m = app.add_subcommand(
        "merge", "Combine the shard reports of one campaign exactly (counts, maxima, "
                 "histograms); refuses reports of another campaign or a shard twice, and exits 1 "
                 "when shards are missing.");
    m->add_option("--out", a->out, "the merged report's directory")->type_name("DIR")->required();
    add_history_options(m, a->history, a->commit);
    m->add_option("reports", a->inputs, "report.json files")
        ->type_name("REPORT.json")
        ->required()
        ->check(CLI::ExistingFile);
    return {m, [a](const std::string& command) { return run_merge(*a, command); }, {}};
}

} // namespace linequad::cli
