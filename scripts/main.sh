#!/usr/bin/env bash
# The main job: install, build, solve the shipped examples with every solver (and the example
# scenes with the scene solvers), then the default audit campaign, the spawned-ray audit, the
# scene audit and the peer libraries' audit.
#
# It writes this machine's reports under REPORTS (default reports/local/, which git ignores), so
# that running it leaves the clone as it was: the committed reports (reports/latest/ and
# reports/peers/, which the docs' tables quote) change only when someone means them to, with
# REPORTS=reports. The terminal gets a short account of each step; what the steps print in full
# (the build, every result line) goes to files beside the reports.
set -euo pipefail
cd "$(dirname "$0")/.."
reports="${REPORTS:-reports/local}"
mkdir -p "$reports/latest"
start=$SECONDS

# step NAME LOG COMMAND...: runs COMMAND with its output in LOG, says how long it took, and on a
# failure shows the end of LOG.
step() {
  local name="$1" log="$2" t0=$SECONDS
  shift 2
  if "$@" >"$log" 2>&1; then
    printf '%-28s %4ds  (output: %s)\n' "$name" $((SECONDS - t0)) "$log"
  else
    local rc=$?
    printf '%-28s failed (exit %d); the end of %s:\n' "$name" "$rc" "$log" >&2
    tail -n 30 "$log" >&2
    exit "$rc"
  fi
}

step "install and build" "$reports/build.log" bash scripts/build.sh
linequad=./build/compare/linequad
$linequad --version
# The Python module, where Debian's python3 finds it (import linequad; docs/python.md).
if [ -d build/python/linequad ]; then
  sudo=""
  [ "$(id -u)" = 0 ] || sudo="sudo"
  step "install the Python module" "$reports/python_install.log" \
    $sudo cmake --install build --component python
fi

# The shipped examples, every solver: a result line per case and solver (a peer library's
# "unrepresented" is an answer: that library has no such shape).
$linequad solve --solver all --summary examples/cases.jsonl >"$reports/examples.jsonl"
$linequad solve --solver stable,correct,exact --summary examples/scenes.jsonl \
  >"$reports/scenes.jsonl"

echo "the default audit (every family, shape and range; a progress line every tenth):"
$linequad audit --out "$reports/latest" | sed 's/^/  /'
step "spawned-ray audit" "$reports/latest/spawn.log" \
  $linequad spawn --cases 5000 --out "$reports/latest/spawn.md"
step "scene audit" "$reports/latest/scenes.log" \
  $linequad scenes --scenes 400 --out "$reports/latest/scenes.md"
step "peer libraries' audit" "$reports/peers.log" env OUT="$reports/peers" bash scripts/peers.sh
# The tracking audit on each shipped model: the tracker transport codes write, graded against
# the exact tracks.
mkdir -p "$reports/latest/cells"
for model in examples/models/*.json; do
  name=$(basename "$model" .json)
  step "tracking audit: $name" "$reports/latest/cells/$name.log" \
    $linequad cells "$model" --audit --rays 20000 --out "$reports/latest/cells/$name"
done
# OpenMC's own files of the pin cell and of four pins of an assembly: a geometry.xml has no
# source box of its own.
step "tracking audit: pin_cell_openmc" "$reports/latest/cells/pin_cell_openmc.log" \
  $linequad cells examples/models/pin_cell_openmc.xml --audit --rays 20000 \
  --box -0.625,-0.625,-1,0.625,0.625,1 --out "$reports/latest/cells/pin_cell_openmc"
step "tracking audit: assembly_openmc" "$reports/latest/cells/assembly_openmc.log" \
  $linequad cells examples/models/assembly_openmc.xml --audit --rays 20000 \
  --box -1.26,-1.26,-10,1.26,1.26,10 --out "$reports/latest/cells/assembly_openmc"

cat <<SUMMARY
main job done in $((SECONDS - start)) s. Reports:
  $reports/latest/report.html   the default audit (report.md, report.json beside it)
  $reports/latest/spawn.md      rays leaving a hit
  $reports/latest/scenes.md     scenes
  $reports/peers/report.html    five other libraries beside linequad's correct
  $reports/latest/cells/*/report.html   particles tracked through the shipped models (examples/models/)
SUMMARY
