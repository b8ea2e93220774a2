"""The energy balance of moving walls: runs tests/apps/scenes/moving_floor.toml (lossless
contacts, a rising and shaking floor inside a fixed drum, gravity) for 0 and --steps steps and
checks that the grains' energy change equals the work the walls did (the run summary's
walls[k].work):

    (KE + PE_gravity + elastic)(end) - (KE + PE_gravity + elastic)(start) = sum_k work_k

within --tol of the work, the elastic energy 1/2 k delta^2 of every overlap (grain pairs and
grain-wall) computed here from --dump and the walls' motion. The work must be a sizeable part
of the energy (the floor lifts the grains), and the fixed drum must do none.

usage: wall_work_check.py --mpiexec M --app APP --scene moving_floor.toml --out DIR --np N
                          [--steps 2000] [--tol 0.01]
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

# The scene's contact stiffness, time step and walls (moving_floor.toml).
STIFFNESS = 1e4
DT = 0.0005
FLOOR = {"z": 0.5, "v": 0.5, "amplitude": 0.05, "frequency": 3.0}
DRUM = {"centre": (3.0, 3.0), "radius": 2.9}


def run(a, stem, steps):
    command = [a.mpiexec, "-n", str(a.np), "--oversubscribe", a.app, a.scene, "--quiet",
               "--steps", str(steps), "--json", stem + ".json", "--dump", stem + ".csv"]
    done = subprocess.run(command, capture_output=True, text=True, timeout=600, check=False)
    if done.returncode != 0:
        sys.exit(f"wall_work_check: {' '.join(command)} exited with {done.returncode}\n"
                 f"{done.stdout}\n{done.stderr}")
    with open(stem + ".json", encoding="utf-8") as f:
        summary = json.load(f)
    with open(stem + ".csv", encoding="utf-8") as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    return summary, rows


def elastic(rows, time):
    """1/2 k delta^2 over every overlap at `time`."""
    e = 0.0
    for i, p in enumerate(rows):
        for q in rows[i + 1:]:
            d = math.dist((p["x"], p["y"], p["z"]), (q["x"], q["y"], q["z"]))
            e += 0.5 * STIFFNESS * max(0.0, p["radius"] + q["radius"] - d) ** 2
    phase = 2 * math.pi * FLOOR["frequency"] * time
    floor = FLOOR["z"] + FLOOR["v"] * time + FLOOR["amplitude"] * math.sin(phase)
    for p in rows:
        e += 0.5 * STIFFNESS * max(0.0, p["radius"] - (p["z"] - floor)) ** 2
        rho = math.hypot(p["x"] - DRUM["centre"][0], p["y"] - DRUM["centre"][1])
        e += 0.5 * STIFFNESS * max(0.0, p["radius"] - (DRUM["radius"] - rho)) ** 2
    return e


def main():
    p = argparse.ArgumentParser()
    for k in ("--mpiexec", "--app", "--scene", "--out"):
        p.add_argument(k, required=True)
    p.add_argument("--np", type=int, default=1)
    p.add_argument("--steps", type=int, default=2000)
    p.add_argument("--tol", type=float, default=0.01)
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    stem = os.path.join(a.out, f"wall_work_np{a.np}")
    s0, rows0 = run(a, stem + "_start", 0)
    s1, rows1 = run(a, stem + "_end", a.steps)

    def energy(s, rows, time):
        c = s["conserved"]
        return c["kinetic_energy"] + c["potential_energy"] + elastic(rows, time)

    e0 = energy(s0, rows0, 0.0)
    e1 = energy(s1, rows1, a.steps * DT)
    work = [w["work"] for w in s1["walls"]]
    total = math.fsum(work)
    print(f"energy {e0:.9g} -> {e1:.9g} (change {e1 - e0:.9g}); walls' work {work}; "
          f"floor force {s1['walls'][0]['force']}")
    if len(work) != 2 or len(rows1) != len(rows0) or s1["left_domain"] != 0:
        sys.exit("expected two walls and no grain lost")
    if not abs(total) > 0.1 * abs(e0):
        sys.exit(f"the walls did too little work ({total}) to test the balance")
    if abs(work[1]) > 1e-9 * abs(total):
        sys.exit(f"the fixed drum did work {work[1]}")
    error = abs((e1 - e0) - total) / abs(total)
    print(f"balance error {error:.3g} of the work (tolerance {a.tol})")
    if not error <= a.tol:
        sys.exit("the energy change does not follow the walls' work")


if __name__ == "__main__":
    main()
