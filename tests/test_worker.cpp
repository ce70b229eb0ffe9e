// Plugins run in a worker process of their own: whatever a plugin does (crash, exit, throw,
// hang, overflow its stack, print, change the rounding mode or flush subnormals to zero) is
// counted and named against its cases, the run goes on, and not one bit of linequad's own answers
// moves. Replays reproduce what was graded, conventions are graded as the library means them,
// and rays from far away find what users report.
#include "support.hpp"

#include "linequad/audit.hpp"
#include "linequad/audit_solver.hpp"
#include "linequad/exact.hpp"
#include "linequad/solvers.hpp"

#include "numeric/fp_environment.hpp"
#include "run/plugin_worker.hpp"

#include <nlohmann/json.hpp>

#include <cfenv>
#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <set>
#include <spawn.h>
#include <thread>

extern char** environ;

using namespace linequad;
using namespace linequad::test;
namespace fs = std::filesystem;

namespace {

// A solver's rows as report.json writes them, without the timings (which differ run to run).
std::map<std::string, std::string> rows_of(const audit::Report& r, const std::string& solver) {
    std::map<std::string, std::string> out;
    auto j = nlohmann::json::parse(audit::to_json(r));
    for (auto& row : j["rows"])
        if (row["solver"] == solver) {
            row.erase("ns_per_solve");
            out[row["family"].get<std::string>() + "/" + row["shape"].get<std::string>()] =
                row.dump();
        }
    return out;
}

// The lines of a text, without empty ones.
std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) out.push_back(line);
    return out;
}

// The replay commands of a report.md (each on its own line, in a code span).
std::vector<std::string> replay_commands(const std::string& md) {
    std::vector<std::string> out;
    for (const std::string& line : lines_of(md)) {
        std::size_t at = line.find("`echo '");
        if (at == std::string::npos || line.find("linequad replay") == std::string::npos) continue;
        std::size_t end = line.rfind('`');
        out.push_back(line.substr(at + 1, end - at - 1));
    }
    return out;
}

// Runs a shell command line (a report's replay command, as a user pastes it) in dir, with the
// linequad under test first on PATH. Its standard output.
std::string run_in_shell(const std::string& command, const fs::path& dir) {
    std::string path = fs::path(LINEQUAD_BIN).parent_path().string() + ":" + std::getenv("PATH");
    std::string script = "cd '" + dir.string() + "' && PATH='" + path + "' && " + command +
                         " > replay.out 2> replay.err";
    std::ofstream(dir / "replay.sh") << script << "\n";
    int raw = std::system(("bash '" + (dir / "replay.sh").string() + "'").c_str());
    INFO(slurp(dir / "replay.err"));
    CHECK(WIFEXITED(raw));
    return slurp(dir / "replay.out");
}

// Every worst case report.md shows (each solver's worst rows) replays, from another directory, to
// the solver's answer and the reference its grade used, bit for bit, as report.json holds them.
// Returns how many were replayed.
int replay_every_worst_case(const fs::path& dir) {
    audit::Report r = read_report(dir);
    std::string md = slurp(dir / "report.md");
    std::vector<std::string> commands = replay_commands(md);
    std::set<std::pair<std::string, std::string>> graded;
    std::size_t rows_with_worst = 0;
    for (const auto& [key, row] : r.rows) {
        rows_with_worst += !row.worst.empty();
        for (const audit::Worst& w : row.worst)
            graded.emplace(w.solver_line(), w.oracle_line());
    }
    // Each solver shows the worst of up to five of its rows.
    CHECK(commands.size() <= 5 * r.solvers.size());
    CHECK(commands.size() >= std::min<std::size_t>(rows_with_worst, 1));
    fs::path elsewhere = scratch("replay_elsewhere");
    for (const std::string& command : commands) {
        INFO(command);
        // Markdown code spans hold the command as it is (no escapes inside them).
        std::vector<std::string> got = lines_of(run_in_shell(command, elsewhere));
        REQUIRE(got.size() == 2);
        CHECK(graded.count({got[0], got[1]}) == 1);
    }
    // And every row's worst cases in report.json, each through the command the report would
    // write for it: the case as posed, the solver's plugin by its absolute path.
    int replayed = 0;
    for (const auto& [key, row] : r.rows)
        for (const audit::Worst& w : row.worst) {
            std::string command = audit::replay_command(r, w, key.solver);
            INFO(command);
            std::vector<std::string> got = lines_of(run_in_shell(command, elsewhere));
            REQUIRE(got.size() == 2);
            CHECK(got[0] == w.solver_line());
            CHECK(got[1] == w.oracle_line());
            ++replayed;
        }
    return replayed;
}

