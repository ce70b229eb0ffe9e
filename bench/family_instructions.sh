#!/usr/bin/env bash
# Instructions per solve family by family under callgrind, repeatable on a loaded machine: each
# family's audit cases (linequad cases --families F --cases N --seed S: every shape and range the
# family applies to) solved once by each solver, less the same run without the solves, over the
# count; then, for two solvers, the second's over the first's, family by family and over all
# families (weighted by their cases, as the audit weighs them).
#   bash bench/family_instructions.sh [BUILD_DIR] [CASES] [SEED] [SOLVERS] [FAMILY...]
#   (defaults: build, 200, 9, correct,exact, every family; SOLVERS comma-separated)
#   SHAPE=NAME in the environment counts that shape's cases only (audit --shapes' names).
set -euo pipefail
build="${1:-build}"
cases="${2:-200}"
seed="${3:-9}"
solvers="${4:-correct,exact}"
shift $(($# < 4 ? $# : 4))
exe="$build/bench/linequad_family_instructions"
[ -x "$exe" ] || { echo "no $exe: build first (bash scripts/build.sh)" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "valgrind is not installed" >&2; exit 2; }
families=("$@")
[ ${#families[@]} -gt 0 ] || mapfile -t families < <("$exe" --families)
IFS=, read -r -a names <<<"$solvers"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
ir() { # instructions of one run; the cases it made go to $tmp/cases
  if ! valgrind --tool=callgrind --callgrind-out-file="$tmp/out" "$exe" "$@" \
    >/dev/null 2>"$tmp/err"; then
    echo "family_instructions.sh: $* failed under valgrind:" >&2
    grep -v '^==' "$tmp/err" | head -20 >&2
    exit 1
  fi
  grep -v '^==' "$tmp/err" | tail -1 >"$tmp/cases"
  awk '/^(summary|totals):/ { print $2; exit }' "$tmp/out"
}
echo "# ${SHAPE:+SHAPE=$SHAPE }bash bench/family_instructions.sh $build $cases $seed $solvers${*:+ $*} (callgrind; (Ir(solved) - Ir(not solved)) / cases)"
for family in "${families[@]}"; do
  printf '%s' "$family" >>"$tmp/rows"
  for solver in "${names[@]}"; do
    base=$(ir "$solver" "$family" "$cases" "$seed" 0 ${SHAPE:+"$SHAPE"})
    full=$(ir "$solver" "$family" "$cases" "$seed" 1 ${SHAPE:+"$SHAPE"})
    printf ' %s %s' "$(cat "$tmp/cases")" $((full - base)) >>"$tmp/rows"
  done
  printf '\n' >>"$tmp/rows"
done
python3 - "$solvers" "$tmp/rows" <<'PY'
import sys
names = sys.argv[1].split(",")
rows = [l.split() for l in open(sys.argv[2])]
pair = len(names) == 2
print(f"{'family':18} {'cases':>6}" + "".join(f" {n:>10}" for n in names) +
      (f" {names[1] + '/' + names[0]:>14}" if pair else ""))
totals = [0] * len(names)
for r in rows:
    n = int(r[1])
    if n == 0:  # the family does not apply to SHAPE
        continue
    ir = [int(r[2 + 2 * i]) for i in range(len(names))]
    totals = [t + x for t, x in zip(totals, ir)]
    print(f"{r[0]:18} {n:6d}" + "".join(f" {x // n:10d}" for x in ir) +
          (f" {ir[1] / ir[0]:14.2f}" if pair else ""))
if pair:
    print(f"{'all':18} {'':6}" + " " * 11 * len(names) + f" {totals[1] / totals[0]:14.2f}")
PY
