"""Two materials in one scene reproduce each pair's restitution and friction, on 1 and 2 ranks
(tests/apps/scenes/two_materials.toml: three oblique collisions of equal spheres, types 0-0,
0-1 and 1-1, e = 0.9 and 0.5, mu = 0.2 and 0.6, and a grain of type 0 falling onto a floor of
type 2, e = 0.3, mu = 0.4; unlike pairs mix by the geometric mean).

usage: material_pairs.py --mpiexec M --app APP --scene SCENE --out DIR --np N

For each pair, from the final velocities (--dump): the normal restitution is the ratio of the
normal velocities after and before, -v_x' / v_x (the spring-dashpot's e for the free
collision); the friction coefficient is the ratio of the tangential to the normal velocity
change of either grain, |dv_y| / |dv_x| (the Coulomb limit: the spins make the surfaces slide
throughout, and the grains start without a velocity along y), which is mu times the ratio of
the repulsive part of the normal impulse to the whole, as the unclamped spring-dashpot turns
slightly attractive before the grains part and the friction limit is mu max(F_n, 0)
(particles/kernels/SpringDashpot.hpp); that ratio follows from the damped oscillator
delta(t) = e^(-gamma t) sin(omega t) of the pair's e. Both must match the pair's mixed values
(1 % each: the contact ends within a step, 1/200 of its duration). Exit 1 with the reason if not.
"""
import argparse
import csv
import math
import os
import subprocess
import sys

# (uid a, uid b, restitution, friction) of the three pairs.
PAIRS = [(0, 1, 0.9, 0.2), (2, 3, math.sqrt(0.9 * 0.5), math.sqrt(0.2 * 0.6)), (4, 5, 0.5, 0.6)]
APPROACH = 0.5  # each grain's initial |v_x|, and the falling grain's |v_z|
FLOOR = (6, math.sqrt(0.9 * 0.3), math.sqrt(0.2 * 0.4))  # (uid, restitution, friction)


def repulsive_share(e):
    """The repulsive part of the normal impulse over the whole, for the free collision of the
    linear spring-dashpot with restitution e: F ~ -delta'' over one half period."""
    zeta = -math.log(e) / math.sqrt(math.pi ** 2 + math.log(e) ** 2)  # gamma / omega_0
    gamma, omega = zeta, math.sqrt(1.0 - zeta * zeta)
    steps = 100000
    positive = total = 0.0
    for k in range(steps):
        t = (k + 0.5) * math.pi / omega / steps
        # -delta'' of delta = e^(-gamma t) sin(omega t)
        force = math.exp(-gamma * t) * ((omega * omega - gamma * gamma) * math.sin(omega * t)
                                        + 2.0 * gamma * omega * math.cos(omega * t))
        positive += max(force, 0.0)
        total += force
    return positive / total


def main():
    parser = argparse.ArgumentParser()
    for option in ("--mpiexec", "--app", "--scene", "--out", "--np"):
        parser.add_argument(option, required=True)
    args = parser.parse_args()
    dump = os.path.join(args.out, f"two_materials.np{args.np}.csv")
    command = [args.mpiexec, "-n", args.np, "--oversubscribe", args.app, args.scene, "--quiet",
               "--output", os.path.join(args.out, f"two_materials.np{args.np}"), "--dump", dump]
    done = subprocess.run(command, capture_output=True, text=True, timeout=60, check=False)
    if done.returncode != 0:
        sys.exit(f"{' '.join(command)} exited with {done.returncode}\n{done.stderr}")
    with open(dump, encoding="utf-8") as f:
        grains = {int(row["uid"]): row for row in csv.DictReader(f)}
    for a, b, e, mu_pair in PAIRS:
        for uid in (a, b):
            vx, vy = float(grains[uid]["vx"]), float(grains[uid]["vy"])
            sign = 1.0 if uid == a else -1.0  # a came from the left moving +x, +y
            restitution = -sign * vx / APPROACH
            friction = abs(vy) / abs(vx - sign * APPROACH)
            mu = mu_pair * repulsive_share(e)
            if abs(restitution - e) > 0.01 * e or abs(friction - mu) > 0.01 * mu:
                sys.exit(f"grain {uid} (pair {a}-{b}): restitution {restitution:.5f}, friction "
                         f"{friction:.5f}; expected {e:.5f} and {mu:.5f}")
            print(f"grain {uid}: e = {restitution:.5f} (expected {e:.5f}), "
                  f"mu = {friction:.5f} (expected {mu:.5f})")
    uid, e, mu_pair = FLOOR  # the wall is at rest: the grain's own velocities
    vy, vz = float(grains[uid]["vy"]), float(grains[uid]["vz"])
    restitution, friction = vz / APPROACH, abs(vy) / abs(vz + APPROACH)
    mu = mu_pair * repulsive_share(e)
    if abs(restitution - e) > 0.01 * e or abs(friction - mu) > 0.01 * mu:
        sys.exit(f"grain {uid} on the floor: restitution {restitution:.5f}, friction "
                 f"{friction:.5f}; expected {e:.5f} and {mu:.5f}")
    print(f"grain {uid} on the floor: e = {restitution:.5f} (expected {e:.5f}), "
          f"mu = {friction:.5f} (expected {mu:.5f})")


if __name__ == "__main__":
    main()
