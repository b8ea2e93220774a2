"""The second paper's two-agglomerates instances through the coupled step under self-gravity
update policies: time per step and the force error the run measured itself
(gravity.check_every: checks against the direct sum on ~300 grains), side by side.

Policies (--policies, each run on every rank count of --ranks, alternating within a repeat):
  auto:<a>       gravity.self = "auto" for gravity.accuracy = a, update_threshold "auto" (the
                 adaptive interval, the field extrapolated between updates)
  every:<n>      the tree at --theta, the field extrapolated, updated every n steps
  threshold:<d>  the tree at --theta, the field kept until a grain moved d (m; "paper": twice
                 the instance's largest radius, the paper's rule)
  each-step      the tree at --theta, a new field every step
The paper's column: its Barnes-Hut run (one process, its machine, its threshold) per step.

usage: agglomerates_policies.py [--build build/default] [--out bench/out]
                                [--instances small medium large] [--steps 5000 2000 1000]
                                [--ranks 1 2] [--repeats 1] [--theta 0.5]
                                [--policies auto:1e-3 ...] [--csv agglomerates_policies.csv]
Writes <out>/<csv> (one row per run) and <out>/<csv stem>_points.csv (per instance and policy,
the medians in the columns gravity_pareto.py --extra reads: method,param,median_err,p99_err,
time_s with time_s the gravity seconds per step, amortised over the run, one rank; a run without
a check, i.e. without a second update, has no point).
"""
import argparse
import csv
import os
import statistics
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
sys.path.insert(0, HERE)
from agglomerates_bench import INSTANCES, ROOT, SCENE, write_csv  # noqa: E402
from run_summary import run_app  # noqa: E402


def instance_args(name):
    count, (rmin, rmax), radius, *_ = INSTANCES[name]
    args = [SCENE]
    for k in (0, 1):
        args += ["--set", f"particles[{k}].count={count}",
                 "--set", f"particles[{k}].grain_radius=[{rmin},{rmax}]",
                 "--set", f"particles[{k}].radius={radius}"]
    return args


def policy_args(policy, instance, theta):
    kind, _, value = policy.partition(":")
    tree = ["--set", "gravity.self=tree", "--set", f"gravity.theta={theta}"]
    if kind == "auto":
        return ["--set", "gravity.self=auto", "--set", f"gravity.accuracy={value}",
                "--set", "gravity.update_threshold=auto"]
    if kind == "every":
        return tree + ["--set", "gravity.update_threshold=0",
                       "--set", f"gravity.update_every={value}"]
    if kind == "threshold":
        distance = INSTANCES[instance][3] if value == "paper" else float(value)
        return tree + ["--set", f"gravity.update_threshold={distance}"]
    if kind == "each-step":
        return tree + ["--set", "gravity.update_threshold=0"]
    sys.exit(f"agglomerates_policies.py: unknown policy {policy!r}")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build", "default"))
    p.add_argument("--out", default=os.path.join(ROOT, "bench", "out"))
    p.add_argument("--instances", nargs="+", default=["small", "medium", "large"])
    p.add_argument("--steps", type=int, nargs="+", default=[5000, 2000, 1000],
                   help="steps per instance (in --instances order; the last repeats)")
    p.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    p.add_argument("--repeats", type=int, default=1)
    p.add_argument("--theta", type=float, default=0.5)
    p.add_argument("--policies", nargs="+", default=["auto:1e-3"])
    p.add_argument("--csv", default="agglomerates_policies.csv")
    a = p.parse_args()
    app = os.path.join(a.build, "bin", "regolith")
    rows = []
    for i, name in enumerate(a.instances):
        steps = a.steps[min(i, len(a.steps) - 1)]
        paper_ms = 1e3 * INSTANCES[name][4] / 100_000
        for repeat in range(a.repeats):
            for policy in a.policies:
                for np in a.ranks:
                    s = run_app(app, np, [*instance_args(name), *policy_args(policy, name, a.theta),
                                          "--steps", str(steps)])
                    g, t = s["gravity"], s["timing_s"]
                    # No check without a second update (the paper's threshold in a short run).
                    error = g.get("error", {}) if g.get("error", {}).get("checks", 0) else {}
                    ms = 1e3 * s["wall_s"] / steps
                    rows.append({"instance": name, "grains": s["particles"], "policy": policy,
                                 "ranks": np, "repeat": repeat, "steps": steps,
                                 "wall_s": s["wall_s"], "ms_per_step": ms,
                                 "gravity_ms_per_step": 1e3 * t["gravity"] / steps,
                                 "updates": g["updates"], "checks": error.get("checks", 0),
                                 "error_median": error.get("median", float("nan")),
                                 "error_p99": error.get("p99", float("nan")),
                                 "paper_ms_per_step": paper_ms, "paper_over_ours": paper_ms / ms})
                    r = rows[-1]
                    print(f"{name:6s} {policy:16s} np{np} #{repeat}: {ms:.3f} ms/step (gravity "
                          f"{r['gravity_ms_per_step']:.3f}), {r['updates']} updates in {steps} "
                          f"steps, measured error {r['error_median']:.2g} (p99 "
                          f"{r['error_p99']:.2g}); paper {paper_ms:.1f} ms/step: "
                          f"x{r['paper_over_ours']:.0f}", flush=True)
    os.makedirs(a.out, exist_ok=True)
    path = os.path.join(a.out, a.csv)
    write_csv(path, rows)
    points = []
    print(f"\nmedians over {a.repeats} repeat(s) (range) -> {path}")
    for name in a.instances:
        for policy in a.policies:
            for np in a.ranks:
                mine = [r for r in rows if (r["instance"], r["policy"], r["ranks"]) ==
                        (name, policy, np)]
                ms = [r["ms_per_step"] for r in mine]
                med = {k: statistics.median(r[k] for r in mine)
                       for k in ("gravity_ms_per_step", "updates", "error_median", "error_p99")}
                print(f"{name:6s} {policy:16s} np{np}: {statistics.median(ms):.3f} ms/step "
                      f"({min(ms):.3f}-{max(ms):.3f}), gravity {med['gravity_ms_per_step']:.3f}, "
                      f"{med['updates']:.0f} updates, measured error {med['error_median']:.2g} "
                      f"(p99 {med['error_p99']:.2g})")
                if np == min(a.ranks) and med["error_median"] == med["error_median"]:
                    kind, _, value = policy.partition(":")
                    points.append([f"run: {kind}", value or "-", med["error_median"],
                                   med["error_p99"], 1e-3 * med["gravity_ms_per_step"]])
    stem, ext = os.path.splitext(path)
    with open(f"{stem}_points{ext}", "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(["method", "param", "median_err", "p99_err", "time_s"])
        w.writerows(points)


if __name__ == "__main__":
    main()
