// A stop request (SIGINT, SIGTERM) for the run in progress: the audit's handler sets it, and what
// waits on other processes (a plugin's worker) looks at it, so that a run ends promptly with its
// report saved whatever the code it waits on is doing.
#pragma once

#include <csignal>

namespace linequad::audit {

// Whether a stop was requested since the running audit installed its handlers.
bool stop_requested();

// While one lives, SIGINT and SIGTERM request a stop (stop_requested) instead of ending the
// process: a long run ends early with what it has, saved. The handlers before it come back after.
class StopOnSignal {
  public:
    StopOnSignal();
    ~StopOnSignal();
    StopOnSignal(const StopOnSignal&) = delete;
    StopOnSignal& operator=(const StopOnSignal&) = delete;

  private:
    struct sigaction old_int_ {
    }, old_term_{};
};

} // namespace linequad::audit
