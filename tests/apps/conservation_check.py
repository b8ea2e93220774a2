"""Conservation over the small two-agglomerates instance (validation): runs
scenes/two-agglomerates.toml (3,866 grains, elastic contacts, dt = 0.01 s) for --steps steps
with one gravity method and compares the final state with the initial one, both read from
--dump (exact sums with math.fsum):

- total momentum P: Newton's third law holds pair by pair for contacts (one evaluation, equal
  and opposite) and for the direct sum and the mutual tree, so |P(t) - P(0)| stays at round-off
  relative to sum m|v|; Barnes-Hut and the mesh do not pair their forces, so they drift;
- centre of mass: moves with P(0) / M, so its error is |C(t) - C(0) - P(0) t / M| (the paper
  reports 0.1 m for its large instance; we ask at most --com-tol, 1e-3 m by default).

--expect exact asserts both at round-off (direct, mutual-tree); --expect drift asserts only the
centre-of-mass bound and prints the momentum drift (tree, pm). Grains that leave the domain
would change M: none may.

usage: conservation_check.py --mpiexec M --app APP --scene two-agglomerates.toml --out DIR
                             --np N --method direct|mutual-tree|tree|pm [--steps 1000]
                             [--expect exact|drift] [--set KEY=VALUE ...]
"""
import argparse
import csv
import math
import os
import subprocess
import sys


def run(a, stem, steps):
    command = [a.mpiexec, "-n", str(a.np), "--oversubscribe", a.app, a.scene, "--quiet",
               "--set", f"gravity.self={a.method}", "--steps", str(steps),
               "--dump", stem + ".csv"]
    for s in a.set:
        command += ["--set", s]
    done = subprocess.run(command, capture_output=True, text=True, timeout=600, check=False)
    if done.returncode != 0:
        sys.exit(f"conservation_check: {' '.join(command)} exited with {done.returncode}\n"
                 f"{done.stdout}\n{done.stderr}")
    with open(stem + ".csv", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def totals(rows):
    m = [float(r["mass"]) for r in rows]
    mass = math.fsum(m)
    p = [math.fsum(mi * float(r[v]) for mi, r in zip(m, rows)) for v in ("vx", "vy", "vz")]
    c = [math.fsum(mi * float(r[x]) for mi, r in zip(m, rows)) / mass for x in ("x", "y", "z")]
    scale = math.fsum(mi * math.sqrt(sum(float(r[v]) ** 2 for v in ("vx", "vy", "vz")))
                      for mi, r in zip(m, rows))
    return mass, p, c, scale


def main():
    p = argparse.ArgumentParser()
    for k in ("--mpiexec", "--app", "--scene", "--out"):
        p.add_argument(k, required=True)
    p.add_argument("--np", type=int, default=1)
    p.add_argument("--method", default="direct")
    p.add_argument("--steps", type=int, default=1000)
    p.add_argument("--dt", type=float, default=0.01, help="the scene's time.dt [s]")
    p.add_argument("--expect", choices=("exact", "drift"), default="exact")
    p.add_argument("--momentum-tol", type=float, default=1e-12,
                   help="|dP| / sum m|v| allowed with --expect exact")
    p.add_argument("--com-tol", type=float, default=1e-3, help="centre-of-mass error [m]")
    p.add_argument("--set", action="append", default=[])
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    stem = os.path.join(a.out, f"conservation_{a.method}_np{a.np}")
    start, end = run(a, stem + "_start", 0), run(a, stem + "_end", a.steps)
    if len(start) != len(end):
        sys.exit(f"conservation_check: {len(start)} grains at the start, {len(end)} at the end "
                 "(grains left the domain)")
    mass, p0, c0, scale = totals(start)
    mass1, p1, c1, _ = totals(end)
    t = a.steps * a.dt
    dp = math.sqrt(sum((x - y) ** 2 for x, y in zip(p1, p0))) / scale
    com = math.sqrt(sum((c1[k] - c0[k] - p0[k] / mass * t) ** 2 for k in range(3)))
    print(f"conservation {a.method} np{a.np}: {len(end)} grains, {a.steps} steps (t = {t:g} s): "
          f"|dP| / sum m|v| = {dp:.3e}, centre-of-mass error = {com:.3e} m")
    if mass1 != mass:
        sys.exit(f"conservation_check: total mass changed from {mass!r} to {mass1!r}")
    if not com <= a.com_tol:
        sys.exit(f"conservation_check: centre-of-mass error {com:.3e} m above {a.com_tol:g} m")
    if a.expect == "exact" and not dp <= a.momentum_tol:
        sys.exit(f"conservation_check: momentum drift {dp:.3e} above {a.momentum_tol:g}")


if __name__ == "__main__":
    main()
