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
                                [--progress-seconds 10] [--last-part 0.2]
                                [--max-seconds S S S]
Writes <out>/<csv> (one row per run), <out>/<csv stem>_progress.csv (the runs' progress lines
as they come, one row each: step, loop seconds, the run's measured error so far; a run cut
short keeps its rows) and <out>/<csv stem>_points.csv (per instance and policy, the medians in
the columns gravity_pareto.py --extra reads: method,param,median_err,p99_err,time_s with time_s
the gravity seconds per step, amortised over the run, one rank; a run without a check, i.e.
without a second update, has no point).

Long runs (the paper's 100,000 steps): the adaptive update interval grows over the first few
thousand steps, so each row also gives the time per step over the run's last part (--last-part,
a fraction of the steps reached, from the progress lines), where the interval has settled.
--max-seconds (per instance, in --instances order; the last repeats; 0: no limit) stops a run
after that many wall seconds: its row then gives the steps reached and the error of its last
progress line. Each row gives the load average (1 minute) at the run's start and end: the
machine may be shared.
"""
import argparse
import csv
import os
import re
import signal
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
sys.path.insert(0, HERE)
from agglomerates_bench import INSTANCES, ROOT, SCENE, write_csv  # noqa: E402
from run_summary import MPI_ENV, mpiexec, summary_or_exit  # noqa: E402

# A progress line (apps/regolith/ProgressLine.cpp): the steps done, the mean rate since the
# loop's start, and once checked the run's measured error so far.
PROGRESS = re.compile(r"^step (\d+)/\d+ .*?  ([0-9.e+-]+) steps/s"
                      r"(?:.*force error ([0-9.e+-]+) \(p99 ([0-9.e+-]+)\))?")


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


def run_logged(app, ranks, args, progress_seconds, max_seconds, record):
    """Runs `app` on `ranks` ranks with `args`, passing each progress line's (step, loop seconds,
    median, p99) to `record` as it comes; returns the run summary, or None for a run stopped
    after `max_seconds` (> 0). A failed run ends the script with its command and output."""
    with tempfile.TemporaryDirectory() as tmp:
        summary = os.path.join(tmp, "summary.json")
        command = [*mpiexec(ranks), app, *args, "--set",
                   f"output.progress_seconds={progress_seconds}", "--json", summary]
        start = time.monotonic()
        proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                text=True, env={**os.environ, **MPI_ENV}, start_new_session=True)
        stopped = False
        lines = []
        for line in proc.stdout:
            lines.append(line)
            m = PROGRESS.match(line)
            if m and float(m[2]) > 0:
                err = [float(x) if x else float("nan") for x in (m[3], m[4])]
                record(int(m[1]), int(m[1]) / float(m[2]), *err)
            if max_seconds > 0 and time.monotonic() - start > max_seconds and not stopped:
                os.killpg(proc.pid, signal.SIGTERM)
                stopped = True
        proc.wait()
        if stopped:
            return None
        return summary_or_exit(command, proc.returncode, "".join(lines[-40:]), summary)


def last_part_ms(progress, steps, fraction):
    """ms per step between the progress line nearest to (1 - fraction) of `steps` and the
    end (steps, loop seconds); NaN without two lines."""
    if len(progress) < 2:
        return float("nan")
    end = progress[-1]
    begin = min(progress[:-1], key=lambda p: abs(p[0] - (1 - fraction) * steps))
    return 1e3 * (end[1] - begin[1]) / (end[0] - begin[0])


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
    p.add_argument("--progress-seconds", type=float, default=10.0)
    p.add_argument("--last-part", type=float, default=0.2,
                   help="the fraction of the steps at the end timed on its own")
    p.add_argument("--max-seconds", type=float, nargs="+", default=[0.0],
                   help="per instance (in --instances order; the last repeats); 0: no limit")
    a = p.parse_args()
    app = os.path.join(a.build, "bin", "regolith")
    rows = []
    os.makedirs(a.out, exist_ok=True)
    path = os.path.join(a.out, a.csv)
    stem, ext = os.path.splitext(path)
    progress_file = open(f"{stem}_progress{ext}", "w", newline="", encoding="utf-8")
    progress_csv = csv.writer(progress_file)
    progress_csv.writerow(["instance", "policy", "ranks", "repeat", "step", "loop_s",
                           "error_median", "error_p99"])
    for i, name in enumerate(a.instances):
        steps = a.steps[min(i, len(a.steps) - 1)]
        paper_ms = 1e3 * INSTANCES[name][4] / 100_000
        limit = a.max_seconds[min(i, len(a.max_seconds) - 1)]
        for repeat in range(a.repeats):
            for policy in a.policies:
                for np in a.ranks:
                    progress = []

                    def record(step, loop_s, median, p99):
                        progress.append((step, loop_s, median, p99))
                        progress_csv.writerow([name, policy, np, repeat, step, loop_s, median,
                                               p99])
                        progress_file.flush()

                    load_start = os.getloadavg()[0]
                    s = run_logged(app, np, [*instance_args(name),
                                             *policy_args(policy, name, a.theta),
                                             "--steps", str(steps)],
                                   a.progress_seconds, limit, record)
                    row = {"instance": name, "grains": 2 * INSTANCES[name][0], "policy": policy,
                           "ranks": np, "repeat": repeat, "steps": steps,
                           "load_start": load_start, "load_end": os.getloadavg()[0]}
                    if s is None:  # stopped: what the progress lines tell
                        last = progress[-1] if progress else (0, float("nan"), float("nan"),
                                                              float("nan"))
                        row.update({"steps_reached": last[0], "wall_s": float("nan"),
                                    "loop_s": last[1], "ms_per_step": 1e3 * last[1] / last[0]
                                    if last[0] else float("nan"),
                                    "gravity_ms_per_step": float("nan"), "updates": -1,
                                    "checks": -1, "error_median": last[2],
                                    "error_p99": last[3]})
                    else:
                        g, t = s["gravity"], s["timing_s"]
                        # No check without a second update (the paper's threshold, short runs).
                        error = g.get("error", {}) if g.get("error", {}).get("checks", 0) else {}
                        progress.append((steps, s["wall_s"]))
                        row.update({"steps_reached": steps, "wall_s": s["wall_s"],
                                    "loop_s": s["wall_s"],
                                    "ms_per_step": 1e3 * s["wall_s"] / steps,
                                    "gravity_ms_per_step": 1e3 * t["gravity"] / steps,
                                    "updates": g["updates"], "checks": error.get("checks", 0),
                                    "error_median": error.get("median", float("nan")),
                                    "error_p99": error.get("p99", float("nan"))})
                    reached = row["steps_reached"]
                    row["last_part_ms_per_step"] = last_part_ms(progress, reached, a.last_part)
                    row["paper_ms_per_step"] = paper_ms
                    row["paper_over_ours"] = paper_ms / row["ms_per_step"]
                    rows.append(row)
                    r = row
                    print(f"{name:6s} {policy:16s} np{np} #{repeat}: {reached} of {steps} "
                          f"steps, {r['ms_per_step']:.3f} ms/step (last "
                          f"{100 * a.last_part:.0f} %: {r['last_part_ms_per_step']:.3f}; gravity "
                          f"{r['gravity_ms_per_step']:.3f}), {r['updates']} updates, measured "
                          f"error {r['error_median']:.2g} (p99 {r['error_p99']:.2g}); paper "
                          f"{paper_ms:.1f} ms/step: x{r['paper_over_ours']:.0f}; load "
                          f"{r['load_start']:.1f}-{r['load_end']:.1f}", flush=True)
    progress_file.close()
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
    with open(f"{stem}_points{ext}", "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(["method", "param", "median_err", "p99_err", "time_s"])
        w.writerows(points)


if __name__ == "__main__":
    main()
