// Everything from outside is data: names, paths, case files, reports, ids and options from other
// people run nothing, read nothing outside a report, lose nothing produced and make no
// comparison lie. One test per class of attack; each fails if its fix regresses.
#include "support.hpp"

#include "linequad/audit.hpp"

#include "io/escape.hpp"
#include "report/history.hpp"

#include <nlohmann/json.hpp>

#include <regex>

using namespace linequad;
using namespace linequad::test;
namespace fs = std::filesystem;

namespace {

// A name that runs a command wherever it is pasted into a shell or a gnuplot script, breaks a
// markdown table, and is raw HTML.
const std::string hostile_name = "x'; system('touch PWNED'); print '|<b>$(touch PWNED2)`x`";

// Every file under dir, by its path from dir.
std::vector<std::string> files_under(const fs::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        out.push_back(fs::relative(e.path(), dir).string());
    return out;
}

} // namespace

TEST_CASE("outside data: no shell is started from compare/", "[outside]") {
    // Every program compare/ starts is started with an argument vector (process.hpp); a call to
    // system() or popen(), or a command for a shell, would let text from data become a command.
    const std::regex shell(
        R"((\bsystem\s*\()|(\bpopen\s*\()|(\bexecl[pe]?\s*\()|("/bin/sh")|("sh",\s*"-c"))");
    int files = 0;
    for (const auto& e :
         fs::recursive_directory_iterator(fs::path(LINEQUAD_SOURCE_DIR) / "compare")) {
        std::string ext = e.path().extension().string();
        if (ext != ".cpp" && ext != ".hpp" && ext != ".h") continue;
        ++files;
        std::string text = slurp(e.path());
        std::smatch m;
        INFO(e.path().string());
        CHECK_FALSE(std::regex_search(text, m, shell));
    }
    CHECK(files > 20);
}

TEST_CASE("outside data: a name from a cases file or a report runs nothing and breaks nothing",
          "[outside][cli]") {
    fs::path dir = scratch("outside_names");
    REQUIRE(program("cases --families near_tangent --shapes cylinder --cases 6 > c.jsonl", dir)
                .status == 0);
    // The family's name and the output directory are someone else's.
    std::string cases = slurp(dir / "c.jsonl"), family = nlohmann::json(hostile_name).dump();
    const std::string field = "\"family\":\"near_tangent\"";
    for (std::size_t at; (at = cases.find(field)) != std::string::npos;)
        cases.replace(at, field.size(), "\"family\":" + family);
    std::ofstream(dir / "hostile.jsonl") << cases;
    std::string out = "out '$(touch PWNED3)'";
    Ran ran = program("audit --cases-file hostile.jsonl --solvers stable,correct --out " +
                          escape::shell_word(out),
                      dir);
    REQUIRE(ran.status == 0);
    for (const char* pwned : {"PWNED", "PWNED2", "PWNED3"}) {
        CHECK_FALSE(fs::exists(dir / pwned));
        CHECK_FALSE(fs::exists(dir / out / pwned));
    }
    audit::Report r = read_report(dir / out);
    REQUIRE(r.families == std::vector<std::string>{hostile_name});
    // Its figure's file name is made of the name, and holds no path.
    std::string figure = audit::difficulty_figure(hostile_name);
    CHECK(fs::exists(dir / out / figure));
    CHECK(figure.find('/') == std::string::npos);
    // In report.md, every mark of the name is escaped: the table keeps its columns.
    std::string md = slurp(dir / out / "report.md");
    CHECK(md.find(escape::markdown_text(hostile_name)) != std::string::npos);
    std::istringstream lines(md);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("| ", 0) == 0) CHECK(line.find("|<b>") == std::string::npos); // a table row

    // In report.html, the name is text, never markup.
    std::string html = slurp(dir / out / "report.html");
    CHECK(html.find("<b>$(touch") == std::string::npos);
    CHECK(html.find("&lt;b&gt;$(touch PWNED2)") != std::string::npos);
    // In the figure, the same.
    CHECK(slurp(dir / out / figure).find("<b>") == std::string::npos);

    // A hand-edited report given to merge: its solver named so, merged and drawn, runs nothing.
    auto j = nlohmann::json::parse(slurp(dir / out / "report.json"));
    j.erase("cases_file"), j.erase("cases_count");
    j["seed"] = 1, j["cases_per_group"] = 6, j["families"] = {"near_tangent"};
    nlohmann::json rows = nlohmann::json::array(), curves = nlohmann::json::array();
    for (auto& row : j["rows"])
        if (row["solver"] == "correct")
            row["family"] = "near_tangent", row["solver"] = hostile_name, rows.push_back(row);
    for (auto& c : j["curves"])
        if (c["solver"] == "correct")
            c["family"] = "near_tangent", c["solver"] = hostile_name, curves.push_back(c);
    j["rows"] = rows, j["curves"] = curves, j["solvers"] = {hostile_name};
    {
        // As a campaign's report, it carries the mark of its shard's cases (merge checks it).
        audit::Report as_campaign;
        std::string why;
        REQUIRE(audit::from_json(j.dump(), &as_campaign, &why));
        char mark[24];
        std::snprintf(mark, sizeof mark, "%016llx",
                      (unsigned long long)audit::shard_mark(as_campaign, 0));
        j["shard_marks"] = {{0, mark}};
    }
    fs::create_directories(dir / "edited");
    std::ofstream(dir / "edited" / "report.json") << j.dump();
    Ran merged = program("merge --out merged edited/report.json", dir);
    INFO(merged.err);
    CHECK((merged.status == 0 || merged.status == 1));
    CHECK_FALSE(fs::exists(dir / "PWNED"));
    CHECK(slurp(dir / "merged" / "report.md").find(escape::markdown_text(hostile_name)) !=
          std::string::npos);
}

