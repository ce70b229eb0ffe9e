// The attacks on the linequad program, each kept as a test: write errors, hostile lines, numbers
// out of range, damaged or mismatched reports, killed runs. Each runs the installed-to-be binary
// through /bin/sh, as a user or a CI job would.
#include "support.hpp"

#include "linequad/audit.hpp"

#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>
#include <sys/wait.h>

using namespace linequad;
using namespace linequad::test;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Runs a shell command line as it is (for ulimit and timeout) in dir; returns its status.
int shell(const std::string& cmd, const fs::path& dir) {
    int raw = std::system(("cd '" + dir.string() + "' && " + cmd).c_str());
    return WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);)
        out.push_back(l);
    return out;
}

const std::string good_case =
    R"({"id":"ok","shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[-2,0,0.5],"v":[1,0,0]})";

// Three shards of one small campaign, each saved as a report in dir/shardK.
void three_shards(const fs::path& dir) {
    for (int k = 0; k < 3; ++k) {
        audit::Options o;
        o.cases_per_group = 12, o.seed = 3, o.plots = false;
        o.families = {Family::generic, Family::near_tangent};
        o.solvers = {"stable", "correct"};
        o.shard = k, o.shards = 3;
        o.out_dir = (dir / ("shard" + std::to_string(k))).string();
        audit::run(o);
    }
}

// A copy of a report with one change made to its JSON.
fs::path edited(const fs::path& report, const fs::path& to, void (*change)(json&)) {
    json j = json::parse(slurp(report));
    change(j);
    fs::create_directories(to.parent_path());
    std::ofstream(to) << j.dump();
    return to;
}

} // namespace

TEST_CASE("cli: a write error is fatal and named and never exit 0", "[cli]") {
    fs::path dir = scratch("cli_write");
    std::ofstream(dir / "cases.jsonl") << good_case << "\n";
    Ran full = program("solve cases.jsonl > /dev/full", dir);
    CHECK(full.status == 2);
    CHECK_THAT(full.err, Catch::Contains("standard output") && Catch::Contains("No space left"));
    // A closed standard output: the descriptor is not handed to a file opened later.
    Ran closed = program("solve cases.jsonl >&-", dir);
    CHECK(closed.status == 2);
    CHECK_THAT(closed.err, Catch::Contains("cannot write standard output"));
    Ran cases = program("cases --cases 10 > /dev/full", dir);
    CHECK(cases.status == 2);
    fs::remove_all(dir);
}

TEST_CASE("cli: files that are not files and arguments left over are refused", "[cli]") {
    fs::path dir = scratch("cli_files");
    std::ofstream(dir / "cases.jsonl") << good_case << "\n";
    Ran directory = program("solve .", dir);
    CHECK(directory.status == 2);
    CHECK_THAT(directory.err, Catch::Contains("Is a directory"));
    Ran missing = program("solve no-such-file.jsonl", dir);
    CHECK(missing.status == 2);
    CHECK_THAT(missing.err, Catch::Contains("no-such-file.jsonl"));
    Ran second = program("solve cases.jsonl cases.jsonl", dir);
    CHECK(second.status == 2);
    CHECK_THAT(second.err, Catch::Contains("not expected"));
    fs::remove_all(dir);
}

TEST_CASE("cli: numbers out of range are refused with the option's name", "[cli]") {
    fs::path dir = scratch("cli_numbers");
    struct Bad {
        const char* args;
        const char* option;
    } bad[] = {
        {"audit --cases -5", "--cases"},
        {"audit --cases 0", "--cases"},
        {"audit --cases 1e3", "--cases"},
        {"audit --cases 99999999999999999999999", "--cases"},
        {"cases --seed -1", "--seed"},
        {"audit --shard 0/99999999999", "--shard"},
        {"audit --shard 3/3", "--shard"},
        {"audit --shard -1/3", "--shard"},
        {"solve --max-line-bytes 0", "--max-line-bytes"},
        {"solve --need some", "--need"},
        {"solve --solver stable,nope", "--solver"},
        {"solve --solver all,stable", "--solver"},
        {"audit --families generic,nope", "--families"},
    };
    for (const Bad& b : bad) {
        Ran r = program(b.args, dir);
        INFO(b.args << "\n" << r.err);
        CHECK(r.status == 2);
        CHECK_THAT(r.err, Catch::Contains(b.option));
        CHECK(r.out.empty());
    }
    fs::remove_all(dir);
}