// Starts linequad with these arguments in dir, without waiting: its pid.
pid_t start_linequad(const std::vector<std::string>& args, const fs::path& dir) {
    std::vector<std::string> argv = {LINEQUAD_BIN};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<char*> c;
    for (std::string& a : argv)
        c.push_back(a.data());
    c.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addchdir_np(&fa, dir.c_str());
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid = -1;
    REQUIRE(posix_spawn(&pid, LINEQUAD_BIN, &fa, nullptr, c.data(), environ) == 0);
    posix_spawn_file_actions_destroy(&fa);
    return pid;
}

// Its exit status once it ends, waiting at most `seconds`; -1 if it did not end.
int wait_for(pid_t pid, double seconds) {
    auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < until) {
        int status = 0;
        if (::waitpid(pid, &status, WNOHANG) == pid)
            return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return -1;
}

const std::string hostile = LINEQUAD_HOSTILE_PLUGIN;

} // namespace

TEST_CASE("worker: each way a plugin misbehaves is counted and named, and the run goes on",
          "[worker][cli]") {
    fs::path dir = scratch("worker_hostile");
    const std::string families = " --families generic --shapes cylinder --cases 40 --no-plots";
    Ran plain = program("audit --solvers correct" + families + " --out plain", dir);
    REQUIRE(plain.status == 0);
    Ran ran = program("audit --plugin '" + hostile +
                          "' --solvers correct,rounds_up,throws,segfaults,overflows,exits,hangs,"
                          "chatty,aborts --solver-timeout 0.3" +
                          families + " --out hostile",
                      dir);
    REQUIRE(ran.status == 0);
    audit::Report r = read_report(dir / "hostile");
    CHECK(r.status == audit::Status::complete);
    // linequad's own answers, graded as without the plugin, bit for bit.
    CHECK(rows_of(r, "correct") == rows_of(read_report(dir / "plain"), "correct"));
    // Each misbehaviour, by its name, on the cases it hit (a tenth of them), the others graded.
    auto expect = [&](const std::string& solver, const std::string& name) {
        INFO(solver);
        audit::Row t = r.total(solver);
        CHECK(t.cases > 0);
        std::uint64_t n = 0;
        for (const auto& [what, count] : t.foreign)
            if (what.rfind(name, 0) == 0) n += count;
        CHECK(n > 0);
        CHECK(n < t.cases / 4);
        CHECK(t.unrepresented_why.at("open finite cylinders only") > 0); // its own reason
    };
    expect("throws", "threw: vector::_M_range_check");
    expect("segfaults", "crashed (SIGSEGV)");
    expect("overflows", "crashed (SIGSEGV)"); // a stack overflow
    expect("exits", "exited (0)");
    expect("hangs", "timed out");
    expect("aborts", "crashed (SIGABRT)");
    CHECK(r.external.at("segfaults").restarts > 0);
    CHECK(r.external.at("throws").restarts == 0); // an exception does not end the worker
    // The rounding mode it leaves is noted at every call it answers, and put back.
    audit::Row up = r.total("rounds_up");
    REQUIRE(up.environment.size() == 1);
    CHECK(up.environment.begin()->first.find("rounding toward +infinity") != std::string::npos);
    CHECK(up.environment.begin()->second == up.cases);
    // What a plugin prints is the report's, never linequad's output.
    CHECK(r.external.at("chatty").output.find("chatty: solving") != std::string::npos);
    CHECK(r.external.at("chatty").output_bytes > 1000);
    // (Its own lines, that is: the audit's summary names the solver, "chatty: ... right".)
    for (const char* own : {"chatty: solving", "chatty: to stderr"}) {
        CHECK(ran.out.find(own) == std::string::npos);
        CHECK(ran.err.find(own) == std::string::npos);
    }
    std::string md = slurp(dir / "hostile" / "report.md");
    CHECK(md.find("chatty: to stderr") != std::string::npos);
    // Every worst case of every one of them replays: a crash as the same refusal.
    CHECK(replay_every_worst_case(dir / "hostile") > 10);
}

