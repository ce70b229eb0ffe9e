// linequad: solve cases with any solver; audit solvers against the exact oracle.
#include "linequad/audit.hpp"
#include "linequad/case_io.hpp"
#include "linequad/registry.hpp"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace {

using namespace linequad;

const char* const usage = R"(usage:
  linequad solve [--solver NAME[,NAME...]|all] [--need any|nearest|all] [--no-points] [FILE|-]
      Solves every case of a JSON Lines file (or standard input) and writes one result line per
      case and solver. A malformed line gets an error result naming the line and the field.
  linequad audit [--cases N] [--seed S] [--families F,...] [--solvers S,...] [--shard K/N]
                 [--out DIR] [--no-plots] [--check]
      Grades solvers against the exact oracle over the case families; writes DIR/report.json,
      report.md and plots (default DIR: reports/latest). N cases per family, shape and range.
      --check: exit 1 if a solver breaks a claim the README makes for it.
  linequad audit --cases-file CASES --results RESULTS [--out DIR]
      Grades someone else's answers (result lines whose ids match the cases).
  linequad cases [--cases N] [--seed S] [--families F,...] [--shard K/N]
      Writes a campaign's cases (for your own solver to answer).
  linequad merge --out DIR REPORT.json...
      Combines shard reports exactly (counts, maxima, histograms).
  linequad solvers          lists the solver names
  linequad --version        version, compiler and floating-point flags
)";

int fail(const std::string& msg) {
    std::fprintf(stderr, "linequad: %s\n", msg.c_str());
    return 2;
}

