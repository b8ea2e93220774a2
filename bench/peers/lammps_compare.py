#!/usr/bin/python3
"""Regolith side by side with LAMMPS: the same grains, contact model, time step and
steps on one core, runs alternating (regolith, lmp, regolith, lmp, ...) so that a change of
machine load hits both alike. Reports PUpCS (particle updates per core-second of the time-step
loop: Regolith's wall_s, LAMMPS's "Loop time") and the ratio Regolith / LAMMPS: the median of
the per-pair ratios, their range, and the ratio of each code's best run (on a virtual machine
whose speed jumps between runs by up to 1.5x, the least disturbed run of each side). The CSV
also holds each run's phases (Regolith's timers, LAMMPS's Pair / Neigh / Comm / Modify).

Cases:
  sparse   the sparse granular gas of scenes/granular-gas.toml (sc spacing 1, r = 0.4,
           velocities uniform in [-0.1, 0.1], periodic), --box^3 grains
  mesapd   MESA-PD's static "GranularGas" geometry: sc spacing 1, r = 0.6, every sphere
           overlapping its six neighbours, at rest, periodic
  ramp     the dense ramp of scenes/dense-ramp.toml (hcp of touching spheres r = 0.5, walls
           at z = 0 and 8, periodic x/y, gravity 1 tilted 30 degrees, 0.1 down the ramp),
           --box x (--box sqrt(3)/2) x 8; LAMMPS walls are fix wall/gran hooke/history with
           Regolith's sphere-wall damping (effective mass m, not m/2)

The initial state comes from Regolith itself (--steps 0 --dump) and is written as a LAMMPS data
file, so both codes start from the same bits. Contact: Regolith's spring-dashpot with k_n =
contact.stiffness, damping from the restitution e (c_n = 2 m_eff gamma), k_t = 2/7 k_n, c_t =
c_n / 2, Coulomb mu; LAMMPS pair_style gran/hooke/history with the same numbers (gamma_n = c_n /
m_eff, gamma_t = gamma_n / 2), velocity Verlet on both sides (fix nve/sphere). Both use Verlet
lists with the same skin, --skin (LAMMPS's neighbor command, Regolith's contact.neighbour_skin;
before that key existed, Regolith ran with its default r/4: 0.1 for the gas, 0.15 for the
lattice, 0.125 for the ramp). Both decide their ghost copies with a skin and only copy them
between decisions: LAMMPS always (its ghost cut-off is the pair cut-off plus the neighbour
skin), Regolith with sync.skin (scenes/README.md), set here to --skin on every Regolith run (a
later --set sync.skin=... overrides it, e.g. 0 for the paper's per-step Alg. 1). Decks:
granular.in (periodic cube), ramp.in (walls, gravity).

--set KEY=VALUE (repeatable) passes a scene override to every Regolith run, e.g.
--set time.orientation=true: the three scenes leave orientations out by default (as LAMMPS's
fix nve/sphere does; positions, velocities and spins are bit for bit the same either way),
this adds the quaternion update per grain and step.

usage: lammps_compare.py [--build build/default] [--out bench/out] [--cases sparse mesapd ramp]
                         [--box 30] [--steps 500] [--repeats 3] [--skin 0.1] [--set KEY=VALUE]
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
from dataclasses import dataclass, field

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
ENV = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}


@dataclass(frozen=True)
class Case:
    """One comparison: the Regolith scene and overrides, the contact parameters both codes
    use (passed to Regolith from here too, so that the two cannot differ), and the LAMMPS deck
    with its extra variables."""
    scene: str
    deck: str
    stiffness: float
    restitution: float
    friction: float
    dt: float
    args: list = field(default_factory=list)
    extent: tuple = (0.0, 0.0, 0.0)
    lammps_vars: dict = field(default_factory=dict)

    def regolith_args(self, overrides=()):
        """The --set arguments of the Regolith runs: the case's, its contact parameters and
        time step, then `overrides` (KEY=VALUE)."""
        out = list(self.args)
        for key, value in (("contact.stiffness", self.stiffness),
                           ("contact.restitution", self.restitution),
                           ("contact.friction", self.friction), ("time.dt", self.dt)):
            out += ["--set", f"{key}={value!r}"]
        for o in overrides:
            out += ["--set", o]
        return out


def make_case(name, box):
    """The Case `name` for a box of edge `box` (the ramp: box x box sqrt(3)/2 x 8)."""
    if name in ("sparse", "mesapd"):
        gas = ["--set", "granular_gas.scaling=strong",
               "--set", f"granular_gas.box=[{box},{box},{box}]"]
        if name == "mesapd":
            gas += ["--set", "particles[0].radius=0.6", "--set",
                    "particles[0].velocity={random=[0.0,0.0],seed=1}",
                    "--set", "contact.initial_overlap=0.5"]
        return Case(os.path.join(ROOT, "scenes", "granular-gas.toml"),
                    os.path.join(HERE, "granular.in"), 50.0, 0.9, 0.5, 0.01, gas,
                    (box, box, box))
    if name == "ramp":
        # Regolith's weak-scaling layout on one rank: the run of dem_bench.py for box 30.
        extent = (float(box), box * math.sqrt(3.0) / 2.0, 8.0)
        gravity, inclination = 1.0, 30.0
        angle = math.radians(inclination)
        return Case(os.path.join(ROOT, "scenes", "dense-ramp.toml"),
                    os.path.join(HERE, "ramp.in"), 2000.0, 0.5, 0.5, 0.002,
                    ["--set", f"dense_ramp.per_rank=[{extent[0]!r},{extent[1]!r},{extent[2]!r}]",
                     "--set", f"dense_ramp.gravity={gravity!r}",
                     "--set", f"dense_ramp.inclination={inclination!r}"],
                    extent, {"g": gravity, "gx": math.sin(angle), "gz": -math.cos(angle)})
    sys.exit(f"lammps_compare: unknown case {name}")


def regolith(app, case, args, json_path, extra=()):
    command = [app, case.scene, *args, *extra, "--quiet", "--json", json_path]
    done = subprocess.run(command, capture_output=True, text=True, env=ENV, check=False)
    if done.returncode != 0:
        sys.exit(f"lammps_compare: {' '.join(command)} failed\n{done.stdout}\n{done.stderr}")
    with open(json_path, encoding="utf-8") as f:
        return json.load(f)


def write_data(dump_csv, extent, path):
    """LAMMPS data file (atom_style sphere: id type diameter density x y z) from a dump: type 1
    for the grains of the smallest radius, 2 for the larger ones (neighbor multi's
    collections). Returns the dump's rows."""
    with open(dump_csv, encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    small = min(float(r["radius"]) for r in rows)
    types = 2 if any(float(r["radius"]) > small for r in rows) else 1
    with open(path, "w", encoding="utf-8") as f:
        f.write(f"Regolith initial state\n\n{len(rows)} atoms\n{types} atom types\n\n")
        for axis, length in zip("xyz", extent):
            f.write(f"0 {length!r} {axis}lo {axis}hi\n")
        f.write("\nAtoms # sphere\n\n")
        for r in rows:
            radius, mass = float(r["radius"]), float(r["mass"])
            density = mass / (4.0 / 3.0 * math.pi * radius ** 3)
            kind = 1 if radius == small else 2
            f.write(f"{int(r['uid']) + 1} {kind} {2 * radius!r} {density!r} {r['x']} {r['y']} "
                    f"{r['z']}\n")
        f.write("\nVelocities\n\n")
        for r in rows:
            f.write(f"{int(r['uid']) + 1} {r['vx']} {r['vy']} {r['vz']} {r['wx']} {r['wy']} "
                    f"{r['wz']}\n")
    return rows


def lammps_params(case, mass):
    """gran/hooke/history parameters equal to Regolith's spring-dashpot for equal grains:
    c_n = 2 zeta sqrt(k m_eff) with zeta from the restitution, so gamma_n = c_n / m_eff =
    2 zeta sqrt(k / m_eff); m_eff = m/2 between two grains, m against a wall."""
    ln_e = math.log(case.restitution)
    zeta = -ln_e / math.sqrt(math.pi ** 2 + ln_e ** 2)
    gamma_pair = 2.0 * zeta * math.sqrt(case.stiffness / (mass / 2.0))
    gamma_wall = 2.0 * zeta * math.sqrt(case.stiffness / mass)
    return {"kn": case.stiffness, "kt": 2.0 / 7.0 * case.stiffness, "gamman": gamma_pair,
            "gammat": gamma_pair / 2.0, "xmu": case.friction, "gammanw": gamma_wall,
            "gammatw": gamma_wall / 2.0, "zhi": case.extent[2], **case.lammps_vars}


def lammps_command(case, data, params, steps, skin, log):
    command = ["lmp", "-in", case.deck, "-log", log, "-screen", "none", "-var", "data", data,
               "-var", "dt", repr(case.dt), "-var", "steps", str(steps), "-var", "skin",
               str(skin)]
    for k, v in params.items():
        command += ["-var", k, repr(v)]
    return command


def lammps(case, data, params, steps, skin, workdir):
    log = os.path.join(workdir, "lmp.log")
    command = lammps_command(case, data, params, steps, skin, log)
    done = subprocess.run(command, capture_output=True, text=True, cwd=workdir, check=False)
    if done.returncode != 0:
        sys.exit(f"lammps_compare: {' '.join(command)} failed\n{done.stdout}\n{done.stderr}")
    with open(log, encoding="utf-8") as f:
        text = f.read()
    m = re.search(r"Loop time of ([0-9.eE+-]+) on 1 procs for (\d+) steps with (\d+) atoms", text)
    if not m:
        sys.exit(f"lammps_compare: no loop time in {log}")
    return float(m.group(1)), int(m.group(2)), int(m.group(3)), text


# Where each code's time goes: Regolith's run-summary timers and LAMMPS's "MPI task timing
# breakdown" sections, per run in the CSV.
OUR_PHASES = ("contact", "sync", "integrate")
LAMMPS_SECTIONS = ("Pair", "Neigh", "Comm", "Modify")


def lammps_sections(log):
    """The average seconds of each section of LAMMPS's timing breakdown in `log` (text)."""
    out = {}
    for name in LAMMPS_SECTIONS:
        m = re.search(rf"^{name}\s*\|\s*[0-9.eE+-]+\s*\|\s*([0-9.eE+-]+)", log, re.MULTILINE)
        if m:
            out[name] = float(m.group(1))
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build", "default"))
    p.add_argument("--out", default=os.path.join(ROOT, "bench", "out"))
    p.add_argument("--cases", nargs="*", default=["sparse", "mesapd", "ramp"])
    p.add_argument("--box", type=int, default=30)
    p.add_argument("--steps", type=int, default=500)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--skin", type=float, default=0.1)
    p.add_argument("--set", action="append", default=[], dest="overrides",
                   help="scene override for the Regolith runs (repeatable)")
    a = p.parse_args()
    app = os.path.join(a.build, "bin", "regolith")
    os.makedirs(a.out, exist_ok=True)
    rows = []
    print("| case | grains | steps | Regolith PUpCS (median) | LAMMPS PUpCS (median) | "
          "ratio (median) | ratio range | ratio of best runs |")
    print("|---|---|---|---|---|---|---|---|")
    for case in a.cases:
        with tempfile.TemporaryDirectory() as tmp:
            c = make_case(case, a.box)
            args = c.regolith_args([f"sync.skin={a.skin!r}",
                                    f"contact.neighbour_skin={a.skin!r}"] + a.overrides)
            dump = os.path.join(tmp, "init.csv")
            regolith(app, c, args, os.path.join(tmp, "init.json"),
                     ["--steps", "0", "--dump", dump])
            data = os.path.join(tmp, "grains.data")
            grains = write_data(dump, c.extent, data)
            params = lammps_params(c, float(grains[0]["mass"]))
            ours, theirs, ratios = [], [], []
            for repeat in range(a.repeats):
                s = regolith(app, c, args, os.path.join(tmp, "run.json"),
                             ["--steps", str(a.steps)])
                loop, steps, atoms, log = lammps(c, data, params, a.steps, a.skin, tmp)
                if atoms != s["particles"] or steps != s["steps"]:
                    sys.exit(f"lammps_compare: LAMMPS ran {atoms} atoms x {steps} steps, Regolith "
                             f"{s['particles']} x {s['steps']}")
                lmp_pupcs = steps * atoms / loop
                ours.append(s["pupcs"])
                theirs.append(lmp_pupcs)
                ratios.append(s["pupcs"] / lmp_pupcs)
                sections = lammps_sections(log)
                rows.append([case, repeat, atoms, steps, s["wall_s"], s["pupcs"], loop, lmp_pupcs,
                             s["pupcs"] / lmp_pupcs, s["conserved"]["kinetic_energy"]] +
                            [s["timing_s"].get(k, "") for k in OUR_PHASES] +
                            [sections.get(k, "") for k in LAMMPS_SECTIONS])
            print(f"| {case} | {len(grains)} | {a.steps} | {statistics.median(ours):.3e} | "
                  f"{statistics.median(theirs):.3e} | {statistics.median(ratios):.2f} | "
                  f"{min(ratios):.2f}–{max(ratios):.2f} | {max(ours) / max(theirs):.2f} |",
                  flush=True)
    with open(os.path.join(a.out, "lammps_compare.csv"), "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(["case", "repeat", "grains", "steps", "regolith_wall_s", "regolith_pupcs",
                    "lammps_loop_s", "lammps_pupcs", "ratio", "regolith_kinetic_energy"] +
                   [f"regolith_{k}_s" for k in OUR_PHASES] +
                   [f"lammps_{k.lower()}_s" for k in LAMMPS_SECTIONS])
        w.writerows(rows)


if __name__ == "__main__":
    main()
