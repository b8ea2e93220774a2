"""Particle snapshots (output.dump_every, output.dump_format) end to end on
tests/apps/scenes/restart.toml (1000 grains falling on a floor, reproducible mode), 2 ranks.

usage: snapshot_runs.py --mpiexec M --app APP --scene SCENE --out DIR

Checks (exit 1 with the reason on the first failure):
 1. csv, 20 steps, a snapshot every 10: output.dir/dumps holds particles_00000000.csv,
    particles_00000010.csv and particles_00000020.csv and nothing else, each a header and 1000
    grains; the last is the same bytes as the run's --dump;
 2. hdf5: particles_<step>.h5 at steps 0, 10, 20; restarted from the step-20 snapshot to the
    scene's 40 steps, the run ends with the checksum of the uninterrupted 40-step run (the
    snapshot holds the whole state, as a checkpoint does).
"""
import argparse
import json
import os
import shutil
import subprocess
import sys


def fail(message):
    sys.exit(f"snapshot_runs: {message}")


def run(args, extra):
    command = [args.mpiexec, "-n", "2", "--oversubscribe", args.app, args.scene, "--quiet", *extra]
    done = subprocess.run(command, capture_output=True, text=True, timeout=90, check=False)
    if done.returncode != 0:
        fail(f"{' '.join(command)} exited with {done.returncode}\n{done.stderr}")


def checksum(directory):
    with open(os.path.join(directory, "summary.json"), encoding="utf-8") as f:
        return json.load(f)["checksum"]


def main():
    parser = argparse.ArgumentParser()
    for option in ("--mpiexec", "--app", "--scene", "--out"):
        parser.add_argument(option, required=True)
    args = parser.parse_args()
    out = os.path.join(args.out, "snapshots")
    shutil.rmtree(out, ignore_errors=True)

    csv_dir = os.path.join(out, "csv")
    final = os.path.join(out, "final.csv")
    run(args, ["--output", csv_dir, "--steps", "20", "--set", "output.dump_every=10",
               "--dump", final])
    names = sorted(os.listdir(os.path.join(csv_dir, "dumps")))
    expected = [f"particles_{s:08d}.csv" for s in (0, 10, 20)]
    if names != expected:
        fail(f"{csv_dir}/dumps holds {names}, expected {expected}")
    for name in names:
        with open(os.path.join(csv_dir, "dumps", name), encoding="utf-8") as f:
            lines = f.read().splitlines()
        if len(lines) != 1001 or not lines[0].startswith("uid,x,y,z"):
            fail(f"{name}: {len(lines)} lines, header {lines[0]!r}")
    with open(os.path.join(csv_dir, "dumps", names[-1]), "rb") as a, open(final, "rb") as b:
        if a.read() != b.read():
            fail("the step-20 snapshot differs from the run's --dump")

    reference = os.path.join(out, "reference")
    run(args, ["--output", reference])
    h5_dir = os.path.join(out, "hdf5")
    run(args, ["--output", h5_dir, "--steps", "20", "--set", "output.dump_every=10",
               "--set", "output.dump_format=hdf5"])
    names = sorted(os.listdir(os.path.join(h5_dir, "dumps")))
    expected = [f"particles_{s:08d}.h5" for s in (0, 10, 20)]
    if names != expected:
        fail(f"{h5_dir}/dumps holds {names}, expected {expected}")
    restarted = os.path.join(out, "restarted")
    run(args, ["--output", restarted, "--restart", os.path.join(h5_dir, "dumps", names[-1])])
    if checksum(restarted) != checksum(reference):
        fail(f"restarted from {names[-1]}: checksum {checksum(restarted)}, the uninterrupted "
             f"run's {checksum(reference)}")


if __name__ == "__main__":
    main()
