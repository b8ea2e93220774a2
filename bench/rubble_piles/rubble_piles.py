#!/usr/bin/python3
"""Rubble-pile figures from the app spin_up (docs/guide/rubble-piles.md):

  chart CSV [CSV ...]  draws a record of spin_up (pile.file): spin / omega_c, the equivalent
                       ellipsoid's axes, the mass shed and the largest remnant against time,
                       to CSV's name with .png
  spin-up              runs scenes/spin-up.toml (or --scene) at each --rates, --repeats times,
                       and prints the failure spin (the peak spin over omega_c) and the spin
                       at which mass was first shed; writes <out>/spin_up_rates.csv and the
                       first run's chart
  cost                 the CPU time per step of scenes/spin-up.toml scaled to --grains grains
                       (a sphere packed to 0.24: radius 22.1 for 20,000), from runs of
                       --cost-steps steps (the difference of a long and a short run, so the
                       packing and set-up cancel), alternated --repeats times; prints the
                       median and range, and the hours a spin-up of --estimate-steps takes at
                       that cost on 2 cores
  flyby                runs scenes/flyby.toml at each --periapses (Roche radii) and draws the
                       mass lost (1 - largest remnant) and the mass shed against periapsis:
                       <out>/flyby.csv and <out>/flyby.png

usage: rubble_piles.py chart CSV... | spin-up [--rates 0.05] [--repeats 1] [--steps N] |
       cost [--grains 20000] [--cost-steps 200 600] [--estimate-steps 18000] |
       flyby [--periapses 0.4 0.5 0.6 0.8 1.0]
       [--build build/default] [--ranks 2] [--out bench/out/rubble_piles] [--set KEY=VALUE ...]
       [--images docs/images] [--no-chart]
"""
import argparse
import csv
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MPI_ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def read_record(path):
    """The record's header values (# key=value ...) and its rows as dicts of floats."""
    with open(path, encoding="utf-8") as f:
        header = dict(kv.split("=") for kv in f.readline()[1:].split())
        rows = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]
    return {k: float(v) for k, v in header.items()}, rows


def chart(path, title=None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    header, rows = read_record(path)
    t = [r["time"] for r in rows]
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(6.4, 6.0))
    top.plot(t, [r["spin_over_omega_c"] for r in rows], label="spin / omega_c")
    top.axhline(1.0, color="grey", lw=0.8, ls="--")
    if "perturber_distance" in rows[0]:
        top.plot(t, [r["perturber_distance"] for r in rows], label="perturber distance [Roche radii]")
    top.set_ylabel("spin / omega_c")
    top.legend(loc="upper left")
    twin = top.twinx()
    for key, style in (("axis_a", "-"), ("axis_b", "--"), ("axis_c", ":")):
        twin.plot(t, [r[key] / header["bulk_radius"] for r in rows], "k" + style, lw=0.8,
                  label=key.replace("axis_", "") + " / R0")
    twin.set_ylabel("semi-axes / initial bulk radius")
    twin.legend(loc="center left")
    bottom.plot(t, [r["shed_fraction"] for r in rows], label="mass shed")
    bottom.plot(t, [1.0 - r["remnant_fraction"] for r in rows], label="1 - largest remnant")
    bottom.set_xlabel("time (from the end of the settling)")
    bottom.set_ylabel("fraction of the initial mass")
    bottom.legend(loc="best")
    fig.suptitle(title or os.path.basename(path))
    fig.tight_layout()
    png = os.path.splitext(path)[0] + ".png"
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return png


def run_app(args, scene, out, sets):
    program = os.path.join(os.path.abspath(args.build), "bin", "spin_up")
    if not os.path.exists(program):
        sys.exit(f"{program} is missing: build first (make build)")
    os.makedirs(out, exist_ok=True)
    cmd = ["mpiexec", "--oversubscribe", "-n", str(args.ranks), program, scene, "--output", out]
    for s in list(sets) + list(args.set):
        cmd += ["--set", s]
    result = subprocess.run(cmd, cwd=ROOT, env=MPI_ENV, capture_output=True, text=True,
                            check=False)
    open(os.path.join(out, "spin_up.log"), "w", encoding="utf-8").write(result.stdout +
                                                                       result.stderr)
    if result.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed:\n{result.stdout}{result.stderr}")
    return result.stdout


def spin(text, what):
    m = re.search(what + r" ([0-9.]+) omega_c", text)
    return float(m.group(1)) if m else float("nan")


