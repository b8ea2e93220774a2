"""The per-entry keys of [[particles]] end to end (tests/apps/scenes/entry_keys.toml), through
--dump on 1 and on 2 ranks.

usage: entry_keys.py --mpiexec M --app APP --scene SCENE --out DIR

Checks (exit 1 with the reason on the first failure):
 1. the initial state (--steps 0) is the same bytes on 1 and 2 ranks (radii drawn per uid);
 2. lattice (radius = [0.3, 0.45]): every radius in [0.3, 0.45), not all equal, mass
    4/3 pi r^3; every grain's angular velocity [0, 0, 2];
 3. list (radius = { uniform = [0.2, 0.4], seed = 3 }): radii in [0.2, 0.4), angular velocity
    [1, 0, 0];
 4. agglomerate (velocity [0.1, 0, 0], angular_velocity [0, 0, 1] about its center
    [8, 8, 8]): every grain's velocity is v + w x (x - center), its angular velocity w;
 5. after 1000 steps (0.2 time units) on 2 ranks the fixed grain is where it was, at rest,
    and the grain that ran into it at speed 1 came back (v_x < 0).
"""
import argparse
import csv
import math
import os
import subprocess
import sys


def fail(message):
    sys.exit(f"entry_keys: {message}")


def run(args, np, name, extra):
    dump = os.path.join(args.out, f"entry_keys.{name}.csv")
    command = [args.mpiexec, "-n", str(np), "--oversubscribe", args.app, args.scene, "--quiet",
               "--output", os.path.join(args.out, "entry_keys"), "--dump", dump, *extra]
    done = subprocess.run(command, capture_output=True, text=True, timeout=60, check=False)
    if done.returncode != 0:
        fail(f"{' '.join(command)} exited with {done.returncode}\n{done.stderr}")
    with open(dump, encoding="utf-8") as f:
        text = f.read()
    rows = list(csv.DictReader(text.splitlines()))
    return text, [{k: float(v) for k, v in row.items()} for row in rows]


def vec(row, *keys):
    return [row[k] for k in keys]


def close(a, b, tol=1e-12):
    return all(abs(x - y) <= tol * max(1.0, abs(y)) for x, y in zip(a, b))


def main():
    parser = argparse.ArgumentParser()
    for option in ("--mpiexec", "--app", "--scene", "--out"):
        parser.add_argument(option, required=True)
    args = parser.parse_args()
    text1, start = run(args, 1, "start.np1", ["--steps", "0"])
    text2, _ = run(args, 2, "start.np2", ["--steps", "0"])
    if text1 != text2:
        fail("the initial state differs between 1 and 2 ranks")

    lattice = [g for g in start if g["x"] < 4.5]
    listed = [g for g in start if abs(g["x"] - 6.0) < 1e-9]
    agglomerate = [g for g in start if math.dist(vec(g, "x", "y", "z"), [8, 8, 8]) < 2.0]
    radii = [g["radius"] for g in lattice]
    if len(lattice) != 64 or not all(0.3 <= r < 0.45 for r in radii) or len(set(radii)) < 32:
        fail(f"lattice radii: {len(lattice)} grains, {sorted(radii)[:3]}...{sorted(radii)[-3:]}")
    for g in lattice:
        if not close([g["mass"]], [4.0 / 3.0 * math.pi * g["radius"] ** 3]) or \
                vec(g, "wx", "wy", "wz") != [0.0, 0.0, 2.0]:
            fail(f"lattice grain {g}: mass or angular velocity wrong")
    if len(listed) != 3 or not all(0.2 <= g["radius"] < 0.4 for g in listed) or \
            any(vec(g, "wx", "wy", "wz") != [1.0, 0.0, 0.0] for g in listed):
        fail(f"list grains: {listed}")
    if len(agglomerate) != 50:
        fail(f"{len(agglomerate)} agglomerate grains, expected 50")
    for g in agglomerate:
        dx, dy = g["x"] - 8.0, g["y"] - 8.0
        expected = [0.1 - dy, dx, 0.0]  # v + (0, 0, 1) x (x - c)
        if not close(vec(g, "vx", "vy", "vz"), expected) or \
                vec(g, "wx", "wy", "wz") != [0.0, 0.0, 1.0]:
            fail(f"agglomerate grain {g}: expected velocity {expected} and spin [0, 0, 1]")

    fixed = next(g for g in start if g["x"] == 10.0)
    mover = next(g for g in start if g["x"] == 8.9)
    _, end = run(args, 2, "end.np2", [])
    after = {g["uid"]: g for g in end}
    f, m = after[fixed["uid"]], after[mover["uid"]]
    if vec(f, "x", "y", "z", "vx", "vy", "vz") != [10.0, 2.0, 2.0, 0.0, 0.0, 0.0]:
        fail(f"the fixed grain moved: {f}")
    if not m["vx"] < -0.5:
        fail(f"the grain that hit the fixed one did not come back: {m}")


if __name__ == "__main__":
    main()