TEST_CASE("cli: --check on no graded case fails", "[cli]") {
    fs::path dir = scratch("cli_vacuous");
    // 9 cases in all (one family, 3 shapes, 3 ranges); shard 50 of 100 holds none of them.
    Ran r = program("audit --cases 1 --families generic --shard 50/100 --check --no-plots "
                    "--out report",
                    dir);
    CHECK(r.status == 1);
    CHECK_THAT(r.err, Catch::Contains("no case was graded"));
    fs::remove_all(dir);
}

TEST_CASE("cli: a hostile line costs one named error and the next line is still solved", "[cli]") {
    fs::path dir = scratch("cli_hostile");
    {
        std::ofstream f(dir / "cases.jsonl");
        f << "{\"id\":1,\"L0\":["; // 40 MB of numbers in one line
        for (int i = 0; i < 20000000; ++i)
            f << "0,";
        f << "0]}\n" << good_case << "\n";
    }
    // Under a 2 GB address-space limit, as the attack ran.
    int status = shell("ulimit -v 2000000; '" + std::string(LINEQUAD_BIN) +
                           "' solve cases.jsonl > out.txt 2> err.txt",
                       dir);
    CHECK(status == 1);
    std::vector<std::string> out = lines(slurp(dir / "out.txt"));
    REQUIRE(out.size() == 2);
    json first = json::parse(out[0]), second = json::parse(out[1]);
    CHECK(first["code"] == "malformed_case");
    CHECK_THAT(first["error"].get<std::string>(),
               Catch::Contains("line 1") && Catch::Contains("--max-line-bytes"));
    CHECK(second["id"] == "ok");
    CHECK(second["hits"].size() == 2);

    // 160,000 distinct keys: refused by name, without a scan quadratic in the key count.
    {
        std::ofstream f(dir / "keys.jsonl");
        f << "{\"id\":2,\"shape\":\"cylinder\"";
        for (int i = 0; i < 160000; ++i)
            f << ",\"k" << i << "\":0";
        f << "}\n";
    }
    Ran keys = program("solve --max-line-bytes 8000000 keys.jsonl", dir);
    CHECK(keys.status == 1);
    CHECK_THAT(keys.err, Catch::Contains("not a field of a cylinder case"));
    fs::remove_all(dir);
}

TEST_CASE("cli: every result line is JSON whatever the id was", "[cli]") {
    fs::path dir = scratch("cli_ids");
    {
        std::ofstream f(dir / "cases.jsonl", std::ios::binary);
        f << "{\"id\":\"\xff\xfe\",\"shape\":\"cylinder\"}\n";                    // invalid UTF-8
        f << "{\"id\":\"caf\\u00e9 \\ud83d\\ude00\",\"shape\":\"cone\"}\n";       // escapes
        f << "{\"id\":{\"nested\":[1,2,{\"x\":null}]},\"shape\":\"cylinder\"}\n"; // any value
        f << "{\"id\":\"q\\\"uote\\\\\",\"shape\":\"cylinder\"\n";                // cut short
        f << good_case << "\n";
    }
    Ran r = program("solve --solver stable,exact cases.jsonl", dir);
    CHECK(r.status == 1);
    std::vector<std::string> out = lines(r.out);
    REQUIRE(out.size() == 10);
    for (const std::string& l : out) {
        INFO(l);
        CHECK(json::accept(l)); // strict: UTF-8 checked too
    }
    CHECK(json::parse(out[2])["id"] == "caf\xc3\xa9 \xf0\x9f\x98\x80");
    CHECK(json::parse(out[4])["id"] == json::parse(R"({"nested":[1,2,{"x":null}]})"));
    CHECK(json::parse(out[8])["id"] == "ok");
    fs::remove_all(dir);
}