TEST_CASE("outside data: report.html inlines no file that is not the report's own",
          "[outside][cli]") {
    fs::path dir = scratch("outside_symlink");
    REQUIRE(program("audit --cases 2 --families generic --solvers stable --out r", dir).status ==
            0);
    // A figure replaced by a link to another file, whose bytes must not reach the page.
    std::ofstream(dir / "secret.txt") << "the secret bytes";
    fs::remove(dir / "r" / "pareto.svg");
    fs::create_symlink(dir / "secret.txt", dir / "r" / "pareto.svg");
    REQUIRE(program("html r", dir).status == 0);
    std::string html = slurp(dir / "r" / "report.html");
    CHECK(html.find("dGhlIHNlY3JldCBieXRlcw") == std::string::npos); // base64 of the secret
    CHECK(html.find("figure pareto.svg not drawn") != std::string::npos);
    // report.md itself a link: refused, naming it.
    fs::rename(dir / "r" / "report.md", dir / "r" / "real.md");
    fs::create_symlink(dir / "secret.txt", dir / "r" / "report.md");
    Ran ran = program("html r", dir);
    CHECK(ran.status == 2);
    CHECK(ran.err.find("report.md: not a report's own file") != std::string::npos);
}

TEST_CASE("outside data: merge never writes over an input", "[outside][cli]") {
    fs::path dir = scratch("outside_merge");
    for (int k = 0; k < 2; ++k)
        REQUIRE(program("audit --cases 3 --families generic --solvers stable --no-plots --shard " +
                            std::to_string(k) + "/2 --out s" + std::to_string(k),
                        dir)
                    .status == 0);
    std::string before = slurp(dir / "s0" / "report.json");
    Ran ran = program("merge --out s0 s0/report.json s1/report.json", dir);
    CHECK(ran.status == 2);
    CHECK(ran.err.find("merge never writes over an input") != std::string::npos);
    CHECK(slurp(dir / "s0" / "report.json") == before);
    Ran into_other = program("merge --out ./s1/. s0/report.json s1/report.json", dir);
    CHECK(into_other.status == 2);
    CHECK(program("merge --out m s0/report.json s1/report.json", dir).status == 0);
}

TEST_CASE("outside data: a new run never leaves an earlier run's files presented as its own",
          "[outside]") {
    fs::path dir = scratch("outside_stale");
    for (const char* f : {"report.md", "report.html", "pareto.svg", "difficulty_rim.svg"})
        std::ofstream(dir / f) << "an earlier run's, complete";
    std::ofstream(dir / "report.json") << "{}";
    {
        audit::OutputDirectory held(dir.string());
        // Before anything of this run is written, nothing of the earlier one but its record.
        std::vector<std::string> left = files_under(dir);
        std::sort(left.begin(), left.end());
        CHECK(left == std::vector<std::string>{".lock", "report.json"});
    }
}

TEST_CASE("outside data: a file-size limit is a named error, with no litter and no false "
          "'complete'",
          "[outside][cli]") {
    fs::path dir = scratch("outside_xfsz");
    // 64 KiB: enough for the first saves, not for the final report.
    std::string cmd = "ulimit -f 64 && '" + std::string(LINEQUAD_BIN) +
                      "' audit --cases 200 --families generic,near_tangent,rim --out r > out.txt "
                      "2> err.txt";
    std::ofstream(dir / "run.sh") << "cd '" << dir.string() << "' && " << cmd << "\n";
    int raw = std::system(("bash '" + (dir / "run.sh").string() + "'").c_str());
    REQUIRE(WIFEXITED(raw));
    CHECK(WEXITSTATUS(raw) == 2);
    std::string err = slurp(dir / "err.txt");
    CHECK(err.find("File too large") != std::string::npos);
    for (const std::string& f : files_under(dir / "r"))
        CHECK(f.find(".tmp") == std::string::npos);
    std::string json = slurp(dir / "r" / "report.json");
    CHECK(json.find("\"status\":\"complete\"") == std::string::npos);
}

