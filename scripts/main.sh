#!/usr/bin/env bash
# The main job: install, build, solve the shipped examples with every solver (and the example
# scenes with the scene solvers), then the default audit campaign (reports/latest: report.md,
# report.json, figures), the spawned-ray audit and the scene audit.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
./build/compare/linequad --version
./build/compare/linequad solve --solver all examples/cases.jsonl
./build/compare/linequad solve --solver stable,correct,exact examples/scenes.jsonl
./build/compare/linequad audit --out reports/latest
./build/compare/linequad spawn --cases 5000 --out reports/latest/spawn.md
./build/compare/linequad scenes --scenes 400 --out reports/latest/scenes.md
bash scripts/peers.sh
