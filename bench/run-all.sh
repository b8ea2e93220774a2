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
# rank and step from 1 to 64 ranks, oversubscribed (docs/results.md, issues 4 and 5).
/usr/bin/python3 bench/sync/sync_bench.py --build "$build" --out "$out" --repeats 5 \
    --comm-ranks 1 2 3 4 8 27 64 | tee "$out/sync_bench.txt"

# DEM suite (issue 5): PUpCS of NNS / SOS / hybrid on the three reference scenes (1 and 2
# ranks), PUpCS against the large radius (chart), memory per grain; and LAMMPS side by side.
# The method ratios need many pairs of runs on a shared VM (docs/results.md, "Methods at equal
# machine speed"); the radius chart in docs/results.md took five.
/usr/bin/python3 bench/dem/dem_bench.py methods --repeats 9 --build "$build" --out "$out" \
    | tee "$out/dem_bench.txt"
/usr/bin/python3 bench/dem/dem_bench.py radius memory skin --repeats 5 --build "$build" \
    --out "$out" | tee -a "$out/dem_bench.txt"
if command -v lmp >/dev/null; then
  /usr/bin/python3 bench/peers/lammps_compare.py --build "$build" --out "$out" --box 30 \
      --steps 300 --repeats 7 | tee "$out/lammps_compare.txt"
  # Blocks per rank as a user runs them (the first paper's scenes A, B, C with defaults only,
  # 1 to 512 blocks per rank, LAMMPS in the same invocation; docs/results.md, "Blocks per
  # rank"): the chart on one rank, the two-rank weak scaling with and without merging.
  /usr/bin/python3 bench/peers/blocks_per_rank.py --build "$build" --out "$out/blocks-ab" \
      --scenes a b --repeats 3 --subdomains merged blocks | tee "$out/blocks_per_rank_np1.txt"
  /usr/bin/python3 bench/peers/blocks_per_rank.py --build "$build" --out "$out/blocks-c" \
      --scenes c --repeats 3 | tee -a "$out/blocks_per_rank_np1.txt"
  /usr/bin/python3 bench/peers/blocks_per_rank.py --chart docs/images/dem-blocks-per-rank.png \
      --chart-from "$out/blocks-ab/blocks_per_rank_np1.csv" "$out/blocks-c/blocks_per_rank_np1.csv"
  /usr/bin/python3 bench/peers/blocks_per_rank.py --build "$build" --out "$out" --ranks 2 \
      --scenes a b --blocks 1 8 32 64 --repeats 5 --subdomains merged blocks \
      | tee "$out/blocks_per_rank_np2.txt"
else
  echo "lmp not found (apt-get install lammps): LAMMPS comparison skipped"
fi

# Self-gravity (issue 7): time and error vs the direct sum per instance, method and θ (one
# rank; ~10 min), the 2.1e6-grain Plummer sphere (tree), and the tree on 1 vs 2 ranks.
mpi=(env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpiexec --oversubscribe)
"${mpi[@]}" -n 1 "$build/bin/gravity_bench" --csv "$out/gravity_np1.csv" \
    | tee "$out/gravity_np1.txt"
"${mpi[@]}" -n 1 "$build/bin/gravity_bench" --instances plummer2.1e6 --methods tree \
    --thetas 0.5,0.7 --repeat 1 --samples 1000 --csv "$out/gravity_2e6.csv" \
    | tee "$out/gravity_2e6.txt"
for np in 1 2; do
    "${mpi[@]}" -n "$np" "$build/bin/gravity_bench" --instances agg38358,plummer1e6 \
        --methods tree --thetas 0.5,0.7 --samples 1000 --csv "$out/gravity_tree_np$np.csv" \
        | tee "$out/gravity_tree_np$np.txt"
done

# Grid gravity (issue 6): Poisson set-up / solve / iterations against unknowns for CG+GAMG and
# CG+hypre BoomerAMG, cold vs. warm start, on 1 and 2 ranks (CSV per rank count).
for np in 1 2; do
    OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpiexec --oversubscribe -n "$np" \
        "$build/bin/grid_bench" --max-cells 128 --csv "$out/grid_bench_np$np.csv" \
        | tee "$out/grid_bench_np$np.txt"
done

# Coupled runs (issue 8): the two-agglomerates instances on 1 and 2 ranks, time per step and
# phase against the paper's; centre-of-mass, momentum and energy error per gravity method.
/usr/bin/python3 bench/coupled/agglomerates_bench.py --build "$build" --out "$out" \
    | tee "$out/agglomerates_bench.txt"

# Grid gravity at matched accuracy (issue 6): PETSc (set-up reused; cold and warm start over a
# tolerance ladder) against the FFT, φ error against the analytic potential, CPU seconds; and
# the error of g against the direct sum with the time per evaluation for the mesh, P3M and the
# tree on the 38,358-grain agglomerate (the error-versus-time points; CSV
# method,param,median_err,p99_err,time_s,...).
OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpiexec --oversubscribe -n 1 \
    "$build/bin/grid_matched_bench" --min-cells 32 --max-cells 128 \
    --csv "$out/grid_matched_np1.csv" | tee "$out/grid_matched_np1.txt"
OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpiexec --oversubscribe -n 1 \
    "$build/bin/grid_agglomerate_bench" --cells 32,64,128 --cutoffs 2,4 \
    --csv "$out/grid_agglomerate_np1.csv" | tee "$out/grid_agglomerate_np1.txt"

# Checkpoint size and write / read time per grain for 103,823 grains on 1, 2, 4 ranks
# (docs/results.md, issue 9).
/usr/bin/python3 bench/io/checkpoint_bench.py --app "$build/bin/regolith" --np 1 2 4 \
    --repeats 3 --out "$out/ckpt-bench" | tee "$out/checkpoint_bench.txt"

# The grid fields the driver writes for ParaView, read back with VTK and drawn (docs/results.md,
# issue 9: docs/images/grid-fields.png).
/usr/bin/python3 bench/io/grid_fields_figure.py --app "$build/bin/regolith" --np 2 --steps 20 \
    --out "$out/grid-figure" | tee "$out/grid_fields_figure.txt"

# Charts (issue 9; docs/results.md, "Charts"): PNG + CSV in bench/out/, PNGs copied to
# docs/images/. Gravity error against time (Pareto) with the θ and grid-spacing stability maps,
# on agg11100 (~1.5 min) and the paper's 38,358-grain agglomerate; DEM energy error and PUpCS
# against dt and the dt-stiffness stability map; the NNS radius / block-edge map.
/usr/bin/python3 bench/gravity/gravity_pareto.py --build "$build" --out "$out" \
    --instance agg11100 | tee "$out/gravity_pareto_agg11100.txt"
/usr/bin/python3 bench/gravity/gravity_pareto.py --build "$build" --out "$out" \
    --instance agg38358 --spacings 4,2,1,0.5,0.35 | tee "$out/gravity_pareto_agg38358.txt"
/usr/bin/python3 bench/dem/dem_timestep.py --build "$build" --out "$out" \
    | tee "$out/dem_timestep.txt"
/usr/bin/python3 bench/sync/nns_radius_map.py --build "$build" --out "$out" \
    | tee "$out/nns_radius_map.txt"
