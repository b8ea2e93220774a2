#!/usr/bin/python3
"""Self-gravity charts from one gravity_bench run on one rank: force error against
time per evaluation for every method and parameter (a Pareto chart), and two stability maps,
the opening angle θ against the tree's error and the cell spacing against the mesh's error,
with the region above the target error shaded.

Methods: direct sum (the reference, error 0), Barnes-Hut tree and mutual tree at each θ
(θ > 1 with gravity.allow_large_theta), the second paper's tree-at-nodes (each θ) and
occupied-cells baselines at node spacings of 2.5 (the paper's) and 1.25 x the largest
diameter, particle-mesh
(PETSc Poisson) at each cell spacing, and the update threshold (the tree's field kept until
the fastest grain moved the threshold: error just before the update against the time per
step, amortised). Extra points of the same shape (CSV with columns
method,param,median_err,p99_err,time_s, e.g. P3M) join the Pareto chart with --extra; a method
named "run: <policy>" is a whole coupled run (bench/coupled/agglomerates_policies.py): its
error measured during the run, its time the gravity time per step, amortised (hollow).

usage: gravity_pareto.py [--build build/default] [--out bench/out] [--instance agg11100|agg38358]
                         [--thetas ...] [--spacings ...] [--thresholds ...] [--target 1e-2]
                         [--extra p3m.csv ...] [--from-csv raw.csv] [--cpu] [--no-docs]

Writes <out>/gravity_pareto_<instance>.csv (method,param,median_err,p99_err,time_s,cpu_s),
the raw gravity_bench CSV <out>/gravity_bench_<instance>.csv, and the charts
gravity-pareto-<instance>.png, gravity-theta-map-<instance>.png,
gravity-grid-map-<instance>.png (copied to docs/images/). A benchmark: it asserts nothing.
"""
import argparse
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from chart_output import ROOT, pyplot, read_csv, save_chart, write_csv  # noqa: E402
from run_summary import MPI_ENV, mpiexec  # noqa: E402

METHODS = "direct,tree,mutual,tree-nodes,occupied-cells,pm,stale-tree"
# Legend label, marker, colour and what `param` is, per method.
STYLE = {
    "direct": ("direct sum (reference)", "*", "black", ""),
    "tree": ("Barnes-Hut tree", "o", "tab:blue", "θ"),
    "mutual": ("mutual tree", "s", "tab:orange", "θ"),
    "tree-nodes": ("tree at nodes (paper)", "^", "tab:green", "θ"),
    "occupied-cells": ("occupied cells (paper)", "v", "tab:olive", "h/d"),
    "pm": ("particle-mesh (PETSc)", "D", "tab:red", "h/d"),
    "stale-tree": ("update threshold, tree (per step)", "P", "tab:purple", "δ/r"),
}
AMORTISED = ("stale-tree",)  # time per step, not per evaluation: not on the Pareto front


def amortised(method):
    """Whether a series' time is per step, amortised over updates (the update threshold, and
    whole coupled runs from --extra, method "run: <policy>"), not per evaluation."""
    return method in AMORTISED or method.startswith("run:")


def error_floor(rows, key):
    """Where an exact (zero-error) point is drawn on the log axis: below every other point."""
    nonzero = [r[key] for r in rows if r[key] > 0.0]
    return min(nonzero, default=1e-6) / 4.0


def run_bench(a, raw):
    command = [*mpiexec(1), os.path.join(a.build, "bin", "gravity_bench"),
               "--instances", a.instance, "--methods", a.methods, "--thetas", a.thetas,
               "--spacings", a.spacings,
               "--node-spacings", a.node_spacings, "--thresholds", a.thresholds,
               "--step-displacement", str(a.step_displacement),
               "--samples", str(a.samples), "--repeat", str(a.repeat), "--csv", raw]
    print(" ".join(command), flush=True)
    subprocess.run(command, check=True, env={**os.environ, **MPI_ENV})


