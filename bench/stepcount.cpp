// Counts the instructions a program retires between two marks, by single-stepping it under
// ptrace: the counter for code valgrind cannot run (AVX-512, which callgrind does not decode) on a
// machine without a hardware instruction counter (a VM whose perf has none). Every instruction
// the CPU retires is one step, as callgrind counts them (a repeated string instruction is one step
// per repetition; the kernels have none).
//   linequad_stepcount PROGRAM [ARGS...]
// The program marks the region by raising SIGUSR1 before and after it, when LINEQUAD_STEP_MARKS
// is set in its environment (bench/instructions.cpp does); the count printed includes the few
// instructions of the marks themselves, which bench/instructions.sh cancels by subtracting a run
// with no solves. Slow (a system call per instruction): for regions of up to a few million
// instructions.
#include <sys/ptrace.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

// Lets the traced program run to its next stop; false when it has exited.
bool resume(pid_t child, int& status, int signal_to_pass, bool step) {
    long r = ptrace(step ? PTRACE_SINGLESTEP : PTRACE_CONT, child, nullptr,
                    reinterpret_cast<void*>(static_cast<long>(signal_to_pass)));
    if (r != 0) {
        std::perror("linequad_stepcount: ptrace");
        std::exit(2);
    }
    if (waitpid(child, &status, 0) != child) {
        std::perror("linequad_stepcount: waitpid");
        std::exit(2);
    }
    return WIFSTOPPED(status);
}

bool marked(int status) {
    return WIFSTOPPED(status) && WSTOPSIG(status) == SIGUSR1;
}

// The signal a stop should pass on to the program: none for a trace trap or a mark.
int to_pass(int status) {
    int sig = WSTOPSIG(status);
    return sig == SIGTRAP || sig == SIGUSR1 ? 0 : sig;
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s PROGRAM [ARGS...]\n", argv[0]);
        return 2;
    }
    pid_t child = fork();
    if (child < 0) {
        std::perror("linequad_stepcount: fork");
        return 2;
    }
    if (child == 0) {
        setenv("LINEQUAD_STEP_MARKS", "1", 1);
        if (ptrace(PTRACE_TRACEME, 0, nullptr, nullptr) != 0) {
            std::fprintf(stderr, "linequad_stepcount: ptrace is not permitted here: %s\n",
                         std::strerror(errno));
            _exit(126);
        }
        execvp(argv[1], argv + 1);
        std::fprintf(stderr, "linequad_stepcount: cannot run %s: %s\n", argv[1],
                     std::strerror(errno));
        _exit(127);
    }
    int status = 0;
    waitpid(child, &status, 0); // stopped at exec
    if (!WIFSTOPPED(status)) {
        std::fprintf(stderr, "linequad_stepcount: %s did not start\n", argv[1]);
        return 2;
    }
    // Run freely to the first mark, count steps to the second, then run to the end.
    int pass = 0;
    while (resume(child, status, pass, false) && !marked(status))
        pass = to_pass(status);
    if (!WIFSTOPPED(status)) {
        std::fprintf(stderr, "linequad_stepcount: %s exited before its first mark\n", argv[1]);
        return 2;
    }
    unsigned long long steps = 0;
    pass = 0;
    while (resume(child, status, pass, true) && !marked(status)) {
        ++steps;
        pass = to_pass(status);
    }
    if (!WIFSTOPPED(status)) {
        std::fprintf(stderr, "linequad_stepcount: %s exited inside its marks\n", argv[1]);
        return 2;
    }
    pass = 0;
    while (resume(child, status, pass, false))
        pass = to_pass(status);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        std::fprintf(stderr, "linequad_stepcount: %s failed\n", argv[1]);
        return 1;
    }
    std::printf("%llu\n", steps);
    return 0;
}
