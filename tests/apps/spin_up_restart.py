#!/usr/bin/python3
"""spin_up's record and state continue bit for bit across a restart on another rank count:
a fly-by of 80 grains (reproducible mode, direct gravity) runs 600 steps on 2 ranks with a
checkpoint at step 300, then again from that checkpoint on 1 rank; the record (pile.file,
rows after the checkpoint written again) and the summary's checksum must be identical.

usage: spin_up_restart.py --mpiexec MPIEXEC --app SPIN_UP --scene FLYBY_TOML --out DIR
"""
import argparse
import filecmp
import json
import os
import shutil
import subprocess
import sys


def run(args, np, out, extra):
    cmd = [args.mpiexec, "--oversubscribe", "-n", str(np), args.app, args.scene, "--quiet",
           "--output", out, "--set", "time.steps=600", "--set", "pile.settle_steps=100",
           "--set", "pile.record_every=50", "--set", "output.checkpoint_every=300",
           "--set", "sync.reproducible=true", "--set", "gravity.self=direct",
           "--set", "particles.0.count=80", "--set", "flyby.periapsis=0.5"] + extra
    result = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if result.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed:\n{result.stdout}{result.stderr}")


def main():
    p = argparse.ArgumentParser()
    for key in ("--mpiexec", "--app", "--scene", "--out"):
        p.add_argument(key, required=True)
    args = p.parse_args()
    whole, resumed = os.path.join(args.out, "whole"), os.path.join(args.out, "resumed")
    for d in (whole, resumed):
        shutil.rmtree(d, ignore_errors=True)
    run(args, 2, whole, [])
    os.makedirs(resumed)
    shutil.copy(os.path.join(whole, "flyby.csv"), resumed)  # the record as the run left it
    run(args, 1, resumed, ["--restart", os.path.join(whole, "checkpoint_00000300.h5")])
    a, b = (os.path.join(d, "flyby.csv") for d in (whole, resumed))
    rows = sum(1 for _ in open(a, encoding="utf-8"))
    if rows != 2 + 500 // 50 + 1 or not filecmp.cmp(a, b, shallow=False):
        sys.exit(f"the records differ ({rows} lines in the whole run's): {a} {b}")
    sums = [json.load(open(os.path.join(d, "summary.json")))["checksum"] for d in (whole, resumed)]
    if sums[0] != sums[1]:
        sys.exit(f"checksums differ: {sums}")
    print(f"record and checksum {sums[0]} identical after the restart")


if __name__ == "__main__":
    main()