def param_of(row):
    """The parameter a raw row varies (θ, spacing / largest diameter or threshold / r_min)."""
    method = row["method"]
    if method in ("pm", "occupied-cells"):
        return float(row["spacing"])
    if method == "stale-tree":
        return float(row["threshold"])
    return float(row["theta"])


def normalise(raw_rows):
    return [{"method": r["method"], "param": param_of(r), "median_err": float(r["err_median"]),
             "p99_err": float(r["err_p99"]), "time_s": float(r["wall_ms"]) / 1e3,
             "cpu_s": float(r["cpu_ms"]) / 1e3, "spacing": float(r.get("spacing") or 0)}
            for r in raw_rows]


def number_or_label(text):
    """A parameter as a number if it is one (θ, h / d_max), else its label (e.g. P3M's
    "32^3 h=163m rc=2h")."""
    try:
        return float(text)
    except ValueError:
        return text


def param_text(param):
    return f"{param:.3g}" if isinstance(param, float) else str(param).replace(" ", "\n")


def read_extra(paths):
    rows = []
    for path in paths:
        for r in read_csv(path):
            rows.append({"method": r["method"], "param": number_or_label(r["param"]),
                         "median_err": float(r["median_err"]), "p99_err": float(r["p99_err"]),
                         "time_s": float(r["time_s"]), "cpu_s": float(r.get("cpu_s") or "nan"),
                         "extra": True})
    return rows


PAPER_SPACING = 2.5  # the paper's node spacing / the largest diameter


def series_key(r):
    """A chart series: the method, and for tree-at-nodes (parameter θ) also a node spacing
    other than the paper's."""
    if r["method"] == "tree-nodes" and r.get("spacing", 0) not in (0, PAPER_SPACING):
        return f"tree-nodes@{r['spacing']:g}"
    return r["method"]


def style_of(key):
    """(label, marker, colour, parameter name, line style) of a series."""
    method, _, spacing = key.partition("@")
    label, marker, colour, pname = STYLE.get(method, (method, None, None, "param"))
    if spacing:
        return f"{label}, h = {spacing} d_max", marker, colour, pname, "--"
    return label, marker, colour, pname, "-"


def series(rows):
    """Rows grouped by series_key, each group sorted by its parameter."""
    groups = {}
    for r in rows:
        groups.setdefault(series_key(r), []).append(r)
    for g in groups.values():
        # labelled parameters (from --extra) have no order of their own: by time
        g.sort(key=lambda r: r["param"] if isinstance(r["param"], float) else r["time_s"])
    return groups


def pareto_front(points):
    """The points no other point beats in both time and error, by time."""
    front, best = [], float("inf")
    for t, e in sorted(points):
        if e < best:
            front.append((t, e))
            best = e
    return front


