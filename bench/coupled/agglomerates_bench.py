"""The second paper's two-agglomerates scene through the coupled time step (figures).

1. Time per step and per phase for the three instances (small 3,866 / medium 11,100 / large
   38,358 grains) on 1 and 2 ranks with the paper's settings (Barnes-Hut, gravity updated after
   any grain moved twice the largest radius), the number of gravity updates, and the ratio of
   the paper's reported time (Nesmachnow et al., Tables 1-3: Barnes-Hut, one process, one
   gravity thread, 100,000 steps, on their machine) to ours extrapolated to 100,000 steps.
2. For each gravity method on the small instance (gravity every step, no friction, so the
   total energy is conserved up to the integrator): centre-of-mass error, momentum drift and
   energy error after --steps steps.

usage: agglomerates_bench.py [--build build/default] [--out bench/out] [--steps 1000]
                             [--instances small medium large] [--ranks 1 2]
                             [--skip-time] [--skip-conservation]
                             [--methods direct mutual-tree tree pm]
Writes <out>/agglomerates_time.csv and <out>/agglomerates_conservation.csv.
"""
import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from run_summary import run_app  # noqa: E402

# The repository (this file is bench/<part>/<script>.py): defaults that work from any directory.
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

SCENE = os.path.join(ROOT, "scenes", "two-agglomerates.toml")
# count per agglomerate, grain radii, agglomerate radius, update threshold (2 r_max), and the
# paper's Barnes-Hut run with 1 process and 1 gravity thread: total seconds for 100,000 steps,
# gravity updates, seconds per update (Tables 1-3).
INSTANCES = {
    "small": (1933, (50.0, 100.0), 1450.0, 200.0, 4.09e3, 1167, 2.60),
    "medium": (5550, (35.0, 70.0), 1500.0, 140.0, 2.80e4, 1828, 12.18),
    "large": (19179, (20.0, 60.0), 1730.0, 120.0, 8.58e4, 3813, 16.06),
}
PAPER_STEPS = 100_000


def instance_args(name):
    count, (rmin, rmax), radius, threshold, *_ = INSTANCES[name]
    args = [SCENE, "--set", f"gravity.update_threshold={threshold}"]
    for k in (0, 1):
        args += ["--set", f"particles[{k}].count={count}",
                 "--set", f"particles[{k}].grain_radius=[{rmin},{rmax}]",
                 "--set", f"particles[{k}].radius={radius}"]
    return args


def timing(app, out, steps, instances, ranks):
    rows = []
    for name in instances:
        for np in ranks:
            s = run_app(app, np, instance_args(name) + ["--steps", str(steps)])
            t = s["timing_s"]
            paper_total, paper_updates, paper_per_update = INSTANCES[name][4:]
            per_step = s["wall_s"] / steps
            updates = s["gravity"]["updates"]
            row = {
                "instance": name, "grains": s["particles"], "ranks": np, "steps": steps,
                "wall_s": s["wall_s"], "ms_per_step": 1e3 * per_step,
                **{f"{k}_ms_per_step": 1e3 * t[k] / steps for k in t},
                "gravity_updates": updates,
                "gravity_s_per_update": t.get("gravity", 0.0) / max(updates, 1),
                "extrapolated_100k_s": per_step * PAPER_STEPS,
                "paper_100k_s": paper_total, "paper_updates_100k": paper_updates,
                "paper_s_per_update": paper_per_update,
                "paper_over_ours": paper_total / (per_step * PAPER_STEPS),
            }
            rows.append(row)
            print(f"{name:6s} {s['particles']:6d} grains np{np}: {row['ms_per_step']:.2f} ms/step "
                  f"(sync {row.get('sync_ms_per_step', 0):.2f}, contact "
                  f"{row.get('contact_ms_per_step', 0):.2f}, gravity "
                  f"{row.get('gravity_ms_per_step', 0):.2f}, integrate "
                  f"{row.get('integrate_ms_per_step', 0):.2f}), {updates} gravity updates in "
                  f"{steps} steps; 100,000 steps ~ {row['extrapolated_100k_s']:.0f} s, paper "
                  f"{paper_total:.3g} s (their machine): x{row['paper_over_ours']:.0f}",
                  flush=True)
    write_csv(os.path.join(out, "agglomerates_time.csv"), rows)


def totals(s):
    c = s["conserved"]
    return c["momentum"], c["center_of_mass"], c["kinetic_energy"] + c["potential_energy"]


METHODS = ("direct", "mutual-tree", "tree", "pm")


def conservation(app, out, steps, ranks, methods=METHODS):
    rows = []
    common = ["--set", "gravity.update_threshold=0", "--set", "contact.friction=0",
              "--set", "domain.cells_per_block=[8,8,8]"]
    start = run_app(app, ranks, instance_args("small") + common +
                    ["--set", "gravity.self=direct", "--steps", "0"])
    p0, c0, e0 = totals(start)
    for method in methods:
        s = run_app(app, ranks, instance_args("small") + common +
                    ["--set", f"gravity.self={method}", "--steps", str(steps)])
        p1, c1, e1 = totals(s)
        # The centre of mass moves with the initial momentum P(0) / M.
        mass = start["conserved"]["mass"]
        t = steps * 0.01
        row = {"method": method, "ranks": ranks, "steps": steps, "wall_s": s["wall_s"],
               "momentum_drift": math.dist(p1, p0),
               "energy_error": abs(e1 - e0) / abs(e0),
               "com_error_m": math.sqrt(sum((c1[k] - c0[k] - p0[k] / mass * t) ** 2
                                            for k in range(3)))}
        rows.append(row)
        print(f"{method:11s} np{ranks}: {steps} steps in {s['wall_s']:.1f} s, |dP| = "
              f"{row['momentum_drift']:.3e} kg m/s, centre-of-mass error {row['com_error_m']:.3e} m, "
              f"|dE|/|E| = {row['energy_error']:.3e}",
              flush=True)
    write_csv(os.path.join(out, "agglomerates_conservation.csv"), rows)


def write_csv(path, rows):
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--build", default=os.path.join(ROOT, "build", "default"))
    p.add_argument("--out", default=os.path.join(ROOT, "bench", "out"))
    p.add_argument("--steps", type=int, default=1000)
    p.add_argument("--instances", nargs="+", default=list(INSTANCES))
    p.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    p.add_argument("--skip-time", action="store_true")
    p.add_argument("--skip-conservation", action="store_true")
    p.add_argument("--methods", nargs="+", choices=METHODS, default=list(METHODS),
                   help="gravity methods of the conservation part")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    app = os.path.join(a.build, "bin", "regolith")
    if not a.skip_time:
        timing(app, a.out, a.steps, a.instances, a.ranks)
    if not a.skip_conservation:
        conservation(app, a.out, a.steps, max(a.ranks), a.methods)


if __name__ == "__main__":
    main()
