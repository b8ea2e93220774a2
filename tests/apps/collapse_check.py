"""Cold collapse through the coupled time step (validation): runs
scenes/cold-collapse.toml (a uniform cloud, radius R = 1, mass M = 1, G = 1, at rest) to the
analytic half-radius time t_1/2 = sqrt(R^3 / (2 G M)) (pi/4 + 1/2) and checks that the grains
of the outer half (initial distance from the centre of mass above R/2, where the enclosed mass
is least noisy) are at half their initial distance: the median ratio r(t_1/2) / r(0) within
--tol (0.03) of 1/2. A wrong force law, sign, G or time step shows up here.

usage: collapse_check.py --mpiexec M --app APP --scene cold-collapse.toml --out DIR --np N
                         [--method direct|tree]
"""
import argparse
import csv
import math
import os
import statistics
import subprocess
import sys


def run(a, stem, steps):
    command = [a.mpiexec, "-n", str(a.np), "--oversubscribe", a.app, a.scene, "--quiet",
               "--set", f"gravity.self={a.method}", "--steps", str(steps),
               "--dump", stem + ".csv"]
    done = subprocess.run(command, capture_output=True, text=True, timeout=240, check=False)
    if done.returncode != 0:
        sys.exit(f"collapse_check: {' '.join(command)} exited with {done.returncode}\n"
                 f"{done.stdout}\n{done.stderr}")
    with open(stem + ".csv", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    return {int(r["uid"]): (float(r["x"]), float(r["y"]), float(r["z"]), float(r["mass"]))
            for r in rows}


def centred(grains):
    mass = sum(g[3] for g in grains.values())
    com = [sum(g[k] * g[3] for g in grains.values()) / mass for k in range(3)]
    return {u: math.dist(g[:3], com) for u, g in grains.items()}


def main():
    p = argparse.ArgumentParser()
    for k in ("--mpiexec", "--app", "--scene", "--out"):
        p.add_argument(k, required=True)
    p.add_argument("--np", type=int, default=1)
    p.add_argument("--method", default="direct")
    p.add_argument("--tol", type=float, default=0.03)
    a = p.parse_args()
    stem = os.path.join(a.out, f"collapse_{a.method}_np{a.np}")
    r0 = centred(run(a, stem + "_start", 0))
    r1 = centred(run(a, stem + "_half", 500))  # the scene's steps: t = t_1/2
    if r0.keys() != r1.keys():
        sys.exit("collapse_check: grains were lost or gained")
    outer = [r1[u] / r0[u] for u in r0 if r0[u] > 0.5]
    ratio = statistics.median(outer)
    print(f"cold collapse {a.method} np{a.np}: median r(t_1/2)/r(0) of {len(outer)} outer "
          f"grains = {ratio:.4f} (analytic 0.5)")
    if not abs(ratio - 0.5) < a.tol:
        sys.exit(f"collapse_check: median ratio {ratio:.4f}, expected 0.5 +- {a.tol}")


if __name__ == "__main__":
    main()
