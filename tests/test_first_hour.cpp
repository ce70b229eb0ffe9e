// What a newcomer meets in the first hour: names that can be listed and are suggested when
// mistyped, a solver that grades nothing named as such, results a person can read, a history
// that can be read without write access, and a library that reports through its caller.
#include "support.hpp"

#include "linequad/audit.hpp"
#include "linequad/audit_solver.hpp"

#include "report/history.hpp"

#include <nlohmann/json.hpp>

#include <fstream>

#include <unistd.h>

using namespace linequad;
using namespace linequad::test;
namespace fs = std::filesystem;

namespace {

const std::string two_hits =
    R"({"id":"cyl-two","shape":"cylinder","C":[0,0,0],"H":[0,0,10],"r":5,"L0":[-10,4,2],"v":[1,0,0]})";

} // namespace

TEST_CASE("first hour: audit --help lists the families and shapes", "[cli][first_hour]") {
    fs::path dir = scratch("first_help");
    Ran help = program("audit --help", dir);
    CHECK(help.status == 0);
    for (const std::string& name : family_names())
        CHECK_THAT(help.out, Catch::Contains(name));
    for (const std::string& name : shape_names())
        CHECK_THAT(help.out, Catch::Contains(name));
    fs::remove_all(dir);
}

TEST_CASE("first hour: a mistyped name gets the list and the nearest name", "[cli][first_hour]") {
    fs::path dir = scratch("first_names");
    Ran family = program("audit --families generic,near_tangnt --no-plots --out r", dir);
    CHECK(family.status == 2);
    CHECK_THAT(family.err, Catch::Contains("no family named 'near_tangnt'") &&
                               Catch::Contains("did you mean 'near_tangent'?") &&
                               Catch::Contains("axis_parallel"));
    Ran shape = program("cases --shapes cilinder", dir);
    CHECK(shape.status == 2);
    CHECK_THAT(shape.err, Catch::Contains("did you mean 'cylinder'?"));
    // Far from every name: the list, and no guess.
    Ran far = program("cases --shapes torus", dir);
    CHECK_THAT(far.err, Catch::Contains("no shape named 'torus'") &&
                            !Catch::Contains("did you mean") && Catch::Contains("capsule"));
    Ran solver = program("solve --solver corect", dir);
    CHECK(solver.status == 2);
    CHECK_THAT(solver.err, Catch::Contains("did you mean 'correct'?"));
    Ran scenes = program("scenes --families nested,coaxal", dir);
    CHECK_THAT(scenes.err, Catch::Contains("did you mean 'coaxial'?"));
    fs::remove_all(dir);
}

TEST_CASE("first hour: replay takes one solver and says so", "[cli][first_hour]") {
    fs::path dir = scratch("first_replay");
    std::ofstream(dir / "case.jsonl") << two_hits << "\n";
    Ran list = program("replay --solver stable,correct case.jsonl", dir);
    CHECK(list.status == 2);
    CHECK_THAT(list.err, Catch::Contains("replay takes one solver"));
    fs::remove_all(dir);
}

TEST_CASE("first hour: solvers --plugin lists what a plugin's solvers declare",
          "[cli][first_hour]") {
    fs::path dir = scratch("first_solvers");
    Ran r = program(std::string("solvers --plugin '") + LINEQUAD_EXAMPLE_PLUGIN + "'", dir);
    CHECK(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains("textbook") && Catch::Contains("(plugin ") &&
                          Catch::Contains("nearest hit, t along v, as posed") &&
                          Catch::Contains("shapes cylinder:"));
    fs::remove_all(dir);
}