def chart_pareto(a, rows, plt):
    fig, axes = plt.subplots(1, 2, figsize=(13, 6.2), sharex=True)
    for ax, key, title in zip(axes, ("median_err", "p99_err"),
                              ("median relative force error", "99th-percentile error")):
        floor = error_floor(rows, key)
        extra_styles = iter(zip("XdhH<>p", ("tab:cyan", "tab:pink", "tab:brown", "tab:gray",
                                            "gold", "navy", "lime")))
        for method, g in series(rows).items():
            label, marker, colour, pname, line = style_of(method)
            if marker is None:  # a method from --extra
                marker, colour = next(extra_styles, ("x", "black"))
            xs = [r[a.time_key] for r in g]
            ys = [max(r[key], floor) for r in g]
            labelled = any(not isinstance(r["param"], float) for r in g)
            ax.plot(xs, ys, marker=marker, color=colour,
                    linestyle=line if len(g) > 1 and not labelled else "",
                    label=label, markersize=6,
                    markerfacecolor="none" if amortised(method) else None)
            for r, x, y in zip(g, xs, ys):
                if pname:
                    ax.annotate(param_text(r["param"]), (x, y), textcoords="offset points",
                                xytext=(4, 3), fontsize=6.5, color=colour or "black")
        front = pareto_front([(r[a.time_key], max(r[key], floor)) for r in rows
                              if not amortised(r["method"])])
        if front:
            fx, fy = zip(*front)
            ax.step(fx, fy, where="post", color="grey", alpha=0.4, linewidth=4,
                    label="Pareto front (per evaluation)", zorder=0)
        ax.axhline(floor, color="black", linewidth=0.5, linestyle=":")
        ax.text(0.99, floor * 1.15, "exact", transform=ax.get_yaxis_transform(),
                ha="right", fontsize=7)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(title)
        ax.set_xlabel(f"{'CPU' if a.cpu else 'wall'} time per evaluation [s]; hollow (update "
                      "threshold, whole runs): per step, amortised", fontsize=8.5)
        ax.grid(True, which="both", alpha=0.25)
    axes[0].set_ylabel("relative force error against the direct sum")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=8, frameon=False)
    fig.suptitle(f"Self-gravity: error against time, {a.instance}, one rank "
                 f"(labels: θ; pm, occupied cells: h / d_max; threshold / r_min)", fontsize=11)
    fig.tight_layout(rect=(0, 0.1, 1, 1))
    save_chart(fig, a.out, f"gravity-pareto-{a.instance}{'-cpu' if a.cpu else ''}", not a.no_docs)


def shade_above(ax, target, label):
    ax.axhspan(target, 1e3, color="tab:red", alpha=0.12, label=label)
    ax.axhline(target, color="tab:red", linewidth=1)


def chart_theta(a, rows, plt):
    fig, ax = plt.subplots(figsize=(7.5, 5))
    groups = series(rows)
    for method in [m for m in groups if m.split("@")[0] in ("tree", "mutual", "tree-nodes")]:
        label, marker, colour, _, line = style_of(method)
        g = groups[method]
        xs = [r["param"] for r in g]
        ax.plot(xs, [r["median_err"] for r in g], marker=marker, color=colour, linestyle=line,
                label=f"{label}, median")
        if line == "-":
            ax.plot(xs, [r["p99_err"] for r in g], marker=marker, color=colour, linestyle=":",
                    alpha=0.7, label=f"{label}, p99")
    shade_above(ax, a.target, f"error > {a.target:g} (fails the target)")
    ax.axvspan(1.0, 10.0, color="grey", alpha=0.12,
               label="θ > 1: only with gravity.allow_large_theta")
    thetas = [r["param"] for r in groups.get("tree", [])] or [0.1, 1.5]
    ax.set_xlim(min(thetas) * 0.9, max(thetas) * 1.05)
    shown = [r[k] for r in rows if r["method"] in ("tree", "mutual")
             for k in ("median_err", "p99_err")]
    ax.set_ylim(min(shown + [1e-4]) / 2, max(shown + [0.5]) * 2)
    ax.set_yscale("log")
    ax.set_xlabel("opening angle θ")
    ax.set_ylabel("relative force error vs the direct sum")
    ax.set_title(f"Where the tree fails: θ against error, {a.instance}")
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=7.5, loc="lower right")
    fig.tight_layout()
    save_chart(fig, a.out, f"gravity-theta-map-{a.instance}", not a.no_docs)


