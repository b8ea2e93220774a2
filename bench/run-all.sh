#!/usr/bin/env bash
# Runs every benchmark and writes its raw output under bench/out/. The figures quoted in
# docs/results.md come from this script (`make bench`). Benchmarks are not tests.
set -euo pipefail
build=${1:-build/default}
out=bench/out
mkdir -p "$out"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"

# Detection + contact cost per particle-step (sparse gas vs. the same with a radius-30 sphere)
# and bytes per particle for 1,000,000 grains.
"$build/bin/particles_bench" --benchmark_out="$out/particles_bench.json" \
    --benchmark_out_format=json | tee "$out/particles_bench.txt"

# Shadow synchronisation: PUpCS of NNS / SOS / hybrid side by side on 2 ranks, and traffic per
# rank and step from 1 to 27 ranks (docs/results.md, issue 4).
/usr/bin/python3 bench/sync/sync_bench.py --build "$build" --out "$out" --repeats 5 \
    | tee "$out/sync_bench.txt"

# DEM suite (issue 5): PUpCS of NNS / SOS / hybrid on the three reference scenes (1 and 2
# ranks), PUpCS against the large radius (chart), memory per grain; and LAMMPS side by side.
/usr/bin/python3 bench/dem/dem_bench.py --build "$build" --out "$out" | tee "$out/dem_bench.txt"
if command -v lmp >/dev/null; then
  /usr/bin/python3 bench/peers/lammps_compare.py --build "$build" --out "$out" \
      | tee "$out/lammps_compare.txt"
else
  echo "lmp not found (apt-get install lammps): LAMMPS comparison skipped"
fi

# Checkpoint size and write / read time per grain for 103,823 grains on 1, 2, 4 ranks
# (docs/results.md, issue 9).
/usr/bin/python3 bench/io/checkpoint_bench.py --app "$build/bin/regolith" --np 1 2 4 \
    --repeats 3 --out "$out/ckpt-bench" | tee "$out/checkpoint_bench.txt"
