// The report's first screen and the gates: the verdict first, shares and bits as people read them,
// roots of the wrong sign counted as such, a CI gate on a user's solver, and markdown made plain
// text for a terminal.
#include "io/escape.hpp"
#include "linequad/audit.hpp"
#include "linequad/audit_solver.hpp"
#include "linequad/solvers.hpp"

#include "support.hpp"

#include <filesystem>

using namespace linequad;
using namespace linequad::test;
namespace fs = std::filesystem;

TEST_CASE("verdict: shares read as people read them", "[report]") {
    CHECK(audit::percent_of(0, 0) == "-");
    CHECK(audit::percent_of(0, 7) == "0 %");
    CHECK(audit::percent_of(7, 7) == "100 %");
    CHECK(audit::percent_of(1, 1000000) == "< 0.01 %");
    CHECK(audit::percent_of(999999, 1000000) == "> 99.99 %");
    CHECK(audit::percent_of(1, 8) == "12.5 %");
    CHECK(audit::percent_of(1, 400) == "0.25 %");
}

TEST_CASE("verdict: report.md opens with it, one line per solver, then the family heat map",
          "[report]") {
    audit::Options o;
    o.cases_per_group = 40;
    o.families = {Family::generic, Family::near_tangent, Family::rim};
    o.shapes = {0, 4};
    o.solvers = {"seed", "correct"};
    audit::Report r = audit::run(o);
    std::string md = audit::markdown(r);
    CHECK(md.rfind("# linequad accuracy audit\n\n## Verdict\n\n", 0) == 0);
    std::size_t verdict = md.find("## Verdict"), next = md.find("\n## ", verdict + 1);
    std::string first = md.substr(verdict, next - verdict);
    INFO(first);
    CHECK(first.find("| [seed](#solver-seed) | ") != std::string::npos);
    CHECK(first.find("| [correct](#solver-correct) | 100 % of ") != std::string::npos);
    CHECK(first.find("### Misclassified, by family (% of the cases graded)") != std::string::npos);
    CHECK(first.find("| rim |") != std::string::npos);
    // Columns that would be empty for every solver are left out: ours declare no tolerance and
    // are asked every case. A solver with cases within its tolerance brings its column back.
    CHECK(first.find("| solver | right | misclassifies most (from k) |") != std::string::npos);
    CHECK(first.find("not asked") == std::string::npos);
    audit::Report tolerant = r;
    for (auto& [key, row] : tolerant.rows)
        if (key.solver == "seed") row.within_tolerance = row.cases_mismatched;
    std::string with = audit::markdown(tolerant);
    CHECK(with.find("| solver | right | within its tolerance | misclassifies most (from k) |") !=
          std::string::npos);
    // Provenance at the end, each solver in a section of its own.
    CHECK(md.find("## Solver\\: seed") != std::string::npos); // ':' escaped for markdown
    CHECK(md.find("## Provenance") > md.find("## Solver\\: seed"));
    CHECK(md.find("## Solver\\: correct") != std::string::npos);
    // The verdicts agree with the rows they sum.
    std::vector<audit::Verdict> v = audit::verdicts(r);
    REQUIRE(v.size() == 2);
    CHECK(v[0].misclassified == r.total("seed").cases_mismatched);
    CHECK(v[1].misclassified == 0);
    CHECK(v[1].t_max_bits() == 0);
    CHECK(audit::verdict_line(v[1]).rfind("correct: 100 % right of ", 0) == 0);
    // At most five worst cases per solver are shown, each with its replay.
    std::size_t replays = 0;
    for (std::size_t at = md.find("| linequad replay"); at != std::string::npos;
         at = md.find("| linequad replay", at + 1))
        ++replays;
    CHECK(replays > 0);
    CHECK(replays <= 5 * r.solvers.size());
}

