// linequad diff: what got worse and what got better between two reports, as markdown for a CI
// job summary and as JUnit XML for CI test views.
#include "linequad/audit.hpp"

#include "io/escape.hpp"
#include "io/jsonl.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

namespace linequad::audit {

namespace {

using Pair = std::pair<std::string, std::string>; // (family, solver)

std::map<Pair, Row> by_family_and_solver(const Report& r) {
    std::map<Pair, Row> out;
    for (const auto& [key, row] : r.rows)
        out[{key.family, key.solver}].merge(row);
    return out;
}

std::string ulps(std::uint64_t u) {
    return u == UINT64_MAX ? "inf" : std::to_string(u);
}
std::string real(double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", x);
    return b;
}
std::string of(std::uint64_t part, std::uint64_t whole) {
    return std::to_string(part) + " of " + std::to_string(whole);
}

// Is a/b above c/d? Exactly, without rounding (counts are below 2^64).
bool rate_above(std::uint64_t a, std::uint64_t b, std::uint64_t c, std::uint64_t d) {
    if (b == 0) return false;
    if (d == 0) return a > 0;
    return (unsigned __int128)a * d > (unsigned __int128)c * b;
}

class Comparer {
  public:
    Comparer(Diff& d, const Pair& p) : d_(d), p_(p) {}

    // A count out of a whole (mismatched of cases): worse when its rate rises at all.
    void rate(const char* measure, std::uint64_t old_n, std::uint64_t old_of, std::uint64_t new_n,
              std::uint64_t new_of) {
        bool up = rate_above(new_n, new_of, old_n, old_of);
        bool down = rate_above(old_n, old_of, new_n, new_of);
        if (up || down)
            add(measure, of(old_n, old_of), of(new_n, new_of), up ? Change::worse : Change::better);
    }
    // An error in ulps: worse beyond growth, worse within it, or better.
    void error(const char* measure, double old_v, double new_v, double growth,
               const std::string& old_text, const std::string& new_text) {
        if (new_v == old_v) return;
        Change::Verdict v = new_v < old_v                  ? Change::better
                            : new_v > old_v * (1 + growth) ? Change::worse
                                                           : Change::worse_within_threshold;
        add(measure, old_text, new_text, v);
    }
    // A median time: gated only when a growth is given; otherwise shown when it moved by 10%.
    void time(double old_ns, double new_ns, double growth) {
        if (old_ns <= 0 || new_ns <= 0) return;
        double ratio = new_ns / old_ns;
        Change::Verdict v = Change::changed;
        if (growth >= 0) {
            if (ratio > 1 + growth)
                v = Change::worse;
            else if (ratio > 1)
                v = Change::worse_within_threshold;
            else if (ratio < 1 / (1 + std::max(growth, 0.1)))
                v = Change::better;
            else
                return;
        } else if (ratio < 1.1 && ratio > 1 / 1.1) {
            return;
        }
        add("median ns", real(old_ns), real(new_ns) + " (" + real(ratio) + "x)", v);
    }
    void add(const char* measure, std::string o, std::string n, Change::Verdict v) {
        d_.changes.push_back({p_.first, p_.second, measure, std::move(o), std::move(n), v});
    }

