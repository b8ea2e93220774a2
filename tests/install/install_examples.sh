#!/usr/bin/env bash
# Installs the build into a fresh prefix, builds examples/ against it as a program of one's own
# would be (find_package(Regolith)), and runs the tutorials at small sizes on two ranks; the
# installed driver runs a few steps of the default scene with VTK output from the prefix.
# Usage: install_examples.sh <build dir> <source dir> <scratch dir>
set -euo pipefail
build=$1 source=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"
for f in lib/cmake/Regolith/RegolithConfig.cmake include/regolith/core/mpi/Comm.hpp \
         lib/libregolith_particles.a lib/libregolith_vtk.so bin/regolith \
         share/regolith/scenes/default.toml include/regolith/apps/regolith/SceneRun.hpp; do
    [[ -e "$work/prefix/$f" ]] || { echo "not installed: $f" >&2; exit 1; }
done
cmake -S "$source/examples" -B "$work/examples" -DCMAKE_PREFIX_PATH="$work/prefix" \
      -DCMAKE_BUILD_TYPE=Release >"$work/configure.log"
cmake --build "$work/examples" -j2 >"$work/build.log"
cd "$work"
mpiexec -n 2 "$work/examples/01-granular-gas" 200
mpiexec -n 2 "$work/examples/02-contact-law" 20000
mpiexec -n 2 "$work/examples/03-spin-up" 8 6000
[[ -s "$work/spin_up.csv" ]] || { echo "03-spin-up wrote no spin_up.csv" >&2; exit 1; }
mpiexec -n 2 "$work/examples/04-grid-field" 400
grep -q 'grid_00000400.vtm' "$work/tutorial04/grid.pvd" ||
    { echo "04-grid-field wrote no grid at step 400" >&2; exit 1; }
mpiexec -n 2 "$work/examples/05-scene-app" --steps 300 --output "$work/app05" --quiet
[[ -s "$work/app05/summary.json" ]] || { echo "05-scene-app wrote no summary.json" >&2; exit 1; }
mpiexec -n 2 "$work/prefix/bin/regolith" --steps 20 --output "$work/run" --quiet \
    --set output.vtk_every=10
[[ -s "$work/run/particles.pvd" ]] || { echo "the installed regolith wrote no particles.pvd" >&2; exit 1; }