TEST_CASE("cli: merge refuses damaged reports by the field's path", "[cli]") {
    fs::path dir = scratch("cli_merge_damaged");
    three_shards(dir);
    fs::path shard0 = dir / "shard0" / "report.json", shard1 = dir / "shard1" / "report.json";
    struct Damage {
        const char* name;
        void (*change)(json&);
        const char* says;
    } damage[] = {
        {"no_k", [](json& j) { j["curves"][0]["points"][0].erase("k"); },
         "curves[0].points[0].k: missing"},
        {"huge_seconds", [](json& j) { j["seconds"] = 1e300; }, ""}, // allowed: finite
        {"negative", [](json& j) { j["rows"][0]["cases"] = -3; }, "rows[0].cases"},
        {"fraction", [](json& j) { j["rows"][1]["graded_roots"] = 2.5; }, "rows[1].graded_roots"},
        {"histogram",
         [](json& j) {
             j["rows"][0]["t_ulps"]["histogram"].push_back({9999, 1});
         },
         "rows[0].t_ulps.histogram"},
        {"unknown_solver", [](json& j) { j["rows"][0]["solver"] = "other"; }, "rows[0].solver"},
        {"format", [](json& j) { j["format"] = "linequad-audit-1"; }, "older report format"},
        {"shard_out_of_range", [](json& j) { j["shards_included"] = {7}; }, "shards_included"},
    };
    for (const Damage& d : damage) {
        fs::path bad = edited(shard1, dir / d.name / "report.json", d.change);
        Ran r = program("merge --out merged '" + shard0.string() + "' '" + bad.string() + "'", dir);
        INFO(d.name << ": " << r.err);
        if (*d.says) {
            CHECK(r.status == 2);
            CHECK_THAT(r.err, Catch::Contains(d.says) && Catch::Contains(bad.string()));
        } else {
            CHECK(r.status == 1); // merged; shard 2 still missing
        }
    }
    // A number JSON cannot hold in a double (1e400) is refused by name, not an abort.
    {
        std::string text = slurp(shard1);
        std::size_t at = text.find("\"seconds\":");
        std::size_t end = text.find(',', at);
        text = text.substr(0, at) + "\"seconds\":1e400" + text.substr(end);
        std::ofstream(dir / "inf.json") << text;
    }
    Ran inf = program("merge --out merged '" + shard0.string() + "' inf.json", dir);
    CHECK(inf.status == 2);
    CHECK_THAT(inf.err, Catch::Contains("inf.json") && Catch::Contains("overflow parsing '1e400'"));
    // An output directory that cannot be made.
    Ran out = program("merge --out '" + shard0.string() + "/sub' '" + shard0.string() + "'", dir);
    CHECK(out.status == 2);
    CHECK_THAT(out.err, Catch::Contains("cannot create") && Catch::Contains("sub"));
    fs::remove_all(dir);
}

