#!/usr/bin/python3
"""The failure spin of a rubble pile against its cohesive strength (docs/guide/rubble-piles.md):
scenes/spin-up.toml (or --scene) spun up to failure without cohesion and with van der Waals
cohesion (contact.model = "vdw") of each --pull-offs, --repeats piles each (seeds 3, 4, ...).

The cohesion of a contact is its pull-off force F_c = A R* / (6 s_min^2) (the vdW model's
force in overlap), set through the Hamaker constant A for a pair of mean grains (R* = r / 2);
the pile's bulk cohesion follows from Rumpf's relation for a packing of porosity n,

    Y = (1 - n) / n * F_c / d^2          (Rumpf 1962, k n ~ pi; d the mean grain diameter),

n from the bulk density the app measures after the settling. Sánchez & Scheeres (2014) take a
rubble pile's strength as this grain-scale cohesion averaged over the packing and compare the
spin it allows with Holsapple's Drucker–Prager limit for a sphere (Holsapple 2004, 2007),

    omega_f^2 = omega_0^2 + 10 cos(phi) / (1 + sin(phi)) * Y / (rho R^2),
    omega_0^2 / omega_c^2 = 2 sin(phi) / (1 + sin(phi)),

omega_0 the cohesionless failure spin, which fixes the friction angle phi. The tree's field
is recomputed on the adaptive schedule (gravity.update_every; the pile changes slowly). Writes
<out>/cohesive_spin_up.csv (one row a run), fits (omega_f^2 - omega_0^2) / omega_c^2 =
a (Y / (rho R^2 omega_c^2))^beta to the cohesive runs, prints a and beta against the
Drucker–Prager a_DP and beta = 1, and draws <out>/cohesive_spin_up.png.

usage: cohesive_spin_up.py [--pull-offs 2 4 8 16 32] [--repeats 2] [--steps 35000]
       [--final-spin 2.0] [--ranks 2] [--build build/default] [--out bench/out/rubble_piles]
       [--set KEY=VALUE ...] [--images docs/images] [--no-chart]
"""
import argparse
import csv
import math
import os
import re
import shutil
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rubble_piles import (ROOT, add_run_options, parse_run_options, run_app,  # noqa: E402
                          spin)

MEAN_GRAIN_RADIUS = 0.5     # scenes/spin-up.toml: grain radii 0.4-0.6
MIN_SEPARATION = 0.01       # s_min: 2 % of a mean grain's radius
CUTOFF = 0.05               # s_c: the attraction reaches a tenth of a mean radius


def reference(text):
    """The pile's mass, bulk radius, bulk density and omega_c the app printed."""
    m = re.search(r"rubble pile: mass ([0-9.e+-]+), bulk radius ([0-9.e+-]+), bulk density "
                  r"([0-9.e+-]+), omega_c ([0-9.e+-]+)", text)
    return [float(v) for v in m.groups()]


def run_pile(args, scene, pull_off, seed):
    out = os.path.join(args.out, f"cohesive_spin_up_F{pull_off:g}_seed{seed}")
    sets = [f"particles[0].seed={seed}", f"spin_up.final_spin={args.final_spin}",
            f"time.steps={args.steps}", "pile.file=spin_up.csv",
            'gravity.update_every="adaptive"']
    hamaker = 0.0
    if pull_off > 0:
        hamaker = 6.0 * MIN_SEPARATION**2 * pull_off / (MEAN_GRAIN_RADIUS / 2.0)
        sets += ['contact.model="vdw"', f"contact.hamaker={hamaker:.6g}",
                 f"contact.min_separation={MIN_SEPARATION}", f"contact.cutoff={CUTOFF}"]
    text = run_app(args, scene, out, sets)
    _, radius, density, omega_c = reference(text)
    porosity = 1.0 - density  # grain density 1 (scenes/spin-up.toml)
    bulk_cohesion = (1.0 - porosity) / porosity * pull_off / (2.0 * MEAN_GRAIN_RADIUS)**2
    return {"pull_off": pull_off, "hamaker": hamaker, "seed": seed, "bulk_radius": radius,
            "bulk_density": density, "omega_c": omega_c, "bulk_cohesion": bulk_cohesion,
            "strength": bulk_cohesion / (density * radius**2 * omega_c**2),
            "failure_spin": spin(text, r"failure \(peak spin\)"),
            "shedding_spin": spin(text, "mass shed from")}


def linear_coefficient(rows, w0):
    """The least-squares a of (omega_f^2 - omega_0^2) / omega_c^2 = a Y' (the power 1 of the
    Drucker–Prager limit): a / a_DP is the share of Rumpf's cohesion the pile shows."""
    pts = [(r["strength"], r["failure_spin"]**2 - w0**2) for r in rows
           if r["pull_off"] > 0 and not math.isnan(r["failure_spin"])]
    return sum(x * y for x, y in pts) / sum(x * x for x, _ in pts) if pts else float("nan")


