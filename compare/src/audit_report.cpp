// report.md (for people), the gnuplot figures, and the output directory that holds them beside
// report.json.
#include "linequad/audit.hpp"

#include "jsonl.hpp"

#include <algorithm>
#include <cerrno>
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
std::string fmt_ulps(std::uint64_t u) {
    return u == UINT64_MAX ? "inf" : fmt(double(u));
}

// The shell command that replays a case: the solver and the oracle side by side (a plugin's
// solver with its plugin loaded; an external solver's case is the one it was posed).
std::string replay(const Report& r, const Worst& w, const std::string& solver) {
    std::string quoted;
    for (char c : w.case_line())
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    // `solve` takes one line at a time; batch's results are stable's, bit for bit.
    std::string scalar = solver == batch_name ? "stable" : solver;
    std::string plugin;
    if (auto it = r.external.find(solver); it != r.external.end() && !it->second.plugin.empty())
        plugin = " --plugin " + it->second.plugin;
    return "echo '" + quoted + "' | linequad solve" + plugin + " --solver " + scalar + ",exact";
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

// One solver's rows of one family, merged.
Row family_total(const Report& r, const std::string& family, const std::string& solver) {
    Row t;
    for (const auto& [key, row] : r.rows)
        if (key.family == family && key.solver == solver) t.merge(row);
    return t;
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
        md << " " << s << " |";
    md << "\n|---|";
    for (std::size_t i = 0; i < columns.size(); ++i)
        md << "---:|";
    md << "\n";
    for (const std::string& family : r.families) {
        md << "| " << family << " |";
        for (const std::string& name : columns) {
            Row t = family_total(r, family, name);
            if (t.cases == 0) {
                md << " - |";
                continue;
            }
            md << " " << t.cases_mismatched << " of " << t.cases << ", p99 "
               << fmt(t.t_quantile(0.99));
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
        md << "| " << key.first << " | " << key.second << " | " << row.cases << " | " << nw << " | "
           << dd << " | " << ex << " | " << fmt(all ? 100.0 * double(ex) / double(all) : 0) << " | "
           << fmt(row.ns.median()) << " |\n";
    }
    Row certified = r.total("certified");
    if (certified.bounded_roots)
        md << "\nA certified bound below half an ulp of t (the only kind that could prove a "
              "rounding on its own, without the Newton step): "
           << certified.bound_below_half_ulp << " of " << certified.bounded_roots
           << " certified roots.\n";
}

// Each double solver beside its float counterpart (stable beside stable32, ...), family by
// family: cases misclassified, and the t error, each in its own precision's ulps.
void write_float_beside_double(std::ostream& md, const Report& r) {
    std::vector<std::string> pairs;
    for (const std::string& s : r.solvers)
        if (std::find(r.solvers.begin(), r.solvers.end(), s + "32") != r.solvers.end())
            pairs.push_back(s);
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
// How each external solver was handed its cases.
void write_external(std::ostream& md, const Report& r) {
    if (r.external.empty()) return;
    md << "## Solvers from outside linequad\n\nEach is graded on the case as it was posed to it, "
          "against the exact reference for what it answers (every hit, the nearest, or the first "
          "entry into the solid).\n\n| solver | answers | t | surfaces | mapping |\n"
          "|---|---|---|---|---|\n";
    for (const auto& [name, e] : r.external)
        md << "| " << name << (e.plugin.empty() ? "" : " (`" + e.plugin + "`)") << " | "
           << e.answers << " | " << e.parametrisation << " | " << e.surface << " | " << e.mapping
           << " |\n";
    md << "\n";
}
} // namespace

std::string markdown(const Report& r) {
    std::ostringstream md;
    md << "# linequad accuracy audit\n\n";
    md << "| | |\n|---|---|\n";
    md << "| command | `" << r.command << "` |\n| commit | " << r.commit << " |\n| date | "
       << r.date << " |\n";
    md << "| machine | " << r.machine << " |\n| compiler | " << r.compiler << " |\n";
    md << "| fast/ flags | `" << r.flags << "` |\n";
    if (r.from_cases_file())
        md << "| cases | `" << r.cases_file << "` (" << r.cases_count << " cases) |\n";
    else
        md << "| seed | " << r.seed << " |\n| cases per family, shape and range | "
           << r.cases_per_group << " |\n";
    md << "| shapes | ";
    for (const std::string& s : r.shapes)
        md << s << (&s == &r.shapes.back() ? "" : ", ");
    md << " (frames: " << r.frames << ") |\n";
    if (r.grades_results())
        md << "| graded | the answers in `" << r.results_file << "` (not timed) |\n";
    md << "| linequad | " << r.version << " |\n| shards | " << r.shards << " |\n| complete | "
       << status_line(r) << " |\n";
    md << "| run time | " << fmt(r.seconds) << " s |\n\n";
    md << "Errors are distances to the exact oracle's correctly rounded value, in units in the "
          "last "
          "place (0: correctly rounded); bits = log2(1 + ulps) as Herbie counts them. Points: the "
          "largest coordinate error in ulps of the point's scale, max(|p|, |L0|, |t v|). A "
          "mismatch is a "
          "different classification (hit count, tangent, on-surface), a NaN/infinity, or a "
          "refusal; "
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

    md << "## Headline: every family\n\n";
    md << "Scene error: the t error as a distance, |t - t_oracle| |v|, in ulps of the scene's "
          "magnitude (the largest of |L0|, |t v| and the shape's coordinates), p99 / max. "
          "Unrepresented: cases the solver could not take (not graded). A dash: not measured "
          "(no points in the answers, no time for answers read from a file).\n\n";
    md << "| solver | precision | cases | unrepresented | mismatched | uncertain | bound "
          "violations | t max ulps | t p99 | t p50 | mean bits | scene error | point max ulps | "
          "ns/solve (generic) |\n";
    md << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    bool timed = false;
    for (const std::string& s : r.solvers) {
        Row t = r.total(s), generic = family_total(r, "generic", s);
        timed = timed || generic.timed();
        md << "| " << s << " | " << precision_of(t) << " | " << t.cases << " | " << t.unrepresented
           << " | " << t.cases_mismatched << " | "
           << (t.bounded_roots || t.uncertain ? num(t.uncertain) : "-") << " | "
           << (t.bounded_roots ? num(t.bound_violations) + " of " + num(t.bounded_roots) : "-")
           << " | " << fmt_ulps(t.t_max) << " | " << fmt(t.t_quantile(0.99)) << " | "
           << fmt(t.t_quantile(0.5)) << " | "
           << fmt(t.graded_roots ? t.t_bits_sum / double(t.graded_roots) : 0) << " | "
           << scene_error(t) << " | " << point_max(t) << " | " << median_ns(generic) << " |\n";
    }
    if (timed) md << "\n![run time against error](pareto.svg)\n\n";
    write_external(md, r);

    md << "## By family and shape\n\n";
    md << "| family | shape | solver | cases | unrep. | mismatched | by kind | uncertain | "
          "bound viol. | bound/err p50 | t max | t p99 | t p99.9 | t mean | scene error | "
          "point max | ns/solve |\n";
    md << "|---|---|---|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const auto& [key, row] : r.rows) {
        std::string kinds;
        for (int m = 0; m < mismatch_kinds; ++m)
            if (row.mismatches[m])
                kinds += (kinds.empty() ? "" : ", ") + std::string(mismatch_name(m)) + " " +
                         num(row.mismatches[m]);
        // The solver's own refusals, by its names for them (crashes among them).
        for (const auto& [name, n] : row.foreign)
            kinds += (kinds.empty() ? "" : ", ") + ("'" + name + "' ") + num(n);
        md << "| " << key.family << " | " << key.shape << " | " << key.solver << " | " << row.cases
           << " | " << row.unrepresented << " | " << row.cases_mismatched << " | " << kinds << " | "
           << (row.bounded_roots || row.uncertain ? num(row.uncertain) : "-") << " | "
           << (row.bounded_roots ? num(row.bound_violations) : "-") << " | "
           << (row.bounded_roots ? fmt(row.tightness.quantile(0.5)) : "-") << " | "
           << fmt_ulps(row.t_max) << " | " << fmt(row.t_quantile(0.99)) << " | "
           << fmt(row.t_quantile(0.999)) << " | "
           << fmt(row.graded_roots ? row.t_sum / double(row.graded_roots) : 0) << " | "
           << scene_error(row) << " | " << point_max(row) << " | " << median_ns(row) << " |\n";
    }

    write_external_by_family(md, r);
    write_float_beside_double(md, r);
    write_rungs(md, r);

    md << "\n## Error against difficulty\n\n";
    for (const std::string& f : r.families)
        for (const auto& [key, points] : r.curves)
            if (key.family == f && f != "generic") { // write_plots() draws these
                md << "![" << f << "](difficulty_" << f << ".svg)\n\n";
                break;
            }

    md << "## Worst cases\n\nEach replays with the command under it.\n\n";
    for (const auto& [key, row] : r.rows) {
        if (row.worst.empty()) continue;
        md << "### " << key.name() << "\n\n";
        for (const Worst& w : row.worst) {
            md << (w.mismatch ? "- **mismatch**" : "- t error " + fmt_ulps(w.ulps) + " ulps")
               << "\n\n";
            md << "  ```\n  " << w.case_line() << "\n  " << w.solver_line() << "\n  "
               << w.oracle_line() << "\n  ```\n\n";
            md << "  `" << replay(r, w, key.solver) << "`\n\n";
        }
    }
    md << "## Oracle rounding\n\nFloats rounded from the oracle's interval filter alone: "
       << r.oracle_by_intervals
       << ". Values rounded by its double-word enclosures: " << r.oracle_by_filter
       << ". The rest, by MPFR at 64, 128, 256, ... bits: ";
    for (int i = 0; i < 8; ++i)
        md << (i ? ", " : "") << r.oracle_steps[i];
    md << ".\n";
    return md.str();
}

bool write_plots(const Report& r, const std::string& dir) {
    if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
        std::fprintf(stderr,
                     "linequad: gnuplot not found: no plots (apt-get install gnuplot-nox)\n");
        return false;
    }
    std::ostringstream gp;
    auto both_terminals = [&](const std::string& name, const std::string& body) {
        gp << "set terminal svg size 800,500 dynamic noenhanced font 'sans,11'\nset output '" << dir
           << "/" << name << ".svg'\n"
           << body << "set terminal pngcairo size 800,500 noenhanced font 'sans,10'\nset output '"
           << dir << "/" << name << ".png'\nreplot\nunset output\n";
    };
    // Pareto: median ns per solve on generic cases against max and p99 t error over all families.
    {
        std::ostringstream dat;
        dat << "# solver ns_generic max_ulps p99_ulps\n";
        // Only solvers timed on generic cases: an answer read from a file has no time.
        int points = 0;
        for (const std::string& s : r.solvers) {
            Row t = r.total(s), generic = family_total(r, "generic", s);
            if (!generic.timed()) continue;
            ++points;
            dat << s << " " << generic.ns.median() << " " << 1 + double(t.t_max) << " "
                << 1 + t.t_quantile(0.99) << "\n";
        }
        jsonl::write_file(dir + "/pareto.dat", dat.str());
        if (points)
            both_terminals(
                "pareto",
                "set title 'run time against error (every family)'\nset xlabel "
                "'ns per solve, median, generic cases'\n"
                "set ylabel '1 + t error in ulps of its precision (the *32 solvers: float)'\n"
                "set logscale y\nset grid\nset "
                "key outside bottom center horizontal\n"
                "set offsets graph 0.15, graph 0.15, graph 0.1, graph 0.1\n"
                "plot '" +
                    dir +
                    "/pareto.dat' using 2:3:1 with labels offset 0,1 notitle, "
                    "'' using 2:3 with points pt 7 ps 1.5 title 'max', '' using "
                    "2:4 with points pt 5 ps 1.5 title 'p99'\n");
    }
    // Error against difficulty, one figure per family, one curve per solver.
    std::map<std::string, std::vector<std::string>> families;
    for (const auto& [key, points] : r.curves) {
        if (key.family == "generic") continue;
        std::ostringstream dat;
        dat << "# k cases mismatched_fraction 1+max_ulps\n";
        for (const auto& [k, p] : points)
            dat << k << " " << p.cases << " "
                << (p.cases ? double(p.mismatched) / double(p.cases) : 0) << " "
                << 1 + double(p.t_max) << "\n";
        jsonl::write_file(dir + "/difficulty_" + key.family + "_" + key.solver + ".dat", dat.str());
        families[key.family].push_back(key.solver);
    }
    for (const auto& [family, solvers] : families) {
        std::string plot = "set title '" + family +
                           ": error and misclassification against k'\n"
                           "set xlabel 'k (difficulty 2^-k)'\nset ylabel '1 + max t error "
                           "(ulps)'\nset logscale y\n"
                           "set y2label 'fraction of cases misclassified'\nset y2range [0:1]\nset "
                           "y2tics\nset ytics nomirror\n"
                           "set grid\nset key outside right\nplot ";
        for (std::size_t i = 0; i < solvers.size(); ++i) {
            std::string f = "'" + dir + "/difficulty_" + family + "_" + solvers[i] + ".dat'";
            plot += (i ? ", " : "") + f + " using 1:4 with linespoints lw 2 title '" + solvers[i] +
                    " max error', " + f + " using 1:3 axes x1y2 with lines dt 2 title '" +
                    solvers[i] + " misclassified'";
        }
        both_terminals("difficulty_" + family, plot + "\n");
    }
    jsonl::write_file(dir + "/plots.gp", gp.str());
    std::string cmd = "gnuplot '" + dir + "/plots.gp' 2>&1";
    if (std::system(cmd.c_str()) != 0) {
        std::fprintf(stderr, "linequad: gnuplot failed on %s/plots.gp\n", dir.c_str());
        return false;
    }
    return true;
}