def spin_up(args):
    scene = args.scene or os.path.join(ROOT, "scenes", "spin-up.toml")
    rows = []
    for rate in args.rates:
        for k in range(args.repeats):
            out = os.path.join(args.out, f"spin_up_rate{rate}_{k}")
            sets = [f"spin_up.rate={rate}", "pile.file=spin_up.csv"]
            if args.steps:
                sets.append(f"time.steps={args.steps}")
            text = run_app(args, scene, out, sets)
            rows.append({"rate": rate, "repeat": k,
                         "failure_spin": spin(text, r"failure \(peak spin\)"),
                         "shedding_spin": spin(text, "mass shed from"),
                         "omega_c": float(re.search(r"omega_c ([0-9.]+)", text).group(1))})
            print(rows[-1], flush=True)
            if args.chart:
                png = chart(os.path.join(out, "spin_up.csv"), f"spin-up at {rate} omega_c^2")
                if args.images and k == 0:
                    shutil.copy(png, os.path.join(args.images, f"spin_up_rate{rate}.png"))
    with open(os.path.join(args.out, "spin_up_rates.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def cpu_seconds(args, scene, out, sets):
    """CPU time (user + system) of one run of the app, its ranks' summed."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    run_app(args, scene, out, sets)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def cost(args):
    scene = args.scene or os.path.join(ROOT, "scenes", "spin-up.toml")
    # Grains of radius 0.4-0.6 (mean r^3 = 0.13) at packing 0.24: 22.1 for 20,000.
    radius = (args.grains * 0.13 / 0.24) ** (1.0 / 3.0)
    edge = 4.0 * radius
    base = [f"particles[0].count={args.grains}", f"particles[0].radius={radius:.6g}",
            f"domain.min=[{-edge:.6g},{-edge:.6g},{-edge:.6g}]",
            f"domain.max=[{edge:.6g},{edge:.6g},{edge:.6g}]", "pile.settle_steps=100",
            "pile.record_every=100"]
    short, long = args.cost_steps
    per_step = []
    for k in range(args.repeats):
        cpu = {n: cpu_seconds(args, scene, os.path.join(args.out, f"cost{n}"),
                              base + [f"time.steps={n}"]) for n in (short, long)}
        per_step.append((cpu[long] - cpu[short]) / (long - short))
        print(f"run {k}: {cpu}: {per_step[-1]:.4g} CPU-s per step", flush=True)
    med = statistics.median(per_step)
    print(f"{args.grains} grains, {args.ranks} ranks: {med:.4g} CPU-s per step (range "
          f"{min(per_step):.4g}-{max(per_step):.4g}, {len(per_step)} pairs); "
          f"{args.estimate_steps} steps on 2 cores: {args.estimate_steps * med / 2 / 3600:.3g} h")


def flyby(args):
    scene = args.scene or os.path.join(ROOT, "scenes", "flyby.toml")
    rows = []
    for q in args.periapses:
        out = os.path.join(args.out, f"flyby_q{q}")
        run_app(args, scene, out, [f"flyby.periapsis={q}", "pile.file=flyby.csv"])
        _, record = read_record(os.path.join(out, "flyby.csv"))
        last = record[-1]
        rows.append({"periapsis": q, "mass_lost": 1.0 - last["remnant_fraction"],
                     "shed": last["shed_fraction"], "clusters": int(last["clusters"]),
                     "final_distance": last["perturber_distance"]})
        print(rows[-1], flush=True)
    with open(os.path.join(args.out, "flyby.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    if args.chart:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(5.6, 3.8))
        q = [r["periapsis"] for r in rows]
        ax.plot(q, [r["mass_lost"] for r in rows], "o-", label="1 - largest remnant")
        ax.plot(q, [r["shed"] for r in rows], "s--", label="beyond pile.radius")
        ax.set_xlabel("periapsis [Roche radii]")
        ax.set_ylabel("fraction of the pile's mass")
        ax.set_title("rubble pile passing a point mass (scenes/flyby.toml)")
        ax.legend(loc="best")
        fig.tight_layout()
        fig.savefig(os.path.join(args.out, "flyby.png"), dpi=110)
        if args.images:
            shutil.copy(os.path.join(args.out, "flyby.png"),
                        os.path.join(args.images, "flyby_mass_lost.png"))


def add_run_options(p):
    """The options every rubble-pile script shares: where the app is, where its runs go, on how
    many ranks, scene overrides and the charts."""
    p.add_argument("--build", default=os.path.join(ROOT, "build", "default"))
    p.add_argument("--out", default=os.path.join(ROOT, "bench", "out", "rubble_piles"))
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--set", action="append", default=[], help="a scene override, repeated")
    p.add_argument("--no-chart", dest="chart", action="store_false")
    p.add_argument("--images", help="a folder the charts are copied to too (docs/images)")


def parse_run_options(p):
    """The arguments, the folders made absolute (the runs start in the repository) and made
    where a run writes into them."""
    args = p.parse_args()
    args.out = os.path.abspath(args.out)
    if args.images:
        args.images = os.path.abspath(args.images)
    if getattr(args, "what", None) != "chart":
        os.makedirs(args.out, exist_ok=True)
        if args.images:
            os.makedirs(args.images, exist_ok=True)
    return args


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("what", choices=["chart", "spin-up", "cost", "flyby"])
    p.add_argument("csv", nargs="*", help="chart: the records to draw")
    add_run_options(p)
    p.add_argument("--scene")
    p.add_argument("--rates", type=float, nargs="+", default=[0.05])
    p.add_argument("--repeats", type=int, default=1)
    p.add_argument("--steps", type=int, help="spin-up: time.steps (the scene's by default)")
    p.add_argument("--grains", type=int, default=20000)
    p.add_argument("--cost-steps", type=int, nargs=2, default=[200, 600])
    p.add_argument("--estimate-steps", type=int, default=18000)
    p.add_argument("--periapses", type=float, nargs="+", default=[0.4, 0.5, 0.6, 0.8, 1.0])
    args = parse_run_options(p)
    if args.what == "chart":
        for path in args.csv:
            print(chart(path))
    elif args.what == "spin-up":
        spin_up(args)
    elif args.what == "cost":
        cost(args)
    else:
        flyby(args)


if __name__ == "__main__":
    main()
