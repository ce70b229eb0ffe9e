// What the subcommands share: options read strictly, solvers from outside, output.
#include "cli/cli.hpp"

#include "linequad/families.hpp"
#include "linequad/registry.hpp"

#include "io/escape.hpp"
#include "io/jsonl.hpp"
#include "io/process.hpp"
#include "peers/peers.hpp"
#include "run/plugin_worker.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace linequad::cli {

std::string whole_number(const std::string& text, std::uint64_t lo, std::uint64_t hi,
                         std::uint64_t* out) {
    std::uint64_t x = 0;
    const char* end = text.data() + text.size();
    auto [p, ec] = std::from_chars(text.data(), end, x);
    bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
    if (!digits || ec != std::errc() || p != end || x < lo || x > hi)
        return "expected a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
               ", not '" + text + "'";
    if (out) *out = x;
    return "";
}

CLI::Validator WholeNumber(std::uint64_t lo, std::uint64_t hi) {
    return CLI::Validator(
        [=](const std::string& text) { return whole_number(text, lo, hi, nullptr); },
        std::to_string(lo) + ".." + std::to_string(hi));
}

std::uint64_t to_whole(const std::string& text) {
    std::uint64_t x = 0;
    whole_number(text, 0, UINT64_MAX, &x);
    return x;
}

namespace {

// A finite number, all of the text, in [lo, hi] (lo excluded when open); "" or why not.
std::string real_in(const std::string& text, double lo, bool open, double hi, const char* what) {
    char* end = nullptr;
    double x = std::strtod(text.c_str(), &end);
    bool ok = !text.empty() && end == text.c_str() + text.size() && std::isfinite(x) &&
              (open ? x > lo : x >= lo) && x <= hi;
    return ok ? "" : std::string("expected ") + what + ", not '" + text + "'";
}

} // namespace

CLI::Validator PositiveNumber(double hi) {
    char most[32];
    std::snprintf(most, sizeof most, "%g", hi);
    std::string what = "a number above 0 and at most " + std::string(most);
    return CLI::Validator(
        [=](const std::string& t) { return real_in(t, 0, true, hi, what.c_str()); }, "");
}

CLI::Validator Fraction() {
    return CLI::Validator(
        [](const std::string& t) { return real_in(t, 0, false, HUGE_VAL, "a fraction >= 0"); }, "");
}

double to_real(const std::string& text) {
    return std::strtod(text.c_str(), nullptr);
}

std::string shard_error(const std::string& text, int* k, int* n) {
    std::size_t slash = text.find('/');
    std::uint64_t kk = 0, nn = 0;
    if (slash == std::string::npos ||
        !whole_number(text.substr(slash + 1), 1, max_shards, &nn).empty() ||
        !whole_number(text.substr(0, slash), 0, nn - 1, &kk).empty())
        return "expected K/N with 0 <= K < N <= " + std::to_string(max_shards) + ", not '" + text +
               "'";
    if (k) *k = int(kk), *n = int(nn);
    return "";
}

std::vector<std::string> split_list(const std::string& list) {
    std::vector<std::string> out;
    std::size_t start = 0;
    for (;;) {
        std::size_t comma = list.find(',', start);
        out.push_back(list.substr(start, comma - start));
        if (comma == std::string::npos) return out;
        start = comma + 1;
    }
}

CLI::Validator each_of_list(std::function<std::string(const std::string&)> check) {
    return CLI::Validator(
        [check](const std::string& list) {
            for (const std::string& name : split_list(list))
                if (std::string why = check(name); !why.empty()) return why;
            return std::string();
        },
        "");
}

std::string joined(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names)
        out += (out.empty() ? "" : ", ") + n;
    return out;
}

namespace {

// Levenshtein distance: insertions, deletions and substitutions of one character.
std::size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = above;
        }
    }
    return row[b.size()];
}

} // namespace

std::string unknown_name(const Kind& kind, const std::string& name,
                         const std::vector<std::string>& known) {
    if (std::find(known.begin(), known.end(), name) != known.end()) return "";
    std::string why = "no " + kind.one + " named '" + name + "'";
    // A slip: at most a third of the name's letters wrong (and not the whole of a short name).
    std::size_t best = SIZE_MAX;
    std::string nearest;
    for (const std::string& k : known)
        if (std::size_t d = edit_distance(name, k); d < best) best = d, nearest = k;
    if (!nearest.empty() && best <= std::max<std::size_t>(1, name.size() / 3))
        why += " (did you mean '" + nearest + "'?)";
    return why + "; the " + kind.many + ": " + joined(known);
}

CLI::Validator names_in(const Kind& kind, std::vector<std::string> known) {
    return each_of_list(
        [kind, known](const std::string& name) { return unknown_name(kind, name, known); });
}

void add_max_line_bytes(CLI::App* app, std::string& value, const char* help) {
    app->add_option("--max-line-bytes", value, help)
        ->type_name("N")
        ->check(WholeNumber(64, std::uint64_t(1) << 30))
        ->capture_default_str();
}

