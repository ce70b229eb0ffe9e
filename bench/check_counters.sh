#!/usr/bin/env bash
# bench/instructions.sh's two counters agree: per solve, single steps under ptrace
# (COUNTER=steps, the only one for AVX-512) and callgrind count the same instructions on rows
# both can run. They are allowed to differ by one per solve: the difference of two runs also
# holds the few instructions around the solves that depend on N (a dozen in 64 solves here).
#   bash bench/check_counters.sh BUILD_DIR
set -euo pipefail
build="$1"
here="$(dirname "$0")"
# A container that forbids ptrace cannot single-step: skipped (CTest's SKIP_RETURN_CODE).
if "$build/bench/linequad_stepcount" true 2>&1 | grep -q "not permitted"; then
  echo "ptrace is not permitted here: skipped"
  exit 77
fi
rows="seed:cylinder:all:points:direct correct:elliptic_cone:any:no_points:prepared"
table() { ROWS="$rows" COUNTER="$1" bash "$here/instructions.sh" "$build" 64 | awk '!/^#/ && ++n > 1 { print $6 }'; }
callgrind=$(table callgrind)
steps=$(table steps)
echo "callgrind: $(echo $callgrind)"
echo "steps:     $(echo $steps)"
paste <(echo "$callgrind") <(echo "$steps") | awk '
  { d = $1 - $2; if (d < -1 || d > 1 || $1 <= 0) bad = 1 }
  END { if (NR != 3 || bad) { print "the counters disagree"; exit 1 } }'
