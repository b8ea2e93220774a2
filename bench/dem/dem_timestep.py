#!/usr/bin/python3
"""DEM time-step charts on an elastic granular gas (scenes/granular-gas.toml with
restitution 1 and no friction, run by `regolith`): total energy is then kinetic + the normal
springs' energy (elastic_energy.py), so its drift is the integrator's error.

  sweep  energy error and PUpCS against the time step at the scene's stiffness, dt a fraction
         of the contact time t_c (a fixed simulated time, so smaller steps make more steps);
         the paper's gas (v in [-0.1, 0.1]), 20^3 grains, one rank, PUpCS the median of 3.
  map    stability map: time step against contact stiffness on a hot gas (v in [-1, 1]), one
         rank; each run is stable, loses energy conservation (|ΔE| / E > --energy-limit, or the
         run breaks down) or lets grains pass through each other (a final overlap deeper than
         a grain radius); the failure regions are shaded, with the t_c/20 rule of
         time.dt = "auto" (apps/regolith/AutoChoices.cpp) and the t_c/10 guard as lines.

usage: dem_timestep.py [sweep|map ...] [--build build/default] [--out bench/out]
                       [--fractions 80 40 20 10 5 3] [--sweep-box 20] [--sweep-time 20]
                       [--sweep-ranks 1] [--repeats 3]
                       [--stiffness 0.3 1 3 ... 3000] [--map-dt-min 2e-4] [--map-dt-count 13]
                       [--map-time 4] [--no-docs]

Writes <out>/dem_timestep.csv, <out>/dem_stability.csv and the charts dem-timestep.png,
dem-stability.png (copied to docs/images/). A benchmark: it asserts nothing.
"""
import argparse
import math
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from chart_output import ROOT, pyplot, save_chart, write_csv  # noqa: E402
from elastic_energy import run_with_dump, total_energy  # noqa: E402

SCENE = os.path.join(ROOT, "scenes", "granular-gas.toml")
RADIUS = 0.4   # the scene's grains (sc lattice of spacing 1, density 1)
DENSITY = 1.0


def contact_time(stiffness):
    """t_c of two equal grains of the scene, undamped linear spring: π sqrt(m_eff / k)."""
    mass = 4.0 / 3.0 * math.pi * RADIUS ** 3 * DENSITY
    return math.pi * math.sqrt(0.5 * mass / stiffness)


def gas_args(box, stiffness, dt, steps, speed):
    return [SCENE, "--steps", str(steps),
            "--set", "granular_gas.scaling=strong",
            "--set", f"granular_gas.box=[{box},{box},{box}]",
            "--set", "contact.restitution=1.0", "--set", "contact.friction=0.0",
            "--set", f"contact.stiffness={stiffness!r}", "--set", f"time.dt={dt!r}",
            "--set", "time.allow_unstable=true",
            "--set", f"particles[0].velocity={{ random = [{-speed}, {speed}], seed = 1 }}"]


_INITIAL = {}


def initial_energy(app, ranks, box, stiffness, speed):
    """Total energy of the initial state (a run of 0 steps), once per set-up."""
    key = (ranks, box, stiffness, speed)
    if key not in _INITIAL:
        s, rows, _, message = run_with_dump(app, ranks, gas_args(box, stiffness, 1.0, 0, speed))
        if s is None:
            sys.exit(f"dem_timestep: the initial state did not run: {message}")
        _INITIAL[key] = total_energy(s, rows, stiffness, box)[0]
    return _INITIAL[key]


