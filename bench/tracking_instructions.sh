#!/usr/bin/env bash
# Instructions of each tracker on each shipped model, under callgrind: the same generic rays
# tracked (N of them) and not tracked, the difference per ray and per step each tracker took (its
# crossings; the exact tracker's are the cell changes).
#   bash bench/tracking_instructions.sh [BUILD_DIR] [N]     (defaults: build, 2000)
set -euo pipefail
build="${1:-build}"
n="${2:-2000}"
exe="$build/bench/linequad_tracking_instructions"
[ -x "$exe" ] || { echo "no $exe: build first (bash scripts/build.sh)" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "valgrind is not installed" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
ir() {
  valgrind --tool=callgrind --callgrind-out-file="$tmp/out" "$exe" "$@" >"$tmp/printed" 2>"$tmp/err" \
    || { echo "tracking_instructions.sh: $* failed:" >&2; head -20 "$tmp/err" >&2; exit 1; }
  awk '/^(summary|totals):/ { print $2; exit }' "$tmp/out"
}
echo "# bash bench/tracking_instructions.sh $build $n (callgrind; Ir(track) - Ir(no track), per ray and per step, $n generic rays)"
printf '%-26s %-9s %8s %12s %12s\n' model tracker steps instr/ray instr/step
for model in examples/models/*.json; do
  for tracker in textbook stable correct exact; do
    base=$(ir "$model" "$tracker" "$n" 0)
    full=$(ir "$model" "$tracker" "$n" 1)
    steps=$(cat "$tmp/printed")
    printf '%-26s %-9s %8d %12d %12d\n' "$(basename "$model")" "$tracker" "$steps" \
      $(( (full - base) / n )) $(( (full - base) / steps ))
  done
done
