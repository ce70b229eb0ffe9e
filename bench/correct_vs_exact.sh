#!/usr/bin/env bash
# correct beside the exact oracle's solver, family by family, in RUNS audit runs: each run times
# both on every chunk of cases (the audit's medians of chunks of 1024 cases, weighted by each
# shape's cases); the table gives each family's median over the runs of correct's and exact's ns
# per solve and of their ratio (exact's over correct's), then the same over all families. The
# runs' spread, the largest ratio over the smallest, says how far to trust a row. `at generic`:
# the ratio the family would have if correct solved each of its lines in the time it takes for a
# generic line of the same shape (the Newton rung's first pass alone): what a cheaper answer to
# the family's exact questions could reach at most, short of a cheaper first pass.
#   bash bench/correct_vs_exact.sh [BUILD_DIR] [CASES] [RUNS]     (defaults: build, 20000, 3)
set -euo pipefail
build="${1:-build}"
cases="${2:-20000}"
runs="${3:-3}"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for run in $(seq 1 "$runs"); do
  if ! "$build/compare/linequad" audit --solvers correct,exact --cases "$cases" --no-plots \
    --out "$out/report$run" >/dev/null 2>"$out/log"; then
    cat "$out/log" >&2
    exit 1
  fi
done
echo "# bash bench/correct_vs_exact.sh $build $cases $runs (linequad audit --solvers correct,exact --cases $cases, $runs runs; ns per solve, medians over the runs)"
python3 - "$out" "$runs" <<'PY'
import collections, json, statistics, sys
out, runs = sys.argv[1], int(sys.argv[2])
rows = collections.defaultdict(list)  # family -> [(correct, exact, at generic cost) per run]
for run in range(1, runs + 1):
    report = json.load(open(f"{out}/report{run}/report.json"))
    time = collections.defaultdict(collections.Counter)
    cases = collections.Counter()
    generic = {row["shape"]: row["ns_per_solve"]["median"] for row in report["rows"]
               if row["family"] == "generic" and row["solver"] == "correct"}
    for row in report["rows"]:
        if row["solver"] in ("correct", "exact"):
            time[row["family"]][row["solver"]] += row["ns_per_solve"]["median"] * row["cases"]
        if row["solver"] == "correct":
            cases[row["family"]] += row["cases"]
            time[row["family"]]["generic"] += generic[row["shape"]] * row["cases"]
    total = collections.Counter()
    for family in time:
        total.update(time[family])
        rows[family].append(tuple(time[family][k] / cases[family]
                                  for k in ("correct", "exact", "generic")))
    n = sum(cases.values())
    rows["all"].append(tuple(total[k] / n for k in ("correct", "exact", "generic")))
print(f"{'family':18} {'correct':>8} {'exact':>8} {'ratio':>7} {'spread':>7} {'at generic':>11}")
for family in sorted(rows, key=lambda f: (f == "all", f)):
    c = statistics.median(r[0] for r in rows[family])
    e = statistics.median(r[1] for r in rows[family])
    ratios = [r[1] / r[0] for r in rows[family]]
    bound = statistics.median(r[1] / r[2] for r in rows[family])
    print(f"{family:18} {c:8.0f} {e:8.0f} {statistics.median(ratios):7.2f} "
          f"{max(ratios) / min(ratios):7.2f} {bound:11.2f}")
PY
