#!/usr/bin/python3
"""Stability map of the synchronisation: which grain radius / block edge pairs NNS
accepts, against SOS, from actual short runs of the `bidisperse` app (one large sphere among
the sc grains of radius 0.4, one periodic building block cut into n x n x n blocks, 2 ranks).
NNS refuses a grain that is not smaller than the blocks it may touch: the app then exits with
code 2 and one message before the first step; SOS (and hybrid) run every case.

usage: nns_radius_map.py [--build build/default] [--out bench/out] [--edge 24]
                         [--splits 2 3 4 6 8 12] [--ratios 0.25 0.5 ...] [--methods nns sos]
                         [--steps 3] [--ranks 2] [--no-docs] [--replot]

Writes <out>/nns_radius_map.csv and the chart nns-radius-map.png (copied to docs/images/).
A benchmark: it asserts nothing.
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from chart_output import ROOT, pyplot, save_chart, write_csv  # noqa: E402
from run_summary import MPI_ENV, mpiexec  # noqa: E402


def run(a, split, radius, method):
    """(status, PUpCS or '', message): status 'ran', 'refused' (exit 2) or 'failed'."""
    app = os.path.join(a.build, "bin", "bidisperse")
    with tempfile.TemporaryDirectory() as tmp:
        summary = os.path.join(tmp, "summary.json")
        command = [*mpiexec(a.ranks), app, "--steps", str(a.steps),
                   "--set", f"bidisperse.edge={a.edge}",
                   "--set", f"bidisperse.large_radius={radius!r}",
                   "--set", f"bidisperse.blocks_per_building_block=[{split},{split},{split}]",
                   "--set", f"sync.method={method}", "--quiet", "--json", summary]
        done = subprocess.run(command, capture_output=True, text=True, check=False,
                              env={**os.environ, **MPI_ENV})
        said = [l for l in (done.stderr + done.stdout).splitlines()
                if l.startswith("bidisperse:")]
        message = said[0] if said else ""
        if done.returncode == 0:
            with open(summary, encoding="utf-8") as f:
                return "ran", json.load(f)["pupcs"], message
        return ("refused" if done.returncode == 2 else "failed"), "", message


def chart(a, rows, plt):
    from matplotlib.ticker import ScalarFormatter
    fig, axes = plt.subplots(1, len(a.methods), figsize=(5.5 * len(a.methods), 5),
                             sharey=True, squeeze=False)
    marks = {"ran": ("o", "tab:green", "ran"), "refused": ("x", "tab:red", "refused (exit 2)"),
             "failed": ("s", "black", "failed otherwise")}
    edges = sorted({r["block_edge"] for r in rows})
    top = max(r["ratio"] for r in rows) * 1.3
    for ax, method in zip(axes[0], a.methods):
        mine = [r for r in rows if r["method"] == method]
        # Shade above the boundary found: half-way (geometric) between the largest ratio that
        # ran and the smallest that was refused, per block edge.
        bounds = []
        for e in edges:
            ran = [r["ratio"] for r in mine if r["block_edge"] == e and r["status"] == "ran"]
            refused = [r["ratio"] for r in mine
                       if r["block_edge"] == e and r["status"] == "refused"]
            if refused:
                low = max((x for x in ran if x < min(refused)), default=min(refused) / 2)
                bounds.append((e, (low * min(refused)) ** 0.5))
        if bounds:
            bx, by = zip(*bounds)
            ax.fill_between(bx, by, [top] * len(bx), color="tab:red", alpha=0.15,
                            label="refused region (from the runs)")
        for status, (marker, colour, label) in marks.items():
            pts = [(r["block_edge"], r["ratio"]) for r in mine if r["status"] == status]
            if pts:
                xs, ys = zip(*pts)
                ax.plot(xs, ys, marker, color=colour, linestyle="", label=label, markersize=7)
        ax.axhline(1.0, color="black", linestyle="--", linewidth=1, label="radius = block edge")
        ax.set_xscale("log")
        ax.set_yscale("log")
        for axis in (ax.xaxis, ax.yaxis):
            axis.set_major_formatter(ScalarFormatter())
            axis.set_minor_formatter(ScalarFormatter())
        ax.tick_params(which="minor", labelsize=7)
        ax.set_xlim(edges[0] / 1.2, edges[-1] * 1.2)
        ax.set_ylim(min(r["ratio"] for r in rows) / 1.3, top)
        ax.set_xlabel("block edge (building block / blocks per axis)")
        ax.set_title(f"{method.upper()}: {sum(r['status'] == 'ran' for r in mine)} of "
                     f"{len(mine)} ran")
        ax.grid(True, which="both", alpha=0.2)
        ax.legend(fontsize=7.5, loc="upper right")
    axes[0][0].set_ylabel("radius of the large sphere / block edge")
    fig.suptitle(f"Which grain sizes each synchronisation runs: bidisperse, building block "
                 f"{a.edge:g}^3, sc grains r = 0.4, {a.ranks} ranks, {a.steps} steps "
                 f"(radius < half the building block)", fontsize=10)
    fig.tight_layout()
    save_chart(fig, a.out, "nns-radius-map", not a.no_docs)


def replot(a):
    """The chart again from <out>/nns_radius_map.csv (no runs)."""
    with open(os.path.join(a.out, "nns_radius_map.csv"), newline="", encoding="utf-8") as f:
        rows = [dict(r, block_edge=float(r["block_edge"]), radius=float(r["radius"]),
                     ratio=float(r["ratio"])) for r in csv.DictReader(f)]
    chart(a, rows, pyplot())


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build", "default"))
    p.add_argument("--out", default=os.path.join(ROOT, "bench", "out"))
    p.add_argument("--edge", type=float, default=24.0, help="building-block edge")
    p.add_argument("--splits", type=int, nargs="*", default=[2, 3, 4, 6, 8, 12],
                   help="blocks per building block and axis")
    p.add_argument("--ratios", type=float, nargs="*",
                   default=[0.25, 0.5, 0.9, 0.99, 1.0, 1.01, 1.5, 2.5, 4.0],
                   help="large radius / block edge")
    p.add_argument("--methods", nargs="*", default=["nns", "sos"])
    p.add_argument("--steps", type=int, default=3)
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--no-docs", action="store_true", help="do not copy PNGs to docs/images")
    p.add_argument("--replot", action="store_true", help="chart the CSV of an earlier run")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    if a.replot:
        replot(a)
        return
    rows = []
    for split in a.splits:
        block_edge = a.edge / split
        for ratio in a.ratios:
            radius = round(ratio * block_edge, 6)
            if radius >= a.edge / 2:  # the sphere must fit its building block
                continue
            for method in a.methods:
                status, pupcs, message = run(a, split, radius, method)
                rows.append({"block_edge": block_edge, "radius": radius, "ratio": ratio,
                             "method": method, "status": status, "pupcs": pupcs,
                             "message": message})
                print(f"edge {block_edge:g} r {radius:g} ({ratio:g} x edge) {method}: {status}"
                      f"{' ' + message if status != 'ran' else ''}", flush=True)
    keys = ["block_edge", "radius", "ratio", "method", "status", "pupcs", "message"]
    write_csv(os.path.join(a.out, "nns_radius_map.csv"), keys, [[r[k] for k in keys] for r in rows])
    chart(a, rows, pyplot())


if __name__ == "__main__":
    main()