def measure(a, ranks, box, stiffness, dt, sim_time, speed):
    """One run of the elastic gas for `sim_time`; returns a dict with the relative energy
    error, the deepest final overlap / radius, PUpCS and the run's status."""
    app = os.path.join(a.build, "bin", "regolith")
    steps = max(1, round(sim_time / dt))
    e0 = initial_energy(app, ranks, box, stiffness, speed)
    s, rows, code, message = run_with_dump(app, ranks, gas_args(box, stiffness, dt, steps, speed),
                                           timeout=a.timeout)
    result = {"stiffness": stiffness, "dt": dt, "tc": contact_time(stiffness), "steps": steps,
              "grains": "", "energy_error": "", "deepest_overlap": "", "pupcs": "",
              "status": "ran", "message": ""}
    if s is None:
        result.update(status="failed", message=f"exit {code}: {message}")
        return result
    e1, deepest = total_energy(s, rows, stiffness, box)
    result.update(grains=s["particles"], energy_error=(e1 - e0) / e0, deepest_overlap=deepest,
                  pupcs=s["pupcs"])
    return result


FIELDS = ["stiffness", "dt", "tc", "dt_over_tc", "steps", "grains", "energy_error",
          "deepest_overlap", "pupcs", "status", "message"]


def as_row(r):
    return [r["stiffness"], r["dt"], r["tc"], r["dt"] / r["tc"], r["steps"], r["grains"],
            r["energy_error"], r["deepest_overlap"], r["pupcs"], r["status"], r["message"]]


