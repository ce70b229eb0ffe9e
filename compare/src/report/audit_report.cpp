// report.md (for people), the SVG figures, and the output directory that holds them beside
// report.json.
#include "linequad/audit.hpp"

#include "linequad/case_io.hpp"

#include "io/escape.hpp"
#include "io/jsonl.hpp"
#include "report/svg_plot.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <sys/file.h>
#include <unistd.h>

namespace linequad::audit {

// The command that replays a worst case: the case as the solver saw it (for a solver from
// outside, the posed case: replay does not pose it again), its answer and the reference its grade
// used, as `linequad replay` prints them. Every word is quoted for the shell.
// A solver `linequad replay` cannot run (a Python callable): the case's exact answer instead.
std::string replay_command(const Report& r, const Worst& w, const std::string& solver) {
    std::string plugin, replayed = solver;
    if (auto it = r.external.find(solver); it != r.external.end()) {
        if (!it->second.plugin.empty())
            plugin = " --plugin " + escape::shell_word(it->second.plugin);
        if (!it->second.not_replayable.empty()) replayed = "exact";
    }
    return "echo " + escape::shell_word(w.case_line()) + " | linequad replay" + plugin +
           " --solver " + escape::shell_word(replayed);
}

namespace {

std::string num(std::uint64_t x) {
    return std::to_string(x);
}

std::string fmt(double x) {
    char b[32];
    if (x == 0) return "0";
    if (x < 1e4 && x == std::floor(x))
        std::snprintf(b, sizeof b, "%.0f", x);
    else if (x < 1e4)
        std::snprintf(b, sizeof b, "%.3g", x);
    else
        std::snprintf(b, sizeof b, "%.2e", x);
    return b;
}
// An ulp count; one past what 64 bits hold (an infinite point, a scene error beyond the
// format's range) says so.
std::string fmt_ulps(std::uint64_t u) {
    return u == UINT64_MAX ? "beyond 2^64" : fmt(double(u));
}
// A count with its share of the cases graded: "1234 (0.57 %)".
std::string with_share(std::uint64_t n, std::uint64_t cases) {
    return n ? std::to_string(n) + " (" + percent_of(n, cases) + ")" : "0";
}

// A library's output as a person reads it: a line repeated in a run (ODE repeats its internal
// error once per crash) shown once, with how many times it came; a last line cut off where the
// kept text ends (cut: there was more) marked as such.
std::vector<std::string> runs_counted(const std::string& text, bool cut) {
    std::vector<std::string> out;
    std::string last;
    std::uint64_t repeats = 0;
    auto flush = [&] {
        if (repeats)
            out.push_back(repeats == 1 ? last
                                       : last + "   (" + std::to_string(repeats) + " times)");
    };
    std::size_t at = 0;
    while (at < text.size()) {
        std::size_t nl = text.find('\n', at);
        std::string line = text.substr(at, nl == std::string::npos ? nl : nl - at);
        if (nl == std::string::npos && cut) line += " [cut: more followed]";
        at = nl == std::string::npos ? text.size() : nl + 1;
        if (repeats && line == last) {
            ++repeats;
            continue;
        }
        flush();
        last = std::move(line), repeats = 1;
    }
    flush();
    return out;
}

// A point error where the answers carry points; a time where one was measured.
std::string point_max(const Row& row) {
    return row.graded_coords ? fmt_ulps(row.p_max) : "-";
}
std::string median_ns(const Row& row) {
    return row.timed() ? fmt(row.ns.median()) : "-";
}
std::string scene_error(const Row& row) {
    return row.graded_roots ? fmt(row.s_quantile(0.99)) + " / " + fmt_ulps(row.s_max) : "-";
}

std::string status_line(const Report& r) {
    std::string shards;
    if (r.shards > 1) {
        shards = std::to_string(r.shards_included.size()) + " of " + std::to_string(r.shards) +
                 " shards";
        if (r.shards_included.size() < 5) {
            shards += " (";
            for (std::size_t i = 0; i < r.shards_included.size(); ++i)
                shards += (i ? ", " : "") + std::to_string(r.shards_included[i]);
            shards += ")";
        }
    }
    switch (r.status) {
    case Status::running:
        return "**no: running** (saved while the run goes on" +
               (shards.empty() ? "" : "; " + shards) + ")";
    case Status::stopped:
        return "**no: stopped early**" + (shards.empty() ? "" : " (" + shards + ")");
    case Status::complete:
        if (r.complete()) return shards.empty() ? "yes" : "yes (" + shards + ")";
        return "**no: " + shards + "**";
    }
    return "";
}

// The precision a row's answers were graded in: float ulps for binary32 cases.
std::string precision_of(const Row& row) {
    if (row.binary32_cases == 0) return "double";
    return row.binary32_cases == row.cases ? "float" : "mixed";
}

// One row per family, one column per solver: misclassified of cases and the t error p99 (and
// the scene error p99).
void write_by_family(std::ostream& md, const Report& r, const std::vector<std::string>& columns,
                     bool scene) {
    md << "| family |";
    for (const std::string& s : columns)
        md << " " << escape::markdown_text(s) << " |";
    md << "\n|---|";
    for (std::size_t i = 0; i < columns.size(); ++i)
        md << "---:|";
    md << "\n";
    for (const std::string& family : r.families) {
        md << "| " << escape::markdown_text(family) << " |";
        for (const std::string& name : columns) {
            Row t = family_total(r, family, name);
            if (t.cases == 0) {
                md << " - |";
                continue;
            }
            md << " " << t.cases_mismatched << " of " << t.cases;
            if (t.within_tolerance) md << " (" << t.within_tolerance << " within tolerance)";
            md << ", p99 " << fmt(t.t_quantile(0.99));
            if (scene) md << ", scene " << fmt(t.s_quantile(0.99));
            md << " |";
        }
        md << "\n";
    }
}

// How often the correct solvers (correct, and correct32 rounding to float) needed each rung of
// their ladder, by family.
void write_rungs(std::ostream& md, const Report& r) {
    std::map<std::pair<std::string, std::string>, Row> by_family;
    for (const auto& [key, row] : r.rows)
        if (key.solver == "correct" || key.solver == "correct32")
            by_family[{key.family, key.solver}].merge(row);
    if (by_family.empty()) return;
    md << "\n## The correct solvers' rungs\n\n"
          "Results settled by the Newton rung, the double-double rung (each only where its bounds "
          "proved every sign and every rounding) and the exact rung, by family; ns/solve is the "
          "median of the mix. correct32 rounds to float: its Newton rung evaluates g in double "
          "first.\n\n";
    md << "| family | solver | cases | Newton | double-double | exact | exact % | ns/solve |\n";
    md << "|---|---|---:|---:|---:|---:|---:|---:|\n";
    for (const auto& [key, row] : by_family) {
        std::uint64_t nw = row.rungs[std::size_t(Rung::newton)];
        std::uint64_t dd = row.rungs[std::size_t(Rung::double_double)];
        std::uint64_t ex = row.rungs[std::size_t(Rung::exact)], all = nw + dd + ex;
        md << "| " << escape::markdown_text(key.first) << " | " << key.second << " | " << row.cases
           << " | " << nw << " | " << dd << " | " << ex << " | "
           << fmt(all ? 100.0 * double(ex) / double(all) : 0) << " | " << fmt(row.ns.median())
           << " |\n";
    }
    Row certified = r.total("certified");
    if (certified.bounded_roots)
        md << "\nA certified bound below half an ulp of t (the only kind that could prove a "
              "rounding on its own, without the Newton step): "
           << certified.bound_below_half_ulp << " of " << certified.bounded_roots
           << " certified roots.\n";
}

// The double solvers whose float counterpart (stable32 for stable) the report holds too.
std::vector<std::string> float_pairs(const Report& r) {
    std::vector<std::string> pairs;
    for (const std::string& s : r.solvers)
        if (std::find(r.solvers.begin(), r.solvers.end(), s + "32") != r.solvers.end())
            pairs.push_back(s);
    return pairs;
}

// Each double solver beside its float counterpart (stable beside stable32, ...), family by
// family: cases misclassified, and the t error, each in its own precision's ulps.
void write_float_beside_double(std::ostream& md, const Report& r) {
    std::vector<std::string> pairs = float_pairs(r);
    if (pairs.empty()) return;
    std::vector<std::string> columns;
    for (const std::string& s : pairs)
        columns.push_back(s), columns.push_back(s + "32");
    md << "\n## Float beside double\n\n"
          "Each solver in float (binary32 cases, errors in float ulps) beside the same solver in "
          "double (binary64 cases, double ulps), family by family: cases misclassified (of "
          "cases), and the t error p99.\n\n";
    write_by_family(md, r, columns, false);
}

// Solvers from outside linequad beside linequad's, family by family.
void write_external_by_family(std::ostream& md, const Report& r) {
    if (r.external.empty()) return;
    md << "\n## Every solver by family\n\n"
          "Cases misclassified (of the cases each could take), the t error p99 in ulps of t, and "
          "the scene error p99 (|t - t_oracle| |v| in ulps of the scene's magnitude), which stays "
          "meaningful where t is near 0.\n\n";
    write_by_family(md, r, r.solvers, true);
}

} // namespace

namespace {
// How each external solver was handed its cases, its conventions, and what it did besides
// answering: what it wrote, how loading it changed the floating-point environment, how often its
// worker was started again.
void write_external(std::ostream& md, const Report& r) {
    if (r.external.empty()) return;
    using escape::markdown_text;
    md << "## Solvers from outside linequad\n\nEach is graded on the case as it was posed to it, "
          "against the exact reference for what it answers (every hit, the nearest, the first "
          "entry into the solid or the first exit from it) and for the conventions it declares. "
          "A plugin runs in a worker process of its own: its crashes, exits, exceptions and "
          "timeouts are refusals of its own (by kind, below), and nothing it does reaches "
          "linequad's answers.\n\n"
          "| solver | answers | t | surfaces | start inside | contact | its conventions | "
          "mapping |\n"
          "|---|---|---|---|---|---|---|---|\n";
    for (const auto& [name, e] : r.external)
        md << "| " << markdown_text(name)
           << (e.plugin.empty() ? "" : " (" + markdown_text(e.plugin) + ")")
           << (e.batch ? ", batch entry" : "") << " | " << markdown_text(e.answers) << " | "
           << markdown_text(e.parametrisation) << " | " << markdown_text(e.surface) << " | "
           << (e.inside.empty() ? "-" : markdown_text(e.inside)) << " | "
           << (e.contact.empty() ? "interval" : markdown_text(e.contact)) << " | "
           << (e.conventions.empty() ? "-" : markdown_text(e.conventions)) << " | "
           << markdown_text(e.mapping) << " |\n";
    md << "\n";
    for (const auto& [name, e] : r.external) {
        if (!e.load_environment.empty())
            md << "- " << markdown_text(name) << ": loading its plugin changed the floating-point "
               << "environment (" << markdown_text(e.load_environment)
               << "); every call starts from that environment.\n";
        if (e.restarts)
            md << "- " << markdown_text(name) << ": " << e.restarts
               << " of its calls crashed, exited or timed out, ending its worker process, which "
                  "was started again for the next call.\n";
        if (e.batch_fallbacks)
            md << "- " << markdown_text(name) << ": " << e.batch_fallbacks
               << " calls of its batch entry failed (declined, crashed, exited or timed out); "
                  "their cases were asked again one at a time.\n";
        if (e.output_bytes) {
            md << "- " << markdown_text(name) << " wrote " << e.output_bytes << " bytes "
               << (e.plugin.empty() ? "through its library's message hooks"
                                    : "on its standard output and error")
               << " (kept apart from linequad's); the first of them, each run of one line once "
                  "with its count:\n\n";
            bool cut = e.output_bytes > e.output.size();
            md << escape::markdown_block(runs_counted(e.output, cut), "  ") << "\n";
        }
    }
    md << "\n";
}

// What a row's solver did besides its answers, for the "by kind" column: each name escaped.
std::string notes_of(const Row& row) {
    std::string kinds;
    auto add = [&](const std::string& s) { kinds += (kinds.empty() ? "" : ", ") + s; };
    for (int m = 0; m < mismatch_kinds; ++m)
        if (row.mismatches[m]) add(std::string(mismatch_name(m)) + " " + num(row.mismatches[m]));
    // The solver's own refusals, by its names for them (crashes, exits, timeouts among them).
    for (const auto& [name, n] : row.foreign)
        add("'" + escape::markdown_text(name) + "' " + num(n));
    for (const auto& [why, n] : row.unrepresented_why)
        add("unrepresented, " + escape::markdown_text(why) + " " + num(n));
    for (const auto& [why, n] : row.not_asked)
        add("not asked, " + escape::markdown_text(why) + " " + num(n));
    for (const auto& [how, n] : row.environment)
        add("changed the floating-point environment (" + escape::markdown_text(how) + ") " +
            num(n));
    return kinds;
}
} // namespace

namespace {

// What was run, where, how (at the end: the verdict comes first), and how to read the tables.
void write_provenance(std::ostream& md, const Report& r) {
    md << "## Provenance\n\n";
    md << "| | |\n|---|---|\n";
    using escape::markdown_text;
    if (!r.run.empty()) md << "| run | " << markdown_text(r.run) << " |\n";
    md << "| command | " << markdown_text(r.command) << " |\n| commit | " << markdown_text(r.commit)
       << " |\n| date | " << markdown_text(r.date) << " |\n";
    md << "| machine | " << markdown_text(r.machine) << " |\n| compiler | "
       << markdown_text(r.compiler) << " |\n";
    md << "| fast/ flags | " << markdown_text(r.flags) << " |\n";
    if (r.from_cases_file())
        md << "| cases | " << markdown_text(r.cases_file) << " (" << r.cases_count << " cases) |\n";
    else
        md << "| seed | " << r.seed << " |\n| cases per family, shape and range | "
           << r.cases_per_group << " |\n";
    md << "| shapes | ";
    for (const std::string& s : r.shapes)
        md << markdown_text(s) << (&s == &r.shapes.back() ? "" : ", ");
    md << " (frames: " << markdown_text(r.frames) << ") |\n";
    if (r.grades_results())
        md << "| graded | the answers in " << markdown_text(r.results_file) << " (not timed) |\n";
    md << "| linequad | " << markdown_text(r.version) << " |\n| shards | " << r.shards
       << " |\n| complete | " << status_line(r) << " |\n";
    md << "| run time | " << fmt(r.seconds) << " s |\n\n";
    md << "Errors are distances to the exact oracle's correctly rounded value, in units in the "
          "last "
          "place (0: correctly rounded); bits = log2(1 + ulps) as Herbie counts them. Points: the "
          "largest coordinate error in ulps of the point's scale, max(|p|, |L0|, |t v|). A "
          "mismatch is a "
          "different classification (a hit invented or missed, a tangent, on-surface or part "
          "wrong), a NaN/infinity, a refusal or a call that crashed; "
          "errors are only measured on cases classified like the oracle. A certified solver may "
          "call a "
          "case uncertain (counted apart, not as a mismatch); each of its roots carries a bound, "
          "violated when |t - t_oracle| exceeds it by more than half an ulp (the oracle's "
          "rounding); "
          "bound/err is how loose the bound is. A float solver (precision float) answers the "
          "same families posed in binary32 (every input a float) and is graded in float ulps "
          "against the oracle's answer rounded to float. ns/solve: median over "
          "chunks of "
       << chunk_size
       << " cases, this run, this machine. batch is stable's batch path (its "
          "results equal stable's bit for bit): graded on every case, one line per call; its "
          "ns is per line, each chunk's lines solved as one batch against four of the chunk's "
          "shapes.\n\n";
}

// Every solver over every family: the headline table and the Pareto figure.
void write_headline(std::ostream& md, const Report& r) {
    using escape::markdown_text;
    md << "## Headline: every family\n\n";
    md << "Scene error: the t error as a distance, |t - t_oracle| |v|, in ulps of the scene's "
          "magnitude (the largest of |L0|, |t v| and the shape's coordinates), p99 / max. "
          "Unrepresented: cases the solver could not take (not graded). Not asked: cases outside "
          "the contract it declares (a first exit from outside, a start inside it leaves "
          "undefined). Within tolerance: classified otherwise than the exact surface, but right "
          "for a surface within the tolerance the solver declares (not mismatched). A dash: not "
          "measured "
          "(no points in the answers, no time for answers read from a file).\n\n";
    md << "| solver | precision | cases | unrepresented | not asked | within tolerance | "
          "mismatched | uncertain | bound "
          "violations | t max ulps | t p99 | t p50 | mean bits | scene error | point max ulps | "
          "ns/solve (generic) |\n";
    md << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    bool timed = false;
    for (const std::string& s : r.solvers) {
        Row t = r.total(s), generic = family_total(r, "generic", s);
        timed = timed || generic.timed();
        md << "| " << markdown_text(s) << " | " << precision_of(t) << " | " << t.cases << " | "
           << t.unrepresented << " | " << not_asked_count(t) << " | " << t.within_tolerance << " | "
           << t.cases_mismatched << " | "
           << (t.bounded_roots || t.uncertain ? num(t.uncertain) : "-") << " | "
           << (t.bounded_roots ? num(t.bound_violations) + " of " + num(t.bounded_roots) : "-")
           << " | " << fmt_ulps(t.t_max) << " | " << fmt(t.t_quantile(0.99)) << " | "
           << fmt(t.t_quantile(0.5)) << " | "
           << fmt(t.graded_roots ? t.t_bits_sum / double(t.graded_roots) : 0) << " | "
           << scene_error(t) << " | " << point_max(t) << " | " << median_ns(generic) << " |\n";
    }
    if (timed) md << "\n![run time against error](pareto.svg)\n\n";
}

// Every row: a family, a shape and a solver.
void write_rows(std::ostream& md, const Report& r) {
    using escape::markdown_text;
    md << "## By family and shape\n\n";
    md << "| family | shape | solver | cases | unrep. | not asked | within tol. | mismatched | "
          "by kind | uncertain | "
          "bound viol. | bound/err p50 | t max | t p99 | t p99.9 | t mean | scene error | "
          "point max | ns/solve |\n";
    md << "|---|---|---|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|-"
          "--:|"
          "\n";
    for (const auto& [key, row] : r.rows) {
        std::string kinds = notes_of(row);
        md << "| " << markdown_text(key.family) << " | " << markdown_text(key.shape) << " | "
           << markdown_text(key.solver) << " | " << row.cases << " | " << row.unrepresented << " | "
           << not_asked_count(row) << " | " << with_share(row.within_tolerance, row.cases) << " | "
           << with_share(row.cases_mismatched, row.cases) << " | " << kinds << " | "
           << (row.bounded_roots || row.uncertain ? num(row.uncertain) : "-") << " | "
           << (row.bounded_roots ? num(row.bound_violations) : "-") << " | "
           << (row.bounded_roots ? fmt(row.tightness.quantile(0.5)) : "-") << " | "
           << fmt_ulps(row.t_max) << " | " << fmt(row.t_quantile(0.99)) << " | "
           << fmt(row.t_quantile(0.999)) << " | "
           << fmt(row.graded_roots ? row.t_sum / double(row.graded_roots) : 0) << " | "
           << scene_error(row) << " | " << point_max(row) << " | " << median_ns(row) << " |\n";
    }
}

// The figures of error against difficulty, and against distance.
void write_difficulty(std::ostream& md, const Report& r) {
    using escape::markdown_text;
    md << "\n## Error against difficulty\n\n";
    bool scale = false, far = false;
    for (const std::string& f : r.families)
        for (const auto& [key, points] : r.curves)
            if (key.family == f && f != "generic") { // write_plots() draws these
                scale = scale || f == "scale", far = far || f == "far_origin";
                md << "![" << markdown_text(f) << "](" << difficulty_figure(f) << ")\n\n";
                break;
            }
    if (scale && far)
        md << "Error against distance: the shape's size and distance from the world origin "
              "(scale) beside the ray origin's distance from the shape (far_origin).\n\n"
              "![distance](distance.svg)\n\n";
}

// What the verdict is of: the run, whether it is whole, its cases, and where the rest is.
void write_run_line(std::ostream& md, const Report& r) {
    md << "Run " << escape::markdown_text(r.run.empty() ? "-" : r.run)
       << ", complete: " << status_line(r) << ". ";
    if (r.from_cases_file())
        md << grouped(r.cases_count) << " cases from " << escape::markdown_text(r.cases_file);
    else
        md << grouped(r.cases_per_group) << " cases per family, shape and range (seed " << r.seed
           << ")";
    md << ", " << r.solvers.size() << " solvers, " << escape::markdown_text(r.date)
       << ". How it was run: [Provenance](#provenance).\n\n";
}

// The verdict: per solver, the share of its cases classified right, where it breaks and its t
// error in bits; then every family's share misclassified, solver by solver.
void write_verdict(std::ostream& md, const Report& r) {
    using escape::markdown_text;
    md << "## Verdict\n\n";
    md << "Right: classified as the exact oracle classifies it (a hit invented or missed, a wrong "
          "kind or part, a refusal or a crash is not), of the cases each solver was asked; the "
          "families it misclassifies most, with the difficulty k from which it misses 1 % of "
          "them. Errors in bits, log2(1 + ulps): 0 is correctly rounded, 52 every bit of a "
          "double wrong.\n\n";
    // A column only where some solver has something in it: linequad's own solvers declare no
    // tolerance and are asked every case.
    std::vector<Verdict> all = verdicts(r);
    bool tolerance = false, unasked = false;
    for (const Verdict& v : all)
        tolerance |= v.within_tolerance > 0, unasked |= v.not_asked > 0;
    md << "| solver | right |" << (tolerance ? " within its tolerance |" : "")
       << (unasked ? " not asked |" : "") << " misclassifies most (from k) | t error, worst | "
       << "t error, p99 |\n";
    md << "|---|---:|" << (tolerance ? "---:|" : "") << (unasked ? "---:|" : "")
       << "---|---:|---:|\n";
    for (const Verdict& v : all) {
        md << "| [" << markdown_text(v.solver) << "](#" << escape::anchor("Solver: " + v.solver)
           << ") | ";
        std::string asked = unasked ? (v.not_asked ? grouped(v.not_asked) : "-") + " | " : "";
        if (v.cases == 0) {
            md << "graded no case | " << (tolerance ? "- | " : "") << asked << "- | - | - |\n";
            continue;
        }
        md << percent_of(v.cases - v.misclassified - v.within_tolerance, v.cases) << " of "
           << grouped(v.cases) << " | ";
        if (tolerance)
            md << (v.within_tolerance ? percent_of(v.within_tolerance, v.cases) : "-") << " | ";
        md << asked;
        std::string most;
        for (std::size_t i = 0; i < v.worst_families.size() && i < 2; ++i) {
            const FamilyShare& f = v.worst_families[i];
            most += (i ? ", " : "") + markdown_text(f.family) + " " +
                    percent_of(f.misclassified, f.cases) +
                    (f.breaks_at >= 0 ? " (" + std::to_string(f.breaks_at) + ")" : "");
        }
        md << (most.empty() ? "-" : most) << " | ";
        if (v.errors)
            md << bits_text(v.t_max_ulps) << " bits (" << fmt(v.t_max_ulps) << " ulps) | "
               << bits_text(v.t_p99_ulps) << " bits |\n";
        else
            md << "- | - |\n";
    }
    md << "\n### Misclassified, by family (% of the cases graded)\n\n";
    md << "| family |";
    for (const std::string& s : r.solvers)
        md << " " << markdown_text(s) << " |";
    md << "\n|---|";
    for (std::size_t i = 0; i < r.solvers.size(); ++i)
        md << "---:|";
    md << "\n";
    for (const std::string& family : r.families) {
        md << "| " << markdown_text(family) << " |";
        for (const std::string& s : r.solvers) {
            Row t = family_total(r, family, s);
            md << " " << percent_of(t.cases_mismatched, t.cases) << " |";
        }
        md << "\n";
    }
    md << "\n";
    write_run_line(md, r);
}

// Links to each solver's section and to every section after them.
void write_contents(std::ostream& md, const Report& r, const std::vector<std::string>& sections) {
    md << "## Contents\n\n";
    md << "Each solver: ";
    for (std::size_t i = 0; i < r.solvers.size(); ++i)
        md << (i ? " · " : "") << "[" << escape::markdown_text(r.solvers[i]) << "](#"
           << escape::anchor("Solver: " + r.solvers[i]) << ")";
    md << ". Then: ";
    for (std::size_t i = 0; i < sections.size(); ++i)
        md << (i ? " · " : "") << "[" << escape::markdown_text(sections[i]) << "](#"
           << escape::anchor(sections[i]) << ")";
    md << ".\n\n";
}

// A worst case as a person compares it: the solver's answer beside the reference's, field by
// field, in decimal and hex, the fields that differ in bold; then the command that replays it.
void write_worst_case(std::ostream& md, const Report& r, const RowKey& key, const Worst& w) {
    using escape::markdown_text;
    Case c;
    ParsedResult got, want;
    std::string why;
    bool parsed = parse_case(w.case_line(), &c, &why) &&
                  parse_result(w.solver_line(), &got, &why) &&
                  parse_result(w.oracle_line(), &want, &why);
    md << "**" << markdown_text(key.family) << ", " << markdown_text(key.shape);
    if (parsed) md << ", k = " << c.k;
    md << "**: ";
    if (w.mismatch)
        md << "misclassified";
    else if (w.ulps == UINT64_MAX)
        md << "a root of the wrong sign (or 0 against a nonzero root)";
    else
        md << "t error " << bits_text(double(w.ulps)) << " bits (" << fmt_ulps(w.ulps) << " ulps)";
    md << "\n\n";
    if (parsed) {
        auto answer = [](const ParsedResult& p) -> std::string {
            if (!p.error_code.empty()) return "refused: " + escape::markdown_text(p.error_code);
            if (p.result.on_surface) return "on the surface";
            return std::to_string(p.result.count) + (p.result.count == 1 ? " hit" : " hits");
        };
        auto value = [](double x) {
            char b[40];
            std::snprintf(b, sizeof b, "%.17g", x);
            return std::string(b) + " `" + hex(x) + "`";
        };
        auto kind = [](const Result& x, int i) -> std::string {
            if (i >= x.count) return "-";
            return x.hits[i].kind == HitKind::tangent ? "tangent" : "cross";
        };
        std::vector<std::array<std::string, 3>> fields = {{"answer", answer(got), answer(want)}};
        const Result &g = got.result, &o = want.result;
        if (got.error_code.empty() && want.error_code.empty()) {
            if (g.on_surface || o.on_surface) {
                fields.push_back({"on the surface from", g.on_surface ? value(g.s0) : "-",
                                  o.on_surface ? value(o.s0) : "-"});
                fields.push_back(
                    {"to", g.on_surface ? value(g.s1) : "-", o.on_surface ? value(o.s1) : "-"});
            }
            for (int i = 0; i < std::max(g.count, o.count); ++i) {
                std::string n = std::to_string(i + 1);
                fields.push_back({"t of hit " + n, i < g.count ? value(g.hits[i].t) : "-",
                                  i < o.count ? value(o.hits[i].t) : "-"});
                if (got.has_kinds && want.has_kinds)
                    fields.push_back({"kind of hit " + n, kind(g, i), kind(o, i)});
            }
        }
        md << "| | " << markdown_text(key.solver) << " | " << markdown_text(want.solver)
           << " |\n|---|---|---|\n";
        for (const auto& [field, mine, exact] : fields) {
            bool differs = mine != exact;
            md << "| " << field << " | " << (differs ? "**" + mine + "**" : mine) << " | " << exact
               << " |\n";
        }
        md << "\n";
    }
    md << escape::markdown_code(replay_command(r, w, key.solver)) << "\n\n";
}

// How many worst cases a solver's section shows (every row's are in report.json).
constexpr std::size_t worst_shown = 5;

// One solver: what it is, its families, and its worst cases with their replays.
void write_solver(std::ostream& md, const Report& r, const std::string& solver) {
    using escape::markdown_text;
    md << "## " << markdown_text("Solver: " + solver) << "\n\n";
    Row t = r.total(solver);
    md << "Precision " << precision_of(t) << "; " << grouped(t.cases) << " cases graded";
    if (t.unrepresented) md << ", " << grouped(t.unrepresented) << " it could not represent";
    if (not_asked_count(t)) md << ", " << grouped(not_asked_count(t)) << " not asked";
    md << ". Misclassified: " << with_share(t.cases_mismatched, t.cases);
    std::string kinds;
    for (int m = 0; m < mismatch_kinds; ++m)
        if (t.mismatches[m])
            kinds += (kinds.empty() ? "" : ", ") + std::string(mismatch_name(m)) + " " +
                     grouped(t.mismatches[m]);
    if (!kinds.empty()) md << " (" << markdown_text(kinds) << ")";
    md << ".";
    if (t.t_sign_wrong) md << " Roots of the wrong sign: " << grouped(t.t_sign_wrong) << ".";
    if (auto it = r.external.find(solver); it != r.external.end()) {
        const Report::External& e = it->second;
        md << " From outside linequad: " << markdown_text(e.answers) << ", "
           << markdown_text(e.parametrisation) << ", " << markdown_text(e.surface);
        if (!e.conventions.empty()) md << "; " << markdown_text(e.conventions);
        md << ".";
    }
    md << "\n\n";
    md << "| family | graded | misclassified | by kind | within its tolerance | from k | t bits "
          "p99 | t bits worst | scene p99 (ulps) |\n";
    md << "|---|---:|---:|---|---:|---:|---:|---:|---:|\n";
    for (const std::string& family : r.families) {
        Row f = family_total(r, family, solver);
        if (f.cases == 0) continue;
        std::string by_kind;
        for (int m = 0; m < mismatch_kinds; ++m)
            if (f.mismatches[m])
                by_kind += (by_kind.empty() ? "" : ", ") + std::string(mismatch_name(m)) + " " +
                           num(f.mismatches[m]);
        int k = breaks_at(r, family, solver);
        md << "| " << markdown_text(family) << " | " << f.cases << " | "
           << with_share(f.cases_mismatched, f.cases) << " | "
           << (by_kind.empty() ? "-" : markdown_text(by_kind)) << " | "
           << (f.within_tolerance ? with_share(f.within_tolerance, f.cases) : "-") << " | "
           << (k >= 0 ? std::to_string(k) : "-") << " | "
           << (f.graded_roots ? bits_text(f.t_quantile(0.99)) : "-") << " | "
           << (f.graded_roots ? bits_text(double(f.t_max)) : "-") << " | "
           << (f.graded_roots ? fmt(f.s_quantile(0.99)) : "-") << " |\n";
    }
    md << "\n";
    // Its worst cases over all its rows, the worst of each row, mismatches first.
    std::vector<std::pair<const RowKey*, const Worst*>> worst;
    for (const auto& [key, row] : r.rows)
        if (key.solver == solver && !row.worst.empty()) worst.emplace_back(&key, &row.worst[0]);
    std::stable_sort(worst.begin(), worst.end(), [](const auto& a, const auto& b) {
        if (a.second->mismatch != b.second->mismatch) return a.second->mismatch;
        return a.second->ulps > b.second->ulps;
    });
    if (worst.size() > worst_shown) worst.resize(worst_shown);
    if (worst.empty()) return;
    md << "### Its worst cases\n\n"
          "Each replays with the command under it: the case as the solver saw it, its answer "
          "and the reference its grade used, as above (the `linequad` on your `PATH`; in a "
          "clone, `export PATH=\"$PWD/build/compare:$PATH\"` first). Every row's worst cases are "
          "in report.json.";
    if (auto it = r.external.find(solver);
        it != r.external.end() && !it->second.not_replayable.empty())
        md << " " << markdown_text(solver) << " cannot be run by `linequad replay` ("
           << markdown_text(it->second.not_replayable)
           << "): its commands show the exact answer, and its own is in the table above.";
    md << "\n\n";
    for (const auto& [key, w] : worst)
        write_worst_case(md, r, *key, *w);
}

// How the oracle rounded its answers.
void write_oracle_rounding(std::ostream& md, const Report& r) {
    md << "## Oracle rounding\n\nFloats rounded from the oracle's interval filter alone: "
       << r.oracle_by_intervals
       << ". Values rounded by its double-word enclosures: " << r.oracle_by_filter
       << ". The rest, by MPFR at 64, 128, 256, ... bits: ";
    for (int i = 0; i < 8; ++i)
        md << (i ? ", " : "") << r.oracle_steps[i];
    md << ".\n";
}

} // namespace

std::string markdown(const Report& r) {
    std::ostringstream md;
    md << "# linequad accuracy audit\n\n";
    write_verdict(md, r);
    std::vector<std::string> sections = {"Headline: every family"};
    if (!r.external.empty())
        sections.insert(sections.end(),
                        {"Solvers from outside linequad", "Every solver by family"});
    sections.insert(sections.end(), {"Error against difficulty", "By family and shape"});
    if (float_pairs(r).size()) sections.push_back("Float beside double");
    if (r.total("correct").cases || r.total("correct32").cases)
        sections.push_back("The correct solvers' rungs");
    sections.insert(sections.end(), {"Provenance", "Oracle rounding"});
    write_contents(md, r, sections);
    for (const std::string& s : r.solvers)
        write_solver(md, r, s);
    write_headline(md, r);
    write_external(md, r);
    write_external_by_family(md, r);
    write_difficulty(md, r);
    write_rows(md, r);
    write_float_beside_double(md, r);
    write_rungs(md, r);
    md << "\n";
    write_provenance(md, r);
    write_oracle_rounding(md, r);
    return md.str();
}

std::string difficulty_figure(const std::string& family) {
    return "difficulty_" + escape::file_name(family) + ".svg";
}

namespace {

// One family's error and misclassification against its difficulty k, a pair of curves per
// solver in one colour: the largest t error (left, logarithmic) and the fraction misclassified
// (right, dashed).
plot::Chart difficulty_chart(const Report& r, const std::string& family, const std::string& x) {
    plot::Chart c;
    c.title = family + ": error and misclassification against k";
    c.x_label = x;
    c.y_label = "max t error, bits (log2(1 + ulps))";
    c.y2_label = "fraction of cases misclassified";
    int color = 0;
    for (const auto& [key, points] : r.curves) {
        if (key.family != family) continue;
        plot::Series error, wrong;
        error.name = key.solver + " max error", wrong.name = key.solver + " misclassified";
        wrong.right = wrong.dashed = true, wrong.markers = false;
        error.color = wrong.color = color++;
        int last = INT32_MIN;
        for (const auto& [k, p] : points) {
            // No line across difficulties without cases: a gap there.
            if (last != INT32_MIN && k > last + 1)
                error.points.emplace_back(last + 1, NAN), wrong.points.emplace_back(last + 1, NAN);
            last = k;
            error.points.emplace_back(k, std::log2(1 + double(p.t_max)));
            wrong.points.emplace_back(k, p.cases ? double(p.mismatched) / double(p.cases) : 0);
        }
        c.series.push_back(error);
        c.series.push_back(wrong);
    }
    return c;
}

} // namespace

bool write_plots(const Report& r, const std::string& dir) {
    // Pareto: median ns per solve on generic cases against max and p99 t error over all families;
    // only solvers timed on generic cases (an answer read from a file has no time).
    plot::Chart pareto;
    pareto.title = "run time against error (every family)";
    pareto.x_label = "ns per solve, median, generic cases";
    pareto.y_label = "t error, bits of its precision (log2(1 + ulps); the *32 solvers: float)";
    plot::Series max, p99;
    max.name = "max", p99.name = "p99";
    max.lines = p99.lines = false;
    p99.square = true;
    double widest = 0;
    for (const std::string& s : r.solvers)
        if (family_total(r, "generic", s).timed())
            widest = std::max(widest, family_total(r, "generic", s).ns.median());
    for (const std::string& s : r.solvers) {
        Row t = r.total(s), generic = family_total(r, "generic", s);
        if (!generic.timed()) continue;
        double ns = generic.ns.median(), bits = std::log2(1 + double(t.t_max));
        max.points.emplace_back(ns, bits);
        p99.points.emplace_back(ns, std::log2(1 + t.t_quantile(0.99)));
        // Solvers at nearly one point share one label ("stable, batch"), so no two labels pile up.
        auto near = std::find_if(pareto.labels.begin(), pareto.labels.end(), [&](const auto& l) {
            return std::fabs(l.x - ns) < 0.06 * widest && std::fabs(l.y - bits) < 3;
        });
        if (near != pareto.labels.end())
            near->text += ", " + s;
        else
            pareto.labels.push_back({ns, bits, s});
    }
    pareto.series = {max, p99};
    if (!max.points.empty()) jsonl::write_file(dir + "/pareto.svg", plot::svg({pareto}));
    // Error against difficulty, one figure per family.
    std::vector<std::string> families;
    for (const auto& [key, points] : r.curves)
        if (key.family != "generic" &&
            std::find(families.begin(), families.end(), key.family) == families.end())
            families.push_back(key.family);
    for (const std::string& f : families)
        jsonl::write_file(dir + "/" + difficulty_figure(f),
                          plot::svg({difficulty_chart(r, f, "k (difficulty 2^-k)")}));
    // Distance: the shape from the world origin beside the ray's origin from the shape.
    auto has = [&](const char* f) {
        return std::find(families.begin(), families.end(), f) != families.end();
    };
    if (has("scale") && has("far_origin"))
        jsonl::write_file(
            dir + "/distance.svg",
            plot::svg({difficulty_chart(r, "scale",
                                        "k: the scene scaled by 2^+-k, or the shape 2^min(k,50) "
                                        "from the origin"),
                       difficulty_chart(r, "far_origin",
                                        "k: the ray's origin 2^k shape sizes from the shape")}));
    return true;
}

namespace {

// Files an earlier run left that would describe another report: report.md and report.html, and
// the figures (report.json stays: it is the record until this run's replaces it).
bool earlier_file(const std::string& name) {
    auto ends = [&](const char* e) {
        std::size_t n = std::strlen(e);
        return name.size() >= n && name.compare(name.size() - n, n, e) == 0;
    };
    bool figure = ends(".svg") || ends(".png") || ends(".dat");
    return name == "plots.gp" || name == "report.html" || name == "report.md" ||
           (figure && (name.rfind("pareto.", 0) == 0 || name.rfind("difficulty_", 0) == 0 ||
                       name.rfind("distance.", 0) == 0));
}

} // namespace

OutputDirectory::OutputDirectory(const std::string& dir) : dir_(dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw std::runtime_error("cannot create " + dir + ": " + ec.message());
    if (!fs::is_directory(dir, ec)) throw std::runtime_error(dir + " is not a directory");
    std::string lock = dir + "/.lock";
    lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (lock_fd_ < 0)
        throw std::runtime_error("cannot write " + lock + ": " + std::strerror(errno));
    if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
        char holder[32] = {};
        ssize_t n = ::pread(lock_fd_, holder, sizeof holder - 1, 0);
        ::close(lock_fd_);
        lock_fd_ = -1;
        throw std::runtime_error(dir + " is in use by another run (" + lock + " is locked" +
                                 (n > 0 ? std::string(" by process ") + holder : "") + ")");
    }
    std::string pid = std::to_string(::getpid());
    if (::ftruncate(lock_fd_, 0) != 0 || ::pwrite(lock_fd_, pid.data(), pid.size(), 0) < 0)
        throw std::runtime_error("cannot write " + lock + ": " + std::strerror(errno));
    for (const auto& entry : fs::directory_iterator(dir, ec))
        if (earlier_file(entry.path().filename().string())) {
            fs::remove(entry.path(), ec);
            if (ec)
                throw std::runtime_error("cannot remove " + entry.path().string() +
                                         " (an earlier run's): " + ec.message());
        }
}

