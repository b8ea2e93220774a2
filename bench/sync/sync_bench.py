#!/usr/bin/python3
"""Synchronisation figures from `regolith` run summaries, on the sparse granular gas
of scenes/granular-gas.toml:

  pupcs  PUpCS of NNS, SOS and hybrid on the same scene and rank count, runs alternating
         (nns, sos, hybrid, nns, ...) so that a change of machine load hits every method alike;
         reported as the median over the repeats and as ratios to NNS.
  comm   messages, bytes and distinct peers per rank per step of the synchronisation for
         1, 2, 3, 4, 8 (and 27) ranks, one block of 10^3 grains per rank (weak scaling),
         --comm-steps steps each (--steps is the pupcs part's).

usage: sync_bench.py --build build/default --out bench/out [--repeats 3] [--steps 200]
                     [--ranks 2] [--box 40] [--comm-ranks 1 2 3 4 8 27] [--comm-steps 50]

Writes <out>/sync_pupcs.csv, <out>/sync_comm.csv and prints Markdown tables for
docs/results.md. Not a test: it asserts nothing about time.
"""
import argparse
import csv
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from run_summary import run_app  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "scenes", "granular-gas.toml")
METHODS = ("nns", "sos", "hybrid")


def run(app, ranks, args):
    """Runs the granular gas scene with `app` on `ranks` ranks; returns its run summary."""
    return run_app(app, ranks, [SCENE, *args])


def layout(ranks):
    """One block per rank in the most cubic grid of `ranks` blocks (as apps/scenarios/RankGrid
    lays out the granular gas)."""
    best = (ranks, 1, 1)
    for x in range(1, ranks + 1):
        for y in range(1, ranks + 1):
            if ranks % (x * y) == 0:
                z = ranks // (x * y)
                if max(x, y, z) - min(x, y, z) < max(best) - min(best):
                    best = (x, y, z)
    return sorted(best, reverse=True)


def lattice(a, extent):
    """The lattice region: shifted by --offset so that one layer of grains straddles every
    block face from the start (sites at offset + 0.5 + i; the paper's gas has none there)."""
    o = a.offset
    return ["--set", f"particles[0].region={{min=[{o},{o},{o}],max=[{extent[0]},{extent[1]},"
            f"{extent[2]}]}}"]


def bench_pupcs(app, a, out):
    box = a.box
    blocks = layout(a.ranks)
    per_rank = [1, 1, 1] if a.blocks is None else [b // g for b, g in zip(a.blocks, blocks)]
    blocks = [g * p for g, p in zip(blocks, per_rank)]
    common = ["--steps", str(a.steps), "--set", "granular_gas.scaling=strong",
              "--set", f"granular_gas.box=[{box},{box},{box}]",
              "--set", f"granular_gas.blocks_per_rank=[{per_rank[0]},{per_rank[1]},{per_rank[2]}]",
              *lattice(a, (box, box, box))]
    samples = {m: [] for m in METHODS}
    rows = []
    for repeat in range(a.repeats):
        for method in METHODS:
            s = run(app, a.ranks, common + ["--set", f"sync.method={method}"])
            samples[method].append(s["pupcs"])
            rows.append([repeat, method, a.ranks, "x".join(map(str, blocks)), s["particles"],
                         s["steps"], s["wall_s"], s["pupcs"], s["timing_s"]["sync"],
                         s["timing_s"]["contact"], s["timing_s"]["integrate"]])
    with open(os.path.join(out, "sync_pupcs.csv"), "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(["repeat", "method", "ranks", "blocks", "particles", "steps", "wall_s",
                    "pupcs", "sync_s", "contact_s", "integrate_s"])
        w.writerows(rows)
    nns = statistics.median(samples["nns"])
    print(f"\nPUpCS, sparse gas (lattice offset {a.offset}) {box}^3 = {rows[0][4]} grains, {a.ranks} ranks, blocks "
          f"{'x'.join(map(str, blocks))}, {a.steps} steps, median of {a.repeats} alternating "
          "runs\n")
    print("| method | PUpCS (median) | min | max | ratio to NNS (median of per-repeat ratios) |")
    print("|---|---|---|---|---|")
    for m in METHODS:
        ratios = [p / n for p, n in zip(samples[m], samples["nns"])]
        print(f"| {m} | {statistics.median(samples[m]):.3e} | {min(samples[m]):.3e} | "
              f"{max(samples[m]):.3e} | {statistics.median(ratios):.3f} "
              f"(range {min(ratios):.3f}–{max(ratios):.3f}) |")
    return nns


def bench_comm(app, a, out):
    rows = []
    for ranks in a.comm_ranks:
        bx, by, bz = layout(ranks)
        edge = 10
        extent = (bx * edge, by * edge, bz * edge)
        args = ["--steps", str(a.comm_steps),
                "--set", f"granular_gas.per_rank=[{edge},{edge},{edge}]",
                *lattice(a, extent)]
        for method in METHODS:
            s = run(app, ranks, args + ["--set", f"sync.method={method}"])
            c = s["comm"]
            rows.append([ranks, f"{bx}x{by}x{bz}", method, s["particles"],
                         c["messages_per_step"] / ranks, c["bytes_per_step"] / ranks,
                         c["max_peers"], s["shadows"]])
    with open(os.path.join(out, "sync_comm.csv"), "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(["ranks", "blocks", "method", "particles", "messages_per_rank_step",
                    "bytes_per_rank_step", "max_peers", "shadows"])
        w.writerows(rows)
    print(f"\nSynchronisation traffic per rank and step, sparse gas, one block of 10^3 grains "
          f"per rank, periodic, lattice offset {a.offset} (a layer of grains on every block face), "
          f"{a.comm_steps} steps\n")
    print("| ranks | blocks | method | messages / rank / step | bytes / rank / step | "
          "max peers | shadows |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r[0]} | {r[1]} | {r[2]} | {r[4]:.1f} | {r[5]:.0f} | {r[6]} | {r[7]} |")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build", "default"))
    p.add_argument("--out", default=os.path.join(ROOT, "bench", "out"))
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--steps", type=int, default=200)
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--box", type=int, default=40)
    p.add_argument("--blocks", type=int, nargs=3, default=None)
    p.add_argument("--comm-ranks", type=int, nargs="*", default=[1, 2, 3, 4, 8, 27])
    p.add_argument("--comm-steps", type=int, default=50)
    p.add_argument("--offset", type=float, default=0.3)
    p.add_argument("--only", choices=("pupcs", "comm"), default=None)
    a = p.parse_args()
    app = os.path.join(a.build, "bin", "regolith")
    os.makedirs(a.out, exist_ok=True)
    if a.only in (None, "pupcs"):
        bench_pupcs(app, a, a.out)
    if a.only in (None, "comm"):
        bench_comm(app, a, a.out)


if __name__ == "__main__":
    main()
