"""The block outlines of a run that rebalances show the blocks changing owner (blocks.pvd).

usage: balance_vtk_check.py --mpiexec M --app APP --scene SCENE --out DIR

Runs SCENE for 300 steps on 2 ranks with a new cut whenever a better one exists
(balance.every = 10, threshold = 1; the blocks do not split, balance.split_levels = 0, so
the forest keeps its 128) and VTK output at steps 0 and 300, then reads the
piece headers of vtk/blocks_<step>_r<rank>.vtu: at both steps the two pieces hold every
block of the forest between them, and rank 0 holds another number of blocks at the end than
at the start. Exit 1 with the reason otherwise.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys


def fail(message):
    sys.exit(f"balance_vtk_check: {message}")


def cells(path):
    with open(path, "rb") as f:
        head = f.read(4096).decode("latin-1")
    match = re.search(r'NumberOfCells="(\d+)"', head)
    if not match:
        fail(f"{path}: no NumberOfCells in the piece header")
    return int(match.group(1))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--mpiexec", required=True)
    parser.add_argument("--app", required=True)
    parser.add_argument("--scene", required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    out = os.path.join(args.out, "balance_vtk")
    shutil.rmtree(out, ignore_errors=True)
    command = [args.mpiexec, "-n", "2", "--oversubscribe", args.app, args.scene, "--quiet",
               "--output", out, "--set", "time.steps=300", "--set", "balance.every=10",
               "--set", "balance.threshold=1", "--set", "balance.split_levels=0",
               "--set", "output.vtk_every=300"]
    done = subprocess.run(command, capture_output=True, text=True, timeout=60, check=False)
    if done.returncode != 0:
        fail(f"{' '.join(command)} exited with {done.returncode}\n{done.stderr}")
    counts = {}
    for step in (0, 300):
        pieces = [cells(os.path.join(out, "vtk", f"blocks_{step:08d}_r{r:04d}.vtu"))
                  for r in (0, 1)]
        if sum(pieces) != 128:
            fail(f"step {step}: the pieces hold {pieces} blocks, expected 128 in all")
        counts[step] = pieces
    if counts[0][0] == counts[300][0]:
        fail(f"rank 0 holds {counts[0][0]} blocks at steps 0 and 300: no block moved")
    print(f"balance_vtk_check: blocks per rank {counts[0]} at step 0, {counts[300]} at 300")


if __name__ == "__main__":
    main()
