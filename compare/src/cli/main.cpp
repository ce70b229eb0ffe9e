// linequad: solve cases with any solver; audit solvers against the exact oracle. Each subcommand
// is in a file of its own (cli/cli.hpp).
#include "cli/cli.hpp"
#include "linequad/audit.hpp"

#include "io/jsonl.hpp"

#include <csignal>
#include <cstdlib>
#include <iostream>
#include <malloc.h>
#include <new>
#include <sys/resource.h>

using namespace linequad;

namespace {

std::string joined(int argc, char** argv) {
    std::string s = "linequad";
    for (int i = 1; i < argc; ++i)
        s += std::string(" ") + argv[i];
    return s;
}

int main_checked(int argc, char** argv) {
    CLI::App app{"linequad: line-quadric intersection solvers, graded against an exact oracle"};
    app.require_subcommand(0, 1);
    bool version = false;
    app.add_flag("--version", version, "version, compiler and floating-point flags");
    const cli::Command commands[] = {
        cli::solve_command(app),   cli::sense_command(app),   cli::cells_command(app),
        cli::replay_command(app),  cli::audit_command(app),   cli::cases_command(app),
        cli::merge_command(app),   cli::diff_command(app),    cli::html_command(app),
        cli::history_command(app), cli::spawn_command(app),   cli::scenes_command(app),
        cli::solvers_command(app), cli::version_command(app), cli::worker_command(app)};
    try {
        app.parse(argc, argv);
        for (const cli::Command& c : commands)
            if (c.check && c.app->parsed())
                if (auto [option, why] = c.check(); !why.empty())
                    throw CLI::ValidationError(option, why);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) { // --help, on standard output
            app.exit(e);
            std::cout.flush();
            if (!std::cout) throw std::runtime_error("cannot write standard output");
            return 0;
        }
        std::fprintf(stderr, "linequad: %s\nrun 'linequad --help' for the commands and options\n",
                     e.what());
        return 2;
    }
    if (version) return cli::print_version();
    for (const cli::Command& c : commands)
        if (c.app->parsed()) return c.run(joined(argc, argv));
    std::fputs(app.help().c_str(), stderr);
    return 2;
}

// Memory kept back for a run that exhausts the rest. The first failed allocation gives it up and
// is tried again in its room, and a running audit stops at its next chunk (audit::stop_for_memory)
// with its report saved and marked stopped: a std::bad_alloc thrown into the exact oracle's number
// type (CGAL's Mpzf) corrupts the heap. A later failure is an ordinary std::bad_alloc, which every
// reader names with its input.
char* memory_reserve = nullptr;
constexpr std::size_t memory_reserve_bytes = std::size_t(16) << 20;

void on_out_of_memory() {
    if (memory_reserve) {
        std::free(memory_reserve);
        memory_reserve = nullptr;
        audit::stop_for_memory();
        return;
    }
    std::set_new_handler(nullptr);
    throw std::bad_alloc();
}

} // namespace

int main(int argc, char** argv) {
    jsonl::guard_standard_descriptors();
    // Under an address-space limit, one malloc arena for every thread: each thread's own arena
    // reserves 64 MB of address space, and once none can be had glibc maps every allocation on
    // its own pages (an audit under 200 MB ran 80 times slower and then out of memory).
    if (rlimit space{}; ::getrlimit(RLIMIT_AS, &space) == 0 && space.rlim_cur != RLIM_INFINITY)
        ::mallopt(M_ARENA_MAX, 1);
    memory_reserve = static_cast<char*>(std::malloc(memory_reserve_bytes));
    std::set_new_handler(on_out_of_memory);
    // A file-size limit makes a write fail (EFBIG, named like any write error, its temporary
    // file removed) instead of killing the process with nothing said.
    std::signal(SIGXFSZ, SIG_IGN);
    // A reader that goes away (`linequad audit 2>&1 | head -1`) makes a write fail (EPIPE) instead
    // of killing the process mid-run: the audit's progress is then dropped, its report finished,
    // and a failed write to the standard output is a named error.
    std::signal(SIGPIPE, SIG_IGN);
    try {
        return main_checked(argc, argv);
    } catch (const audit::Stopped& e) {
        cli::fail(e.what());
        return 130;
    } catch (const std::bad_alloc&) {
        return cli::fail("out of memory");
    } catch (const std::exception& e) {
        return cli::fail(e.what());
    }
}
