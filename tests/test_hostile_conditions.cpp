// Hostile conditions, third round: a reader that goes away, a NUL inside a line, outputs that are
// not plain files or are the inputs, plugins that fork or close the worker's descriptors, a path
// that holds a newline in a replay command, and a diff of solvers that graded other cases.
#include "io/escape.hpp"
#include "linequad/audit.hpp"

#include "support.hpp"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace linequad;
using namespace linequad::test;
namespace fs = std::filesystem;

namespace {

// Runs a bash command line in dir (the pipelines under test: bash for PIPESTATUS and $'...'),
// its exit status.
int shell(const std::string& line, const fs::path& dir) {
    std::ofstream(dir / "command.sh") << line << "\n";
    std::string cmd = "cd '" + dir.string() + "' && bash command.sh";
    int raw = std::system(cmd.c_str());
    return WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
}

std::string bin() {
    return "'" + std::string(LINEQUAD_BIN) + "'";
}

} // namespace

TEST_CASE("pipes: an audit whose reader goes away finishes its report", "[hostile][cli]") {
    fs::path dir = scratch("broken_pipe");
    // head takes the first progress line and leaves: the next write finds no reader.
    int status = shell(bin() + " audit --cases 300 --families generic --out r 2>&1 | head -1 "
                               "> first.txt; exit ${PIPESTATUS[0]}",
                       dir);
    INFO(slurp(dir / "first.txt"));
    // Not killed by the signal: finished, the summary's write failing as a named error (2).
    CHECK((status == 0 || status == 2));
    audit::Report r = read_report(dir / "r");
    CHECK(r.status == audit::Status::complete);
    CHECK(fs::exists(dir / "r" / "report.html"));
    // solve too: the broken standard output is named, not a death by signal.
    status = shell(bin() + " solve --solver correct '" + std::string(LINEQUAD_SOURCE_DIR) +
                       "/examples/cases.jsonl' 2> err.txt | head -1 > /dev/null; exit "
                       "${PIPESTATUS[0]}",
                   dir);
    CHECK((status == 0 || status == 2));
    if (status != 0) CHECK(slurp(dir / "err.txt").find("standard output") != std::string::npos);
}

TEST_CASE("input: a NUL byte inside a line is a named error, not the end of the line",
          "[hostile][cli]") {
    fs::path dir = scratch("nul_byte");
    {
        std::ofstream f(dir / "cases.jsonl", std::ios::binary);
        std::string line = R"({"id":"a","shape":"sphere","C":[0,0,0],"r":1,"L0":[-2,0,0],)";
        line += '\0';
        line += R"("v":[1,0,0]})";
        f << line << "\n";
    }
    Ran solve = program("solve --solver correct cases.jsonl", dir);
    CHECK(solve.status != 0);
    CHECK(solve.out.find("a NUL byte at byte") != std::string::npos);
    Ran audit = program("audit --cases-file cases.jsonl --solvers correct --out r", dir);
    CHECK(audit.status != 0);
    CHECK(audit.err.find("NUL") != std::string::npos);
}

TEST_CASE("outputs: a FIFO, a link and an input are refused, named, and left as they were",
          "[hostile][cli]") {
    fs::path dir = scratch("outputs");
    REQUIRE(program("audit --cases 10 --solvers seed --families generic --shapes sphere "
                    "--no-plots --out a",
                    dir)
                .status == 0);
    REQUIRE(::mkfifo((dir / "fifo").c_str(), 0644) == 0);
    std::ofstream(dir / "kept.md") << "kept\n";
    fs::create_symlink(dir / "kept.md", dir / "link.md");
    std::string diff = "diff a/report.json a/report.json --markdown ";
    Ran fifo = program(diff + "fifo", dir);
    CHECK(fifo.status != 0);
    CHECK(fifo.err.find("fifo: a FIFO") != std::string::npos);
    CHECK(fs::is_fifo(dir / "fifo"));
    Ran link = program(diff + "link.md", dir);
    CHECK(link.status != 0);
    CHECK(link.err.find("a symbolic link") != std::string::npos);
    CHECK(fs::is_symlink(dir / "link.md"));
    CHECK(slurp(dir / "kept.md") == "kept\n");
    std::string before = slurp(dir / "a" / "report.json");
    Ran input = program(diff + "a/report.json", dir);
    CHECK(input.status != 0);
    CHECK(input.err.find("is the input") != std::string::npos);
    CHECK(slurp(dir / "a" / "report.json") == before);
    REQUIRE(program("history h.db --add a/report.json", dir).status == 0);
    std::string db = slurp(dir / "h.db");
    Ran plot = program("history h.db --solver seed --plot h.db", dir);
    CHECK(plot.status != 0);
    CHECK(plot.err.find("is the input") != std::string::npos);
    CHECK(slurp(dir / "h.db") == db);
}

