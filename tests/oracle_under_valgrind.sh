#!/usr/bin/env bash
# The oracle answers the same under valgrind as natively. Valgrind ignores the processor's
# rounding mode for SSE, which CGAL's interval arithmetic (the oracle's filter) relies on: the
# oracle must notice and take its exact path, not answer wrongly. `--tool=none` runs the program
# on valgrind's emulated processor without instrumenting it, so it is fast.
#   bash tests/oracle_under_valgrind.sh LINEQUAD WORK_DIR
set -euo pipefail
linequad="$1"
work="$2"
mkdir -p "$work"
"$linequad" cases --cases 10 >"$work/cases.jsonl"
"$linequad" solve --solver exact "$work/cases.jsonl" >"$work/native.jsonl"
valgrind -q --tool=none --error-exitcode=3 "$linequad" solve --solver exact "$work/cases.jsonl" \
  >"$work/valgrind.jsonl"
cases=$(wc -l <"$work/cases.jsonl")
if ! cmp -s "$work/native.jsonl" "$work/valgrind.jsonl"; then
  echo "the oracle answers differently under valgrind on $(diff "$work/native.jsonl" \
    "$work/valgrind.jsonl" | grep -c '^<') of $cases cases; the first:" >&2
  diff "$work/native.jsonl" "$work/valgrind.jsonl" | head -4 >&2
  exit 1
fi
echo "the oracle's $cases answers are the same under valgrind"
