#!/usr/bin/python3
"""DEM benchmark suite on the apps of the first paper's scenes, from their run
summaries. Benchmarks, not tests: nothing here asserts a time.

  methods  PUpCS of NNS, SOS and hybrid for granular_gas, dense_ramp and bidisperse on 1 and 2
           ranks, the three methods run alternating (nns, sos, hybrid, nns, ...) so that a
           change of machine load hits all alike; ratios to the NNS run next to each, raw and
           at equal machine speed (normalised by the contact + integration seconds); --scenes
           picks scenes. Run it alone: its ranks are bound to cores (run_summary.mpiexec).
  radius   the paper's Fig. 7/8 analogue: PUpCS against the radius of the large sphere in one
           building block, sparse (sc, r = 0.4) and dense (hcp, r = 0.4) surroundings, 4x4x4 and
           8x8x8 blocks per building block, --repeats runs per point (methods alternating;
           median and range); NNS points stop where NNS refuses. CSV + PNG.
  radius-chart  the radius chart again from the CSV of an earlier `radius` run.
  memory   peak resident memory per grain of the sparse gas on 2 ranks for 1 M and 4 M grains.
  skin     with and without a sync skin (sync.skin = --skin, 0), alternating, on each of --ranks:
           the sparse gas (NNS, hybrid) and the bidisperse scene (hybrid, large radius 8 and
           16: NNS class, and SOS class, which leaves the list idle); PUpCS ratio skin / none.

usage: dem_bench.py [methods|radius|radius-chart|memory|skin ...] [--build build/default]
                    [--out bench/out] [--repeats 3] [--ranks 1 2] [--scenes ...] [--steps N]
                    [--set app.key=value ...] [--edge 40]
                    [--radii 4 8 12 16 20 24] [--skin 0.1] [--no-docs]
"""
import argparse
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from chart_output import ROOT, pyplot, read_csv, save_chart, write_csv  # noqa: E402
from run_summary import run_app  # noqa: E402
METHODS = ("nns", "sos", "hybrid")

# Per scene: app, arguments for a benchmark-sized run on one rank's share (weak scaling: the
# paper's per-process boxes), steps. The gas starts on its lattice, 0.1 from every face: in the
# first ~100 steps no grain touches a block face or another grain, so its run is long enough
# (1000 steps) to be dominated by the mixed state, where shadows and contacts are steady. The
# bidisperse scene's small grains start the same way (100 steps took 0.04 s, and ran 8x the
# PUpCS of the mixed state): 1000 steps too.
SCENES = {
    "granular_gas": ("granular_gas", ["--set", "granular_gas.per_rank=[30,30,30]"], 1000),
    "dense_ramp": ("dense_ramp", ["--set", "dense_ramp.per_rank=[30,25.98076211353316,8]"], 200),
    "bidisperse": ("bidisperse", ["--set", "bidisperse.edge=40", "--set",
                                  "bidisperse.large_radius=8"], 1000),
}


def run(build, app, ranks, args, refusal=None):
    return run_app(os.path.join(build, "bin", app), ranks, args, refusal)


# How NNS refuses a grain too large for the blocks it may touch (ParticleSync); the only
# refusal the radius sweep expects.
NNS_REFUSAL = "(NNS only reaches next neighbours)"


def median_range(ratios, digits=3):
    """'median (min–max)' of a list of ratios."""
    return (f"{statistics.median(ratios):.{digits}f} "
            f"({min(ratios):.2f}–{max(ratios):.2f})")


def fixed_work_s(s):
    """Seconds of a run's phases whose work is meant not to depend on the sync method (contact
    detection and evaluation, integration: the same grains and contacts under all three; see
    methods for where it does after all)."""
    return s["timing_s"]["contact"] + s["timing_s"]["integrate"]