TEST_CASE("first hour: a solver asked for that grades nothing is named, and fails --check",
          "[cli][first_hour]") {
    fs::path dir = scratch("first_idle");
    std::string plugin = std::string(" --plugin '") + LINEQUAD_EXAMPLE_PLUGIN + "'";
    std::string run = "audit" + plugin +
                      " --solvers correct,textbook --shapes sphere --families generic --cases 5 "
                      "--no-plots --out r";
    Ran warned = program(run, dir);
    CHECK(warned.status == 0);
    CHECK_THAT(
        warned.err,
        Catch::Contains("warning: solver 'textbook' graded no case") &&
            Catch::Contains("it takes none of the shapes asked for (sphere); it takes cylinder"));
    Ran checked = program(run + " --check", dir);
    CHECK(checked.status == 1);
    CHECK_THAT(checked.err, Catch::Contains("solver 'textbook' graded no case"));
    // On a shape it takes, the same command is quiet about it.
    Ran graded = program("audit" + plugin +
                             " --solvers correct,textbook --shapes cylinder --families generic "
                             "--cases 5 --no-plots --out r2",
                         dir);
    CHECK(graded.status == 0);
    CHECK_THAT(graded.err, !Catch::Contains("graded no case"));
    fs::remove_all(dir);
}

TEST_CASE("first hour: solve writes numbers for a person, and sums up", "[cli][first_hour]") {
    fs::path dir = scratch("first_decimal");
    std::ofstream(dir / "cases.jsonl")
        << two_hits << "\n"
        << R"({"id":"far","shape":"sphere","C":[0,0,0],"r":1,"L0":[0.1,-5,0],"v":[0,1,0]})"
        << "\n";
    Ran decimal = program("solve --solver stable --format decimal cases.jsonl", dir);
    CHECK(decimal.status == 0);
    std::vector<std::string> out;
    for (std::size_t at = 0, nl; (nl = decimal.out.find('\n', at)) != std::string::npos;
         at = nl + 1)
        out.push_back(decimal.out.substr(at, nl - at));
    REQUIRE(out.size() == 2);
    CHECK(out[0] == R"({"id":"cyl-two","solver":"stable","hits":[{"t":7.0,"kind":"cross",)"
                    R"("part":"lateral","p":[-3.0,4.0,2.0]},{"t":13.0,"kind":"cross",)"
                    R"("part":"lateral","p":[3.0,4.0,2.0]}],"on_surface":null})");
    // The decimal read back is the double the hex line holds, bit for bit.
    Ran hex = program("solve --solver stable cases.jsonl", dir);
    nlohmann::json d = nlohmann::json::parse(out[1]),
                   h = nlohmann::json::parse(hex.out.substr(hex.out.find('\n') + 1));
    REQUIRE(d["hits"].size() == 2);
    for (int i = 0; i < 2; ++i)
        CHECK(d["hits"][i]["t"].get<double>() ==
              std::strtod(h["hits"][i]["t"].get<std::string>().c_str(), nullptr));
    Ran summary = program("solve --solver stable,ode,nothing_like_it --summary cases.jsonl", dir);
    CHECK(summary.status == 2); // an unknown solver is refused before any work
    Ran counted = program("solve --solver all --summary cases.jsonl", dir);
    CHECK(counted.status == 0);
    CHECK_THAT(counted.err, Catch::Contains("solve: ") && Catch::Contains(" answered (") &&
                                Catch::Contains("unrepresented: "));
    fs::remove_all(dir);
}

TEST_CASE("first hour: a history is read without being written or created",
          "[history][first_hour]") {
    fs::path dir = scratch("first_history");
    audit::Options o;
    o.cases_per_group = 4, o.plots = false;
    o.families = {Family::generic};
    o.solvers = {"stable"};
    audit::Report r = audit::run(o);
    r.commit = "c0ffee";
    std::string db = (dir / "h.db").string();
    { audit::History(db).add(r); }
    std::string before = slurp(db);
    {
        audit::History read(db, audit::History::Access::read_only);
        CHECK(read.trend("stable").size() == 1);
    }
    CHECK(slurp(db) == before);
    Ran shown = program("history h.db --solver stable", dir);
    CHECK(shown.status == 0);
    CHECK_THAT(shown.out, Catch::Contains("c0ffee"));
    CHECK(slurp(db) == before);
    // Asked to read what is not there: said so, and nothing created.
    Ran missing = program("history none.db", dir);
    CHECK(missing.status == 2);
    CHECK_THAT(missing.err, Catch::Contains("none.db: no such history"));
    CHECK(!fs::exists(dir / "none.db"));
    // A file that is not linequad's history, read: refused, and left as it was.
    std::ofstream(dir / "other.db") << "not a database at all, only text\n";
    Ran other = program("history other.db", dir);
    CHECK(other.status == 2);
    CHECK(slurp(dir / "other.db") == "not a database at all, only text\n");
    if (::geteuid() != 0) { // root writes through a read-only mode; others cannot
        fs::permissions(db, fs::perms::owner_read | fs::perms::group_read);
        std::ofstream(dir / "r.json") << audit::to_json(r);
        Ran ro = program("history h.db --solver stable", dir);
        CHECK(ro.status == 0);
        CHECK(program("history h.db --add r.json", dir).status == 2);
    }
    fs::remove_all(dir);
}