TEST_CASE("worker: a plugin's rounding mode or flush-to-zero never reaches linequad's answers",
          "[worker][cli]") {
    fs::path dir = scratch("worker_environment");
    REQUIRE(program("cases --families scale,near_tangent,degenerate_frame --cases 8 > c.jsonl", dir)
                .status == 0);
    // Subnormal coordinates, which flush-to-zero would take for zero.
    std::ofstream(dir / "c.jsonl", std::ios::app)
        << R"({"id":"sub","shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[-2,"0x1p-1070","0x1.8p-2"],"v":[1,"0x1p-1060",0]})"
        << "\n"
        << R"({"id":"sub2","shape":"cylinder","C":["0x1p-1073",0,0],"H":[0,0,1],"r":"0x1p-1030","L0":[-2,0,"0x1p-1074"],"v":[1,0,0]})"
        << "\n";
    Ran own = program("solve --solver correct,exact c.jsonl", dir);
    REQUIRE(own.status == 0);
    for (const char* plugin : {LINEQUAD_HOSTILE_PLUGIN, LINEQUAD_HOSTILE_FTZ_PLUGIN}) {
        INFO(plugin);
        Ran with = program(std::string("solve --plugin '") + plugin +
                               "' --solver rounds_up,correct,exact c.jsonl",
                           dir);
        REQUIRE(with.status == 0);
        std::string linequads;
        for (const std::string& line : lines_of(with.out))
            if (line.find("\"solver\":\"rounds_up\"") == std::string::npos)
                linequads += line + "\n";
        CHECK(linequads == own.out);
        CHECK(with.err.find("rounding toward +infinity") != std::string::npos);
    }
    // The -ffast-math library's flush-to-zero is its worker's, named in the report.
    Ran audited = program(std::string("audit --plugin '") + LINEQUAD_HOSTILE_FTZ_PLUGIN +
                              "' --solvers correct,chatty --families scale --shapes cylinder "
                              "--cases 10 --no-plots --out ftz",
                          dir);
    REQUIRE(audited.status == 0);
    audit::Report r = read_report(dir / "ftz");
    CHECK(r.external.at("chatty").load_environment == "flush-to-zero set, denormals-are-zero set");
    CHECK(r.total("correct").cases_mismatched == 0);
}

TEST_CASE("worker: an exit inside a solver does not end a checked audit, nor lose its report",
          "[worker][cli]") {
    fs::path dir = scratch("worker_exit");
    Ran ran = program("audit --check --plugin '" + hostile +
                          "' --solvers correct,exits --families generic --shapes cylinder "
                          "--cases 30 --no-plots --out out",
                      dir);
    CHECK(ran.status == 0);
    CHECK(ran.out.find("every claim holds") != std::string::npos);
    audit::Report r = read_report(dir / "out");
    CHECK(r.status == audit::Status::complete);
    CHECK(r.total("exits").foreign.at("exited (0)") > 0);
}

