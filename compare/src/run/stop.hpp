// A stop request (SIGINT, SIGTERM) for the run in progress: the audit's handler sets it, and what
// waits on other processes (a plugin's worker) looks at it, so that a run ends promptly with its
// report saved whatever the code it waits on is doing.
#pragma once

namespace linequad::audit {

// Whether a stop was requested since the running audit installed its handlers.
bool stop_requested();

} // namespace linequad::audit