def sweep(a, plt):
    tc = contact_time(a.sweep_stiffness)
    results = []
    print(f"sweep: k = {a.sweep_stiffness:g}, t_c = {tc:.4g}, box {a.sweep_box}^3, "
          f"{a.sweep_ranks} ranks, simulated time {a.sweep_time:g}")
    for n in a.fractions:
        # Repeats for PUpCS only (the machine's load moves it); the energy is the first run's.
        runs = [measure(a, a.sweep_ranks, a.sweep_box, a.sweep_stiffness, tc / n, a.sweep_time,
                        0.1) for _ in range(a.repeats)]
        r = runs[0]
        speeds = sorted(x["pupcs"] for x in runs if x["status"] == "ran")
        if speeds:
            r.update(pupcs=statistics.median(speeds), pupcs_min=speeds[0], pupcs_max=speeds[-1])
        results.append(r)
        print(f"  dt = t_c/{n:g}: {r['steps']} steps, energy error {r['energy_error']}, "
              f"PUpCS {r['pupcs']} ({speeds[0] if speeds else ''}-{speeds[-1] if speeds else ''})"
              f" {r['status']} {r['message']}", flush=True)
    write_csv(os.path.join(a.out, "dem_timestep.csv"), FIELDS + ["pupcs_min", "pupcs_max"],
              [as_row(r) + [r.get("pupcs_min", ""), r.get("pupcs_max", "")] for r in results])

    fig, (ax_e, ax_p) = plt.subplots(1, 2, figsize=(12, 4.6))
    ok = [r for r in results if r["status"] == "ran"]
    x = [r["dt"] / r["tc"] for r in ok]
    gain = [r for r in ok if r["energy_error"] > 0]
    loss = [r for r in ok if r["energy_error"] <= 0]
    ax_e.plot(x, [abs(r["energy_error"]) for r in ok], "-", color="tab:blue")
    ax_e.plot([r["dt"] / r["tc"] for r in gain], [r["energy_error"] for r in gain], "^",
              color="tab:red", label="energy gained")
    ax_e.plot([r["dt"] / r["tc"] for r in loss], [-r["energy_error"] for r in loss], "v",
              color="tab:blue", label="energy lost")
    if len(ok) >= 2:  # guides: errors growing like dt and like dt², through the middle point
        mid = ok[len(ok) // 2]
        x0, y0 = mid["dt"] / mid["tc"], abs(mid["energy_error"])
        for power, style in ((1, ":"), (2, "--")):
            ax_e.plot(x, [y0 * (xi / x0) ** power for xi in x], style, color="grey",
                      linewidth=0.8, label=f"∝ dt^{power}")
    ax_e.set_yscale("log")
    ax_e.set_ylabel("|E_end − E_0| / E_0  (kinetic + spring)")
    ax_e.set_title(f"Energy error after simulated time {a.sweep_time:g}")
    ax_p.errorbar(x, [r["pupcs"] for r in ok],
                  yerr=[[r["pupcs"] - r["pupcs_min"] for r in ok],
                        [r["pupcs_max"] - r["pupcs"] for r in ok]],
                  fmt="o-", color="tab:green", capsize=3, label=f"median of {a.repeats} (range)")
    ax_p.legend(fontsize=8)
    ax_p.set_ylabel("PUpCS")
    ax_p.set_ylim(bottom=0)
    ax_p.set_title(f"PUpCS ({ok[0]['grains'] if ok else '?'} grains, {a.sweep_ranks} "
                   f"rank(s))")
    for ax in (ax_e, ax_p):
        ax.set_xscale("log")
        ax.axvline(1 / 20, color="black", linestyle="--", linewidth=1)
        ax.axvline(1 / 10, color="tab:red", linestyle=":", linewidth=1)
        ax.text(1 / 20, 0.02, " t_c/20 (auto)", transform=ax.get_xaxis_transform(), fontsize=7)
        ax.text(1 / 10, 0.08, " t_c/10 (guard)", transform=ax.get_xaxis_transform(), fontsize=7,
                color="tab:red")
        ax.set_xticks([r["dt"] / r["tc"] for r in results])
        ax.set_xticklabels([f"1/{r['tc'] / r['dt']:.3g}" for r in results], fontsize=8)
        ax.minorticks_off()
        ax.set_xlabel("dt / t_c")
        ax.grid(True, which="both", alpha=0.25)
    ax_e.legend(fontsize=8)
    fig.suptitle(f"Elastic granular gas (e = 1, no friction, k = {a.sweep_stiffness:g}, "
                 f"t_c = {tc:.3g}): time step against energy error and speed", fontsize=11)
    fig.tight_layout()
    save_chart(fig, a.out, "dem-timestep", not a.no_docs)


def classify(r, energy_limit):
    if r["status"] != "ran" or not math.isfinite(r["energy_error"]):
        return "blow-up"
    if abs(r["energy_error"]) > energy_limit:
        return "blow-up"
    if r["deepest_overlap"] > 1.0:
        return "pass-through"
    return "stable"


def stability_map(a, plt):
    dts = [a.map_dt_min * 2 ** i for i in range(a.map_dt_count)]
    results = []
    for k in a.stiffness:
        for dt in dts:
            r = measure(a, 1, a.map_box, k, dt, a.map_time, a.map_speed)
            r["class"] = classify(r, a.energy_limit)
            results.append(r)
            print(f"  k = {k:g} dt = {dt:.3g} (t_c/{r['tc'] / dt:.3g}): {r['class']}, energy "
                  f"{r['energy_error']}, overlap {r['deepest_overlap']} {r['message']}",
                  flush=True)
    write_csv(os.path.join(a.out, "dem_stability.csv"), FIELDS + ["class"],
              [as_row(r) + [r["class"]] for r in results])

    import numpy as np
    from matplotlib.colors import ListedColormap
    classes = ["stable", "blow-up", "pass-through"]
    grid = np.array([[classes.index(next(r["class"] for r in results
                                         if r["stiffness"] == k and r["dt"] == dt))
                      for k in a.stiffness] for dt in dts])
    # Cell edges half-way (in log) between the sampled values.
    def edges(v):
        lv = np.log10(v)
        mid = (lv[1:] + lv[:-1]) / 2
        return 10 ** np.concatenate([[2 * lv[0] - mid[0]], mid, [2 * lv[-1] - mid[-1]]])
    fig, ax = plt.subplots(figsize=(8, 7))
    ax.pcolormesh(edges(np.array(a.stiffness)), edges(np.array(dts)), grid,
                  cmap=ListedColormap(["white", "tab:red", "tab:orange"]), vmin=0, vmax=2,
                  alpha=0.35, shading="flat")
    marks = {"stable": ("o", "tab:green"), "blow-up": ("x", "tab:red"),
             "pass-through": ("s", "tab:orange")}
    labels = {"stable": "stable (|ΔE|/E ≤ {:g})".format(a.energy_limit),
              "blow-up": f"energy error > {a.energy_limit:g} or run broke down",
              "pass-through": "grains pass through (overlap > radius)"}
    for c in classes:
        pts = [(r["stiffness"], r["dt"]) for r in results if r["class"] == c]
        if pts:
            xs, ys = zip(*pts)
            ax.plot(xs, ys, marks[c][0], color=marks[c][1], linestyle="", label=labels[c])
    ks = np.logspace(math.log10(min(a.stiffness)) - 0.5, math.log10(max(a.stiffness)) + 0.5, 50)
    ax.plot(ks, [contact_time(k) / 20 for k in ks], "k--", label='t_c/20: time.dt = "auto"')
    ax.plot(ks, [contact_time(k) / 10 for k in ks], ":", color="tab:red",
            label="t_c/10: the guard (time.allow_unstable lifts it)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(ks[0], ks[-1])
    ax.set_ylim(dts[0] / 1.5, dts[-1] * 1.5)
    ax.set_xlabel("contact stiffness k (spring-dashpot, e = 1, no friction)")
    ax.set_ylabel("time step dt")
    ax.set_title(f"Where the DEM fails: hot elastic gas, {a.map_box}^3 grains, v in "
                 f"[-{a.map_speed:g}, {a.map_speed:g}], simulated time {a.map_time:g}",
                 fontsize=10)
    ax.legend(fontsize=7.5, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=2,
              frameon=False)
    ax.grid(True, which="both", alpha=0.2)
    fig.tight_layout()
    save_chart(fig, a.out, "dem-stability", not a.no_docs)


PARTS = ("sweep", "map")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("parts", nargs="*", metavar="part", help="sweep, map (default: both)")
    p.add_argument("--build", default=os.path.join(ROOT, "build", "default"))
    p.add_argument("--out", default=os.path.join(ROOT, "bench", "out"))
    p.add_argument("--fractions", type=float, nargs="*", default=[80, 40, 20, 10, 5, 3],
                   help="sweep: dt = t_c / each")
    p.add_argument("--sweep-stiffness", type=float, default=50.0)
    p.add_argument("--sweep-box", type=int, default=20)
    p.add_argument("--sweep-ranks", type=int, default=1)
    p.add_argument("--repeats", type=int, default=3, help="sweep: runs per time step (PUpCS)")
    p.add_argument("--sweep-time", type=float, default=20.0)
    p.add_argument("--stiffness", type=float, nargs="*",
                   default=[0.3, 1, 3, 10, 30, 100, 300, 1000, 3000])
    p.add_argument("--map-dt-min", type=float, default=2e-4)
    p.add_argument("--map-dt-count", type=int, default=13)
    p.add_argument("--map-box", type=int, default=6)
    p.add_argument("--map-speed", type=float, default=1.0)
    p.add_argument("--map-time", type=float, default=4.0)
    p.add_argument("--energy-limit", type=float, default=1e-2)
    p.add_argument("--timeout", type=float, default=600.0)
    p.add_argument("--no-docs", action="store_true", help="do not copy PNGs to docs/images")
    a = p.parse_args()
    unknown = [part for part in a.parts if part not in PARTS]
    if unknown:  # (argparse's choices refuse an empty list with nargs="*")
        p.error(f"unknown part {unknown[0]!r}: expected sweep or map")
    os.makedirs(a.out, exist_ok=True)
    plt = pyplot()
    for part in a.parts or PARTS:  # none named: both (what bench/run-all.sh asks for)
        {"sweep": sweep, "map": stability_map}[part](a, plt)


if __name__ == "__main__":
    main()
