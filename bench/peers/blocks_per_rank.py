#!/usr/bin/python3
"""Blocks per rank, as a user runs them: the first paper's scenes A, B and C
(bench/peers/scenes/scene-*.toml, written as a user writes them: contact parameters, grains,
nothing else; `gas` is scene A on a 40^3 box, 64,000 grains) with 1, 8, 64 and 512 blocks per rank and every other key at its default, next
to LAMMPS (7 Jan 2022 from Debian) on the same grains in the same invocation. Runs alternate
(every block count, then LAMMPS, then again) so that a change of machine load hits all alike.

Reports PUpCS (particle updates per core-second of the time-step loop: Regolith's wall_s,
LAMMPS's "Loop time") per scene and block count: the median over the repeats and the range, the
ratio to one block per rank (median of the per-repeat ratios) and to LAMMPS (median of the
per-repeat ratios). --ranks 2 runs the weak-scaled scenes (the box doubled along x) on two
ranks, LAMMPS on two too. --subdomains blocks adds the runs with one particle subdomain per
block (sync.subdomains = "blocks", the synchronisation crossing every block face), to show what
merging a rank's blocks saves. --chart draws PUpCS against blocks per rank with LAMMPS's as a
line (docs/images/dem-blocks-per-rank.png). --against DIR runs a second build's regolith right
after each of this build's runs, with the same keys, and reports this build's PUpCS over it
(median of the per-repeat ratios, and the range): a change measured side by side on a shared
machine. A block count of 0 leaves domain.blocks unset: the run's own choice (one block per
rank, cut with the least surface), what a user gets without the key.

LAMMPS: pair_style gran/hooke/history with Regolith's spring-dashpot numbers (k_t = 2/7 k_n,
gamma_t = gamma_n / 2), neighbor 0.1 (bin for A and B; multi with comm_modify mode multi for C),
neigh_modify delay 0 every 1 check yes, newton on (with newton off LAMMPS computes each pair
across a periodic face twice: B runs ~1.2x longer), fix nve/sphere; decks granular.in, ramp.in,
boulder.in.

usage: blocks_per_rank.py [--build build/default] [--out bench/out] [--scenes a b c gas]
                          [--blocks 1 8 64 512] [--steps 1000] [--repeats 3] [--ranks 1]
                          [--subdomains merged [blocks]] [--small] [--against DIR]
                          [--chart PNG [--chart-from CSV...]]
"""
import argparse
import csv
import json
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile
from types import SimpleNamespace

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from lammps_compare import lammps_params, write_data  # noqa: E402  (the same numbers, data)

ENV = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}
MPIEXEC = ["mpiexec", "--oversubscribe"]

# Per scene: the file, its extent per rank, the LAMMPS deck and its extra variables, and the
# contact numbers (the scene file's; lammps_params needs them).
SCENES = {
    "a": dict(file="scene-a.toml", extent=(20.0, 20.0, 20.0), deck="granular.in", vars={},
              stiffness=33.0734, restitution=0.9, friction=0.5),
    "b": dict(file="scene-b.toml", extent=(20.0, 10.0 * math.sqrt(3.0), 8.0), deck="ramp.in",
              vars={"g": 1.0, "gx": 0.5, "gz": -math.sqrt(3.0) / 2.0},
              stiffness=64.5964, restitution=0.9, friction=0.5),
    "c": dict(file="scene-c.toml", extent=(80.0, 80.0, 80.0), deck="boulder.in", vars={},
              stiffness=33.0734, restitution=0.9, friction=0.5),
    # Scene A's gas on a 40^3 box: 64,000 grains, the sparse gas for blocks per rank.
    "gas": dict(file="scene-a.toml", extent=(40.0, 40.0, 40.0), deck="granular.in", vars={},
                stiffness=33.0734, restitution=0.9, friction=0.5),
}
LAMMPS_SKIN = 0.1