TEST_CASE("cli: merge takes one campaign's shards once each and is complete only with all of them",
          "[cli]") {
    fs::path dir = scratch("cli_merge_campaign");
    three_shards(dir);
    std::string s0 = "shard0/report.json", s1 = "shard1/report.json", s2 = "shard2/report.json";
    Ran twice = program("merge --out m " + s0 + " " + s1 + " " + s1, dir);
    CHECK(twice.status == 2);
    CHECK_THAT(twice.err, Catch::Contains("shard 1 is already merged"));

    Ran partial = program("merge --out m " + s0 + " " + s2, dir);
    CHECK(partial.status == 1);
    CHECK_THAT(partial.err, Catch::Contains("shards missing: 1"));
    CHECK_THAT(slurp(dir / "m" / "report.md"), Catch::Contains("**no: 2 of 3 shards (0, 2)**"));

    Ran all = program("merge --out m " + s2 + " " + s0 + " " + s1, dir);
    CHECK(all.status == 0);
    audit::Report merged;
    std::string why;
    REQUIRE(audit::read_json((dir / "m" / "report.json").string(), &merged, &why));
    CHECK(merged.complete());
    CHECK(merged.shards_included == std::vector<int>{0, 1, 2});

    struct Other {
        const char* name;
        void (*change)(json&);
        const char* says;
    } other[] = {
        {"families", [](json& j) { j["families"].push_back("scale"); }, "families differ"},
        {"solvers",
         [](json& j) {
             j["solvers"] = {"stable", "correct", "seed"};
         },
         "solvers differ"},
        {"flags", [](json& j) { j["flags"] = "-O3 -ffast-math"; }, "fast/ compiler flags differ"},
        {"seed", [](json& j) { j["seed"] = 4; }, "seeds differ"},
        {"cases", [](json& j) { j["cases_per_group"] = 13; }, "case counts"},
        {"version", [](json& j) { j["version"] = "0.0.1"; }, "versions differ"},
        {"shards", [](json& j) { j["shards"] = 4; }, "shard counts differ"},
    };
    for (const Other& o : other) {
        fs::path changed = edited(dir / s1, dir / o.name / "report.json", o.change);
        Ran r = program("merge --out m " + s0 + " '" + changed.string() + "'", dir);
        INFO(o.name << ": " << r.err);
        CHECK(r.status == 2);
        CHECK_THAT(r.err, Catch::Contains(o.says));
    }
    fs::remove_all(dir);
}

TEST_CASE("cli: a killed audit leaves a report that says it is running and holds what it had",
          "[cli]") {
    fs::path dir = scratch("cli_killed");
    // A finished report first: the killed run must not leave it claiming to be current.
    REQUIRE(program("audit --cases 20 --families generic --no-plots --out out", dir).status == 0);
    REQUIRE(json::parse(slurp(dir / "out" / "report.json"))["status"] == "complete");
    std::ofstream(dir / "out" / "pareto.svg") << "<svg/>"; // an earlier run's figure
    // Killed (SIGKILL: no handler runs) 5 s in; reports are saved every 2 s.
    int status = shell("timeout -s KILL 5 '" + std::string(LINEQUAD_BIN) +
                           "' audit --cases 1000000 --out out > /dev/null 2>&1",
                       dir);
    CHECK(status == 128 + 9);
    audit::Report r;
    std::string why;
    REQUIRE(audit::read_json((dir / "out" / "report.json").string(), &r, &why));
    CHECK(r.status == audit::Status::running);
    CHECK(r.cases_per_group == 1000000);
    CHECK(r.total("stable").cases > 0);
    CHECK_FALSE(fs::exists(dir / "out" / "pareto.svg"));
    // report.md is the saved report.json, rendered.
    CHECK(slurp(dir / "out" / "report.md") == audit::markdown(r));
    CHECK_THAT(slurp(dir / "out" / "report.md"), Catch::Contains("**no: running**"));
    fs::remove_all(dir);
}

