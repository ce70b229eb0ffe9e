// linequad diff: two reports compared family by family and solver by solver; a CI gate.
#include "cli/cli.hpp"

#include "linequad/audit.hpp"

#include "io/jsonl.hpp"

namespace linequad::cli {

namespace {

struct DiffArgs {
    std::string old_report, new_report, markdown_file = "-", junit_file, format = "auto";
    std::string max_growth = "0", p99_growth = "0", time_growth;
    bool any_campaign = false;
};

int run_diff(const DiffArgs& a) {
    audit::Report old_report, new_report;
    std::string why;
    for (const std::string& out : {a.markdown_file, a.junit_file})
        if (std::string no = output_is_input(out, {a.old_report, a.new_report}); !no.empty())
            return fail("diff: " + no);
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
        out.text(for_standard_output(md, a.format));
        out.finish();
    } else {
        jsonl::write_file(a.markdown_file, md);
    }
    if (!a.junit_file.empty())
        jsonl::write_file(a.junit_file, audit::diff_junit(d, a.old_report, a.new_report));
    // A gate that compared other cases, or fewer, would pass on what it did not measure.
    if (!d.comparable() && !a.any_campaign) {
        std::string what = d.campaigns.empty() ? "" : "not the same campaign: " + d.campaigns;
        if (!d.incomplete.empty()) what += (what.empty() ? "" : "; ") + d.incomplete;
        fail("diff: " + what +
             "; not a comparison of the same cases (--any-campaign compares them anyway)");
        return 1;
    }
    return d.worse() ? 1 : 0;
}

} // namespace

Command diff_command(CLI::App& app) {
    auto a = std::make_shared<DiffArgs>();
    CLI::App* d = app.add_subcommand(
        "diff", "Compare two reports family by family and solver by solver: what got worse (new "
                "misclassifications or bound violations, a larger max or p99 error, a slower "
                "median when --time-growth is given) and what got better. Exits 1 when anything "
                "got worse beyond the thresholds, or when the reports are not of the same "
                "complete campaign.");
    d->add_option("old", a->old_report, "the earlier report.json")
        ->type_name("OLD.json")
        ->required()
        ->check(CLI::ExistingFile);
    d->add_option("new", a->new_report, "the later report.json")
        ->type_name("NEW.json")
        ->required()
        ->check(CLI::ExistingFile);
    d->add_option("--max-growth", a->max_growth,
                  "how much larger a max error may get: new <= old * (1 + F)")
        ->type_name("F")
        ->check(Fraction())
        ->capture_default_str();
    d->add_option("--p99-growth", a->p99_growth, "the same for the p99 error")
        ->type_name("F")
        ->check(Fraction())
        ->capture_default_str();
    d->add_option("--time-growth", a->time_growth,
                  "how much slower a median may get (default: times are shown, never fail)")
        ->type_name("F")
        ->check(Fraction());
    d->add_flag("--any-campaign", a->any_campaign,
                "compare reports of different campaigns, or incomplete ones (said at the top of "
                "the markdown); without it such a diff exits 1");
    d->add_option("--markdown", a->markdown_file, "where the markdown goes (- : stdout)")
        ->type_name("FILE")
        ->capture_default_str();
    d->add_option("--junit", a->junit_file, "also write JUnit XML here")->type_name("FILE");
    add_format_option(d, a->format);
    return {d, [a](const std::string&) { return run_diff(*a); }, {}};
}

} // namespace linequad::cli