# --small (the check of docs/results.md's commands, bench/results_commands.py): each scene on a
# box of a few hundred grains, its lattice periods kept (scene C's sphere moved into it).
SMALL = {
    "a": dict(extent=(6.0, 6.0, 6.0), sets=[]),
    "gas": dict(extent=(8.0, 8.0, 8.0), sets=[]),
    "b": dict(extent=(6.0, 3.0 * math.sqrt(3.0), 8.0), sets=[]),
    "c": dict(extent=(20.0, 20.0, 20.0),
              sets=["particles[0].position=[[10.0,10.0,10.0]]", "particles[0].radius=4.0"]),
}


# Blocks per rank as a root grid per rank (x, y, z); the ranks are laid along x.
LAYOUTS = {1: (1, 1, 1), 2: (2, 1, 1), 4: (2, 2, 1), 8: (2, 2, 2), 16: (4, 2, 2),
           32: (4, 4, 2), 64: (4, 4, 4), 128: (8, 4, 4), 256: (8, 8, 4), 512: (8, 8, 8)}


def blocks_arg(per_rank, ranks):
    """domain.blocks for `per_rank` blocks on each of `ranks` ranks (LAYOUTS, ranks along x)."""
    if per_rank not in LAYOUTS:
        sys.exit(f"blocks_per_rank: no layout for {per_rank} blocks per rank: {sorted(LAYOUTS)}")
    n = LAYOUTS[per_rank]
    return f"domain.blocks=[{n[0] * ranks},{n[1]},{n[2]}]"


def scene_args(scene, ranks, steps):
    """The --set arguments that weak-scale `scene` to `ranks` ranks along x, and the steps."""
    e = SCENES[scene]["extent"]
    sets = [x for kv in SCENES[scene].get("sets", []) for x in ("--set", kv)]
    return ["--steps", str(steps), "--set", f"domain.max=[{e[0] * ranks!r},{e[1]!r},{e[2]!r}]",
            *sets]


def regolith(app, scene, ranks, args, json_path):
    command = [*MPIEXEC, "-n", str(ranks), app, os.path.join(HERE, "scenes",
                                                             SCENES[scene]["file"]),
               *args, "--quiet", "--json", json_path]
    done = subprocess.run(command, capture_output=True, text=True, env=ENV, check=False)
    if done.returncode != 0:
        sys.exit(f"blocks_per_rank: {' '.join(command)} failed\n{done.stdout}\n{done.stderr}")
    with open(json_path, encoding="utf-8") as f:
        return json.load(f)


def lammps(scene, ranks, data, params, steps, workdir):
    """Loop seconds and atoms of one LAMMPS run."""
    log = os.path.join(workdir, "lmp.log")
    command = [*MPIEXEC, "-n", str(ranks), "lmp", "-in",
               os.path.join(HERE, SCENES[scene]["deck"]), "-log", log, "-screen", "none",
               "-var", "data", data, "-var", "dt", "0.01", "-var", "steps", str(steps),
               "-var", "skin", str(LAMMPS_SKIN)]
    for k, v in params.items():
        command += ["-var", k, repr(v)]
    done = subprocess.run(command, capture_output=True, text=True, cwd=workdir, env=ENV,
                          check=False)
    if done.returncode != 0:
        sys.exit(f"blocks_per_rank: {' '.join(command)} failed\n{done.stdout}\n{done.stderr}")
    with open(log, encoding="utf-8") as f:
        m = re.search(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) "
                      r"atoms", f.read())
    if not m:
        sys.exit(f"blocks_per_rank: no loop time in {log}")
    return float(m.group(1)), int(m.group(4))


