// compare/'s input and output, in process: the strict JSON reader, report round trips and
// validation, strict grading of results files, and the output directory's lock and saves.
#include "support.hpp"

#include "linequad/audit.hpp"

#include "io/jsonl.hpp"

#include <fstream>
#include <limits>
#include <sstream>

using namespace linequad;
using namespace linequad::test;
namespace fs = std::filesystem;

namespace {

audit::Options small_campaign() {
    audit::Options o;
    o.cases_per_group = 8, o.seed = 11, o.plots = false;
    o.families = {Family::generic, Family::scale};
    o.solvers = {"stable", "certified", "correct"};
    return o;
}

// A cases file and the given result lines; returns the options that grade them.
audit::Options results_files(const fs::path& dir, const std::vector<std::string>& cases,
                             const std::vector<std::string>& results) {
    std::ofstream c(dir / "cases.jsonl"), r(dir / "results.jsonl");
    for (const std::string& l : cases)
        c << l << "\n";
    for (const std::string& l : results)
        r << l << "\n";
    audit::Options o;
    o.plots = false;
    o.cases_file = (dir / "cases.jsonl").string();
    o.results_file = (dir / "results.jsonl").string();
    return o;
}

std::string error_of(const audit::Options& o) {
    try {
        audit::run(o);
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST_CASE("jsonl: repeated keys and deep nesting are refused at any level", "[jsonl]") {
    jsonl::Json j;
    std::string why;
    CHECK_FALSE(jsonl::parse(R"({"a":{"b":1,"b":2}})", &j, &why));
    CHECK_THAT(why, Catch::Contains("\"b\" appears twice"));
    CHECK(jsonl::parse(R"({"a":{"b":1},"b":{"b":2}})", &j, &why)); // same key, other objects
    std::string deep(jsonl::max_depth + 1, '[');
    CHECK_FALSE(jsonl::parse(deep + std::string(jsonl::max_depth + 1, ']'), &j, &why));
    CHECK_THAT(why, Catch::Contains("nesting deeper"));
    CHECK(jsonl::parse(std::string(jsonl::max_depth, '[') + std::string(jsonl::max_depth, ']'), &j,
                       &why));
    CHECK_FALSE(jsonl::parse("{\"id\":\"\xc3\x28\"}", &j, &why)); // invalid UTF-8
    CHECK_FALSE(jsonl::parse("[1] [2]", &j, &why));
    CHECK_FALSE(jsonl::parse("", &j, &why));
}

TEST_CASE("jsonl: the JSON integer -0 is negative zero wherever it stands", "[jsonl]") {
    for (const char* text : {"-0", " -0 ", "[-0]", "[1,-0]", "[-0,1]", "{\"a\":-0}", "[ -0 , 0]"}) {
        jsonl::Json j;
        std::string why;
        INFO(text);
        REQUIRE(jsonl::parse(text, &j, &why));
        const jsonl::Json& zero = j.is_number() ? j : j.is_array() ? j[j[0] == 1 ? 1 : 0] : j["a"];
        REQUIRE(zero.is_number_float());
        CHECK(std::signbit(zero.get<double>()));
    }
    jsonl::Json j;
    std::string why;
    REQUIRE(jsonl::parse("[0, 10, -10, -0.0, 100]", &j, &why));
    CHECK_FALSE(std::signbit(j[0].get<double>()));
    CHECK(j[1] == 10);
    CHECK(j[2] == -10);
    CHECK(std::signbit(j[3].get<double>()));
    // In a case: a direction of (-0, 0, 1) keeps its signed zero.
    Case c;
    REQUIRE(parse_case(R"({"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[0,0,-0],)"
                       R"("v":[-0,0,1]})",
                       &c, &why));
    CHECK(same_bits(c.line.v.x, -0.0));
    CHECK(same_bits(c.line.L0.z, -0.0));
    CHECK(same_bits(c.line.v.y, 0.0));
}

TEST_CASE("case format: every NaN reads as the one NaN written and k survives without a family",
          "[case_io]") {
    Case c;
    std::string why;
    REQUIRE(parse_case(R"j({"shape":"cylinder","C":["nan(0x123)","-nan",0],"H":[0,0,1],"r":1,)j"
                       R"j("L0":[0,0,0],"v":[1,0,0],"k":7})j",
                       &c, &why));
    const auto& cyl = std::get<Cylinder>(c.shape);
    CHECK(same_bits(cyl.C.x, std::numeric_limits<double>::quiet_NaN()));
    CHECK(same_bits(cyl.C.y, std::numeric_limits<double>::quiet_NaN()));
    Case back;
    REQUIRE(parse_case(format_case(c), &back, &why));
    CHECK(format_case(back) == format_case(c));
    CHECK(back.k == 7);
}

TEST_CASE("report: JSON round trip is exact and report.md is rendered from it", "[report]") {
    audit::Report r = audit::run(small_campaign());
    std::string text = audit::to_json(r);
    audit::Report back;
    std::string why;
    REQUIRE(audit::from_json(text, &back, &why));
    CHECK(audit::to_json(back) == text);
    CHECK(audit::markdown(back) == audit::markdown(r));

    fs::path dir = scratch("report_pair");
    {
        audit::OutputDirectory out(dir.string());
        out.finish(r, false);
    }
    REQUIRE(audit::read_json((dir / "report.json").string(), &back, &why));
    CHECK(slurp(dir / "report.md") == audit::markdown(back));
    fs::remove_all(dir);
}

TEST_CASE("report: inconsistent statistics are refused by path", "[report]") {
    audit::Report r = audit::run(small_campaign());
    std::string text = audit::to_json(r), why;
    jsonl::Json j = jsonl::Json::parse(text);
    auto refused = [&](const jsonl::Json& changed, const char* says) {
        audit::Report out;
        std::string w;
        INFO(says);
        CHECK_FALSE(audit::from_json(changed.dump(), &out, &w));
        CHECK_THAT(w, Catch::Contains(says));
    };
    jsonl::Json k = j;
    k["rows"][0]["graded_roots"] = k["rows"][0]["graded_roots"].get<std::uint64_t>() + 1;
    refused(k, "rows[0].t_ulps.histogram: holds");
    k = j;
    k["rows"][0]["cases_mismatched"] = k["rows"][0]["cases"].get<std::uint64_t>() + 1;
    refused(k, "rows[0].cases_mismatched");
    k = j;
    k["rows"].push_back(k["rows"][0]);
    refused(k, "appears twice");
    k = j;
    k["status"] = "finished";
    refused(k, "status");
    k = j;
    k["oracle_rounding_steps"].push_back(1);
    refused(k, "oracle_rounding_steps");
    k = j;
    k["families"].push_back("generic");
    refused(k, "listed twice");
    k = j;
    k["shards_included"] = {0, 0};
    refused(k, "shards_included");
}

TEST_CASE("grading: duplicate ids are refused with their line numbers", "[grading]") {
    fs::path dir = scratch("grading_dups");
    Case a = make_case(Family::generic, 0, Range::line, 1, 0);
    Case b = make_case(Family::generic, 1, Range::line, 1, 1);
    std::string ra = format_result(a.id, "mine", run("stable", a.shape, a.line));
    std::string rb = format_result(b.id, "mine", run("stable", b.shape, b.line));

    std::string e =
        error_of(results_files(dir, {format_case(a), format_case(b), format_case(a)}, {ra}));
    CHECK_THAT(e, Catch::Contains("line 3") && Catch::Contains("repeats line 1"));
    e = error_of(results_files(dir, {format_case(a), format_case(b)}, {ra, rb, "", ra}));
    CHECK_THAT(e, Catch::Contains("line 4") && Catch::Contains("first is on line 1"));
    // The same case answered by two solvers is two answers, not a duplicate.
    std::string other = format_result(a.id, "theirs", run("seed", a.shape, a.line));
    CHECK(error_of(results_files(dir, {format_case(a), format_case(b)}, {ra, other})).empty());
    // An answer to no case, and a line that names no case, are refused.
    e = error_of(results_files(dir, {format_case(a)}, {ra, rb}));
    CHECK_THAT(e, Catch::Contains("line 2") && Catch::Contains("no case"));
    e = error_of(results_files(dir, {format_case(a)}, {"{not json"}));
    CHECK_THAT(e, Catch::Contains("line 1") && Catch::Contains("not valid JSON"));
    fs::remove_all(dir);
}

TEST_CASE("grading: an empty results file counts every case as refused", "[grading]") {
    fs::path dir = scratch("grading_empty");
    std::vector<std::string> cases;
    for (std::uint64_t i = 0; i < 6; ++i)
        cases.push_back(format_case(make_case(Family::near_tangent, int(i % 3), Range::ray, 2, i)));
    audit::Report r = audit::run(results_files(dir, cases, {}));
    REQUIRE(r.solvers == std::vector<std::string>{"results"});
    audit::Row t = r.total("results");
    CHECK(t.cases == 6);
    CHECK(t.mismatches[audit::refused] == 6);
    CHECK(t.cases_mismatched == 6);
    // An answer with neither hits nor an error is no answer: refused too.
    Case c;
    std::string why;
    REQUIRE(parse_case(cases[0], &c, &why));
    r = audit::run(results_files(dir, cases, {"{\"id\":" + c.id + ",\"solver\":\"mine\"}"}));
    CHECK(r.total("mine").mismatches[audit::refused] == 6);
    fs::remove_all(dir);
}

TEST_CASE("output directory: a second run into it is refused by its lock", "[report]") {
    fs::path dir = scratch("locked");
    audit::Options o = small_campaign();
    o.out_dir = dir.string();
    {
        audit::OutputDirectory held(dir.string());
        std::string e = error_of(o);
        CHECK_THAT(e, Catch::Contains("in use by another run") && Catch::Contains(".lock"));
    }
    CHECK(error_of(o).empty()); // released with its holder
    fs::remove_all(dir);
}

TEST_CASE("diff: a report made worse is caught and the reverse is better", "[diff]") {
    audit::Report before = audit::run(small_campaign()), after = before;
    const audit::RowKey key = after.rows.begin()->first;
    INFO(key.name() << " t_max " << after.rows.begin()->second.t_max);
    after.rows.begin()->second.cases_mismatched += 1;
    after.rows.begin()->second.t_max += 5;
    // Every chunk of this family and solver: 2.4 times as slow (20 buckets of 1/16 octave).
    auto of_pair = [&](const audit::RowKey& k) {
        return k.family == key.family && k.solver == key.solver;
    };
    for (audit::Report* r : {&before, &after})
        for (auto& [k, row] : r->rows)
            if (of_pair(k)) {
                row.ns.count.fill(0);
                row.ns.count[r == &before ? 180 : 200] = 1;
            }

    auto measures = [](const audit::Diff& d, audit::Change::Verdict v) {
        std::vector<std::string> out;
        for (const audit::Change& c : d.changes)
            if (c.verdict == v) out.push_back(c.measure);
        return out;
    };
    audit::Diff worse = audit::diff(before, after, {});
    CHECK(worse.worse());
    CHECK(measures(worse, audit::Change::worse) ==
          std::vector<std::string>{"mismatched", "t max ulps"});
    CHECK(measures(worse, audit::Change::changed) == std::vector<std::string>{"median ns"});
    CHECK(worse.changes.front().family == key.family);
    CHECK(worse.changes.front().solver == key.solver);

    audit::Diff better = audit::diff(after, before, {});
    CHECK_FALSE(better.worse());
    CHECK(measures(better, audit::Change::better) ==
          std::vector<std::string>{"mismatched", "t max ulps"});

    // Thresholds: the max may grow by 10^6, the time by half (it grew 2.4 times).
    audit::DiffThresholds loose;
    loose.max_growth = 1e6, loose.time_growth = 0.5;
    audit::Diff gated = audit::diff(before, after, loose);
    CHECK(measures(gated, audit::Change::worse) ==
          std::vector<std::string>{"mismatched", "median ns"});
    CHECK(measures(gated, audit::Change::worse_within_threshold) ==
          std::vector<std::string>{"t max ulps"});

    std::string junit = audit::diff_junit(worse, "a", "b");
    CHECK_THAT(junit, Catch::Contains("failures=\"1\"") && Catch::Contains("<failure"));
    CHECK_THAT(audit::diff_markdown(worse, "a", "b"), Catch::Contains("**Worse**"));
    CHECK_THAT(audit::diff_markdown(better, "b", "a"), Catch::Contains("**Not worse**"));
    CHECK(audit::diff(before, before, loose).changes.empty());
    // A family and solver no longer graded is worse.
    audit::Report fewer = before;
    for (auto it = fewer.rows.begin(); it != fewer.rows.end();)
        it = of_pair(it->first) ? fewer.rows.erase(it) : std::next(it);
    CHECK(audit::diff(before, fewer, {}).worse());
}
