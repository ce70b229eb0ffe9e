#!/usr/bin/env bash
# The peer libraries' audit (reports/peers): linequad's correct beside every peer library built
# in (compare/peers/), on axis-aligned circular shapes, which all of them can hold.
set -euo pipefail
cd "$(dirname "$0")/.."
linequad=./build/compare/linequad
peers=$($linequad solvers | awk '/\(peer library\)/ {printf ",%s", $1}')
if [ -z "$peers" ]; then
  echo "peers: no peer library is built in (scripts/install-deps.sh installs them)" >&2
  exit 0
fi
$linequad audit --solvers "correct$peers" --frames axis --cases "${PEER_CASES:-5000}" --seed 1 \
  --out reports/peers
