#!/usr/bin/env bash
# Installs the Debian packages Regolith needs that are not installed yet.
# Idempotent: when everything is present it only asks dpkg and returns at once.
set -euo pipefail

packages=(
  build-essential cmake make pkg-config
  openmpi-bin libopenmpi-dev         # MPI
  libeigen3-dev                      # Vec3 / Quat / small linear algebra
  petsc-dev                          # Poisson solve (gravity)
  libfftw3-dev                       # FFT free-space reference solver (gravity)
  libhdf5-openmpi-dev                # parallel checkpoints (io)
  libvtk9-dev                        # ParaView output (io)
  xvfb xauth                         # regolith-render's off-screen pictures without a display
  libgtest-dev libgmock-dev          # tests
  libbenchmark-dev                   # bench/
  libtomlplusplus-dev libcli11-dev   # scene files and command line
  libfmt-dev libspdlog-dev           # formatting and logging
  python3                            # tests/apps scripts (summary checks, run comparisons)
)

# `install-deps.sh --bench` adds what only `make bench` needs: LAMMPS for the side-by-side runs
# and matplotlib for the charts.
if [[ "${1:-}" == "--bench" ]]; then
  packages+=(lammps python3-matplotlib)
fi

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "install-deps: installing ${missing[*]}"
sudo=""
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "install-deps: not root and no sudo; install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
$sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