TEST_CASE("replay: a path holding a newline is quoted byte for byte", "[hostile][cli]") {
    // In single quotes a newline survives a shell, but not a markdown code span (where the
    // report shows the command): such a word is written $'...', each control byte as \xHH.
    std::string word = escape::shell_word("dir\nwith 'quote'/lib.so");
    CHECK(word == "$'dir\\x0awith \\x27quote\\x27/lib.so'");
    CHECK(word.find('\n') == std::string::npos);
    fs::path dir = scratch("newline_path");
    std::ofstream(dir / "echo.sh") << "printf '%s' " << word << " > out.txt\n";
    REQUIRE(shell("source echo.sh", dir) == 0);
    CHECK(slurp(dir / "out.txt") == "dir\nwith 'quote'/lib.so");
    // End to end: a plugin under such a path, its worst case replayed from report.md's command.
    fs::path odd = dir / "a\nb";
    fs::create_directories(odd);
    fs::copy_file(LINEQUAD_EXAMPLE_PLUGIN, odd / "libtextbook.so");
    std::string plugin = escape::shell_word((odd / "libtextbook.so").string());
    // Through bash, which reads $'...' (the tests' std::system shell, dash, does not).
    std::ofstream(dir / "audit.sh") << bin() << " audit --plugin " << plugin
                                    << " --solvers textbook --families near_tangent --shapes "
                                       "cylinder --cases 50 --no-plots --out r 2> audit.err\n";
    REQUIRE(shell("source audit.sh", dir) == 0);
    std::string md = slurp(dir / "r" / "report.md");
    std::size_t at = md.find("`echo '");
    REQUIRE(at != std::string::npos);
    std::string command = md.substr(at + 1, md.find('`', at + 1) - at - 1);
    INFO(command);
    CHECK(command.find("--plugin $'") != std::string::npos);
    std::string path = fs::path(LINEQUAD_BIN).parent_path().string();
    std::ofstream(dir / "replay.sh") << "PATH='" << path << "':$PATH\n"
                                     << command << " > replay.out\n";
    CHECK(shell("source replay.sh", dir) == 0);
    CHECK(slurp(dir / "replay.out").find("\"solver\":\"textbook\"") != std::string::npos);
}

TEST_CASE("diff: a solver that graded other cases is not 'better'", "[hostile][report]") {
    audit::Options o;
    o.cases_per_group = 20;
    o.families = {Family::generic};
    o.shapes = {4};
    o.solvers = {"seed"};
    audit::Report before = audit::run(o), after = before;
    // The new run's solver graded half its cases (it declared the rest unrepresented): fewer
    // mismatches of fewer cases.
    for (auto& [key, row] : after.rows)
        if (key.solver == "seed") {
            row.unrepresented += row.cases / 2;
            row.cases -= row.cases / 2;
            row.cases_mismatched = 0;
        }
    audit::Diff d = audit::diff(before, after, {});
    CHECK_FALSE(d.comparable());
    CHECK(d.campaigns.find("seed in generic graded") != std::string::npos);
    CHECK(d.worse());
}