TEST_CASE("worker: SIGTERM ends a run promptly while a plugin's call hangs", "[worker][cli]") {
    fs::path dir = scratch("worker_sigterm");
    pid_t pid = start_linequad({"audit", "--plugin", hostile, "--solvers", "correct,hangs",
                                "--families", "generic", "--shapes", "cylinder", "--cases", "200",
                                "--solver-timeout", "60", "--no-plots", "--out", "out"},
                               dir);
    // Long enough for the worker to reach a case it hangs on (a tenth of them).
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    ::kill(pid, SIGTERM);
    int status = wait_for(pid, 2);
    if (status < 0) ::kill(pid, SIGKILL), ::waitpid(pid, nullptr, 0);
    CHECK(status == 130);
    audit::Report r = read_report(dir / "out");
    CHECK(r.status == audit::Status::stopped);
}

TEST_CASE("worker: what a plugin prints never mixes into solve's JSON Lines", "[worker][cli]") {
    fs::path dir = scratch("worker_stdout");
    REQUIRE(program("cases --families generic --shapes cylinder --cases 5 > c.jsonl", dir).status ==
            0);
    Ran ran = program("solve --plugin '" + hostile + "' --solver chatty,correct c.jsonl", dir);
    REQUIRE(ran.status == 0);
    std::vector<std::string> lines = lines_of(ran.out);
    CHECK(lines.size() == 2 * 15);
    for (const std::string& line : lines) {
        INFO(line);
        CHECK(nlohmann::json::accept(line));
    }
    CHECK(ran.err.find("chatty: solving") != std::string::npos); // shown apart, on stderr
}

TEST_CASE("worker: replays reproduce what was graded, posed cases and references included",
          "[worker][cli]") {
    fs::path dir = scratch("worker_replay");
    // The example plugin (nearest hits, t along v), the conventions' solvers (unit directions,
    // from-to segments, closed solids, first entries and exits, starts inside, contacts).
    Ran ran = program(std::string("audit --plugin '") + LINEQUAD_EXAMPLE_PLUGIN + "' --plugin '" +
                          LINEQUAD_CONVENTIONS_PLUGIN +
                          "' --solvers correct,batch,textbook,nearest_at_zero,first_entry_no_hit,"
                          "nearest_at_t0,first_exit,contact_point --families "
                          "generic,near_tangent,inside_start,axis_parallel --cases 20 "
                          "--no-plots --out out",
                      dir);
    REQUIRE(ran.status == 0);
    CHECK(replay_every_worst_case(dir / "out") > 30);
}

TEST_CASE("worker: a library that answers as it declares grades with no mismatch",
          "[worker][cli]") {
    fs::path dir = scratch("worker_conventions");
    const char* solvers[] = {"nearest_at_zero", "first_entry_no_hit", "nearest_at_t0", "first_exit",
                             "contact_point"};
    Ran ran = program(std::string("audit --plugin '") + LINEQUAD_CONVENTIONS_PLUGIN +
                          "' --solvers nearest_at_zero,first_entry_no_hit,nearest_at_t0,"
                          "first_exit,contact_point --families generic,inside_start,near_tangent,"
                          "axis_parallel,rim,cap_plane,cap_axis,two_nappes --cases 60 --no-plots "
                          "--out out",
                      dir);
    REQUIRE(ran.status == 0);
    audit::Report r = read_report(dir / "out");
    for (const char* s : solvers) {
        INFO(s);
        audit::Row t = r.total(s);
        CHECK(t.cases > 200);
        CHECK(t.cases_mismatched == 0);
        CHECK(t.t_max == 0);
        CHECK(t.p_max == 0);
    }
    // Where a convention applied: starts inside answered at 0 or t0, exits from inside, contacts.
    audit::Row inside;
    for (const auto& [key, row] : r.rows)
        if (key.solver == "nearest_at_zero" && key.family == "inside_start") inside.merge(row);
    CHECK(inside.cases > 100);
    CHECK(r.total("first_exit")
              .not_asked.count("first exit: the range does not start inside the solid") == 1);
    CHECK(r.external.at("nearest_at_zero").inside == "a hit at 0");
    CHECK(r.external.at("contact_point").contact == "first point");
}

