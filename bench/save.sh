#!/usr/bin/env bash
# Runs a Google Benchmark program interleaved, medians only, and saves its rows under a header
# that names the command and the machine (what scripts/doc_tables.py quotes beside each table):
#
#   bash bench/save.sh reports/latest/bench_plugin.txt build/bench/linequad_plugin_bench
#   REPETITIONS=10 bash bench/save.sh OUT PROGRAM [--benchmark_filter=...]
set -euo pipefail
out=$1
shift
reps=${REPETITIONS:-10}
args=("$@" "--benchmark_repetitions=$reps" --benchmark_enable_random_interleaving=true
      --benchmark_report_aggregates_only=true)
machine=$(awk -F': ' '/^model name/ { print $2; exit }' /proc/cpuinfo)
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
# The command as a shell reads it back: an argument with anything but plain characters in single
# quotes (a filter's | is not a pipe).
shell_words() {
  local word words=()
  for word in "$@"; do
    if [[ $word =~ ^[A-Za-z0-9_./=:+,-]+$ ]]; then
      words+=("$word")
    else
      words+=("'${word//\'/\'\\\'\'}'")
    fi
  done
  printf '%s' "${words[*]}"
}
"${args[@]}" 2>/dev/null | grep '_median ' >"$tmp"
{
  printf '# %s\n' "$(shell_words "${args[@]}")"
  printf '# %s, %s (%s cores), medians of %s, interleaved (name, wall time, CPU time, repetitions, counters)\n' \
    "$(date -u '+%Y-%m-%d %H:%M UTC')" "$machine" "$(nproc)" "$reps"
  cat "$tmp"
} >"$out"
cat "$out"