def chart_grid(a, rows, plt):
    fig, ax = plt.subplots(figsize=(7.5, 5))
    groups = series(rows)
    for method in ("pm", "occupied-cells"):
        if method not in groups:
            continue
        label, marker, colour, _, _ = style_of(method)
        g = groups[method]
        xs = [r["param"] for r in g]
        ax.plot(xs, [r["median_err"] for r in g], marker=marker, color=colour,
                label=f"{label}, median")
        ax.plot(xs, [r["p99_err"] for r in g], marker=marker, color=colour, linestyle="--",
                alpha=0.7, label=f"{label}, p99")
    nodes = [r for r in rows if r["method"] == "tree-nodes"]
    if nodes:  # per node spacing, the θ with the smallest median error
        best = {}
        for r in nodes:
            if r["spacing"] not in best or r["median_err"] < best[r["spacing"]]["median_err"]:
                best[r["spacing"]] = r
        pts = sorted(best.values(), key=lambda r: r["spacing"])
        ax.plot([r["spacing"] for r in pts], [r["median_err"] for r in pts], marker="^",
                color="tab:green", label="tree at nodes (best θ), median")
    shade_above(ax, a.grid_target, f"error > {a.grid_target:g} (fails the target)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    from matplotlib.ticker import ScalarFormatter
    ax.xaxis.set_major_formatter(ScalarFormatter())
    ax.xaxis.set_minor_formatter(ScalarFormatter())
    ax.tick_params(axis="x", which="minor", labelsize=7)
    shown = [r["median_err"] for r in rows
             if r["method"] in ("pm", "occupied-cells", "tree-nodes")]
    ax.set_ylim(min(shown + [a.grid_target]) / 3, 1.0)
    ax.set_xlabel("cell (node) spacing h / largest grain diameter")
    ax.set_ylabel("relative force error vs the direct sum")
    ax.set_title(f"Where the grid fails: spacing against error, {a.instance}")
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=7.5, loc="lower right")
    fig.tight_layout()
    save_chart(fig, a.out, f"gravity-grid-map-{a.instance}", not a.no_docs)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build", "default"))
    p.add_argument("--out", default=os.path.join(ROOT, "bench", "out"))
    p.add_argument("--instance", default="agg11100",
                   help="gravity_bench instance: agg3866, agg11100, agg38358")
    p.add_argument("--methods", default=METHODS)
    p.add_argument("--thetas", default="0.2,0.3,0.5,0.7,0.9,1.2,1.5")
    p.add_argument("--spacings", default="4,2,1,0.5,0.25",
                   help="pm cell spacings, multiples of the largest grain diameter")
    p.add_argument("--node-spacings", default="2.5,1.25",
                   help="node spacings of the paper's grid methods, largest diameters")
    p.add_argument("--thresholds", default="0.01,0.1,1,6",
                   help="update thresholds, multiples of the smallest grain radius")
    p.add_argument("--step-displacement", type=float, default=0.001,
                   help="how far the fastest grain moves per step, smallest radii")
    p.add_argument("--samples", type=int, default=2000)
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--target", type=float, default=1e-2, help="shading of the θ map")
    p.add_argument("--grid-target", type=float, default=1e-2, help="shading of the grid map")
    p.add_argument("--extra", nargs="*", default=[],
                   help="CSV files with method,param,median_err,p99_err,time_s (e.g. P3M)")
    p.add_argument("--from-csv", help="a gravity_bench CSV to chart instead of running it")
    p.add_argument("--cpu", action="store_true",
                   help="Pareto chart over CPU time (fairer on a loaded machine) instead of wall")
    p.add_argument("--no-docs", action="store_true", help="do not copy PNGs to docs/images")
    a = p.parse_args()
    a.time_key = "cpu_s" if a.cpu else "time_s"
    os.makedirs(a.out, exist_ok=True)
    raw = a.from_csv or os.path.join(a.out, f"gravity_bench_{a.instance}.csv")
    if not a.from_csv:
        run_bench(a, raw)
    rows = normalise(read_csv(raw))
    write_csv(os.path.join(a.out, f"gravity_pareto_{a.instance}.csv"),
              ["method", "param", "median_err", "p99_err", "time_s", "cpu_s", "spacing"],
              [[r["method"], r["param"], r["median_err"], r["p99_err"], r["time_s"], r["cpu_s"],
                r["spacing"]] for r in rows])
    plt = pyplot()
    chart_pareto(a, rows + read_extra(a.extra), plt)
    chart_theta(a, rows, plt)
    chart_grid(a, rows, plt)


if __name__ == "__main__":
    main()