TEST_CASE("plugins: a call that closes the worker's descriptors is charged, not a later case",
          "[hostile][worker][cli]") {
    fs::path dir = scratch("closes_descriptors");
    // Both solvers misbehave on the same cases (picked by the bits of L0) and answer the same
    // textbook hit on the others: charged on the same cases, their rows are equal.
    Ran ran = program("audit --plugin '" + std::string(LINEQUAD_HOSTILE_PLUGIN) +
                          "' --solvers aborts,closes_descriptors --families generic "
                          "--shapes cylinder --cases 60 --no-plots --out r",
                      dir);
    REQUIRE(ran.status == 0);
    audit::Report r = read_report(dir / "r");
    audit::Row closes = r.total("closes_descriptors"), aborts = r.total("aborts");
    const std::string charged = "crashed the worker: closed or replaced its descriptors";
    REQUIRE(aborts.foreign.count("crashed (SIGABRT)") == 1);
    CHECK(closes.foreign.size() == 1);
    CHECK(closes.foreign[charged] == aborts.foreign["crashed (SIGABRT)"]);
    CHECK(closes.cases == aborts.cases);
    CHECK(closes.mismatches == aborts.mismatches);
    CHECK(closes.cases_mismatched == aborts.cases_mismatched);
    CHECK(closes.t_max == aborts.t_max);
    CHECK(closes.t_sum == aborts.t_sum);
}

TEST_CASE("plugins: a helper a plugin forks neither hides its crash nor outlives the audit",
          "[hostile][worker][cli]") {
    fs::path dir = scratch("forks");
    fs::path pids = dir / "helpers.txt";
    ::setenv("LQ_TEST_HELPER_PIDS", pids.c_str(), 1);
    // A long timeout: a crash taken for a hang would cost it for every such case.
    Ran ran = program("audit --plugin '" + std::string(LINEQUAD_HOSTILE_PLUGIN) +
                          "' --solvers forks_then_aborts --solver-timeout 30 --families generic "
                          "--shapes cylinder --cases 40 --no-plots --out r",
                      dir);
    ::unsetenv("LQ_TEST_HELPER_PIDS");
    REQUIRE(ran.status == 0);
    audit::Row t = read_report(dir / "r").total("forks_then_aborts");
    // Told by the worker's own end: a crash (the worker's SIGABRT), never a timeout.
    CHECK(t.foreign.count("crashed (SIGABRT)") == 1);
    CHECK(t.foreign.count("timed out") == 0);
    CHECK(t.mismatches[audit::crashed] > 0);
    CHECK(t.mismatches[audit::crashed] == t.foreign["crashed (SIGABRT)"]);
    // Every helper it started was ended with its worker's process group.
    std::vector<std::string> helpers;
    {
        std::ifstream in(pids);
        for (std::string line; std::getline(in, line);)
            if (!line.empty()) helpers.push_back(line);
    }
    REQUIRE(!helpers.empty());
    for (const std::string& pid : helpers) {
        INFO("helper " << pid);
        bool gone = false;
        for (int i = 0; i < 100 && !gone; ++i) { // a killed orphan is reaped by init, soon
            gone = ::kill(pid_t(std::stol(pid)), 0) != 0;
            if (!gone) ::usleep(20000);
        }
        CHECK(gone);
    }
}

TEST_CASE("scale-out: a shard walks its own cases only", "[hostile][cli]") {
    // One shard in 10^9 of a campaign of 10^12 cases per group, 3 groups (generic spheres, three
    // ranges): every 10^9th case, 3,000 in all. Walking the whole campaign to find them (3 10^12
    // indices) would never end.
    audit::Options o;
    o.cases_per_group = 1000000000000ull;
    o.families = {Family::generic};
    o.shapes = {4};
    o.shard = 7, o.shards = 1000000000;
    std::uint64_t n = 0;
    audit::for_each_case(o, [&](const Case& c) {
        ++n;
        CHECK(c.id.find("generic/4/") != std::string::npos); // the id as JSON text
    });
    CHECK(n == 3000);
    // The audit of such a shard grades exactly those.
    fs::path dir = scratch("scale_out");
    Ran ran = program("audit --cases 1000000000 --shard 0/1000000 --families generic --shapes "
                      "sphere --solvers correct --no-plots --out r",
                      dir);
    REQUIRE(ran.status == 0);
    CHECK(read_report(dir / "r").total("correct").cases == 3000);
}

TEST_CASE("html: a table too wide for cmark-gfm is refused, named, not rendered for minutes",
          "[hostile][cli]") {
    fs::path dir = scratch("wide_table");
    fs::create_directories(dir / "r");
    std::string row(24000, '|');
    std::ofstream(dir / "r" / "report.md") << "# linequad accuracy audit\n\n" << row << "\n";
    Ran ran = program("html r", dir);
    CHECK(ran.status != 0);
    CHECK(ran.err.find("report.md line 3: a table row of more than 256 cells") !=
          std::string::npos);
    CHECK_FALSE(fs::exists(dir / "r" / "report.html"));
}

