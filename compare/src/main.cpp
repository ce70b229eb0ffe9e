// linequad: solve cases with any solver; audit solvers against the exact oracle.
#include "linequad/case_io.hpp"
#include "linequad/registry.hpp"

#include <cstdio>
#include <cstring>
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
        for (const Solver& s : all_solvers()) out.push_back(&s);
        return out;
    }
    std::size_t start = 0;
    while (start <= list.size()) {
        std::size_t comma = list.find(',', start);
        std::string name = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
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
        if (a == "--solver" && i + 1 < argc) solver_list = argv[++i];
        else if (a == "--need" && i + 1 < argc) {
            std::string n = argv[++i];
            if (n == "any") query.need = Need::any;
            else if (n == "nearest") query.need = Need::nearest;
            else if (n == "all") query.need = Need::all;
            else return fail("--need takes any, nearest or all, not '" + n + "'");
        } else if (a == "--no-points") query.points = false;
        else if (a.size() > 1 && a[0] == '-') return fail("unknown option '" + a + "'\n" + usage);
        else file = a;
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

int cmd_version() {
    BuildInfo b = build_info();
    std::printf("linequad %s\ncompiler: %s\nfast/ flags: %s\n", b.version, b.compiler, b.fast_flags);
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
    return fail("unknown command '" + cmd + "'\n" + usage);
}
