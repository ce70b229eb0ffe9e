#!/usr/bin/env bash
# The audit's speed: cases per CPU-second and wall time, for this build against another
# (OLD_LINEQUAD, a linequad program built from an earlier commit), interleaved run by run so
# that load on a noisy machine falls on both alike. Prints each run and the medians.
#   OLD_LINEQUAD=/path/to/old/linequad bash bench/audit_speed.sh [BUILD_DIR] [CASES] [RUNS]
set -euo pipefail
build="${1:-build}"
cases="${2:-2000}"
runs="${3:-3}"
new="$build/compare/linequad"
[ -x "$new" ] || { echo "no $new: build first (bash scripts/build.sh)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# One audit: prints "wall cpu cases" (cases: every case posed, in both precisions).
one() {
  local exe="$1"; shift
  /usr/bin/time -f "%e %U %S" -o "$tmp/time" "$exe" audit --cases "$cases" --no-plots \
    --out "$tmp/out" "$@" >/dev/null 2>&1
  local total
  # stable's and stable32's cases: every case of the campaign, in each precision
  total=$(grep -o '"solver":"stable3\?2\?","cases":[0-9]*' "$tmp/out/report.json" |
    awk -F: '{ s += $NF } END { print s }')
  read -r wall user sys <"$tmp/time"
  echo "$wall $(echo "$user + $sys" | bc -l) $total"
  rm -rf "$tmp/out"
}
declare -A rows
configs=("new --threads 1" "new --threads 0")
[ -n "${OLD_LINEQUAD:-}" ] && configs=("old" "${configs[@]}")
for ((r = 0; r < runs; r++)); do
  for c in "${configs[@]}"; do
    set -- $c
    exe="$new"; [ "$1" = old ] && exe="$OLD_LINEQUAD"
    shift
    line=$(one "$exe" "$@")
    echo "run $r  $c: wall $(cut -d' ' -f1 <<<"$line") s, cpu $(cut -d' ' -f2 <<<"$line") s, $(cut -d' ' -f3 <<<"$line") cases"
    rows["$c"]+="$line"$'\n'
  done
done
echo "medians over $runs runs (--cases $cases, every family, shape, range and precision):"
median() { sort -g | awk '{v[NR] = $1} END { print v[int((NR + 1) / 2)] }'; }
for c in "${configs[@]}"; do
  wall=$(printf '%s' "${rows[$c]}" | cut -d' ' -f1 | median)
  cpu=$(printf '%s' "${rows[$c]}" | cut -d' ' -f2 | median)
  cases=$(printf '%s' "${rows[$c]}" | head -1 | cut -d' ' -f3)
  printf '  %-18s wall %6.2f s  cpu %6.2f s  %8.0f cases per CPU-second\n' "$c" "$wall" "$cpu" \
    "$(echo "$cases / $cpu" | bc -l)"
done