TEST_CASE("signals: SIGTERM is honoured while a cases file is read", "[hostile][cli]") {
    fs::path dir = scratch("sigterm_reading");
    REQUIRE(::mkfifo((dir / "nobody_writes").c_str(), 0644) == 0);
    REQUIRE(::mkfifo((dir / "endless").c_str(), 0644) == 0);
    // A FIFO no one opens for writing (open() blocks), and one fed without end: SIGTERM after a
    // second; `timeout -k 10` kills it 10 s later if it did not stop (the status then says so).
    std::string stop = "timeout -k 10 -s TERM --preserve-status 1 " + bin();
    int blocked =
        shell(stop + " audit --cases-file nobody_writes --solvers correct --out a 2> a.err", dir);
    CHECK(blocked == 130);
    CHECK(
        slurp(dir / "a.err").find("nobody_writes: stopped (SIGINT or SIGTERM) while it was read") !=
        std::string::npos);
    int endless = shell("(" + bin() +
                            " cases --cases 100000000 --families generic > endless 2> /dev/null &)"
                            "; " +
                            stop + " audit --cases-file endless --solvers correct --out b 2> b.err",
                        dir);
    shell("pkill -f 'cases --cases 100000000 --families generic' || true", dir);
    CHECK(endless == 130);
    CHECK(slurp(dir / "b.err").find("endless: stopped") != std::string::npos);
}

TEST_CASE("signals: a tracking audit stopped writes what it tracked, a plugin's worker ended",
          "[hostile][cli]") {
    fs::path dir = scratch("sigterm_tracking");
    std::string model = std::string(LINEQUAD_SOURCE_DIR) + "/examples/models/pin_cell.json";
    // Ten million rays a family, with a plugin's distances: SIGTERM after a second.
    int status = shell("timeout -k 10 -s TERM --preserve-status 1 " + bin() + " cells '" + model +
                           "' --audit --rays 10000000 --out rep --solvers transport_textbook "
                           "--plugin '" LINEQUAD_TRANSPORT_PLUGIN "' 2> err.txt",
                       dir);
    CHECK(status == 130);
    CHECK(slurp(dir / "err.txt").find("stopped (SIGINT or SIGTERM) at ray ") != std::string::npos);
    std::string md = slurp(dir / "rep/report.md");
    CHECK(md.find("**Stopped** (SIGINT or SIGTERM) at ray ") != std::string::npos);
    CHECK(md.find("**linequad's cells went wrong on 0**") != std::string::npos);
    CHECK(fs::exists(dir / "rep/report.html"));
    // The worker ended with the run.
    CHECK(shell("pgrep -f 'plugin-worker " LINEQUAD_TRANSPORT_PLUGIN "' > /dev/null", dir) != 0);
}

TEST_CASE("memory: running out while reading an input names the input", "[hostile][cli]") {
    fs::path dir = scratch("memory");
    // An endless input under a 600 MB address-space limit: diff, merge and a cases file.
    for (const char* command :
         {"diff /dev/zero /dev/zero", "merge --out m /dev/zero",
          "audit --cases-file /dev/zero --max-line-bytes 1073741824 --solvers correct --out r"}) {
        INFO(command);
        int status = shell("ulimit -v 600000; " + bin() + " " + command + " 2> err.txt", dir);
        std::string err = slurp(dir / "err.txt");
        INFO(err);
        CHECK(status != 0);
        CHECK(status < 128); // an error, not a death by signal
        CHECK(err.find("/dev/zero") != std::string::npos);
    }
}

TEST_CASE("memory: a line whose JSON does not fit is named, not a std::terminate",
          "[hostile][cli]") {
    fs::path dir = scratch("memory_line");
    // 40 MB of one flat array: 20 million values, 16 bytes each in the DOM (and as much again
    // while its vector grows), more than a 400 MB address space holds beside the line itself.
    // nlohmann's destructor allocates a stack as large as the array, so the partly built value
    // could not be destroyed after the std::bad_alloc: the run ended in std::terminate.
    {
        std::ofstream out(dir / "big.jsonl");
        out << "{\"id\":\"x\",\"shape\":\"sphere\",\"pad\":[";
        for (int i = 0; i < 20000000; ++i)
            out << "0,";
        out << "0]}\n";
    }
    int status = shell("ulimit -v 400000; " + bin() +
                           " audit --cases-file big.jsonl --max-line-bytes 100000000 --solvers "
                           "correct --no-plots --out r 2> err.txt",
                       dir);
    std::string err = slurp(dir / "err.txt");
    INFO(err);
    CHECK(status == 2);
    CHECK(err.find("big.jsonl: line 1: out of memory while reading it") != std::string::npos);
}

