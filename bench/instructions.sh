#!/usr/bin/env bash
# Instructions per solve under callgrind, repeatable on a loaded machine: for each row, the
# solver runs over the same pre-built generic cases (bench/generic_cases.hpp) once with N solves
# and once with none, and (Ir(N) - Ir(0)) / N is printed, with its ratio to the floor (the
# textbook cylinder quadratic, bench/floor.hpp).
#   bash bench/instructions.sh [BUILD_DIR] [N]     (defaults: build, 2048)
# ROWS="solver:shape:need:points:prepared ..." chooses the rows (default: the issue's table);
# shape+caps is the shape closed by its discs; ROWS=closed: each shape open and closed. The first
# line printed is the command.
# COUNTER=steps counts by single-stepping the solves under ptrace (bench/stepcount.cpp) instead:
# the only counter here for the AVX-512 rows, which valgrind cannot run; about 15 s per 100k
# instructions, so for a few rows with N of about 1024.
set -euo pipefail
build="${1:-build}"
n="${2:-2048}"
counter="${COUNTER:-callgrind}"
exe="$build/bench/linequad_instructions"
[ -x "$exe" ] || { echo "no $exe: build first (bash scripts/build.sh)" >&2; exit 2; }
case "$counter" in
callgrind) command -v valgrind >/dev/null || { echo "valgrind is not installed" >&2; exit 2; } ;;
steps) [ -x "$build/bench/linequad_stepcount" ] || { echo "no $build/bench/linequad_stepcount" >&2; exit 2; } ;;
*) echo "COUNTER is callgrind or steps, not $counter" >&2; exit 2 ;;
esac
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

ir() { # instructions of one run (a run that fails stops the script, named)
  if [ "$counter" = steps ]; then
    if ! "$build/bench/linequad_stepcount" "$exe" "$@" >"$tmp/out" 2>"$tmp/err"; then
      echo "instructions.sh: $* failed under linequad_stepcount:" >&2
      head -20 "$tmp/err" >&2
      exit 1
    fi
    cat "$tmp/out"
    return
  fi
  if ! valgrind --tool=callgrind --error-exitcode=3 --callgrind-out-file="$tmp/out" "$exe" "$@" \
      >/dev/null 2>"$tmp/err"; then
    echo "instructions.sh: $* failed under valgrind:" >&2
    grep -v '^==[0-9]*== *$' "$tmp/err" | head -20 >&2
    exit 1
  fi
  awk '/^(summary|totals):/ { print $2; exit }' "$tmp/out"
}
per_solve() {
  local base full
  base=$(ir "$@" 0)
  full=$(ir "$@" "$n")
  echo $(( (full - base) / n ))
}

# The command that made the table, as its first line.
{
  printf '#'
  [ -n "${COUNTER:-}" ] && printf ' COUNTER=%s' "$COUNTER"
  [ -n "${ROWS:-}" ] && printf ' ROWS="%s"' "$(echo $ROWS)"
  printf ' bash bench/instructions.sh %s %s (%s; (Ir(N) - Ir(0)) / N over bench/generic_cases.hpp)\n' \
    "$build" "$n" "$counter"
}
floor=$(per_solve floor cylinder all points direct)
printf '%-10s %-18s %-8s %-10s %-9s %8s %7s\n' solver shape need points shape instr ratio
printf '%-10s %-18s %-8s %-10s %-9s %8d %7s\n' floor cylinder all points - "$floor" 1.00
# Default rows: the core redesign's table (the cylinder as given, the cone prepared), then the
# same for the other shapes and the cone as given, for reference.
rows=${ROWS:-}
if [ "$rows" = closed ]; then
  # Each shape with an axis open and closed by its discs, on the same shapes and lines.
  rows=""
  for shape in cylinder elliptic_cylinder elliptic_cone frustum; do
    for s in "$shape" "$shape+caps"; do
      rows="$rows correct:$s:all:points:direct correct:$s:any:no_points:direct"
      rows="$rows stable:$s:all:points:direct"
    done
  done
fi
if [ -z "$rows" ]; then
  for solver in seed stable correct; do rows="$rows $solver:cylinder:all:points:direct"; done
  rows="$rows correct:cylinder:any:no_points:direct correct:cylinder:nearest:no_points:direct"
  # The float target: correct32 on the same cases rounded to float (binary32 end to end).
  rows="$rows correct32:cylinder:all:points:direct correct32:elliptic_cone:all:points:prepared"
  rows="$rows seed32:cylinder:all:points:direct stable32:cylinder:all:points:direct"
  for solver in seed stable correct; do rows="$rows $solver:elliptic_cone:all:points:prepared"; done
  rows="$rows correct:elliptic_cone:any:no_points:prepared"
  rows="$rows correct:elliptic_cone:nearest:no_points:prepared correct:elliptic_cone:any:no_points:direct"
  for shape in elliptic_cylinder elliptic_cone frustum; do
    for solver in seed stable certified correct; do rows="$rows $solver:$shape:all:points:direct"; done
  done
  rows="$rows certified:cylinder:all:points:direct"
  for shape in sphere ellipsoid capsule; do
    for solver in seed stable certified correct; do rows="$rows $solver:$shape:all:points:direct"; done
  done
  rows="$rows correct:capsule:any:no_points:direct"
  # The transport codes' surfaces: a plane and a general quadric (an ellipsoid in GQ form).
  for shape in plane quadric; do
    for solver in seed stable certified correct; do rows="$rows $solver:$shape:all:points:direct"; done
  done
  rows="$rows correct:quadric:nearest:no_points:direct correct32:quadric:all:points:direct"
  # The batch solvers on AVX2 lanes (valgrind runs no AVX-512): 1024 lines against one prepared
  # shape, per line.
  rows="$rows batch-avx2:cylinder:all:points:prepared batchcorrect-avx2:cylinder:all:points:prepared"
  rows="$rows batchcorrect-avx2:cylinder:any:no_points:prepared"
  rows="$rows batch-avx2:quadric:all:points:prepared batchcorrect-avx2:quadric:all:points:prepared"
  rows="$rows batch-avx2:plane:all:points:prepared batchcorrect-avx2:plane:all:points:prepared"
fi
for row in $rows; do
  IFS=: read -r solver shape need points prepared <<<"$row"
  count=$(per_solve "$solver" "$shape" "$need" "$points" "$prepared")
  printf '%-10s %-18s %-8s %-10s %-9s %8d %7.2f\n' "$solver" "$shape" "$need" "$points" \
    "$prepared" "$count" "$(echo "$count / $floor" | bc -l)"
done
