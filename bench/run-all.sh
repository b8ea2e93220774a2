#!/usr/bin/env bash
# `make bench`: runs every command of docs/results.md in page order (bench/results_commands.py
# run) and writes each one's output to bench/out/<label>.log beside the CSV files the page's
# rows name; charts go to docs/images/. Commands that need LAMMPS (`lmp`) or matplotlib are
# skipped with a message where those are missing. Benchmarks are not tests; the page's commands
# are checked in a small mode by ctest (`results_commands`). The full run takes hours on 2 cores.
set -euo pipefail
build=${1:-build/default}
cd "$(dirname "$0")/.."
mkdir -p bench/out
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)" \
    | tee bench/out/machine.txt
exec /usr/bin/python3 bench/results_commands.py run --build "$build"