TEST_CASE("memory: an audit out of memory at any point leaves its report marked, never running",
          "[hostile][cli]") {
    fs::path dir = scratch("memory_audit");
    // Few cases and every family: grading takes little, the report (a million JSON values) much,
    // so that the limits below run out while starting, grading, checking the report's JSON and
    // rendering it (which phase depends on the machine's libraries; each is covered by some).
    for (int megabytes : {80, 100, 120, 140, 200, 400}) {
        INFO(megabytes << " MB");
        fs::path out = dir / ("r" + std::to_string(megabytes));
        int status = shell("ulimit -v " + std::to_string(megabytes * 1000) + "; " + bin() +
                               " audit --cases 200 --no-plots --out " + out.filename().string() +
                               " > /dev/null 2> err.txt",
                           dir);
        std::string err = slurp(dir / "err.txt");
        INFO(err);
        CHECK(status < 128);         // never a death by signal (std::terminate is SIGABRT)
        if (status == 127) continue; // the program could not even be loaded in this much
        if (status == 0) {
            CHECK(read_report(out).status == audit::Status::complete);
            CHECK(fs::exists(out / "report.md"));
            continue;
        }
        CHECK(status == 2);
        CHECK(err.find("out of memory while") != std::string::npos);
        if (!fs::exists(out / "report.json")) { // out of memory before the first save
            CHECK(err.find("out of memory while grading") == std::string::npos);
            continue;
        }
        audit::Report r = read_report(out);
        CHECK(r.status != audit::Status::running);
        // A report.md beside it is this report's, not an earlier checkpoint's.
        if (fs::exists(out / "report.md"))
            CHECK(slurp(out / "report.md").find("no: running") == std::string::npos);
    }
}

TEST_CASE("merge: a shard's report copied and relabelled as another shard is refused",
          "[hostile][cli]") {
    fs::path dir = scratch("relabelled");
    for (int k : {0, 1})
        REQUIRE(program("audit --cases 20 --solvers seed --families generic --shapes sphere "
                        "--no-plots --shard " +
                            std::to_string(k) + "/2 --out s" + std::to_string(k),
                        dir)
                    .status == 0);
    REQUIRE(program("merge --out m s0/report.json s1/report.json", dir).status == 0);
    // Shard 0's report, its label changed to shard 1 (and its mark with it, as a copy keeps it).
    std::string text = slurp(dir / "s0" / "report.json");
    auto relabel = [&](std::string from, std::string to) {
        std::size_t at = text.find(from);
        REQUIRE(at != std::string::npos);
        text.replace(at, from.size(), to);
    };
    relabel("\"shards_included\":[0]", "\"shards_included\":[1]");
    relabel("\"shard_marks\":[[0,", "\"shard_marks\":[[1,");
    fs::create_directories(dir / "fake");
    std::ofstream(dir / "fake" / "report.json") << text;
    Ran ran = program("merge --out m2 s0/report.json fake/report.json", dir);
    CHECK(ran.status != 0);
    CHECK(ran.err.find("fake/report.json: its cases are not shard 1's") != std::string::npos);
}

TEST_CASE("memory: threads that cannot be had are done without", "[hostile][cli]") {
    // 64 workers' stacks (8 MB each) do not fit in 400 MB of address space: the audit runs on
    // the threads it could start (it ended in std::terminate, its report left running).
    fs::path dir = scratch("few_threads");
    int status = shell("ulimit -v 400000; " + bin() +
                           " audit --cases 50 --families generic --threads 64 --no-plots --out r "
                           "2> err.txt",
                       dir);
    INFO(slurp(dir / "err.txt"));
    CHECK(status == 0);
    CHECK(read_report(dir / "r").status == audit::Status::complete);
}
