#include "io/process.hpp"

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace linequad::process {

namespace {

std::vector<char*> argument_vector(const std::vector<std::string>& argv) {
    std::vector<char*> out;
    for (const std::string& a : argv)
        out.push_back(const_cast<char*>(a.c_str()));
    out.push_back(nullptr);
    return out;
}

const char* signal_name(int sig) {
    switch (sig) {
    case SIGSEGV:
        return "SIGSEGV";
    case SIGBUS:
        return "SIGBUS";
    case SIGFPE:
        return "SIGFPE";
    case SIGILL:
        return "SIGILL";
    case SIGABRT:
        return "SIGABRT";
    case SIGKILL:
        return "SIGKILL";
    case SIGTERM:
        return "SIGTERM";
    case SIGINT:
        return "SIGINT";
    case SIGPIPE:
        return "SIGPIPE";
    case SIGXCPU:
        return "SIGXCPU";
    case SIGXFSZ:
        return "SIGXFSZ";
    case SIGTRAP:
        return "SIGTRAP";
    case SIGSYS:
        return "SIGSYS";
    default:
        return nullptr;
    }
}

} // namespace

std::string describe_status(int status) {
    if (WIFEXITED(status)) return "exited (" + std::to_string(WEXITSTATUS(status)) + ")";
    if (WIFSIGNALED(status)) {
        int sig = WTERMSIG(status);
        const char* name = signal_name(sig);
        std::string s = name ? name : "signal " + std::to_string(sig);
        return (sig == SIGKILL || sig == SIGTERM || sig == SIGINT ? "killed (" : "crashed (") + s +
               ")";
    }
    return "ended (status " + std::to_string(status) + ")";
}

Exit run(const std::vector<std::string>& argv, bool capture, std::size_t max_output) {
    Exit e;
    if (argv.empty()) {
        e.why = "no program";
        return e;
    }
    int out[2] = {-1, -1};
    if (capture && ::pipe2(out, O_CLOEXEC) != 0) {
        e.why = std::string("pipe: ") + std::strerror(errno);
        return e;
    }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    if (capture)
        posix_spawn_file_actions_adddup2(&actions, out[1], 1);
    else
        posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    std::vector<char*> args = argument_vector(argv);
    pid_t pid = -1;
    int rc = argv[0].find('/') == std::string::npos
                 ? posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ)
                 : posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (capture) ::close(out[1]);
    if (rc != 0) {
        if (capture) ::close(out[0]);
        e.why = argv[0] + ": " + std::strerror(rc);
        return e;
    }
    e.started = true;
    if (capture) {
        char buf[4096];
        for (;;) {
            ssize_t n = ::read(out[0], buf, sizeof buf);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) break;
            std::size_t room = max_output > e.output.size() ? max_output - e.output.size() : 0;
            e.output.append(buf, std::min(room, std::size_t(n)));
        }
        ::close(out[0]);
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) {
            e.why = std::string("waitpid: ") + std::strerror(errno);
            return e;
        }
    if (WIFEXITED(status)) e.code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) e.signal = WTERMSIG(status);
    if (!e.ok()) e.why = argv[0] + " " + describe_status(status);
    return e;
}

std::string self() {
    char buf[4096];
    ssize_t n = ::readlink("/proc/self/exe", buf, sizeof buf - 1);
    return n > 0 ? std::string(buf, std::size_t(n)) : std::string();
}

std::string absolute(const std::string& path) {
    char* real = ::realpath(path.c_str(), nullptr);
    if (!real) return path;
    std::string out = real;
    std::free(real);
    return out;
}

} // namespace linequad::process