  private:
    Diff& d_;
    const Pair& p_;
};

const char* verdict_name(Change::Verdict v) {
    switch (v) {
    case Change::better:
        return "better";
    case Change::worse:
        return "**worse**";
    case Change::worse_within_threshold:
        return "worse, within threshold";
    case Change::changed:
        return "changed";
    }
    return "";
}

std::size_t count(const Diff& d, Change::Verdict v) {
    std::size_t n = 0;
    for (const Change& c : d.changes)
        n += c.verdict == v;
    return n;
}

} // namespace

bool Diff::worse() const {
    return count(*this, Change::worse) > 0;
}

namespace {

// How two reports' campaigns differ (their cases then differ), or "".
std::string campaign_difference(const Report& a, const Report& b) {
    std::vector<std::string> what;
    auto differ = [&](bool d, const std::string& name) {
        if (d) what.push_back(name);
    };
    differ(a.seed != b.seed,
           "seed " + std::to_string(a.seed) + " against " + std::to_string(b.seed));
    differ(a.cases_per_group != b.cases_per_group, std::to_string(a.cases_per_group) +
                                                       " cases per group against " +
                                                       std::to_string(b.cases_per_group));
    differ(a.families != b.families, "the families");
    differ(a.shapes != b.shapes, "the shapes");
    differ(a.ranges != b.ranges, "the ranges");
    differ(a.frames != b.frames, "the frames (" + a.frames + " against " + b.frames + ")");
    differ(a.cases_file != b.cases_file || a.cases_count != b.cases_count, "the cases file");
    differ(a.results_file != b.results_file, "the results graded");
    std::string out;
    for (const std::string& w : what)
        out += (out.empty() ? "" : "; ") + w;
    return out;
}

std::string incompleteness(const Report& r, const char* which) {
    if (r.complete()) return "";
    return std::string(which) + " is " +
           (r.status != Status::complete ? status_name(r.status)
                                         : std::to_string(r.shards_included.size()) + " of " +
                                               std::to_string(r.shards) + " shards");
}

} // namespace

Diff diff(const Report& old_report, const Report& new_report, const DiffThresholds& t) {
    Diff d;
    d.campaigns = campaign_difference(old_report, new_report);
    for (std::string s : {incompleteness(old_report, "the old report"),
                          incompleteness(new_report, "the new report")})
        if (!s.empty()) d.incomplete += (d.incomplete.empty() ? "" : "; ") + s;
    std::map<Pair, Row> old_rows = by_family_and_solver(old_report),
                        new_rows = by_family_and_solver(new_report);
    bool same_campaign = d.campaigns.empty();
    for (const auto& [pair, o] : old_rows) {
        d.compared.push_back(pair);
        Comparer c(d, pair);
        auto it = new_rows.find(pair);
        if (it == new_rows.end()) {
            c.add("graded", std::to_string(o.cases) + " cases", "absent", Change::worse);
            continue;
        }
        const Row& n = it->second;
        // Of one campaign, a solver grades the same cases in both unless it took fewer (declared
        // more of them unrepresented, or answered them "not asked"): then its rates are of other
        // cases, and the gate says so instead of "better".
        if (same_campaign && o.cases != n.cases) {
            std::string what = pair.second + " in " + pair.first + " graded " +
                               std::to_string(n.cases) + " cases, " + std::to_string(o.cases) +
                               " before";
            d.campaigns += (d.campaigns.empty() ? "" : "; ") + what;
            c.add("graded", std::to_string(o.cases) + " cases", std::to_string(n.cases) + " cases",
                  n.cases < o.cases ? Change::worse : Change::changed);
        }
        c.rate("mismatched", o.cases_mismatched, o.cases, n.cases_mismatched, n.cases);
        c.rate("certain but wrong", o.certain_wrong, o.cases, n.certain_wrong, n.cases);
        c.rate("bound violations", o.bound_violations, o.bounded_roots, n.bound_violations,
               n.bounded_roots);
        c.error("t max ulps", double(o.t_max), double(n.t_max), t.max_growth, ulps(o.t_max),
                ulps(n.t_max));
        double op99 = o.t_error.quantile(0.99), np99 = n.t_error.quantile(0.99);
        c.error("t p99 ulps", op99, np99, t.p99_growth, real(op99), real(np99));
        c.error("point max ulps", double(o.p_max), double(n.p_max), t.max_growth, ulps(o.p_max),
                ulps(n.p_max));
        c.time(o.ns.median(), n.ns.median(), t.time_growth);
    }
    for (const auto& [pair, n] : new_rows)
        if (!old_rows.count(pair)) {
            d.compared.push_back(pair);
            Comparer(d, pair).add("graded", "absent", std::to_string(n.cases) + " cases",
                                  Change::changed);
        }
    return d;
}

std::string diff_markdown(const Diff& d, const std::string& old_name, const std::string& new_name) {
    std::ostringstream md;
    using escape::markdown_text;
    md << "## linequad diff\n\n"
       << markdown_text(old_name) << " → " << markdown_text(new_name) << "\n\n";
    // What makes the comparison say less than it seems to, first.
    if (!d.campaigns.empty())
        md << "**Not the same campaign** (" << markdown_text(d.campaigns)
           << "): their cases differ, so a change below may be the cases' and not the "
              "solvers'.\n\n";
    if (!d.incomplete.empty())
        md << "**Incomplete** (" << markdown_text(d.incomplete)
           << "): a report that did not grade every case of its campaign measures fewer cases.\n\n";
    md << "**" << (d.worse() ? "Worse" : "Not worse") << "**: " << count(d, Change::worse)
       << " measures got worse beyond their thresholds, "
       << count(d, Change::worse_within_threshold) << " within them, " << count(d, Change::better)
       << " got better; " << d.compared.size() << " family/solver pairs compared.\n\n";
    if (d.changes.empty()) {
        md << "No measure changed.\n";
        return md.str();
    }
    md << "| family | solver | measure | old | new | verdict |\n|---|---|---|---:|---:|---|\n";
    for (const Change& c : d.changes)
        md << "| " << markdown_text(c.family) << " | " << markdown_text(c.solver) << " | "
           << c.measure << " | " << c.old_value << " | " << c.new_value << " | "
           << verdict_name(c.verdict) << " |\n";
    return md.str();
}

std::string diff_junit(const Diff& d, const std::string& old_name, const std::string& new_name) {
    // One test case per family and solver; it fails when a measure got worse beyond its
    // threshold.
    std::map<Pair, std::vector<const Change*>> by_pair;
    for (const Change& c : d.changes)
        by_pair[{c.family, c.solver}].push_back(&c);
    std::size_t failures = 0;
    std::ostringstream cases;
    for (const Pair& pair : d.compared) {
        std::string failed;
        for (const Change* c : by_pair[pair])
            if (c->verdict == Change::worse)
                failed += c->measure + ": " + c->old_value + " -> " + c->new_value + "\n";
        cases << "    <testcase classname=\"" << jsonl::markup_text(pair.first) << "\" name=\""
              << jsonl::markup_text(pair.second) << "\"";
        if (failed.empty()) {
            cases << "/>\n";
            continue;
        }
        ++failures;
        cases << ">\n      <failure message=\"got worse\">" << jsonl::markup_text(failed)
              << "</failure>\n    </testcase>\n";
    }
    std::size_t tests = d.compared.size();
    std::ostringstream x;
    x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"linequad diff\" tests=\""
      << tests << "\" failures=\"" << failures << "\">\n  <testsuite name=\""
      << jsonl::markup_text(old_name + " -> " + new_name) << "\" tests=\"" << tests
      << "\" failures=\"" << failures << "\">\n"
      << cases.str() << "  </testsuite>\n</testsuites>\n";
    return x.str();
}

} // namespace linequad::audit