TEST_CASE("outside data: a scene is all or nothing", "[outside][cli]") {
    fs::path dir = scratch("outside_scene");
    std::ofstream(dir / "s.jsonl")
        << R"({"scene":"s1"})"
        << "\n"
        << R"({"shape_id":"a","shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1})"
        << "\n"
        // A shape record whose shape_id is mistyped (it reads as a single case, and a broken one).
        << R"({"shpae_id":"b","shape":"cylinder","C":[3,0,0],"H":[3,0,1],"r":1})"
        << "\n"
        << R"({"id":"l1","L0":[-2,0,0.5],"v":[1,0,0]})"
        << "\n"
        << R"({"scene":"s2"})"
        << "\n"
        << R"({"shape_id":"a","shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1})"
        << "\n"
        << R"({"id":"l2","L0":[-2,0,0.5],"v":[1,0,0]})"
        << "\n"
        // A shape without its shape_id at all, after the lines: it breaks s2 too.
        << R"({"shape":"cylinder","C":[3,0,0],"H":[3,0,1],"r":1})"
        << "\n";
    Ran ran = program("solve --solver correct s.jsonl", dir);
    CHECK(ran.status == 1);
    std::vector<std::string> answers;
    std::istringstream in(ran.out);
    for (std::string line; std::getline(in, line);)
        if (line.find("\"id\":\"l") != std::string::npos) answers.push_back(line);
    REQUIRE(answers.size() == 2);
    for (const std::string& a : answers) {
        INFO(a);
        CHECK(a.find("malformed_scene") != std::string::npos);
        CHECK(a.find("\"hits\"") == std::string::npos);
    }
    CHECK(answers[0].find("line 3") != std::string::npos); // the line that broke it
    CHECK(answers[1].find("line 8") != std::string::npos);
}

TEST_CASE("outside data: an id keeps its JSON text exactly", "[outside][cli]") {
    fs::path dir = scratch("outside_ids");
    std::ofstream(dir / "c.jsonl")
        << R"({"id":18446744073709551617,"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[-2,0,0.5],"v":[1,0,0]})"
        << "\n"
        << R"({"id":[0.1000000000000000000001, "a\u0041", {"k" : -0}],"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[-2,0,0.5],"v":[1,0,0]})"
        << "\n";
    Ran ran = program("solve --solver correct c.jsonl", dir);
    REQUIRE(ran.status == 0);
    CHECK(ran.out.find(R"({"id":18446744073709551617,)") != std::string::npos);
    CHECK(ran.out.find(R"({"id":[0.1000000000000000000001,"a\u0041",{"k":-0}],)") !=
          std::string::npos);
    // 2^64 + 1 and 2^64 are one double: as ids they stay two, and an answer finds only its own.
    std::ofstream(dir / "two.jsonl")
        << R"({"id":18446744073709551616,"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[-2,0,0.5],"v":[1,0,0]})"
        << "\n"
        << R"({"id":18446744073709551617,"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[-2,0,0.5],"v":[1,0,0]})"
        << "\n";
    std::ofstream(dir / "answers.jsonl")
        << R"({"id":18446744073709551617,"solver":"mine","hits":[{"t":1},{"t":3}]})"
        << "\n";
    Ran graded =
        program("audit --cases-file two.jsonl --results answers.jsonl --out r --no-plots", dir);
    REQUIRE(graded.status == 0);
    audit::Report r = read_report(dir / "r");
    CHECK(r.total("mine").cases == 2);
    CHECK(r.total("mine").cases_mismatched == 1); // 2^64 was not answered: refused
}

