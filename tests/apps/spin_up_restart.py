#!/usr/bin/python3
"""spin_up's record and state continue bit for bit across a restart on another rank count:
a fly-by of 80 grains (reproducible mode, direct gravity) runs 600 steps on 2 ranks with a
checkpoint at step 300, then again from that checkpoint on 1 rank; the record (pile.file,
rows after the checkpoint written again) and the summary's checksum must be identical. Before
the record is copied, the restart is refused with a message naming where it probably is.

usage: spin_up_restart.py --mpiexec MPIEXEC --app SPIN_UP --scene FLYBY_TOML --out DIR
"""
import argparse
import filecmp
import json
import os
import shutil
import subprocess
import sys


def run(args, np, out, extra, refused=None):
    cmd = [args.mpiexec, "--oversubscribe", "-n", str(np), args.app, args.scene, "--quiet",
           "--output", out, "--set", "time.steps=600", "--set", "pile.settle_steps=100",
           "--set", "pile.record_every=50", "--set", "output.checkpoint_every=300",
           "--set", "sync.reproducible=true", "--set", "gravity.self=direct",
           "--set", "particles.0.count=80", "--set", "flyby.periapsis=0.5"] + extra
    result = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if refused is not None:
        if result.returncode == 0 or refused not in result.stderr:
            sys.exit(f"{' '.join(cmd)} was not refused with '{refused}':\n"
                     f"{result.stdout}{result.stderr}")
    elif result.returncode != 0:
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
    checkpoint = os.path.join(whole, "checkpoint_00000300.h5")
    run(args, 1, resumed, ["--restart", checkpoint],
        refused=f'pile.file = "{os.path.join(resumed, "flyby.csv")}": no such file; a restart '
                f"continues the record of the run being restarted: copy it there (probably "
                f"{os.path.join(whole, 'flyby.csv')}, beside the checkpoint)")
    shutil.copy(os.path.join(whole, "flyby.csv"), resumed)  # the record as the run left it
    run(args, 1, resumed, ["--restart", checkpoint])
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
