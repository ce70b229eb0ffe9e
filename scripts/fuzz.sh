#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (address and undefined-behaviour sanitizers) and runs
# each for a bounded time: the solvers' target for FUZZ_SECONDS (default 60), the readers' and
# writers' target (JSON, cases, results, reports) for FUZZ_PARSER_SECONDS (default 30). A crash
# or a broken invariant fails the run; the input is left in build-fuzz/ as crash-*, and the
# invariant it broke is printed.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
seconds="${FUZZ_SECONDS:-60}"
parser_seconds="${FUZZ_PARSER_SECONDS:-30}"
sanitize="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined"
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_CXX_FLAGS="$sanitize" -DLINEQUAD_FUZZ=ON -DBUILD_TESTING=OFF \
  -DLINEQUAD_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target linequad_fuzz linequad_fuzz_parser

# Seeds: the shipped cases and the fuzz regressions, one per file; for the parser also the
# example scenes' records, result lines and a small report, when the main build (scripts/build.sh) has made the program.
rm -rf build-fuzz/corpus build-fuzz/corpus-parser
mkdir -p build-fuzz/corpus build-fuzz/corpus-parser
i=0
while IFS= read -r line; do
  printf '%s' "$line" > "build-fuzz/corpus/case-$i"
  printf '%s' "$line" > "build-fuzz/corpus-parser/case-$i"
  i=$((i+1))
done < <(cat examples/cases.jsonl tests/fuzz_regressions.jsonl)
while IFS= read -r line; do # scenes' records, for the parser
  printf '%s' "$line" > "build-fuzz/corpus-parser/scene-$i"
  i=$((i+1))
done < examples/scenes.jsonl
cp examples/scenes.jsonl build-fuzz/corpus-parser/scenes-file # a whole scene file
for model in examples/models/*.json examples/models/*.xml; do cp "$model" "build-fuzz/corpus-parser/model-$(basename "$model")"; done
if [ -x build/compare/linequad ]; then
  while IFS= read -r line; do printf '%s' "$line" > "build-fuzz/corpus-parser/result-$i"; i=$((i+1)); done \
    < <(build/compare/linequad solve --solver all examples/cases.jsonl || true)
  build/compare/linequad audit --cases 2 --families generic --solvers stable,correct --no-plots \
    --out build-fuzz/seed-report >/dev/null 2>&1
  cp build-fuzz/seed-report/report.json build-fuzz/corpus-parser/report
fi

cd build-fuzz
status=0
run() { # target corpus seconds log
  ./compare/fuzz/"$1" -max_total_time="$3" -timeout=10 -rss_limit_mb=4096 -max_len=65536 \
    -print_final_stats=1 "$2" > "$4" 2>&1 || status=$?
  echo "$1:"
  grep -A3 "invariant broken" "$4" || true
  grep -E "^(Done|stat::number_of_executed_units|stat::average_exec_per_sec|SUMMARY)" "$4" \
    || tail -n 20 "$4"
}
run linequad_fuzz corpus "$seconds" fuzz.log
run linequad_fuzz_parser corpus-parser "$parser_seconds" fuzz-parser.log
exit "$status"