TEST_CASE("worker: a packet solver is audited through its batch entry", "[worker][cli]") {
    fs::path dir = scratch("worker_packet");
    Ran ran = program(std::string("audit --plugin '") + LINEQUAD_CONVENTIONS_PLUGIN +
                          "' --solvers correct,packet,packet_crashes --families "
                          "generic,near_tangent,rim --cases 100 --no-plots --out out "
                          "--shapes cylinder,elliptic_cylinder,elliptic_cone,frustum,sphere,"
                          "ellipsoid,capsule", // the shapes the plugin declares
                      dir);
    REQUIRE(ran.status == 0);
    audit::Report r = read_report(dir / "out");
    CHECK(r.external.at("packet").batch);
    CHECK(r.external.at("packet").batch_fallbacks == 0);
    // Its packets crash: each is asked again one case at a time, and no case is charged.
    CHECK(r.external.at("packet_crashes").batch_fallbacks > 0);
    CHECK(r.external.at("packet_crashes").restarts == 0);
    for (const char* s : {"packet", "packet_crashes"}) {
        INFO(s);
        audit::Row t = r.total(s);
        CHECK(t.cases == r.total("correct").cases);
        CHECK(t.cases_mismatched == 0);
        CHECK(t.t_max == 0);
        CHECK(t.foreign.empty());
    }
}

TEST_CASE("worker: the first plugin ABI still loads, and a badly named solver is refused by name",
          "[worker][cli]") {
    fs::path dir = scratch("worker_abi");
    Ran ran = program(std::string("audit --plugin '") + LINEQUAD_ABI1_PLUGIN +
                          "' --solvers first_abi --families generic --shapes cylinder --cases 10 "
                          "--no-plots --out out",
                      dir);
    REQUIRE(ran.status == 0);
    CHECK(read_report(dir / "out").total("first_abi").cases == 30);
    Ran bad = program(
        std::string("audit --plugin '") + LINEQUAD_BAD_NAME_PLUGIN + "' --cases 1 --out out2", dir);
    CHECK(bad.status == 2);
    CHECK(bad.err.find("has a character other than letters, digits and _ . + - in its name") !=
          std::string::npos);
    CHECK(bad.err.find(R"("a/b|c'd")") != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "out2" / "report.json"));
    for (const char* name : {"", "-x", ".x", "a b", "a\nb", "x'y", "a/b", "é"})
        CHECK_FALSE(audit::solver_name_problem(name).empty());
    for (const char* name : {"textbook", "occt-7.6", "jolt_float", "v1.2+fma"})
        CHECK(audit::solver_name_problem(name).empty());
}

TEST_CASE("worker: solve shows only what a plugin declares, and hands a float solver floats",
          "[worker][cli]") {
    fs::path dir = scratch("worker_declared");
    std::ofstream(dir / "c.jsonl")
        << R"({"id":1,"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[-2,0,0.5],"v":[4,0,0],"range":"segment"})"
        << "\n"
        << R"({"id":2,"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[-2,0,0.1],"v":[4,0,0],"range":"segment"})"
        << "\n";
    Ran ran = program(std::string("solve --plugin '") + LINEQUAD_PHYSICS_PLUGIN +
                          "' --solver physics_float c.jsonl",
                      dir);
    REQUIRE(ran.status == 0);
    std::vector<std::string> lines = lines_of(ran.out);
    REQUIRE(lines.size() == 2);
    // Case 1 is all floats: a hit with its t only (no kind, part or point: none declared).
    CHECK(lines[0].find("\"hits\":[{\"t\":") != std::string::npos);
    CHECK(lines[0].find("kind") == std::string::npos);
    CHECK(lines[0].find("\"p\"") == std::string::npos);
    // Case 2's 0.1 is not a float: refused by name, not handed over.
    CHECK(lines[1].find("not_binary32") != std::string::npos);
}