def fit(rows):
    """omega_0 / omega_c (median of the cohesionless runs), the friction angle it implies, the
    Drucker–Prager coefficient, and the least-squares power law through the cohesive runs."""
    w0 = statistics.median(r["failure_spin"] for r in rows if r["pull_off"] == 0)
    sin_phi = w0**2 / (2.0 - w0**2)
    a_dp = 10.0 * math.sqrt(1.0 - sin_phi**2) / (1.0 + sin_phi)
    pts = [(math.log(r["strength"]), math.log(r["failure_spin"]**2 - w0**2)) for r in rows
           if r["pull_off"] > 0 and r["failure_spin"] > w0 and not math.isnan(r["failure_spin"])]
    if len(pts) < 2:
        return w0, math.degrees(math.asin(sin_phi)), a_dp, float("nan"), float("nan")
    mx = statistics.fmean(x for x, _ in pts)
    my = statistics.fmean(y for _, y in pts)
    beta = sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx)**2 for x, _ in pts)
    return w0, math.degrees(math.asin(sin_phi)), a_dp, math.exp(my - beta * mx), beta


def chart(args, rows, w0, a_dp, a, beta):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cohesive = [r for r in rows if r["pull_off"] > 0 and not math.isnan(r["failure_spin"])]
    if math.isnan(w0) or not cohesive:
        print("no chart: a pile did not fail (raise --steps)")
        return
    fig, ax = plt.subplots(figsize=(6.0, 4.2))
    ax.plot([r["strength"] for r in cohesive], [r["failure_spin"] for r in cohesive], "o",
            label="measured (vdW cohesion)")
    xs = [r["strength"] for r in cohesive]
    grid = [min(xs) * (max(xs) / min(xs))**(k / 50.0) for k in range(51)]
    ax.plot(grid, [math.sqrt(w0**2 + a_dp * x) for x in grid], "k--",
            label=f"Drucker–Prager, Y from Rumpf ({a_dp:.2f} Y')")
    if not math.isnan(beta):
        ax.plot(grid, [math.sqrt(w0**2 + a * x**beta) for x in grid], "C1-",
                label=f"fit: {a:.2f} Y'^{beta:.2f}")
    ax.axhline(1.0, color="grey", lw=0.8, ls=":")
    ax.axhline(w0, color="C0", lw=0.8, ls=":", label=f"cohesionless: {w0:.3f}")
    ax.set_xscale("log")
    ax.set_xlabel("bulk cohesion Y' = Y / (rho R^2 omega_c^2)")
    ax.set_ylabel("failure spin / omega_c")
    ax.set_title("cohesive rubble pile spun up to failure (scenes/spin-up.toml)")
    ax.legend(loc="upper left", fontsize=8)
    fig.tight_layout()
    png = os.path.join(args.out, "cohesive_spin_up.png")
    fig.savefig(png, dpi=110)
    plt.close(fig)
    if args.images:
        shutil.copy(png, os.path.join(args.images, "cohesive_spin_up.png"))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_run_options(p)
    p.add_argument("--scene", default=os.path.join(ROOT, "scenes", "spin-up.toml"))
    p.add_argument("--pull-offs", type=float, nargs="+", default=[2.0, 4.0, 8.0, 16.0, 32.0],
                   help="F_c of a pair of mean grains; the cohesionless pile is always run")
    p.add_argument("--repeats", type=int, default=2)
    p.add_argument("--steps", type=int, default=35000)
    p.add_argument("--final-spin", type=float, default=2.0)
    args = parse_run_options(p)
    rows = []
    for pull_off in [0.0] + args.pull_offs:
        for k in range(args.repeats):
            rows.append(run_pile(args, args.scene, pull_off, 3 + k))
            print({k: round(v, 4) if isinstance(v, float) else v for k, v in rows[-1].items()},
                  flush=True)
    with open(os.path.join(args.out, "cohesive_spin_up.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    w0, phi, a_dp, a, beta = fit(rows)
    a1 = linear_coefficient(rows, w0)
    print(f"cohesionless failure {w0:.3f} omega_c: friction angle {phi:.1f} deg; Drucker-Prager "
          f"(omega_f^2 - omega_0^2) / omega_c^2 = {a_dp:.3f} Y'; fit {a:.3f} Y'^{beta:.3f}; "
          f"fit at the power 1: {a1:.3f} Y' = {a1 / a_dp:.3f} of Drucker-Prager's")
    for pull_off in args.pull_offs:
        spins = [r["failure_spin"] for r in rows if r["pull_off"] == pull_off]
        ys = [r["strength"] for r in rows if r["pull_off"] == pull_off]
        x = statistics.median(ys)
        print(f"F_c {pull_off:g}: Y' {x:.4g}, failure {statistics.median(spins):.3f} omega_c "
              f"(range {min(spins):.3f}-{max(spins):.3f}); Drucker-Prager "
              f"{math.sqrt(w0**2 + a_dp * x):.3f}")
    if args.chart:
        chart(args, rows, w0, a_dp, a, beta)


if __name__ == "__main__":
    main()
