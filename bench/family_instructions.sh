#!/usr/bin/env bash
# Instructions per solve family by family under callgrind, repeatable on a loaded machine: each
# family's audit cases (linequad cases --families F --cases N --seed S: every shape and range the
# family applies to) solved once by SOLVER, less the same run without the solves, over the count.
#   bash bench/family_instructions.sh [BUILD_DIR] [CASES] [SEED] [SOLVER] [FAMILY...]
#   (defaults: build, 300, 9, correct, every family)
set -euo pipefail
build="${1:-build}"
cases="${2:-300}"
seed="${3:-9}"
solver="${4:-correct}"
shift $(( $# < 4 ? $# : 4 ))
exe="$build/bench/linequad_family_instructions"
[ -x "$exe" ] || { echo "no $exe: build first (bash scripts/build.sh)" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "valgrind is not installed" >&2; exit 2; }
families=("$@")
[ ${#families[@]} -gt 0 ] || mapfile -t families < <("$exe" --families)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
ir() { # instructions of one run, and the cases it made (on standard error)
  if ! valgrind --tool=callgrind --callgrind-out-file="$tmp/$2.$5.out" "$exe" "$@" \
      >/dev/null 2>"$tmp/$2.$5.err"; then
    echo "family_instructions.sh: $* failed under valgrind:" >&2
    grep -v '^==' "$tmp/$2.$5.err" | head -20 >&2
    exit 1
  fi
  awk '/^(summary|totals):/ { print $2; exit }' "$tmp/$2.$5.out"
}
echo "# bash bench/family_instructions.sh $build $cases $seed $solver ${*:-} (callgrind; (Ir(solved) - Ir(not solved)) / cases)"
printf '%-18s %8s %10s\n' family cases instr
for family in "${families[@]}"; do
  base=$(ir "$solver" "$family" "$cases" "$seed" 0)
  full=$(ir "$solver" "$family" "$cases" "$seed" 1)
  n=$(grep -v '^==' "$tmp/$family.1.err" | tail -1)
  printf '%-18s %8d %10d\n' "$family" "$n" $(( (full - base) / n ))
done