TEST_CASE("worker: the far-origin family finds what users of float cylinder tests report",
          "[worker][cli]") {
    // Jolt issue #1818: cylinder ray casts from about 12 km away right only about 40% of the time
    // in float. A physics engine's float ray test, 2^13 and 2^14 shape sizes away.
    fs::path dir = scratch("worker_far");
    Ran ran = program(std::string("audit --plugin '") + LINEQUAD_PHYSICS_PLUGIN +
                          "' --solvers physics_float,seed32,stable,correct32 --families far_origin "
                          "--shapes cylinder --cases 620 --no-plots --out out",
                      dir);
    REQUIRE(ran.status == 0);
    audit::Report r = read_report(dir / "out");
    auto misclassified = [&](const std::string& solver) {
        std::uint64_t cases = 0, wrong = 0;
        for (int k : {13, 14}) {
            const audit::CurvePoint& p = r.curves.at({"far_origin", solver}).at(k);
            cases += p.cases, wrong += p.mismatched;
        }
        INFO(solver << ": " << wrong << " of " << cases);
        CHECK(cases > 50);
        return double(wrong) / double(cases);
    };
    CHECK(misclassified("physics_float") >= 0.30);
    CHECK(misclassified("seed32") >= 0.30);
    CHECK(misclassified("stable") == 0);
    CHECK(misclassified("correct32") == 0);
}

TEST_CASE("linequad's solvers and oracle answer alike whatever environment their caller leaves",
          "[worker]") {
    // What a plugin in the same process, or the caller itself, may leave: rounding upward,
    // flush-to-zero and denormals-are-zero. Every entry point puts the standard environment in
    // place for its call and the caller's back after.
    std::vector<Case> cases;
    for_each_family_case(5, 4, Precision::binary64, [&](const Case& c) { cases.push_back(c); });
    std::vector<std::string> standard;
    for (const Case& c : cases)
        for (const Solver& s : fast_solvers())
            if (s.precision == Precision::binary64)
                standard.push_back(format_result(c.id, s.name, s(c.shape, c.line)));
    for (const Case& c : cases)
        standard.push_back(format_result(c.id, "exact", exact::intersect(c.shape, c.line)));
    numeric::FpState caller = numeric::fp_state();
    std::fesetround(FE_UPWARD);
    __builtin_ia32_ldmxcsr(__builtin_ia32_stmxcsr() | 0x8040); // FTZ and DAZ
    numeric::FpState hostile_state = numeric::fp_state();
    std::vector<std::string> under;
    for (const Case& c : cases)
        for (const Solver& s : fast_solvers())
            if (s.precision == Precision::binary64)
                under.push_back(format_result(c.id, s.name, s(c.shape, c.line)));
    for (const Case& c : cases)
        under.push_back(format_result(c.id, "exact", exact::intersect(c.shape, c.line)));
    numeric::FpState after = numeric::fp_state();
    numeric::set_fp_state(caller);
    CHECK(after == hostile_state); // the caller's own environment is given back
    REQUIRE(under.size() == standard.size());
    for (std::size_t i = 0; i < under.size(); ++i) {
        INFO(standard[i]);
        CHECK(under[i] == standard[i]);
    }
}

TEST_CASE("an in-process solver that changes the environment is reported, and put back",
          "[worker]") {
    audit::ExternalSolver e;
    e.name = "upward";
    e.on<Cylinder>() = [](const Cylinder& c, const Line& l) -> std::optional<Result> {
        std::fesetround(FE_UPWARD);
        return correct::intersect(c, l);
    };
    audit::Options o;
    o.cases_per_group = 20;
    o.families = {Family::generic};
    o.shapes = {0};
    o.solvers = {"correct", "upward"};
    numeric::FpState before = numeric::fp_state();
    audit::Report r = audit::run(o, {e});
    CHECK(numeric::fp_state() == before);
    audit::Row t = r.total("upward");
    REQUIRE(t.environment.size() == 1);
    CHECK(t.environment.begin()->second == t.cases);
    CHECK(t.cases_mismatched == 0); // correct under FE_UPWARD: its guard keeps it correct
    CHECK(r.total("correct").cases_mismatched == 0);
}

