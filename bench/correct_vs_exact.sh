#!/usr/bin/env bash
# correct beside the exact oracle's solver in one audit run, family by family: each family's
# time per solve (the audit's medians of chunks of 1024 cases, weighted by each shape's cases)
# and exact's over correct's, then over all families.
#   bash bench/correct_vs_exact.sh [BUILD_DIR] [CASES]     (defaults: build, 20000)
set -euo pipefail
build="${1:-build}"
cases="${2:-20000}"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
if ! "$build/compare/linequad" audit --solvers correct,exact --cases "$cases" --no-plots \
  --out "$out/report" >/dev/null 2>"$out/log"; then
  cat "$out/log" >&2
  exit 1
fi
echo "# bash bench/correct_vs_exact.sh $build $cases (linequad audit --solvers correct,exact --cases $cases; ns per solve, this run)"
python3 - "$out/report/report.json" <<'PY'
import collections, json, sys
report = json.load(open(sys.argv[1]))
time = collections.defaultdict(collections.Counter)
cases = collections.Counter()
for row in report["rows"]:
    if row["solver"] in ("correct", "exact"):
        time[row["family"]][row["solver"]] += row["ns_per_solve"]["median"] * row["cases"]
        cases[row["family"]] += row["cases"] if row["solver"] == "correct" else 0
print(f"{'family':18} {'correct':>8} {'exact':>8} {'ratio':>7}")
total = collections.Counter()
for family in sorted(time):
    c, e = time[family]["correct"], time[family]["exact"]
    total.update({"correct": c, "exact": e})
    print(f"{family:18} {c / cases[family]:8.0f} {e / cases[family]:8.0f} {e / c:7.2f}")
n = sum(cases.values())
print(f"{'all':18} {total['correct'] / n:8.0f} {total['exact'] / n:8.0f} "
      f"{total['exact'] / total['correct']:7.2f}")
PY
