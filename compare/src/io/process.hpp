// Other programs, started with an argument vector (posix_spawn) and never through a shell: no
// text from a report, a case file, a name or a path can become a command.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace linequad::process {

// How a program ended.
struct Exit {
    bool started = false; // false: it could not be started (why says so)
    int code = -1;        // its exit status, when it exited
    int signal = 0;       // the signal that ended it, if one did
    std::string output;   // its standard output, when captured (at most the limit)
    std::string why;
    bool ok() const { return started && signal == 0 && code == 0; }
};

// Runs argv[0] (looked up on PATH when it holds no '/') with these arguments and waits for it:
// standard input from /dev/null, standard error discarded, standard output captured up to
// max_output bytes (the rest read and dropped) or discarded.
Exit run(const std::vector<std::string>& argv, bool capture = true,
         std::size_t max_output = std::size_t(1) << 20);

// How a child that ended by `status` (waitpid's) is named in a report: "exited (3)",
// "crashed (SIGSEGV)", "killed (SIGKILL)".
std::string describe_status(int status);

// This program's own path, for starting it again in another mode ("" if unknown).
std::string self();

// An absolute, symlink-free path for an existing file; the path as given if it cannot resolve.
std::string absolute(const std::string& path);

} // namespace linequad::process