TEST_CASE("worker: a transport code's textbook distances are graded on planes and quadrics",
          "[worker][cli]") {
    // OpenMC's formulas in a plugin (tests/plugins/transport_plugin.c), handed LQ_PLANE and
    // LQ_QUADRIC as audit_plugin.h lays them out: a wrong coefficient order or a lost
    // `coincident` would show as mismatches on generic lines, where the formula itself is right.
    fs::path dir = scratch("worker_transport");
    Ran ran = program(std::string("audit --plugin '") + LINEQUAD_TRANSPORT_PLUGIN +
                          "' --solvers correct,transport_textbook --shapes plane,quadric "
                          "--families generic,inside_start,far_origin --cases 100 --no-plots "
                          "--out out",
                      dir);
    REQUIRE(ran.status == 0);
    audit::Report r = read_report(dir / "out");
    std::uint64_t far_mismatched = 0;
    for (const auto& [key, row] : r.rows) {
        INFO(key.name());
        CHECK(row.cases == 300); // 100 cases x 3 ranges, none unrepresented
        if (key.solver == "correct") CHECK(row.cases_mismatched == 0);
        if (key.solver != "transport_textbook") continue;
        if (key.family == "generic") CHECK(row.cases_mismatched == 0);
        if (key.family == "far_origin" && key.shape == "quadric")
            far_mismatched = row.cases_mismatched;
    }
    // The half-b formula cancels for a source 2^10 to 2^40 sizes away.
    CHECK(far_mismatched > 30);
    fs::remove_all(dir);
}

TEST_CASE("worker: a plugin's sides (ABI 4) come back in order, a crash or a side that is no side "
          "named and charged to its point alone",
          "[worker][hostile]") {
    audit::PluginOptions o;
    o.program = LINEQUAD_BIN;
    std::vector<audit::ExternalSolver> all = audit::load_plugin(hostile, o);
    const audit::ExternalSolver* bad = nullptr;
    for (const audit::ExternalSolver& e : all)
        if (e.name == "bad_sides") bad = &e;
    REQUIRE(bad);
    CHECK(bad->has_sense());
    // 400 points at the plane x = 0.25 and a sphere of radius 1, each on a known side of both.
    std::vector<Case> at;
    std::vector<int> expected;
    Plane plane{{1, 0, 0}, 0.25, false};
    Quadric ball{{1, 1, 1, 0, 0, 0, 0, 0, 0, -1}, false};
    for (int i = 0; i < 200; ++i) {
        double x = -2 + i / 50.0 + 1.0 / 1024; // never on either surface
        Vec3 p{x, 0.125, -0.0625};
        Case c;
        c.shape = plane, c.line = Line{p, {0, 0, 1}, Range::ray};
        at.push_back(c), expected.push_back(x > 0.25 ? 1 : -1);
        c.shape = ball;
        at.push_back(c), expected.push_back(x * x + 0.125 * 0.125 + 0.0625 * 0.0625 > 1 ? 1 : -1);
    }
    std::vector<audit::ExternalAnswer> out;
    REQUIRE(bad->sides(at, out));
    REQUIRE(out.size() == at.size());
    int crashed = 0, no_side = 0, right = 0;
    for (std::size_t i = 0; i < at.size(); ++i) {
        INFO("point " << i);
        REQUIRE(out[i].result);
        if (out[i].result->ok()) {
            CHECK(out[i].side == expected[i]);
            ++right;
            continue;
        }
        CHECK(out[i].side == 0);
        std::string why = out[i].result->error().field;
        crashed += why == "crashed (SIGSEGV)";
        no_side += why == "its sense wrote side 7, not -1 or 1";
        CHECK((why == "crashed (SIGSEGV)" || why == "its sense wrote side 7, not -1 or 1"));
    }
    CHECK(crashed > 10);
    CHECK(no_side > 10);
    CHECK(right > 250);
    CHECK(bad->worker->restarts(bad->worker_index) == crashed);
}
