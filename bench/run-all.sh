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

# Grid gravity (issue 6): Poisson set-up / solve / iterations against unknowns for CG+GAMG and
# CG+hypre BoomerAMG, cold vs. warm start, on 1 and 2 ranks (CSV per rank count).
for np in 1 2; do
    OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpiexec --oversubscribe -n "$np" \
        "$build/bin/grid_bench" --max-cells 128 --csv "$out/grid_bench_np$np.csv" \
        | tee "$out/grid_bench_np$np.txt"
done