std::vector<const Solver*> parse_solvers(const std::string& list, std::string* bad) {
    std::vector<const Solver*> out;
    if (list == "all") {
        for (const Solver& s : all_solvers())
            out.push_back(&s);
        return out;
    }
    std::size_t start = 0;
    while (start <= list.size()) {
        std::size_t comma = list.find(',', start);
        std::string name =
            list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        const Solver* s = find_solver(name);
        if (!s) {
            *bad = name;
            return {};
        }
        out.push_back(s);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return out;
}

int cmd_solve(int argc, char** argv) {
    std::string solver_list = "stable", file = "-";
    Query query;
    for (int i = 0; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--solver" && i + 1 < argc)
            solver_list = argv[++i];
        else if (a == "--need" && i + 1 < argc) {
            std::string n = argv[++i];
            if (n == "any")
                query.need = Need::any;
            else if (n == "nearest")
                query.need = Need::nearest;
            else if (n == "all")
                query.need = Need::all;
            else
                return fail("--need takes any, nearest or all, not '" + n + "'");
        } else if (a == "--no-points")
            query.points = false;
        else if (a.size() > 1 && a[0] == '-')
            return fail("unknown option '" + a + "'\n" + usage);
        else
            file = a;
    }
    std::string bad;
    std::vector<const Solver*> solvers = parse_solvers(solver_list, &bad);
    if (solvers.empty()) return fail("no solver named '" + bad + "' (see: linequad solvers)");

    std::ifstream in_file;
    std::istream* in = &std::cin;
    if (file != "-") {
        in_file.open(file);
        if (!in_file) return fail("cannot open '" + file + "': " + std::strerror(errno));
        in = &in_file;
    }
    // Line buffered: a long run that is stopped keeps every result it has written.
    std::setvbuf(stdout, nullptr, _IOLBF, 1 << 16);
    std::string line, why;
    long line_no = 0, errors = 0;
    Case c;
    while (std::getline(*in, line)) {
        ++line_no;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        bool parsed = parse_case(line, &c, &why);
        for (const Solver* s : solvers) {
            std::string out;
            if (!parsed) {
                out = format_failure(c.id, s->name, "malformed_case",
                                     "line " + std::to_string(line_no) + ": " + why);
            } else {
                Result r = (*s)(c.shape, c.line, query);
                out = format_result(c.id, s->name, r, query.points);
            }
            std::fputs(out.c_str(), stdout);
            std::fputc('\n', stdout);
        }
        if (!parsed) {
            ++errors;
            std::fprintf(stderr, "linequad: line %ld: %s\n", line_no, why.c_str());
        }
    }
    std::fflush(stdout);
    return errors ? 1 : 0;
}

// Options shared by audit and cases. Returns an error message, or "" when all is well.
std::string parse_campaign(int argc, char** argv, audit::Options& o, bool* check) {
    o.out_dir = "reports/latest";
    for (int i = 0; i < argc; ++i) {
        std::string a = argv[i];
        auto value = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
        auto number = [&](const std::string& what, std::uint64_t* out) {
            std::string v = value();
            char* end = nullptr;
            unsigned long long x = std::strtoull(v.c_str(), &end, 10);
            if (v.empty() || *end) return what + " takes a whole number, not '" + v + "'";
            *out = x;
            return std::string();
        };
        std::string err;
        if (a == "--cases")
            err = number("--cases", &o.cases_per_group);
        else if (a == "--seed")
            err = number("--seed", &o.seed);
        else if (a == "--out")
            o.out_dir = value();
        else if (a == "--no-plots")
            o.plots = false;
        else if (a == "--check" && check)
            *check = true;
        else if (a == "--results")
            o.results_file = value();
        else if (a == "--cases-file")
            o.cases_file = value();
        else if (a == "--families" || a == "--solvers") {
            std::string list = value();
            std::size_t start = 0;
            while (start < list.size()) {
                std::size_t comma = std::min(list.find(',', start), list.size());
                std::string name = list.substr(start, comma - start);
                start = comma + 1;
                if (a == "--solvers") {
                    if (!find_solver(name) && name != audit::batch_name)
                        return "no solver named '" + name + "' (see: linequad solvers)";
                    o.solvers.push_back(name);
                } else {
                    Family f;
                    if (!parse_family(name, &f)) return "no family named '" + name + "'";
                    o.families.push_back(f);
                }
            }
        } else if (a == "--shard") {
            std::string v = value();
            int k = -1, n = 0;
            if (std::sscanf(v.c_str(), "%d/%d", &k, &n) != 2 || n < 1 || k < 0 || k >= n)
                return "--shard takes K/N with 0 <= K < N, not '" + v + "'";
            o.shard = k, o.shards = n;
        } else {
            return "unknown option '" + a + "'";
        }
        if (!err.empty()) return err;
    }
    if (o.results_file.empty() != o.cases_file.empty())
        return "--results and --cases-file go together";
    return "";
}

std::string joined(int argc, char** argv) {
    std::string s = "linequad";
    for (int i = 0; i < argc; ++i)
        s += std::string(" ") + argv[i];
    return s;
}

int cmd_audit(int argc, char** argv) {
    audit::Options o;
    bool check = false;
    if (std::string err = parse_campaign(argc - 1, argv + 1, o, &check); !err.empty())
        return fail(err);
    o.command = joined(argc, argv);
    audit::Report r;
    try {
        r = audit::run(o);
    } catch (const std::exception& e) {
        return fail(e.what());
    }
    std::fprintf(stderr, "audit: %s/report.md (%.1f s)\n", o.out_dir.c_str(), r.seconds);
    for (const std::string& s : r.solvers) {
        audit::Row t = r.total(s);
        std::printf("%-10s cases %8llu  mismatched %6llu  t max %12s ulps  p99 %8.3g\n", s.c_str(),
                    (unsigned long long)t.cases, (unsigned long long)t.cases_mismatched,
                    t.t_max == UINT64_MAX ? "inf" : std::to_string(t.t_max).c_str(),
                    t.t_error.quantile(0.99));
    }
    if (check) {
        std::vector<std::string> broken = audit::broken_claims(r);
        for (const std::string& b : broken)
            std::fprintf(stderr, "audit --check: %s\n", b.c_str());
        if (!broken.empty()) return 1;
        std::printf("audit --check: every claim holds\n");
    }
    return r.complete ? 0 : 130;
}

int cmd_cases(int argc, char** argv) {
    audit::Options o;
    if (std::string err = parse_campaign(argc - 1, argv + 1, o, nullptr); !err.empty())
        return fail(err);
    audit::for_each_case(o, [](const Case& c) {
        std::fputs(format_case(c).c_str(), stdout);
        std::fputc('\n', stdout);
    });
    return 0;
}

int cmd_merge(int argc, char** argv) {
    std::string out;
    std::vector<std::string> inputs;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--out" && i + 1 < argc)
            out = argv[++i];
        else
            inputs.push_back(a);
    }
    if (out.empty() || inputs.empty())
        return fail("usage: linequad merge --out DIR REPORT.json...");
    audit::Report merged;
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        audit::Report r;
        std::string why;
        if (!audit::read_json(inputs[i], &r, &why)) return fail(why);
        if (i == 0) {
            merged = r;
            merged.shard = 0;
            continue;
        }
        if (r.seed != merged.seed || r.cases_per_group != merged.cases_per_group ||
            r.shards != merged.shards)
            return fail(inputs[i] +
                        " is from another campaign (seed, cases or shard count differ)");
        merged.merge(r);
    }
    merged.command = joined(argc, argv);
    std::filesystem::create_directories(out);
    audit::write_json(merged, out + "/report.json");
    audit::write_markdown(merged, out);
    audit::write_plots(merged, out);
    std::fprintf(stderr, "merge: %zu reports into %s/report.md\n", inputs.size(), out.c_str());
    return 0;
}

int cmd_version() {
    BuildInfo b = build_info();
    std::printf("linequad %s\ncompiler: %s\nfast/ flags: %s\n", b.version, b.compiler,
                b.fast_flags);
    std::printf("FP contraction in fast/: %s\n",
                std::strstr(b.fast_flags, "-ffp-contract=off") ? "off" : "compiler default");
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fputs(usage, stderr);
        return 2;
    }
    std::string cmd = argv[1];
    if (cmd == "--version" || cmd == "version") return cmd_version();
    if (cmd == "--help" || cmd == "help" || cmd == "-h") return std::fputs(usage, stdout), 0;
    if (cmd == "solvers") {
        for (const Solver& s : all_solvers())
            std::printf("%-8s %s\n", std::string(s.name).c_str(), std::string(s.summary).c_str());
        return 0;
    }
    if (cmd == "solve") return cmd_solve(argc - 2, argv + 2);
    if (cmd == "audit") return cmd_audit(argc - 1, argv + 1);
    if (cmd == "cases") return cmd_cases(argc - 1, argv + 1);
    if (cmd == "merge") return cmd_merge(argc - 1, argv + 1);
    return fail("unknown command '" + cmd + "'\n" + usage);
}
