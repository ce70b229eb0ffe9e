#!/usr/bin/env bash
# The peer libraries' audit into OUT (default reports/peers, the committed one; the main job
# passes its own): linequad's correct beside every peer library built in (compare/peers/), on
# axis-aligned circular shapes, which all of them can hold; then VecGeom's alone on elliptic
# sections along the axes (OUT/aligned), which its elliptic solids are.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-reports/peers}"
linequad=./build/compare/linequad
peers=$($linequad solvers | awk '/\(peer library[,)]/ {printf ",%s", $1}')
if [ -z "$peers" ]; then
  echo "peers: no peer library is built in (scripts/install-deps.sh installs them)" >&2
  exit 0
fi
$linequad audit --solvers "correct$peers" --frames axis --cases "${PEER_CASES:-5000}" --seed 1 \
  --out "$out"
if [[ "$peers" == *,vecgeom* ]]; then
  $linequad audit --solvers correct,vecgeom,vecgeom_out --frames aligned \
    --cases "${PEER_CASES:-5000}" --seed 1 --out "$out/aligned"
fi

# Instructions per solve under callgrind (repeatable on a loaded machine): each peer on posed
# generic segments of each shape it takes, (Ir(N) - Ir(0)) / N; correct beside it from
# bench/instructions.sh's generic cylinder.
if command -v valgrind >/dev/null; then
  exe=./build/compare/linequad_peer_instructions
  n=2048
  ir() {
    valgrind --tool=callgrind --callgrind-out-file=/tmp/peers.callgrind.$$ "$exe" "$@" \
      >/dev/null 2>&1 || { echo "-"; return; }
    awk '/^(summary|totals):/ { print $2; exit }' /tmp/peers.callgrind.$$
    rm -f /tmp/peers.callgrind.$$
  }
  {
    echo "# instructions per solve (bash scripts/peers.sh; posed generic segments, axis frames)"
    printf '%-8s %-18s %10s\n' solver shape instructions
    for peer in ${peers//,/ }; do
      for shape in cylinder elliptic_cylinder elliptic_cone frustum sphere ellipsoid capsule; do
        base=$(ir "$peer" "$shape" 0)
        [ "$base" = "-" ] && continue
        full=$(ir "$peer" "$shape" "$n")
        printf '%-8s %-18s %10d\n' "$peer" "$shape" $(( (full - base) / n ))
      done
    done
  } | tee "$out/instructions.txt"
fi