TEST_CASE("cli: diff exits 1 when a report got worse and writes JUnit XML", "[cli]") {
    fs::path dir = scratch("cli_diff");
    three_shards(dir);
    // shard 1 against itself: nothing changed; against a copy with a mismatch more: worse.
    fs::path worse =
        edited(dir / "shard1" / "report.json", dir / "worse" / "report.json", [](json& j) {
            for (json& row : j["rows"])
                if (row["solver"] == "correct" && row["cases"] > 0) {
                    row["cases_mismatched"] = 1;
                    row["mismatches"]["missed"] = 1;
                    break;
                }
        });
    // A shard is a third of its campaign: compared as it is (--any-campaign), which the markdown
    // says at its top (without the flag, diff would exit 1 for that alone).
    Ran same =
        program("diff --any-campaign shard1/report.json shard1/report.json --junit same.xml", dir);
    CHECK(same.status == 0);
    CHECK_THAT(same.out, Catch::Contains("No measure changed"));
    CHECK_THAT(slurp(dir / "same.xml"), Catch::Contains("failures=\"0\""));
    Ran got_worse =
        program("diff --any-campaign shard1/report.json worse/report.json --junit worse.xml "
                "--markdown summary.md",
                dir);
    CHECK(got_worse.status == 1);
    CHECK(got_worse.out.empty());
    CHECK_THAT(slurp(dir / "summary.md"),
               Catch::Contains("| correct | mismatched | 0 of") && Catch::Contains("**worse**"));
    CHECK_THAT(slurp(dir / "worse.xml"), Catch::Contains("failures=\"1\""));
    Ran reverse = program("diff --any-campaign worse/report.json shard1/report.json", dir);
    CHECK(reverse.status == 0);
    Ran bad = program("diff shard1/report.json worse/report.json --max-growth -1", dir);
    CHECK(bad.status == 2);
    CHECK_THAT(bad.err, Catch::Contains("--max-growth"));
    fs::remove_all(dir);
}

TEST_CASE("cli: audit and merge append to the history, which prints and plots a trend", "[cli]") {
    fs::path dir = scratch("cli_history");
    three_shards(dir);
    Ran first = program("audit --cases 6 --seed 3 --solvers stable --families generic --no-plots "
                        "--out a --history h.db --commit one",
                        dir);
    REQUIRE(first.status == 0);
    CHECK_THAT(first.err, Catch::Contains("rows added to h.db"));
    CHECK(fs::exists(dir / "a" / "report.html"));
    Ran merged = program("merge --out m --history h.db --commit two shard0/report.json "
                         "shard1/report.json shard2/report.json",
                         dir);
    REQUIRE(merged.status == 0);
    Ran shown = program("history h.db --solver stable", dir);
    REQUIRE(shown.status == 0);
    // The two runs in the order they were added, each under its commit; different campaigns.
    CHECK_THAT(shown.out, Catch::Contains("| 1 | one |") && Catch::Contains("| 2 | two |") &&
                              Catch::Contains("another campaign"));
    Ran family = program("history h.db --solver correct --family near_tangent", dir);
    CHECK_THAT(family.out,
               Catch::Contains("correct: near\\_tangent") && Catch::Contains("| two |"));
    Ran plotted = program("history h.db --solver stable --plot trend.svg", dir);
    CHECK(plotted.status == 0);
    CHECK_THAT(slurp(dir / "trend.svg"), Catch::Contains("<svg"));
    // Refusals: a plot of two solvers, --commit without --add, a file that is not a database.
    CHECK(program("history h.db --plot t.svg", dir).status == 2);
    CHECK(program("history h.db --commit x", dir).status == 2);
    Ran not_db = program("history m/report.json", dir);
    CHECK(not_db.status == 2);
    CHECK_THAT(not_db.err, Catch::Contains("m/report.json") && Catch::Contains("not a database"));
    // An audit refuses an unusable history before it runs.
    Ran early = program("audit --cases 100000 --out b --history m/report.json", dir);
    CHECK(early.status == 2);
    CHECK_FALSE(fs::exists(dir / "b"));
    fs::remove_all(dir);
}

TEST_CASE("cli: html writes report.html again from report.md", "[cli]") {
    fs::path dir = scratch("cli_html");
    three_shards(dir);
    fs::remove(dir / "shard0" / "report.html");
    Ran html = program("html shard0", dir);
    CHECK(html.status == 0);
    std::string page = slurp(dir / "shard0" / "report.html");
    CHECK_THAT(page, Catch::Contains("<table>") && Catch::Contains("not drawn"));
    CHECK(program("html no-such-dir", dir).status == 2);
    fs::remove_all(dir);
}