TEST_CASE("grading: a root of the wrong sign is counted as such, not as 2^63 ulps",
          "[report][audit]") {
    audit::ExternalSolver flips;
    flips.name = "flips";
    flips.on<Sphere>() = [](const Sphere& s, const Line& l) -> std::optional<Result> {
        Result r = correct::intersect(s, l);
        for (int i = 0; i < r.count; ++i)
            r.hits[i].t = -r.hits[i].t;
        return r;
    };
    audit::Options o;
    o.cases_per_group = 50;
    o.families = {Family::generic};
    o.shapes = {4};
    o.solvers = {"flips"};
    audit::Report r = audit::run(o, {flips});
    audit::Row t = r.total("flips");
    // Its hits are out of order or out of the range at times (then misclassified); those
    // classified alike are graded, each root of the wrong sign counted.
    CHECK(t.t_sign_wrong > 0);
    CHECK(t.t_max < (std::uint64_t(1) << 62));
    audit::Report back;
    std::string why;
    REQUIRE(audit::from_json(audit::to_json(r), &back, &why));
    CHECK(back.total("flips").t_sign_wrong == t.t_sign_wrong);
}

TEST_CASE("expect: a gate on a user's solver, per family, with its exit status", "[cli][report]") {
    audit::Expectation e;
    std::string why;
    REQUIRE(audit::parse_expectation("stable:t_bits_p99<=12.5", &e, &why));
    CHECK(e.solver == "stable");
    CHECK(e.metric == "t_bits_p99");
    CHECK(e.at_most == 12.5);
    CHECK_FALSE(audit::parse_expectation("stable:bits<=1", &e, &why));
    CHECK(why.find("no metric 'bits'") != std::string::npos);
    CHECK_FALSE(audit::parse_expectation("stable:misclassified<=-1", &e, &why));
    CHECK_FALSE(audit::parse_expectation("stable misclassified 1", &e, &why));

    fs::path dir = scratch("expect");
    std::string run = "audit --cases 30 --solvers seed,correct --families generic,rim --no-plots ";
    Ran pass = program(run + "--expect 'correct:misclassified<=0' --expect "
                             "'correct:t_bits_max<=0' --out a",
                       dir);
    CHECK(pass.status == 0);
    CHECK(pass.err.find("audit --expect: 2 held in every family") != std::string::npos);
    Ran fail = program(run + "--expect 'seed:misclassified<=0' --out b", dir);
    CHECK(fail.status == 1);
    CHECK(fail.err.find("audit --expect: seed:misclassified<=0: rim has ") != std::string::npos);
    Ran unknown = program(run + "--expect 'stable:misclassified<=1' --out c", dir);
    CHECK(unknown.status == 2);
    CHECK(unknown.err.find("'stable' is not among --solvers") != std::string::npos);
    // A solver that graded nothing breaks the gate, saying so.
    audit::Report none;
    none.solvers = {"idle"};
    none.families = {"generic"};
    std::vector<std::string> broken = audit::unmet(none, {{"idle", "misclassified", 1}});
    REQUIRE(broken.size() == 1);
    CHECK(broken[0].find("idle graded no case") != std::string::npos);
    // The closing summary reads in words: shares and bits, no 19-digit integers.
    CHECK(pass.out.find("correct: 100 % right of ") != std::string::npos);
    CHECK(pass.out.find("bits at worst") != std::string::npos);
}

TEST_CASE("markdown as text: escapes and marks dropped, tables in columns", "[cli]") {
    std::string md = "# Title\n\nA \\*b\\* **c** `d`\n\n| a | bb |\n|---|---:|\n| xxx\\|y | z |\n";
    std::string text = escape::markdown_as_text(md);
    CHECK(text == "Title\n\nA *b* c d\n\na      bb\n-----  --\nxxx|y  z\n");
}

TEST_CASE("diff and history print plain text with --format text, markdown with --format md",
          "[cli]") {
    fs::path dir = scratch("format");
    REQUIRE(program("audit --cases 5 --solvers seed --families generic --shapes sphere "
                    "--no-plots --out r",
                    dir)
                .status == 0);
    Ran text = program("diff r/report.json r/report.json --format text", dir);
    CHECK(text.status == 0);
    CHECK(text.out.find("\\") == std::string::npos);
    CHECK(text.out.find("# ") == std::string::npos);
    Ran md = program("diff r/report.json r/report.json --format md", dir);
    CHECK(md.out.find("# linequad diff") != std::string::npos);
    // Into a pipe or a file (auto), markdown, as before.
    Ran piped = program("diff r/report.json r/report.json", dir);
    CHECK(piped.out == md.out);
}