void add_plugin_options(CLI::App* app, std::vector<std::string>& plugins, std::string& timeout) {
    app->add_option("--plugin", plugins,
                    "a shared library of solvers (the C ABI of linequad/audit_plugin.h), run in "
                    "a worker process")
        ->type_name("LIB.so")
        ->check(CLI::ExistingFile);
    app->add_option("--solver-timeout", timeout,
                    "seconds a plugin's call may take before it is stopped and answered as "
                    "timed out")
        ->type_name("S")
        ->check(PositiveNumber(3600))
        ->capture_default_str();
}

void add_history_options(CLI::App* app, std::string& history, std::string& commit) {
    CLI::Option* db =
        app->add_option("--history", history,
                        "append the report's summary to this SQLite database (linequad history)")
            ->type_name("DB");
    app->add_option("--commit", commit,
                    "the commit to record it under (default: linequad's own, as the report "
                    "names it): your solver's commit when you audit your solver")
        ->type_name("ID")
        ->needs(db);
}

std::string output_is_input(const std::string& output, const std::vector<std::string>& inputs) {
    struct stat out {};
    if (output == "-" || ::stat(output.c_str(), &out) != 0) return "";
    for (const std::string& in : inputs) {
        struct stat st {};
        if (::stat(in.c_str(), &st) == 0 && st.st_dev == out.st_dev && st.st_ino == out.st_ino)
            return output + " is the input " + in + ": writing it would destroy it";
    }
    return "";
}

void add_format_option(CLI::App* c, std::string& format) {
    c->add_option("--format", format,
                  "the standard output's form: md (markdown), text, or auto (text on a terminal, "
                  "markdown otherwise)")
        ->type_name("auto|md|text")
        ->check(CLI::IsMember({"auto", "md", "text"}))
        ->capture_default_str();
}

std::string for_standard_output(const std::string& md, const std::string& format) {
    bool text = format == "text" || (format == "auto" && ::isatty(STDOUT_FILENO));
    return text ? escape::markdown_as_text(md) : md;
}

std::vector<audit::ExternalSolver> external_solvers(const std::vector<std::string>& plugins,
                                                    const std::string& timeout,
                                                    const std::vector<std::string>& wanted) {
    std::vector<audit::ExternalSolver> out = peers::solvers();
    audit::PluginOptions po;
    po.program = process::self(); // the worker is this program in another mode
    po.timeout_seconds = to_real(timeout);
    std::vector<std::string> paths;
    for (const std::string& path : plugins)
        paths.push_back(process::absolute(path));
    auto asked = [&](const std::vector<std::string>& names) {
        for (const std::string& w : wanted)
            if (w == "*" || std::find(names.begin(), names.end(), w) != names.end()) return true;
        return false;
    };
    // A peer's plugin given with --plugin as well (a report's replay command) is loaded once.
    for (const peers::PluginPeer& p : peers::plugin_peers())
        if (asked(p.solvers) && std::find(paths.begin(), paths.end(), p.path) == paths.end())
            paths.insert(paths.begin(), p.path);
    for (const std::string& path : paths)
        for (audit::ExternalSolver& e : audit::load_plugin(path, po)) {
            for (const audit::ExternalSolver& x : out)
                if (x.name == e.name)
                    throw std::invalid_argument(path + ": solver '" + e.name +
                                                "' is already defined (by " +
                                                (x.plugin.empty() ? "linequad" : x.plugin) + ")");
            if (find_solver(e.name))
                throw std::invalid_argument(path + ": solver '" + e.name +
                                            "' has the name of one of linequad's");
            out.push_back(std::move(e));
        }
    return out;
}

const audit::ExternalSolver* find_external(const std::vector<audit::ExternalSolver>& ext,
                                           const std::string& name) {
    for (const audit::ExternalSolver& e : ext)
        if (e.name == name) return &e;
    return nullptr;
}

std::string solver_error(const std::string& name, bool batch_too,
                         const std::vector<audit::ExternalSolver>& ext) {
    if (find_solver(name) || find_external(ext, name) || (batch_too && name == audit::batch_name))
        return "";
    std::vector<std::string> known;
    for (const Solver& s : all_solvers())
        known.emplace_back(s.name);
    if (batch_too) known.emplace_back(audit::batch_name);
    for (const audit::ExternalSolver& e : ext)
        known.push_back(e.name);
    return unknown_name({"solver", "solvers"}, name, known) +
           " (linequad solvers --plugin LIB lists a plugin's)";
}

void report_plugin_output(const std::vector<audit::ExternalSolver>& ext) {
    for (const audit::ExternalSolver& e : ext)
        if (e.worker && e.worker->output_bytes(e.worker_index))
            std::fprintf(stderr, "linequad: %s wrote %llu bytes of its own; the first lines:\n%s\n",
                         e.name.c_str(), (unsigned long long)e.worker->output_bytes(e.worker_index),
                         e.worker->output(e.worker_index).c_str());
}

int fail(const std::string& msg) {
    std::fprintf(stderr, "linequad: %s\n", msg.c_str());
    return 2;
}

int write_markdown(const std::string& md, const std::string& out_file, const char* what) {
    if (out_file.empty()) {
        jsonl::Output out;
        out.text(md);
        out.finish();
    } else {
        jsonl::write_file(out_file, md);
        std::fprintf(stderr, "%s: %s\n", what, out_file.c_str());
    }
    return 0;
}

} // namespace linequad::cli
