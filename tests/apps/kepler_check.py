"""Kepler orbits through the whole coupled time step (validation): runs
scenes/kepler.toml (two grains of mass 1, G = 1, semi-major axis 1, period
T = 2 pi / sqrt(2)) for a whole number of periods with the given self-gravity method and
checks against the two-body solution:

  period  the final separation vector's angle from the initial one, over 2 pi x periods,
          is the relative period error; it must be below --period-tol (1e-4);
  energy  |E_end - E_0| / |E_0| below --energy-tol (1e-6), E = kinetic + potential from the
          run summary (potential = 1/2 sum m phi of the self-gravity), E_0 = -1/2 for both
          orbits (a = 1);
  momentum and centre of mass stay at zero (below 1e-12).

usage: kepler_check.py --mpiexec M --app APP --scene kepler.toml --out DIR --np N
                       [--eccentric] [--method direct|tree|mutual-tree] [--periods 10]
                       [--steps-per-period 2000] [--threshold T --max-updates N]

With --threshold (gravity.update_threshold) the field is recomputed only after a grain moved
that far; --max-updates bounds the count the summary reports (without it: one per step).
--expect-large turns the error checks round (a test of where a setting fails).
Exit code 1 with the reason on the first failed check.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

PERIOD = 2.0 * math.pi / math.sqrt(2.0)
ECCENTRIC = ["--set", "particles[0].position=[[-0.75,0,0],[0.75,0,0]]", "--set",
             "particles[0].velocity=[[0,-0.408248290463863,0],[0,0.408248290463863,0]]"]


def main():
    p = argparse.ArgumentParser()
    for k in ("--mpiexec", "--app", "--scene", "--out"):
        p.add_argument(k, required=True)
    p.add_argument("--np", type=int, default=1)
    p.add_argument("--eccentric", action="store_true")
    p.add_argument("--method", default="direct")
    p.add_argument("--periods", type=int, default=10)
    p.add_argument("--steps-per-period", type=int, default=2000)
    p.add_argument("--period-tol", type=float, default=1e-4)
    p.add_argument("--energy-tol", type=float, default=1e-6)
    p.add_argument("--threshold", type=float, default=0.0, help="gravity.update_threshold")
    p.add_argument("--expect-large", action="store_true",
                   help="where the method fails: both errors must EXCEED their tolerances")
    p.add_argument("--max-updates", type=int, default=None,
                   help="the field must have been computed at most this often")
    a = p.parse_args()
    stem = os.path.join(a.out, f"kepler_{a.method}_{'ecc' if a.eccentric else 'circ'}_np{a.np}")
    steps = a.periods * a.steps_per_period
    command = [a.mpiexec, "-n", str(a.np), "--oversubscribe", a.app, a.scene, "--quiet",
               "--set", f"gravity.self={a.method}", "--set",
               f"time.dt={PERIOD / a.steps_per_period!r}", "--steps", str(steps),
               "--set", f"gravity.update_threshold={a.threshold!r}",
               # the scene's contacts (k = 5000) would refuse this coarser dt (t_c / 10); the
               # grains never touch
               "--set", "contact.stiffness=1000",
               "--json", stem + ".json", "--dump", stem + ".csv"]
    if a.eccentric:
        command += ECCENTRIC
    done = subprocess.run(command, capture_output=True, text=True, timeout=240, check=False)
    if done.returncode != 0:
        sys.exit(f"kepler_check: {' '.join(command)} exited with {done.returncode}\n"
                 f"{done.stdout}\n{done.stderr}")
    with open(stem + ".json", encoding="utf-8") as f:
        summary = json.load(f)
    with open(stem + ".csv", encoding="utf-8") as f:
        grains = sorted(csv.DictReader(f), key=lambda r: int(r["uid"]))
    dx = float(grains[1]["x"]) - float(grains[0]["x"])
    dy = float(grains[1]["y"]) - float(grains[0]["y"])
    phase = math.atan2(dy, dx)  # starts at 0: grain 1 on +x
    period_error = abs(phase) / (2.0 * math.pi * a.periods)
    c = summary["conserved"]
    energy = c["kinetic_energy"] + c["potential_energy"]
    energy_error = abs(energy + 0.5) / 0.5
    print(f"kepler {a.method} {'e=0.5' if a.eccentric else 'circular'} np{a.np}: relative "
          f"period error {period_error:.3g}, energy error {energy_error:.3g}, "
          f"{summary['gravity']['updates']} gravity updates")
    if summary["gravity"]["method"] != a.method:
        sys.exit(f"kepler_check: ran gravity {summary['gravity']['method']}, not {a.method}")
    if a.expect_large:
        if not (period_error > a.period_tol and energy_error > a.energy_tol):
            sys.exit(f"kepler_check: errors {period_error:.3g} (period) and {energy_error:.3g} "
                     f"(energy) should both exceed {a.period_tol} and {a.energy_tol} here")
    else:
        if not period_error < a.period_tol:
            sys.exit(f"kepler_check: period error {period_error:.3g} >= {a.period_tol}")
        if not energy_error < a.energy_tol:
            sys.exit(f"kepler_check: energy error {energy_error:.3g} >= {a.energy_tol}")
    updates = summary["gravity"]["updates"]
    if a.max_updates is not None and not 0 < updates <= a.max_updates:
        sys.exit(f"kepler_check: {updates} gravity updates, expected 1 to {a.max_updates}")
    if a.max_updates is None and updates != steps + 1:
        sys.exit(f"kepler_check: {updates} gravity updates for {steps} steps, expected one per "
                 "step and one at the set-up")
    for key in ("momentum", "center_of_mass"):
        if max(abs(v) for v in c[key]) > 1e-12:
            sys.exit(f"kepler_check: {key} {c[key]} is not zero")


if __name__ == "__main__":
    main()
