#!/usr/bin/env bash
# The main job: install, build, and solve the shipped example cases with every solver.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
./build/compare/linequad --version
./build/compare/linequad solve --solver all examples/cases.jsonl
