#!/usr/bin/python3
"""The points per time step where the ranks wait for each other: calls of MPI_Allreduce and of
the neighbour exchanges inside DemStep::step, counted by valgrind's callgrind on every rank
(machine-independent: what a step's synchronisation costs on a busy machine is mostly these
waits), and the instructions the step executes outside the MPI libraries (theirs are mostly
the polling of a rank that waits, which varies from run to run). The first paper's scenes A
and B weak-scaled on --ranks ranks, as bench/peers/blocks_per_rank.py runs them, with Hertz
contacts (the spring-dashpot's batch kernel uses AVX-512, which valgrind cannot run; the
step's collectives are the same), the default mode, --steps steps; 0 blocks per rank leaves
domain.blocks to the run.

writing bench/out/framework/collectives_per_step.csv (scene, blocks per rank, rank, steps,
all-reduces, neighbour exchanges, sparse exchanges, instructions outside MPI, checksum).

usage: collectives_per_step.py [--bin build/default/bin/regolith] [--out bench/out/framework]
                               [--scenes a b] [--blocks 1 32] [--ranks 2] [--steps 200]
                               [--small]
"""
import argparse
import collections
import csv
import glob
import json
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "peers"))
from blocks_per_rank import ENV, MPIEXEC, SCENES, SMALL, blocks_arg, scene_args  # noqa: E402

HERTZ = 'model = "hertz"\nyoungs_modulus = 60.1936\npoisson_ratio = 0.3'
COUNTED = {"PMPI_Allreduce": "allreduce", "regolith::core::NeighbourExchange::start()":
           "neighbour_exchanges", "regolith::core::SparseExchange::start()": "sparse_exchanges"}


def calls(profile):
    """Calls of the COUNTED functions in one callgrind profile."""
    names, counts, callee = {}, collections.Counter(), None
    with open(profile, encoding="utf-8", errors="replace") as f:
        for line in f:
            m = re.match(r"(c?fn)=\((\d+)\)(?: (.*))?", line)
            if m:
                if m.group(3):
                    names[m.group(2)] = m.group(3).strip()
                callee = names.get(m.group(2)) if m.group(1) == "cfn" else None
            elif line.startswith("calls=") and callee in COUNTED:
                counts[COUNTED[callee]] += int(line.split()[0][len("calls="):])
                callee = None
    return counts


MPI_OBJECTS = re.compile(r"openmpi|libopen-pal|libopen-rte|libmpi|mca_|libevent|libhwloc")


def instructions_outside_mpi(profile):
    """The self instructions of every function in one callgrind profile whose object is not an
    MPI library (callgrind_annotate's per-function list)."""
    listing = subprocess.run(["callgrind_annotate", "--auto=no", "--threshold=100", profile],
                             capture_output=True, text=True, check=True).stdout
    total, listed = 0, False
    for line in listing.splitlines():
        if "file:function" in line:
            listed = True
            continue
        m = re.match(r"\s*([\d,]+) \(", line)
        if listed and m and not MPI_OBJECTS.search(line):
            total += int(m.group(1).replace(",", ""))
    return total


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--bin", default="build/default/bin/regolith")
    p.add_argument("--out", default="bench/out/framework")
    p.add_argument("--scenes", nargs="*", default=["a", "b"])
    p.add_argument("--blocks", nargs="*", type=int, default=[1, 32])
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--steps", type=int, default=200)
    p.add_argument("--small", action="store_true",
                   help="every scene in a box of a few hundred grains (a check, not a figure)")
    args = p.parse_args()
    if args.small:
        for scene, small in SMALL.items():
            SCENES[scene].update(small)
    os.makedirs(args.out, exist_ok=True)
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for scene in args.scenes:
            source = os.path.join(os.path.dirname(HERE), "peers", "scenes", SCENES[scene]["file"])
            text, n = re.subn(r"^stiffness = .*$", HERTZ, open(source, encoding="utf-8").read(),
                              flags=re.M)
            if n != 1:
                sys.exit(f"{source}: no [contact] stiffness line to replace")
            path = os.path.join(work, f"scene-{scene}-hertz.toml")
            open(path, "w", encoding="utf-8").write(text)
            for blocks in args.blocks:
                for old in glob.glob(os.path.join(work, "cg.*")):
                    os.remove(old)
                summary = os.path.join(work, "run.json")
                cmd = [*MPIEXEC, "-n", str(args.ranks), "valgrind", "--tool=callgrind",
                       f"--callgrind-out-file={work}/cg.%p",
                       "--toggle-collect=regolith::particles::DemStep::step*",
                       os.path.abspath(args.bin), path,
                       *scene_args(scene, args.ranks, args.steps),
                       *(["--set", blocks_arg(blocks, args.ranks)] if blocks else []),
                       "--quiet", "--json", summary]
                run = subprocess.run(cmd, capture_output=True, text=True, env=ENV, check=False)
                if run.returncode != 0:
                    sys.exit(f"{' '.join(cmd)} failed:\n{run.stderr[-2000:]}")
                checksum = json.load(open(summary, encoding="utf-8"))["checksum"]
                for rank, profile in enumerate(sorted(glob.glob(os.path.join(work, "cg.*")))):
                    c = calls(profile)
                    own = instructions_outside_mpi(profile)
                    rows.append({"scene": scene, "blocks_per_rank": blocks, "rank": rank,
                                 "steps": args.steps, **{k: c[k] for k in COUNTED.values()},
                                 "instructions_outside_mpi": own, "checksum": checksum})
                    print(f"scene {scene.upper()}, {blocks} blocks per rank, rank {rank}: "
                          f"{c['allreduce'] / args.steps:.3f} all-reduces, "
                          f"{c['neighbour_exchanges'] / args.steps:.3f} neighbour and "
                          f"{c['sparse_exchanges'] / args.steps:.3f} sparse exchanges per step, "
                          f"{own / 1e6:.1f} M instructions outside MPI", flush=True)
    out = os.path.join(args.out, "collectives_per_step.csv")
    with open(out, "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