OutputDirectory::~OutputDirectory() {
    if (lock_fd_ >= 0) ::close(lock_fd_); // releases the lock
}

void OutputDirectory::checkpoint(const Report& r) {
    jsonl::write_file(dir_ + "/report.json", to_json(r));
    jsonl::write_file(dir_ + "/report.md", markdown(r));
}

void OutputDirectory::finish(const Report& r, bool plots,
                             const std::function<void(const std::string&)>& also) {
    std::string text;
    try {
        text = to_json(r);
        Report saved;
        std::string why;
        if (!from_json(text, &saved, &why))
            throw std::logic_error("the report written does not read back: " + why);
        if (plots) write_plots(saved, dir_);
        jsonl::write_file(dir_ + "/report.md", markdown(saved));
        if (also) also(dir_);
    } catch (const std::bad_alloc&) {
        throw std::runtime_error(saved_out_of_memory(text, r.status));
    }
    jsonl::write_file(dir_ + "/report.json", text);
}

// What is left when the memory runs out at the end of a run: report.json with every result when
// its text was made (else the last checkpoint's, marked stopped: never "running"), and no
// report.md or report.html of an earlier checkpoint that would contradict it. Says which.
std::string OutputDirectory::saved_out_of_memory(const std::string& text, Status status) {
    const std::string json = dir_ + "/report.json";
    std::error_code ec;
    for (const char* stale : {"/report.md", "/report.html"})
        std::filesystem::remove(dir_ + stale, ec);
    std::string rendered = "; render report.md and report.html with `linequad merge --out "
                           "ANOTHER_DIR " +
                           json + "` where there is more memory";
    if (!text.empty()) {
        jsonl::write_file(json, text);
        return "out of memory while writing the report in " + dir_ + ": report.json holds " +
               (status == Status::complete
                    ? "every result"
                    : "what was measured, marked " + std::string(status_name(status))) +
               rendered;
    }
    // The checkpoint's status is its second field (after the format's name), in words of the
    // same length: changed in place, with the memory the reading took.
    std::string saved = jsonl::read_file(json);
    const std::string running = "\"status\":\"running\"";
    std::size_t at = saved.find(running);
    if (at == std::string::npos || at > 40)
        return "out of memory while writing the report in " + dir_ +
               ": its report.json is not a checkpoint of this run";
    saved.replace(at + running.size() - 8, 7, status_name(Status::stopped));
    jsonl::write_file(json, saved);
    return "out of memory while writing the report in " + dir_ +
           ": report.json holds its last checkpoint (saved every few seconds), marked stopped" +
           rendered;
}

} // namespace linequad::audit