def methods(a):
    """PUpCS of SOS and hybrid over NNS, the three alternating within each repeat; per pair of
    runs also the ratio at equal machine speed: the raw ratio times the ratio of the runs'
    fixed-work seconds (fixed_work_s), which takes out the speed this VM had during each run
    (its contact phase alone varies up to 1.8x between neighbouring runs). The last column
    shows each method's median fixed-work seconds: where they differ beyond the noise, the
    work is not the same after all (e.g. a storage order that suits the contact loop better)
    and the equal-speed ratio is biased by that much."""
    rows = []
    print("\n| scene | ranks | grains | NNS PUpCS | SOS / NNS | hybrid / NNS | "
          "SOS / NNS at equal speed | hybrid / NNS at equal speed | "
          f"contact + integration s ({' / '.join(METHODS)}, medians) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for scene, (app, args, steps) in SCENES.items():
        if scene not in a.scenes:
            continue
        args = args + [x for key in a.overrides if key.split(".")[0] == scene
                       for x in ("--set", key)]
        steps = a.steps or steps
        for ranks in a.ranks:
            runs = {m: [] for m in METHODS}
            for repeat in range(a.repeats):
                for m in METHODS:
                    s = run(a.build, app, ranks,
                            args + ["--steps", str(steps), "--set", f"sync.method={m}"])
                    runs[m].append(s)
                    rows.append([scene, ranks, repeat, m, s["particles"], steps, s["wall_s"],
                                 s["pupcs"], s["timing_s"]["sync"], s["timing_s"]["contact"],
                                 s["timing_s"]["integrate"], s["comm"]["bytes_per_step"]])
            raw = {m: [r["pupcs"] / n["pupcs"] for r, n in zip(runs[m], runs["nns"])]
                   for m in METHODS}
            even = {m: [q * fixed_work_s(r) / fixed_work_s(n)
                        for q, r, n in zip(raw[m], runs[m], runs["nns"])] for m in METHODS}
            nns = statistics.median(r["pupcs"] for r in runs["nns"])
            fixed = " / ".join(f"{statistics.median(fixed_work_s(r) for r in runs[m]):.3f}"
                               for m in METHODS)
            print(f"| {scene} | {ranks} | {runs['nns'][0]['particles']} | {nns:.3e} | "
                  f"{median_range(raw['sos'])} | {median_range(raw['hybrid'])} | "
                  f"{median_range(even['sos'])} | {median_range(even['hybrid'])} | {fixed} |",
                  flush=True)
    write_csv(os.path.join(a.out, "dem_methods.csv"),
              ["scene", "ranks", "repeat", "method", "grains", "steps", "wall_s", "pupcs",
               "sync_s", "contact_s", "integrate_s", "bytes_per_step"], rows)


def skin(a):
    """The sparse gas (NNS and hybrid) and the bidisperse scene (hybrid; large radius 8, NNS
    class there, and 16, SOS class, where the list stays idle), each with sync.skin = --skin
    and 0, alternating; PUpCS ratio skin / none of the runs next to each other."""
    gas_app, gas_args, gas_steps = SCENES["granular_gas"]
    bi_app, bi_args, bi_steps = SCENES["bidisperse"]
    cases = [("granular_gas", m, gas_app, gas_args + ["--set", f"sync.method={m}"], gas_steps)
             for m in ("nns", "hybrid")]
    cases += [(f"bidisperse r={r}", "hybrid", bi_app,
               bi_args + ["--set", f"bidisperse.large_radius={r}", "--set", "sync.method=hybrid"],
               bi_steps) for r in (8, 16)]
    rows = []
    print(f"\n| scene | ranks | method | grains | PUpCS without skin | with skin {a.skin:g} | "
          "ratio (range) | sync s without / with |")
    print("|---|---|---|---|---|---|---|---|")
    for ranks in a.ranks:
        for scene, m, app, args, steps in cases:
            runs = {0.0: [], a.skin: []}
            for repeat in range(a.repeats):
                for sk in runs:
                    s = run(a.build, app, ranks,
                            args + ["--steps", str(steps), "--set", f"sync.skin={sk!r}"])
                    runs[sk].append(s)
                    rows.append([scene, ranks, m, sk, repeat, s["particles"], s["wall_s"],
                                 s["pupcs"], s["timing_s"]["sync"], s["comm"]["messages_per_step"],
                                 s["comm"]["bytes_per_step"]])
            ratios = [w["pupcs"] / n["pupcs"] for n, w in zip(runs[0.0], runs[a.skin])]
            med = {sk: statistics.median(r["pupcs"] for r in runs[sk]) for sk in runs}
            sync = {sk: statistics.median(r["timing_s"]["sync"] for r in runs[sk]) for sk in runs}
            print(f"| {scene} | {ranks} | {m} | {runs[0.0][0]['particles']} | {med[0.0]:.3e} | "
                  f"{med[a.skin]:.3e} | {median_range(ratios, 2)} | "
                  f"{sync[0.0]:.3f} / {sync[a.skin]:.3f} |", flush=True)
    write_csv(os.path.join(a.out, "dem_skin.csv"),
              ["scene", "ranks", "method", "skin", "repeat", "grains", "wall_s", "pupcs",
               "sync_s", "messages_per_step", "bytes_per_step"], rows)


def radius(a):
    """Every point --repeats times, the three methods alternating within a repeat (so that a
    change of machine load hits all alike); the chart shows each point's median and range."""
    rows = []
    surroundings = {
        "sparse": ["--set", "particles[1].lattice=sc", "--set", "particles[1].radius=0.4"],
        "dense": ["--set", "particles[1].lattice=hcp", "--set", "particles[1].radius=0.4"],
    }
    for name, extra in surroundings.items():
        for split in (4, 8):
            for r in a.radii:
                pupcs = {m: [] for m in METHODS}
                for repeat in range(a.repeats):
                    for m in METHODS:
                        args = ["--steps", str(a.radius_steps),
                                "--set", f"bidisperse.edge={a.edge}",
                                "--set", f"bidisperse.large_radius={r}", "--set",
                                f"bidisperse.blocks_per_building_block=[{split},{split},{split}]",
                                "--set", f"sync.method={m}", *extra]
                        s = run(a.build, "bidisperse", a.radius_ranks, args,
                                NNS_REFUSAL if m == "nns" else None)
                        rows.append([name, split, a.edge / split, r, m, repeat,
                                     "" if s is None else s["particles"],
                                     "" if s is None else s["pupcs"],
                                     "refused" if s is None else "ran"])
                        if s is not None:
                            pupcs[m].append(s["pupcs"])
                print(f"{name} {split}^3 r={r}: " + ", ".join(
                    f"{m} {statistics.median(p):.3e}" if p else f"{m} refused"
                    for m, p in pupcs.items()), flush=True)
    write_csv(os.path.join(a.out, "dem_radius.csv"),
              ["surroundings", "blocks_per_axis", "block_edge", "large_radius", "method",
               "repeat", "grains", "pupcs", "status"], rows)
    chart_radius(a, rows)


def radius_points(rows, name, split, method):
    """(radius, median, min, max) of the runs of one curve, and the radii where it refused."""
    ran, refused = {}, set()
    for r in rows:
        if r[0] == name and r[1] == split and r[4] == method:
            if r[8] == "ran":
                ran.setdefault(r[3], []).append(r[7])
            else:
                refused.add(r[3])
    points = [(x, statistics.median(p), min(p), max(p)) for x, p in sorted(ran.items())]
    return points, sorted(refused)


def chart_radius(a, rows):
    try:
        plt = pyplot()
    except ImportError:
        print("dem_bench: no matplotlib (apt-get install python3-matplotlib): no chart")
        return
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    styles = {"nns": "o-", "sos": "s--", "hybrid": "^-."}
    for ax, name in zip(axes, ("sparse", "dense")):
        for split in (4, 8):
            for m in METHODS:
                points, refused = radius_points(rows, name, split, m)
                if not points:
                    continue
                xs, med, lo, hi = zip(*points)
                bars = ax.errorbar(xs, med, yerr=[[m_ - l for m_, l in zip(med, lo)],
                                                  [h - m_ for m_, h in zip(med, hi)]],
                                   fmt=styles[m], capsize=3,
                                   label=f"{m.upper()} edge {a.edge / split:g}")
                # Where a method refused (NNS: radius >= block edge), an x on the axis.
                if refused:
                    ax.plot(refused, [0.03 if split == 4 else 0.08] * len(refused), "x",
                            color=bars.lines[0].get_color(), transform=ax.get_xaxis_transform(),
                            markersize=8, markeredgewidth=2,
                            label=f"{m.upper()} edge {a.edge / split:g} refused")
        ax.set_title(f"{name} surroundings, building block {a.edge:g}^3, "
                     f"{a.radius_ranks} rank(s)")
        ax.set_xlabel("radius of the large sphere")
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("PUpCS, median and range (x near the axis: refused)")
    axes[0].set_ylim(bottom=0.0)
    axes[1].legend(fontsize=8)
    fig.tight_layout()
    save_chart(fig, a.out, "dem-radius", not a.no_docs)


def radius_chart(a):
    """The radius chart again from <out>/dem_radius.csv (no runs)."""
    rows = [[r["surroundings"], int(r["blocks_per_axis"]), float(r["block_edge"]),
             float(r["large_radius"]), r["method"], int(r["repeat"]), r["grains"],
             float(r["pupcs"]) if r["pupcs"] else "", r["status"]]
            for r in read_csv(os.path.join(a.out, "dem_radius.csv"))]
    chart_radius(a, rows)


def memory(a):
    rows = []
    print("\n| grains | ranks | peak RSS of the largest rank [MB] | bytes per grain (max rank x "
          "ranks / grains) |")
    print("|---|---|---|---|")
    for edge in a.memory_boxes:
        s = run(a.build, "granular_gas", 2,
                ["--steps", "10", "--set", "granular_gas.scaling=strong",
                 "--set", f"granular_gas.box=[{edge},{edge},{edge}]"])
        per_grain = s["peak_rss_bytes"] * s["ranks"] / s["particles"]
        rows.append([s["particles"], s["ranks"], s["peak_rss_bytes"], per_grain])
        print(f"| {s['particles']} | {s['ranks']} | {s['peak_rss_bytes'] / 1e6:.1f} | "
              f"{per_grain:.0f} |", flush=True)
    write_csv(os.path.join(a.out, "dem_memory.csv"),
              ["grains", "ranks", "peak_rss_bytes_max_rank", "bytes_per_grain"], rows)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parts = {"methods": methods, "radius": radius, "radius-chart": radius_chart,
             "memory": memory, "skin": skin}
    p.add_argument("parts", nargs="*", metavar="part",
                   help=f"any of {', '.join(parts)} (default: all but radius-chart)")
    p.add_argument("--build", default=os.path.join(ROOT, "build", "default"))
    p.add_argument("--out", default=os.path.join(ROOT, "bench", "out"))
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--ranks", type=int, nargs="*", default=[1, 2])
    p.add_argument("--scenes", nargs="*", default=list(SCENES), choices=list(SCENES),
                   help="the scenes `methods` runs")
    p.add_argument("--steps", type=int, default=None,
                   help="methods: steps per run instead of each scene's own")
    p.add_argument("--set", action="append", default=[], dest="overrides", metavar="KEY=VALUE",
                   help="methods: a scene key for the scene whose app section KEY names "
                        "(e.g. granular_gas.per_rank=[6,6,6]); repeatable")
    p.add_argument("--edge", type=float, default=40.0)
    p.add_argument("--radii", type=float, nargs="*", default=[4, 8, 12, 16, 18])
    p.add_argument("--radius-steps", type=int, default=200)
    p.add_argument("--radius-ranks", type=int, default=2)
    p.add_argument("--memory-boxes", type=int, nargs="*", default=[100, 159])
    p.add_argument("--skin", type=float, default=0.1)
    p.add_argument("--no-docs", action="store_true", help="do not copy PNGs to docs/images")
    a = p.parse_args()
    for part in a.parts: # (argparse's choices refuse a list default with nargs="*")
        if part not in parts:
            p.error(f"unknown part {part!r} (choose from {', '.join(parts)})")
    a.parts = a.parts or ["methods", "radius", "memory", "skin"]
    os.makedirs(a.out, exist_ok=True)
    for part in a.parts:
        parts[part](a)


if __name__ == "__main__":
    main()
