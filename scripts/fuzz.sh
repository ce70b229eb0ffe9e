#!/usr/bin/env bash
# Builds the libFuzzer target with clang (address and undefined-behaviour sanitizers) and runs
# it for a bounded time: FUZZ_SECONDS (default 60). Crashes and broken invariants fail the run;
# the input that broke it is left in build-fuzz/ as crash-* for replay.
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
cp examples/cases.jsonl build-fuzz/corpus/ 2>/dev/null || true
i=0
while IFS= read -r line; do printf '%s' "$line" > "build-fuzz/corpus/example-$i"; i=$((i+1)); done < examples/cases.jsonl
cd build-fuzz
./compare/fuzz/linequad_fuzz -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
  -print_final_stats=1 corpus 2>&1 | tail -n 25
