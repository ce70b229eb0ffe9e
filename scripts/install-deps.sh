#!/usr/bin/env bash
# Installs what linequad needs from Debian 12's packages, only what is missing.
set -euo pipefail
packages=(build-essential cmake pkg-config git
          libcgal-dev libgmp-dev libmpfr-dev libeigen3-dev catch2 libbenchmark-dev
          clang libclang-rt-14-dev
          nlohmann-json3-dev libcli11-dev
          # report.html (cmark-gfm), and the test that opens it in headless Chromium.
          libcmark-gfm-dev libcmark-gfm-extensions-dev chromium
          # Campaigns under GNU parallel (scripts/campaign.sh; its test reads the Kubernetes Job with
          # python3-yaml); the audit's history (SQLite).
          parallel libsqlite3-dev python3-yaml
          # A real Slurm for the campaign test (tests/slurm_test.sh starts and stops it).
          slurm-wlm munge
          # The measurement scripts (bench/*.sh): callgrind, GNU time, bc.
          valgrind time bc
          # The peer libraries the audit grades beside linequad (compare/peers/).
          libocct-modeling-algorithms-dev libocct-modeling-data-dev libocct-foundation-dev
          libembree-dev libbullet-dev libode-dev libvecgeom-dev
          # OpenMC's geometry.xml, read into a model of cells (linequad cells).
          libpugixml-dev
          # The Python module (python/) and its tests; PyTorch for the float32 example that the
          # docs' test runs (examples/python/torch_sphere.py).
          pybind11-dev python3-dev python3-numpy python3-pytest python3-torch)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""
  [ "$(id -u)" = 0 ] || sudo="sudo"
  echo "installing: ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
