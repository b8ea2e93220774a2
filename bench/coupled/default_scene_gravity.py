"""Self-gravity in the coupled step on the default scene (two piles of 1,200 grains merging,
`make run`): time and measured force error of the update policies, side by side.

Configurations, each run on every rank count of --ranks, alternating within each repeat (the
machine is shared: the figures are medians over --repeats, with their range):
  every-step   gravity.update_threshold = accuracy x r_min (the "auto" threshold before the
               update interval: the piles' motion as a whole passes it at nearly every step)
  adaptive     the scene as it is: update_threshold = "auto" (update_every = "adaptive")
  stale-<d>    update_threshold = d, the field kept between updates (error-vs-time points)
  every-<n>    update_every = n, the field extrapolated between updates
  baseline     --baseline-app, another build's regolith on the unchanged scene (optional)

usage: default_scene_gravity.py [--build build/default] [--out bench/out] [--ranks 1 2]
                                [--repeats 3] [--steps 4000] [--stale 0.002 0.004 0.008]
                                [--every 10 20 40] [--baseline-app PATH] [--only NAME ...]
                                [--vtk] [--csv default_scene_gravity.csv]
--vtk keeps the scene's VTK output (every 100 steps, as `make run` writes it); without it the
runs write none. Each row has the time steps' wall time (the run summary's wall_s) and the
whole process's (start-up and output included, process_s).
Writes <out>/default_scene_gravity.csv (one row per run) and prints the medians.
"""
import argparse
import csv
import os
import statistics
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from run_summary import run_app  # noqa: E402

# The previous "auto" threshold: gravity.accuracy 3e-3 x the smallest grain radius 0.0500044.
EVERY_STEP_THRESHOLD = "0.0001500133025408786"


def configurations(args, app):
    out = [("every-step", app, ["--set", f"gravity.update_threshold={EVERY_STEP_THRESHOLD}"]),
           ("adaptive", app, [])]
    out += [(f"stale-{d}", app, ["--set", f"gravity.update_threshold={d}"]) for d in args.stale]
    out += [(f"every-{n}", app, ["--set", "gravity.update_threshold=0",
                                 "--set", f"gravity.update_every={n}"]) for n in args.every]
    if args.baseline_app:
        out.append(("baseline", args.baseline_app, []))
    return [c for c in out if not args.only or c[0] in args.only]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--build", default="build/default")
    p.add_argument("--out", default="bench/out")
    p.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--steps", type=int, default=4000)
    p.add_argument("--stale", nargs="*", default=["0.002", "0.004", "0.008"])
    p.add_argument("--every", nargs="*", default=["10", "20", "40"])
    p.add_argument("--baseline-app", default="")
    p.add_argument("--only", nargs="*", default=[], help="run only these configurations")
    p.add_argument("--vtk", action="store_true", help="keep the scene's VTK output")
    p.add_argument("--csv", default="default_scene_gravity.csv")
    args = p.parse_args()
    app = os.path.join(args.build, "bin", "regolith")
    common = ["--steps", str(args.steps)] + ([] if args.vtk else ["--set", "output.vtk_every=0"])
    rows = []
    for repeat in range(args.repeats):
        for np in args.ranks:
            for name, exe, extra in configurations(args, app):
                start = time.monotonic()
                s = run_app(exe, np, [*common, *extra, "--output", os.path.join(args.out, "scene")])
                process = time.monotonic() - start
                g = s["gravity"]
                error = g.get("error", {})
                rows.append({"config": name, "ranks": np, "repeat": repeat,
                             "wall_s": s["wall_s"], "process_s": process,
                             "gravity_s": s["timing_s"]["gravity"],
                             "gravity_share": s["timing_s"]["gravity"] / s["wall_s"],
                             "updates": g["updates"], "interval": g.get("interval", 0),
                             "list_rebuilds": s["neighbour_list"]["rebuilds"],
                             "error_median": error.get("median", float("nan")),
                             "error_p99": error.get("p99", float("nan"))})
                r = rows[-1]
                print(f"{name:11s} np{np} #{repeat}: {r['wall_s']:.2f} s, gravity "
                      f"{100 * r['gravity_share']:.0f} %, {r['updates']} updates, median error "
                      f"{r['error_median']:.2g} (p99 {r['error_p99']:.2g})", flush=True)
    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, args.csv)
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"\nmedians over {args.repeats} repeats (range) -> {path}")
    for name, _, _ in configurations(args, app):
        for np in args.ranks:
            mine = [r for r in rows if r["config"] == name and r["ranks"] == np]
            wall = [r["wall_s"] for r in mine]
            process = [r["process_s"] for r in mine]
            print(f"{name:11s} np{np}: wall {statistics.median(wall):.2f} s ({min(wall):.2f}-"
                  f"{max(wall):.2f}), process {statistics.median(process):.2f} s "
                  f"({min(process):.2f}-{max(process):.2f}), gravity "
                  f"{100 * statistics.median(r['gravity_share'] for r in mine):.0f} %, updates "
                  f"{statistics.median(r['updates'] for r in mine):.0f}, median error "
                  f"{statistics.median(r['error_median'] for r in mine):.2g}, p99 "
                  f"{statistics.median(r['error_p99'] for r in mine):.2g}")


if __name__ == "__main__":
    main()
