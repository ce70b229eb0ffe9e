// The history database: runs appended per commit and campaign, a rerun replacing its run, trends
// read back in order, and databases it cannot use refused by name.
#include "report/history.hpp"

#include "linequad/audit.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace linequad::audit;

namespace {

std::string fresh_path(const std::string& name) {
    std::string path = (std::filesystem::temp_directory_path() / name).string();
    std::filesystem::remove(path);
    return path;
}

Report small_audit(std::uint64_t seed) {
    Options o;
    o.cases_per_group = 4;
    o.seed = seed;
    o.families = {linequad::Family::generic, linequad::Family::near_tangent};
    o.solvers = {"seed", "stable"};
    o.threads = 1;
    return run(o);
}

} // namespace

TEST_CASE("history: runs come back in order, per solver, family and shape", "[history]") {
    std::string path = fresh_path("linequad_history_test.sqlite");
    Report first = small_audit(1), second = small_audit(1);
    {
        History h(path);
        CHECK(h.add(first, "aaa") > 0);
        CHECK(h.add(second, "bbb") > 0);
    }
    History h(path); // reopened: what was added stays
    auto all = h.trend("seed");
    REQUIRE(all.size() == 2);
    CHECK(all[0].commit == "aaa");
    CHECK(all[1].commit == "bbb");
    Row total = first.total("seed");
    CHECK(all[0].cases == total.cases);
    CHECK(all[0].mismatched == total.cases_mismatched);
    CHECK(all[0].t_p99 == total.t_quantile(0.99)); // stored as a double, read back as one
    CHECK(all[0].campaign == campaign_of(first));

    auto near = h.trend("stable", "near_tangent", "cylinder");
    REQUIRE(near.size() == 2);
    std::uint64_t cases = 0;
    for (const auto& [key, row] : first.rows)
        if (key.solver == "stable" && key.family == "near_tangent" && key.shape == "cylinder")
            cases += row.cases;
    CHECK(near[0].cases == cases);
    CHECK(h.trend("no_such_solver").empty());
    CHECK(h.solvers() == std::vector<std::string>{"seed", "stable"});
}

TEST_CASE("history: a second run of one commit's campaign replaces the first", "[history]") {
    std::string path = fresh_path("linequad_history_rerun.sqlite");
    History h(path);
    h.add(small_audit(1), "aaa");
    h.add(small_audit(1), "aaa");
    CHECK(h.trend("stable").size() == 1);
    h.add(small_audit(2), "aaa"); // another seed: another campaign, kept beside it
    CHECK(h.trend("stable").size() == 2);
}

TEST_CASE("history: the trend names what got worse against the run before", "[history]") {
    HistoryPoint a, b;
    a.commit = "aaa", b.commit = "bbb";
    a.campaign = b.campaign = "seed 1";
    a.cases = b.cases = 100;
    a.mismatched = 1, b.mismatched = 3;
    a.t_max = 4, b.t_max = 2;
    std::string md = trend_markdown({a, b}, "stable", "*", "*");
    CHECK(md.find("**worse**: mismatched 1 → 3") != std::string::npos);
    CHECK(md.find("better: t max 4 → 2") != std::string::npos);
    b.campaign = "seed 2";
    CHECK(trend_markdown({a, b}, "stable", "*", "*").find("another campaign") != std::string::npos);
}

TEST_CASE("history: a file that is not a history is refused, naming it", "[history]") {
    std::string path = fresh_path("linequad_history_not_a_db.sqlite");
    std::ofstream(path) << "this is not a database, it is a text file of some length............";
    CHECK_THROWS_WITH(History(path), Catch::Contains(path) && Catch::Contains("not a database"));
    CHECK_THROWS_WITH(History("/nonexistent_dir/x.sqlite"), Catch::Contains("/nonexistent_dir"));
    std::string empty_commit = fresh_path("linequad_history_no_commit.sqlite");
    Report r = small_audit(1);
    r.commit.clear();
    CHECK_THROWS_WITH(History(empty_commit).add(r), Catch::Contains("--commit"));
}