def chart(path, csv_paths):
    """PUpCS against blocks per rank from CSVs this script wrote (one rank count): median and
    range per scene (merged subdomains; one subdomain per block dotted, if measured), LAMMPS's
    median dashed."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = []
    for csv_path in csv_paths:
        with open(csv_path, encoding="utf-8") as f:
            rows += list(csv.DictReader(f))
    ranks = rows[0]["ranks"]
    ours, theirs = {}, {}
    for r in rows:
        if r.get("build") == "against":
            continue
        if r["subdomains"] == "lammps":
            theirs.setdefault(r["scene"], []).append(float(r["pupcs"]))
        else:
            key = (r["scene"], r["subdomains"])
            ours.setdefault(key, {}).setdefault(int(r["blocks_per_rank"]), []).append(
                float(r["pupcs"]))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    colours = {"a": "tab:blue", "b": "tab:orange", "c": "tab:green", "gas": "tab:purple"}
    for (scene, subdomains), points in sorted(ours.items()):
        xs = sorted(points)
        ys = [statistics.median(points[x]) for x in xs]
        lows = [y - min(points[x]) for x, y in zip(xs, ys)]
        highs = [max(points[x]) - y for x, y in zip(xs, ys)]
        merged = subdomains == "merged"
        label = f"scene {scene.upper()}" + ("" if merged else ", one subdomain per block")
        ax.errorbar(xs, ys, yerr=[lows, highs], fmt="-o" if merged else ":x",
                    color=colours[scene], label=label, capsize=3)
    for scene, pupcs in sorted(theirs.items()):
        ax.axhline(statistics.median(pupcs), color=colours[scene], linestyle="--", linewidth=1,
                   label=f"LAMMPS, scene {scene.upper()}")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("blocks per rank")
    ax.set_ylabel("PUpCS (particle updates per core-second)")
    ax.set_title(f"Scenes as a user writes them, defaults only, {ranks} rank(s): "
                 "median and range", fontsize=9)
    ax.legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build", "default"))
    p.add_argument("--out", default=os.path.join(ROOT, "bench", "out"))
    p.add_argument("--scenes", nargs="*", default=["a", "b", "c"], choices=sorted(SCENES))
    p.add_argument("--blocks", nargs="*", type=int, default=[1, 8, 64, 512])
    p.add_argument("--steps", type=int, default=1000)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--ranks", type=int, default=1)
    p.add_argument("--subdomains", nargs="*", default=["merged"])
    p.add_argument("--small", action="store_true",
                   help="every scene in a box of a few hundred grains (a check, not a figure)")
    p.add_argument("--against", help="a second build directory, run alternating with --build")
    p.add_argument("--chart", help="PNG to draw from this run's CSV")
    p.add_argument("--chart-from", nargs="+",
                   help="draw --chart from these CSVs instead of running")
    a = p.parse_args()
    if a.chart_from:
        chart(a.chart, a.chart_from)
        return
    if a.small:
        for scene, small in SMALL.items():
            SCENES[scene].update(small)
    app = os.path.join(a.build, "bin", "regolith")
    builds = [("this", app)] + ([("against", os.path.join(a.against, "bin", "regolith"))]
                                if a.against else [])
    os.makedirs(a.out, exist_ok=True)
    theirs, rows = {}, []
    print(f"ranks {a.ranks}, {a.steps} steps, {a.repeats} repeats, defaults only")
    print("| scene | grains | blocks per rank | subdomains | PUpCS (median) | range | "
          "vs 1 block | vs LAMMPS |")
    print("|---|---|---|---|---|---|---|---|")
    for scene in a.scenes:
        spec = SCENES[scene]
        with tempfile.TemporaryDirectory() as tmp:
            base = scene_args(scene, a.ranks, a.steps)
            dump = os.path.join(tmp, "init.csv")
            regolith(app, scene, 1, scene_args(scene, a.ranks, 0) + ["--dump", dump],
                     os.path.join(tmp, "init.json"))
            data = os.path.join(tmp, "grains.data")
            extent = (spec["extent"][0] * a.ranks, *spec["extent"][1:])
            rows_in = write_data(dump, extent, data)
            grains = len(rows_in)
            small = min(rows_in, key=lambda r: float(r["radius"]))
            mass = float(small["mass"])
            case = SimpleNamespace(stiffness=spec["stiffness"], restitution=spec["restitution"],
                                   friction=spec["friction"], extent=extent,
                                   lammps_vars=spec["vars"])
            params = lammps_params(case, mass)
            runs = {}
            for repeat in range(a.repeats):
                for subdomains in a.subdomains:
                    for b, (build, path) in ((b, x) for b in a.blocks for x in builds):
                        layout = ["--set", blocks_arg(b, a.ranks)] if b else []
                        args = base + layout + ["--set", f'sync.subdomains="{subdomains}"']
                        s = regolith(path, scene, a.ranks, args, os.path.join(tmp, "run.json"))
                        if s["particles"] != grains:
                            sys.exit(f"blocks_per_rank: {s['particles']} grains, the dump "
                                     f"{grains}")
                        key = (subdomains, b) if build == "this" else (subdomains, b, build)
                        runs.setdefault(key, []).append(s["pupcs"])
                        rows.append([scene, a.ranks, subdomains, b, repeat, grains, a.steps,
                                     s["wall_s"], s["pupcs"], s["timing_s"].get("sync", ""),
                                     s["timing_s"].get("contact", ""),
                                     s["timing_s"].get("integrate", ""), s["shadows"],
                                     s["peak_rss_bytes"], build])
                loop, atoms = lammps(scene, a.ranks, data, params, a.steps, tmp)
                if atoms != grains:
                    sys.exit(f"blocks_per_rank: LAMMPS ran {atoms} atoms, Regolith {grains}")
                theirs.setdefault(scene, []).append(a.steps * atoms / (loop * a.ranks))
                rows.append([scene, a.ranks, "lammps", "", repeat, grains, a.steps, loop,
                             theirs[scene][-1], "", "", "", "", "", ""])
            for key, pupcs in sorted(runs.items(), key=lambda kv: (len(kv[0]), kv[0])):
                subdomains, b = key[:2]
                if len(key) == 3:  # --against: its LAMMPS ratio, and this build's over it
                    ours = [x / y for x, y in zip(runs[(subdomains, b)], pupcs)]
                    vs_lmp = statistics.median(x / y for x, y in zip(pupcs, theirs[scene]))
                    print(f"| {scene.upper()} | {grains} | {b} | {subdomains}, --against | "
                          f"{statistics.median(pupcs):.3e} | {min(pupcs):.3e}–{max(pupcs):.3e} "
                          f"| | {vs_lmp:.2f} |  this build / --against: "
                          f"{statistics.median(ours):.3f} ({min(ours):.3f}–{max(ours):.3f})",
                          flush=True)
                    continue
                one = runs[(subdomains, a.blocks[0])]
                vs_one = statistics.median(x / y for x, y in zip(pupcs, one))
                vs_lmp = statistics.median(x / y for x, y in zip(pupcs, theirs[scene]))
                print(f"| {scene.upper()} | {grains} | {b} | {subdomains} | "
                      f"{statistics.median(pupcs):.3e} | {min(pupcs):.3e}–{max(pupcs):.3e} | "
                      f"{vs_one:.2f} | {vs_lmp:.2f} |", flush=True)
            lmp = theirs[scene]
            print(f"| {scene.upper()} | {grains} | LAMMPS | | {statistics.median(lmp):.3e} | "
                  f"{min(lmp):.3e}–{max(lmp):.3e} | | |", flush=True)
    csv_path = os.path.join(a.out, f"blocks_per_rank_np{a.ranks}.csv")
    with open(csv_path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(["scene", "ranks", "subdomains", "blocks_per_rank", "repeat", "grains",
                    "steps", "loop_s", "pupcs", "sync_s", "contact_s", "integrate_s",
                    "shadows", "peak_rss_bytes", "build"])
        w.writerows(rows)
    if a.chart:
        chart(a.chart, [csv_path])


if __name__ == "__main__":
    main()