TEST_CASE("first hour: the library reports progress to its caller, not to the terminal",
          "[audit][first_hour]") {
    audit::Options o;
    o.cases_per_group = 300, o.plots = false;
    o.families = {Family::generic, Family::near_tangent};
    o.shapes = {0};
    o.solvers = {"stable"};
    std::vector<audit::Progress> seen;
    o.progress = [&](const audit::Progress& p) { seen.push_back(p); };
    audit::Report r = audit::run(o);
    REQUIRE(!seen.empty());
    for (std::size_t i = 1; i < seen.size(); ++i)
        CHECK(seen[i].done > seen[i - 1].done);
    CHECK(seen.back().done == seen.back().total);
    CHECK(seen.back().total == r.total("stable").cases);
    CHECK(seen.back().seconds_left() == 0);
    audit::Progress half{50, 100, 2.0};
    CHECK(half.seconds_left() == 2.0);
}

TEST_CASE("first hour: a library's own messages are kept, bounded, for the report",
          "[audit][first_hour]") {
    audit::OwnOutput out;
    CHECK(out.bytes() == 0);
    out.write("ODE INTERNAL ERROR 1: assertion failed\n");
    std::string big(2 * audit::OwnOutput::kept, 'x');
    out.write(big);
    CHECK(out.bytes() == 39 + big.size());
    CHECK(out.head() == "ODE INTERNAL ERROR 1: assertion failed\n"); // whole messages only
    out.write("a later message\n"); // after one that did not fit: the head holds the first
    CHECK(out.head() == "ODE INTERNAL ERROR 1: assertion failed\n");
    CHECK(out.bytes() == 39 + big.size() + 16);
    out.clear();
    CHECK(out.bytes() == 0);
    CHECK(out.head().empty());
    out.write("after a new start\n");
    CHECK(out.head() == "after a new start\n");
}

TEST_CASE("first hour: an in-process library's messages reach the report, runs counted",
          "[audit][first_hour]") {
    audit::ExternalSolver noisy;
    noisy.name = "noisy";
    noisy.answers = audit::Answers::nearest;
    noisy.own_output = std::make_shared<audit::OwnOutput>();
    noisy.on<Cylinder>() = [out = noisy.own_output](const Cylinder&, const Line&) {
        out->write("INTERNAL ERROR 1: the same assertion\n");
        return std::optional<Result>(Result{});
    };
    audit::Options o;
    o.cases_per_group = 5, o.plots = false;
    o.families = {Family::generic};
    o.shapes = {0};
    o.solvers = {"noisy"};
    audit::Report r = audit::run(o, {noisy});
    std::uint64_t calls = r.total("noisy").cases;
    REQUIRE(calls > 1);
    const audit::Report::External& x = r.external.at("noisy");
    CHECK(x.output_bytes == 37 * calls);
    CHECK_THAT(audit::markdown(r), Catch::Contains("noisy wrote " + std::to_string(37 * calls) +
                                                   " bytes through its library's message hooks") &&
                                       Catch::Contains("INTERNAL ERROR 1: the same assertion   (" +
                                                       std::to_string(calls) + " times)"));
}
