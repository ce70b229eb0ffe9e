#!/usr/bin/env bash
# Two builds' Google Benchmark rows side by side (OLD_BUILD, say a worktree of an earlier
# commit, against NEW_BUILD), their runs alternating so that load on a noisy machine falls on
# both alike. Each run takes the median of REPS interleaved repetitions; printed per row: the
# median over the runs for each build, and old / new (above 1: the new build is faster).
#   bash bench/ab_bench.sh OLD_BUILD NEW_BUILD [FILTER] [RUNS] [REPS]
# (defaults: FILTER '1024_lines/batch', 3 runs of 3 repetitions)
set -euo pipefail
[ $# -ge 2 ] || { sed -n '2,7p' "$0" >&2; exit 2; }
old="$1/bench/linequad_bench"
new="$2/bench/linequad_bench"
filter="${3:-1024_lines/batch}"
runs="${4:-3}"
reps="${5:-3}"
for exe in "$old" "$new"; do
  [ -x "$exe" ] || { echo "no $exe: build linequad_bench there first" >&2; exit 2; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for ((r = 0; r < runs; r++)); do
  for side in old new; do
    exe="$old"; [ "$side" = new ] && exe="$new"
    "$exe" --benchmark_filter="$filter" --benchmark_repetitions="$reps" \
      --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true \
      --benchmark_min_time=0.1 2>/dev/null |
      awk -v side="$side" '$1 ~ /_median$/ { sub(/_median$/, "", $1); print side, $1, $2, $3 }' \
        >>"$tmp/rows"
  done
done
[ -s "$tmp/rows" ] || { echo "no benchmark matches '$filter'" >&2; exit 1; }
echo "# bash bench/ab_bench.sh $* ($runs runs of $reps repetitions each, alternating; times in ns)"
printf '%-56s %12s %12s %8s\n' row old new old/new
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }
for row in $(awk '{ print $2 }' "$tmp/rows" | sort -u); do
  o=$(awk -v r="$row" '$1 == "old" && $2 == r { print $3 }' "$tmp/rows" | median)
  n=$(awk -v r="$row" '$1 == "new" && $2 == r { print $3 }' "$tmp/rows" | median)
  printf '%-56s %12.0f %12.0f %8.3f\n' "$row" "$o" "$n" "$(echo "$o / $n" | bc -l)"
done