namespace {

// Files an earlier run left that would describe another report (report.html is written when
// the run ends).
bool earlier_figure(const std::string& name) {
    auto ends = [&](const char* e) {
        std::size_t n = std::strlen(e);
        return name.size() >= n && name.compare(name.size() - n, n, e) == 0;
    };
    bool figure = ends(".svg") || ends(".png") || ends(".dat");
    return name == "plots.gp" || name == "report.html" ||
           (figure && (name.rfind("pareto.", 0) == 0 || name.rfind("difficulty_", 0) == 0));
}

} // namespace

OutputDirectory::OutputDirectory(const std::string& dir) : dir_(dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw std::runtime_error("cannot create " + dir + ": " + ec.message());
    if (!fs::is_directory(dir, ec)) throw std::runtime_error(dir + " is not a directory");
    std::string lock = dir + "/.lock";
    lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
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
        if (entry.is_regular_file() && earlier_figure(entry.path().filename().string()))
            fs::remove(entry.path(), ec);
}

OutputDirectory::~OutputDirectory() {
    if (lock_fd_ >= 0) ::close(lock_fd_); // releases the lock
}

namespace {
// report.json, then report.md from what was saved. Returns the report as read back.
Report save_pair(const Report& r, const std::string& dir) {
    std::string text = to_json(r);
    jsonl::write_file(dir + "/report.json", text);
    Report saved;
    std::string why;
    if (!from_json(text, &saved, &why))
        throw std::logic_error("the report written does not read back: " + why);
    jsonl::write_file(dir + "/report.md", markdown(saved));
    return saved;
}
} // namespace

void OutputDirectory::save(const Report& r) {
    save_pair(r, dir_);
}

void OutputDirectory::checkpoint(const Report& r) {
    jsonl::write_file(dir_ + "/report.json", to_json(r));
    jsonl::write_file(dir_ + "/report.md", markdown(r));
}

void OutputDirectory::save_with_plots(const Report& r) {
    write_plots(save_pair(r, dir_), dir_);
}

} // namespace linequad::audit
