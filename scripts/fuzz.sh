#!/usr/bin/env bash
# Builds the libFuzzer target with clang (address and undefined-behaviour sanitizers) and runs
# it for a bounded time: FUZZ_SECONDS (default 60). A crash or a broken invariant fails the
# run; the input is left in build-fuzz/ as crash-*, and the invariant it broke is printed.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
seconds="${FUZZ_SECONDS:-60}"
sanitize="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined"
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_CXX_FLAGS="$sanitize" -DLINEQUAD_FUZZ=ON -DBUILD_TESTING=OFF \
  -DLINEQUAD_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target linequad_fuzz
mkdir -p build-fuzz/corpus
i=0
while IFS= read -r line; do printf '%s' "$line" > "build-fuzz/corpus/case-$i"; i=$((i+1)); done \
  < <(cat examples/cases.jsonl tests/fuzz_regressions.jsonl)
cd build-fuzz
status=0
./compare/fuzz/linequad_fuzz -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
  -print_final_stats=1 corpus > fuzz.log 2>&1 || status=$?
grep -A3 "invariant broken" fuzz.log || true
grep -E "^(Done|stat::number_of_executed_units|stat::average_exec_per_sec|SUMMARY)" fuzz.log || tail -n 20 fuzz.log
exit "$status"
