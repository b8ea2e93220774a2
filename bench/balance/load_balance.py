"""Dynamic load balance ([balance]) on the scenes whose load moves, static against rebalanced.

usage: load_balance.py [imbalance] [layouts] [wall] [--build build/default]
                       [--out bench/out/balance] [--ranks 8 27] [--blocks 12 16 24 32 12r]
                       [--cases NAME ...] [--repeats N] [--chart FILE] [--steps N] [--reuse]
                       [--split-levels N]

imbalance: each scene on each rank count of --ranks (oversubscribed), once with the blocks
  assigned at the start only (balance.every = 0, the loads still measured) and once with the
  defaults (balance.every = "auto"); the time-averaged and final imbalance max / mean of the
  ranks' loads in work units (a block weighs 1 + its grains [+ its cells for grid gravity],
  coupling/balance), so the figure holds on any machine; the rebalances and their cost in
  steps' time; the blocks split (balance.split_levels) and their number at the end; the
  block floor (the heaviest block over a rank's mean load, the largest measured after the
  splits: no cut of whole blocks goes below it). Writes load_balance_imbalance.csv and,
  with --chart, imbalance against step.
layouts: the cold collapse rebalanced on the largest of --ranks with n x n x n blocks for
  each n of --blocks ("12r": 12 x 12 x 12 with the blocks of the box |x|, |y|, |z| <= 0.7,
  where the cloud collapses to by the end, refined once): how fine the forest must be for
  whole blocks to even its collapsed core, with the blocks splitting (the default) or not
  (--split-levels 0). Writes load_balance_layouts.csv.
wall: on 2 ranks, static and rebalanced alternately (--repeats pairs), the wall time of the
  loop, the ratio's median and range, for the --cases: "settling" (the settling gas at 8
  times its grains), "default" (the default scene: its piles start on one rank each),
  "target-at-rest" (the default scene seen from its second pile: the first hits it at 1.0,
  and the merged pile drifts into one rank's half). Writes load_balance_wall.csv.
Block layouts: tens of blocks per rank, as a user who balances chooses them (a block holds
at most a fraction of a rank's share of the load; the scene's own layout on 2 ranks).
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
SCENES = os.path.join(ROOT, "scenes")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")

# name: (scene file, extra arguments, blocks on 8 ranks, blocks on 27 ranks)
CASES = {
    "settling gas": ("settling-gas.toml", [], "[6,6,12]", "[10,10,20]"),
    "default (two piles merge)": ("default.toml", [], "[16,12,8]", "[24,18,12]"),
    "cold collapse": ("cold-collapse.toml", [], "[8,8,8]", "[12,12,12]"),
    "two agglomerates, bound": (
        "two-agglomerates.toml",
        ["--set", "particles[0].velocity=[0.0,0.27,0.0]",
         "--set", "particles[1].velocity=[0.0,-0.27,0.0]", "--set", "time.steps=2000"],
        "[8,8,4]", "[12,12,6]"),
}


def run(build, np, scene, extra, json_path, steps=None):
    command = ["mpiexec", "-n", str(np), "--oversubscribe",
               os.path.join(build, "bin", "regolith"), os.path.join(SCENES, scene), *extra,
               "--quiet", "--json", json_path]
    if steps:
        command += ["--set", f"time.steps={steps}"]
    done = subprocess.run(command, env=ENV, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        sys.exit(f"{' '.join(command)} exited with {done.returncode}\n{done.stderr}")
    with open(json_path, encoding="utf-8") as f:
        return json.load(f)


def write_csv(path, rows):
    with open(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)


def summary_row(name, np, mode, s):
    b = s["balance"]
    step_seconds = s["wall_s"] / max(s["steps"], 1)
    cost = b["seconds"] / b["rebalances"] / step_seconds if b["rebalances"] else 0.0
    return {"scene": name, "ranks": np, "blocks": s["blocks"], "mode": mode,
            "every": b["every"], "steps": s["steps"],
            "mean_imbalance": round(b["mean_imbalance"], 3),
            "final_imbalance": round(b["final_imbalance"], 3),
            "block_floor": round(b.get("block_floor", 1.0), 3),
            "rebalances": b["rebalances"], "splits": b.get("splits", 0),
            "steps_per_rebalance": round(cost, 2)}


def imbalance(args):
    rows, histories = [], {}
    for np in args.ranks:
        for name, (scene, extra, blocks8, blocks27) in CASES.items():
            blocks = blocks8 if np <= 8 else blocks27
            for mode, every in (("static", ["--set", "balance.every=0"]), ("rebalanced", [])):
                path = os.path.join(args.out, f"balance_{scene}_{np}_{mode}.json")
                if args.reuse and os.path.exists(path):
                    with open(path, encoding="utf-8") as f:
                        s = json.load(f)
                else:
                    s = run(args.build, np, scene,
                            [*extra, "--set", f"domain.blocks={blocks}", *every], path,
                            args.steps)
                b = s["balance"]
                rows.append(summary_row(name, np, mode, s))
                histories[(name, np, mode)] = (b["history"]["step"], b["history"]["imbalance"])
                print(", ".join(f"{k} {v}" for k, v in rows[-1].items()), flush=True)
    write_csv(os.path.join(args.out, "load_balance_imbalance.csv"), rows)
    if args.chart:
        chart(histories, args.ranks, args.chart)


def chart(histories, ranks, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(CASES), figsize=(4 * len(CASES), 3.4), squeeze=False)
    for ax, name in zip(axes[0], CASES):
        for np, colour in zip(ranks, ("tab:blue", "tab:red", "tab:green")):
            for mode, style in (("static", "--"), ("rebalanced", "-")):
                steps, values = histories[(name, np, mode)]
                ax.plot(steps, values, style, color=colour, label=f"{np} ranks, {mode}")
        ax.set_title(name, fontsize=10)
        ax.set_xlabel("step")
        ax.axhline(1.15, color="grey", linewidth=0.6)
        ax.set_ylim(bottom=1.0)
    axes[0][0].set_ylabel("imbalance (max / mean load)")
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"chart: {path}")


def layouts(args):
    rows = []
    np = max(args.ranks)
    for layout in args.blocks:
        n = layout.rstrip("r")
        extra = ["--set", f"domain.blocks=[{n},{n},{n}]"]
        if args.split_levels is not None:
            extra += ["--set", f"balance.split_levels={args.split_levels}"]
        if layout.endswith("r"):
            extra += ["--set", "domain.refine=[{min=[-0.7,-0.7,-0.7],max=[0.7,0.7,0.7],level=1}]"]
        path = os.path.join(args.out, f"balance_layout_{layout}_{np}.json")
        s = run(args.build, np, "cold-collapse.toml", extra, path, args.steps)
        rows.append(summary_row("cold collapse", np, "rebalanced", s))
        print(", ".join(f"{k} {v}" for k, v in rows[-1].items()), flush=True)
    write_csv(os.path.join(args.out, "load_balance_layouts.csv"), rows)


# name: (label, scene file, extra arguments)
WALL_CASES = {
    # The settling gas at 8 times its grains (a 20 x 20 x 40 box): at 1,024 grains its two
    # ranks wait on each other's messages more than they compute.
    "settling": ("settling gas, 8,192 grains", "settling-gas.toml",
                 ["--set", "domain.max=[20,20,40]", "--set", "domain.blocks=[8,8,16]",
                  "--set", "walls[1].point=[0.0,0.0,40.0]"]),
    "default": ("default (two piles merge)", "default.toml", []),
    # The same collision seen from the second pile (a Galilean boost by 0.5 along x): the
    # merged pile drifts at 0.5 into rank 1's half, so the start's even cut does not last.
    "target-at-rest": ("default seen from the second pile", "default.toml",
                       ["--set", "particles[0].velocity=[1.0,0.0,0.0]",
                        "--set", "particles[1].velocity=[0.0,0.0,0.0]"]),
}


def wall(args):
    rows = []
    for case in args.cases:
        name, scene, extra = WALL_CASES[case]
        times = {"static": [], "rebalanced": []}
        imbalances = {"static": [], "rebalanced": []}
        for k in range(args.repeats):
            for mode, every in (("static", ["--set", "balance.every=0"]), ("rebalanced", [])):
                path = os.path.join(args.out, f"balance_wall_{case}_{mode}.json")
                s = run(args.build, 2, scene, [*extra, *every], path, args.steps)
                times[mode].append(s["wall_s"])
                imbalances[mode].append(s["balance"]["mean_imbalance"])
        ratios = [r / s for r, s in zip(times["rebalanced"], times["static"])]
        rows.append({"scene": name, "ranks": 2,
                     "static_s": round(statistics.median(times["static"]), 3),
                     "rebalanced_s": round(statistics.median(times["rebalanced"]), 3),
                     "ratio_median": round(statistics.median(ratios), 3),
                     "ratio_min": round(min(ratios), 3), "ratio_max": round(max(ratios), 3),
                     "static_imbalance": round(statistics.median(imbalances["static"]), 3),
                     "rebalanced_imbalance": round(statistics.median(imbalances["rebalanced"]), 3),
                     "repeats": args.repeats})
        print(", ".join(f"{k} {v}" for k, v in rows[-1].items()), flush=True)
    suffix = "" if args.cases == ["settling", "default"] else "_" + "_".join(args.cases)
    write_csv(os.path.join(args.out, f"load_balance_wall{suffix}.csv"), rows)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("parts", nargs="*", default=["imbalance", "layouts", "wall"])
    parser.add_argument("--build", default="build/default")
    parser.add_argument("--out", default="bench/out/balance")
    parser.add_argument("--ranks", type=int, nargs="*", default=[8, 27])
    parser.add_argument("--blocks", nargs="*", default=["12", "16", "24", "32", "12r"])
    parser.add_argument("--cases", nargs="*", default=["settling", "default"],
                        choices=list(WALL_CASES))
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--chart")
    parser.add_argument("--reuse", action="store_true",
                        help="imbalance: take a run's summary from --out where it exists")
    parser.add_argument("--steps", type=int, help="time.steps of every run (the scenes' own)")
    parser.add_argument("--split-levels", type=int,
                        help="layouts: balance.split_levels of every run (the default \"auto\")")
    args = parser.parse_args()
    args.build = os.path.abspath(args.build)
    os.makedirs(args.out, exist_ok=True)
    if "imbalance" in args.parts:
        imbalance(args)
    if "layouts" in args.parts:
        layouts(args)
    if "wall" in args.parts:
        wall(args)


if __name__ == "__main__":
    main()