TEST_CASE("outside data: diff says when it does not compare the same cases, and fails a gate",
          "[outside][cli]") {
    fs::path dir = scratch("outside_diff");
    const std::string base = "audit --families generic --solvers stable --no-plots ";
    REQUIRE(program(base + "--cases 4 --out a", dir).status == 0);
    REQUIRE(program(base + "--cases 4 --seed 2 --out other", dir).status == 0);
    // A stopped run: the same campaign, marked stopped.
    fs::create_directories(dir / "stopped");
    std::string json = slurp(dir / "a" / "report.json");
    json.replace(json.find("\"status\":\"complete\""), 19, "\"status\":\"stopped\"");
    std::ofstream(dir / "stopped" / "report.json") << json;
    CHECK(program("diff a/report.json a/report.json", dir).status == 0);
    Ran other = program("diff a/report.json other/report.json", dir);
    CHECK(other.status == 1);
    CHECK(other.out.find("**Not the same campaign**") != std::string::npos);
    CHECK(other.err.find("not the same campaign: seed 1 against 2") != std::string::npos);
    Ran stopped = program("diff a/report.json stopped/report.json", dir);
    CHECK(stopped.status == 1);
    CHECK(stopped.out.find("**Incomplete** (the new report is stopped)") != std::string::npos);
    // Asked for, the comparison is made (and said at the top).
    Ran anyway = program("diff --any-campaign a/report.json other/report.json", dir);
    CHECK(anyway.status == 0);
    CHECK(anyway.out.find("**Not the same campaign**") != std::string::npos);
}

TEST_CASE("outside data: a commit's text is one history record whatever it holds",
          "[outside][cli]") {
    fs::path dir = scratch("outside_history");
    REQUIRE(program("audit --cases 2 --families generic --solvers stable --no-plots --out a "
                    "--history h.db --commit \"$(printf 'fix\\n| 9 | forged | row |')\"",
                    dir)
                .status == 0);
    Ran shown = program("history h.db --solver stable", dir);
    REQUIRE(shown.status == 0);
    std::vector<std::string> rows;
    std::istringstream in(shown.out);
    for (std::string line; std::getline(in, line);)
        if (line.rfind("| ", 0) == 0 && line.find("---") == std::string::npos &&
            line.find("| # |") == std::string::npos)
            rows.push_back(line);
    REQUIRE(rows.size() == 1);
    CHECK(rows[0].find("fix \\| 9 \\| forged \\| row \\|") != std::string::npos);
}

TEST_CASE("outside data: every subcommand's numbers are read as the audit's are",
          "[outside][cli]") {
    fs::path dir = scratch("outside_options");
    std::ofstream(dir / "a.json") << "{}";
    for (const char* args :
         {"spawn --seed -1", "spawn --cases 0", "spawn --cases 12abc", "spawn --epsilon nan",
          "spawn --epsilon -1e-4", "spawn --epsilon inf", "scenes --seed -1", "audit --seed -1",
          "audit --cases 1e3", "audit --solver-timeout nan", "solve --solver-timeout 0",
          "diff --max-growth nan a.json a.json"}) {
        Ran ran = program(args, dir);
        INFO(args << ": " << ran.err);
        CHECK(ran.status == 2);
        CHECK(ran.err.find("expected") != std::string::npos);
    }
}

TEST_CASE("outside data: a history the audit cannot write is refused before any work",
          "[outside][cli]") {
    fs::path dir = scratch("outside_readonly");
    { audit::History made((dir / "ro.db").string()); } // empty, as audit --history makes one
    // Read-only even to root: the immutable attribute (where the file system has it).
    if (std::system(("chattr +i '" + (dir / "ro.db").string() + "' 2>/dev/null").c_str()) != 0) {
        WARN("chattr +i is not available here: the read-only history is not tried");
        return;
    }
    Ran ran = program("audit --cases 2 --families generic --no-plots --out a --history ro.db", dir);
    Ran read = program("history ro.db", dir); // reading needs no write access
    std::system(("chattr -i '" + (dir / "ro.db").string() + "'").c_str());
    CHECK(read.status == 0);
    CHECK(ran.status == 2);
    CHECK(ran.err.find("ro.db: cannot write it (read-only)") != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "a" / "report.json")); // refused before the run began
}

TEST_CASE("escape: each place's escaping holds what would break it", "[outside]") {
    using namespace escape;
    CHECK(shell_word("it's $(x) `y`") == R"('it'\''s $(x) `y`')");
    CHECK(markdown_text("a|b*c_d<e>&[f](g)\n`h`") == R"(a\|b\*c\_d\<e\>\&\[f\]\(g\) \`h\`)");
    CHECK(markdown_code("a``b") == "```a``b```");
    CHECK(markdown_code("`a") == "`` `a ``");
    CHECK(markdown_block({"x```y", "z"}, "  ") == "  ````\n  x```y\n  z\n  ````\n");
    CHECK(file_name("near_tangent") == "near_tangent");
    CHECK(file_name("a/b c") == "a-2Fb-20c");
    CHECK(file_name("a-b") == "a-2Db"); // '-' itself is escaped: names stay distinct
    CHECK(file_name(std::string(300, 'x')).size() < 100);
    CHECK(file_name(std::string(300, 'x')) != file_name(std::string(301, 'x')));
}
