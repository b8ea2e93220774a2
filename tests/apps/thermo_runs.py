"""The thermo output (output.thermo_every) and the run summary in output.dir, end to end on
tests/apps/scenes/restart.toml (1000 grains falling on a floor, reproducible mode, 40 steps).

usage: thermo_runs.py --mpiexec M --app APP --scene SCENE --out DIR

Checks, in order (exit 1 with the reason on the first failure):
 1. on 1 and 2 ranks, 40 steps with a row every 10 and no --json: output.dir holds
    summary.json (time 0.4, the initial and final conserved quantities) and thermo.csv with the
    header and the rows of steps 0, 10, ..., 40; the first row's energies, momentum and angular
    momentum are the summary's initial ones, the last row's its final ones (to 1e-12 of the
    largest energy); standard output shows the heading and one line per row;
 2. the rows of 1 and 2 ranks agree (contacts and grains exactly, the rest to 1e-9 relative;
    the last row's wall force is the summary's, and the floor carries the grains' weight;
    the imbalance excepted), and grains touch at the end (contacts > 0, max_overlap > 0); the
    run without thermo output ends in the same state (checksum): measuring changes nothing;
 3. a run of 20 steps writing checkpoints at steps 10 and 20 and a row every 5 steps,
    restarted from step 10 into the same output.dir to 40 steps, leaves thermo.csv with the
    rows of steps 0, 5, ..., 40 once each, equal to the uninterrupted run's (the imbalance
    excepted).
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys

HEADER = ["step", "time", "ke_trans", "ke_rot", "pe_external", "pe_self", "px", "py", "pz",
          "lx", "ly", "lz", "contacts", "max_overlap", "grains", "imbalance",
          "wall0_fx", "wall0_fy", "wall0_fz"]  # the scene's one wall, the floor


def fail(message):
    sys.exit(f"thermo_runs: {message}")


def run(args, np, extra):
    command = [args.mpiexec, "-n", str(np), "--oversubscribe", args.app, args.scene, *extra]
    done = subprocess.run(command, capture_output=True, text=True, timeout=90, check=False)
    if done.returncode != 0:
        fail(f"{' '.join(command)} exited with {done.returncode}\n{done.stderr}")
    return done.stdout


def rows_of(directory):
    with open(os.path.join(directory, "thermo.csv"), encoding="utf-8") as f:
        table = list(csv.reader(f))
    if table[0] != HEADER:
        fail(f"{directory}/thermo.csv: header {table[0]}, expected {HEADER}")
    return [dict(zip(HEADER, map(float, row))) for row in table[1:]]


def summary_of(directory):
    with open(os.path.join(directory, "summary.json"), encoding="utf-8") as f:
        return json.load(f)


def same_conserved(row, conserved, where):
    scale = max(abs(conserved["kinetic_energy"]), abs(conserved["potential_energy"]), 1e-300)
    pairs = [(row["ke_trans"] + row["ke_rot"], conserved["kinetic_energy"], "kinetic energy"),
             (row["ke_rot"], conserved["rotational_kinetic_energy"], "rotational energy"),
             (row["pe_external"] + row["pe_self"], conserved["potential_energy"], "potential")]
    pairs += [(row[k], conserved["momentum"][a], k) for a, k in enumerate(("px", "py", "pz"))]
    pairs += [(row[k], conserved["angular_momentum"][a], k)
              for a, k in enumerate(("lx", "ly", "lz"))]
    for mine, theirs, what in pairs:
        if abs(mine - theirs) > 1e-12 * scale:
            fail(f"{where}: thermo's {what} {mine!r}, the summary's {theirs!r}")


def same_wall_force(row, summary, where):
    force = summary["walls"][0]["force"]
    for a, key in enumerate(("wall0_fx", "wall0_fy", "wall0_fz")):
        if abs(row[key] - force[a]) > 1e-12 * max(abs(force[a]), 1e-300):
            fail(f"{where}: thermo's {key} {row[key]!r}, the summary's {force[a]!r}")


def close(a, b, where):
    for key in HEADER:
        if key == "imbalance":
            continue
        exact = key in ("step", "contacts", "grains")
        if (a[key] != b[key]) if exact else abs(a[key] - b[key]) > 1e-9 * max(abs(a[key]), 1e-9):
            fail(f"{where}: {key} {a[key]!r} vs {b[key]!r}")


def main():
    parser = argparse.ArgumentParser()
    for option in ("--mpiexec", "--app", "--scene", "--out"):
        parser.add_argument(option, required=True)
    args = parser.parse_args()
    out = os.path.join(args.out, "thermo")
    shutil.rmtree(out, ignore_errors=True)

    rows = {}
    for np in (1, 2):
        directory = os.path.join(out, f"np{np}")
        stdout = run(args, np, ["--output", directory, "--set", "output.thermo_every=10"])
        rows[np] = rows_of(directory)
        summary = summary_of(directory)
        if [r["step"] for r in rows[np]] != [0, 10, 20, 30, 40]:
            fail(f"np {np}: rows of steps {[r['step'] for r in rows[np]]}")
        if abs(summary["time"] - 0.4) > 1e-12 or abs(rows[np][-1]["time"] - 0.4) > 1e-12:
            fail(f"np {np}: final time {summary['time']} / {rows[np][-1]['time']}, expected 0.4")
        same_conserved(rows[np][0], summary["conserved_initial"], f"np {np}, step 0")
        same_conserved(rows[np][-1], summary["conserved"], f"np {np}, step 40")
        same_wall_force(rows[np][-1], summary, f"np {np}, step 40")
        lines = [l for l in stdout.splitlines() if l.split()[:3] == ["step", "time", "ke_trans"]]
        if len(lines) != 1 or sum(1 for l in stdout.splitlines()
                                  if l.split() and l.split()[0] in ("0", "10", "20", "30", "40")
                                  and len(l.split()) == len(HEADER)) != 5:
            fail(f"np {np}: standard output lacks the thermo heading or rows:\n{stdout}")
    for a, b in zip(rows[1], rows[2]):
        close(a, b, f"step {a['step']:.0f} on 1 and 2 ranks")
    if not (rows[1][-1]["contacts"] > 0 and rows[1][-1]["max_overlap"] > 0):
        fail(f"no contacts at step 40: {rows[1][-1]}")
    if not rows[1][-1]["wall0_fz"] < 0:  # grains resting on the floor push it down
        fail(f"the floor carries no load at step 40: {rows[1][-1]}")
    plain = os.path.join(out, "plain")
    run(args, 2, ["--quiet", "--output", plain])
    if summary_of(plain)["checksum"] != summary_of(os.path.join(out, "np2"))["checksum"]:
        fail("the run with thermo output ends in another state than the run without")

    reference = os.path.join(out, "reference")
    run(args, 2, ["--quiet", "--output", reference, "--set", "output.thermo_every=5"])
    restarted = os.path.join(out, "restarted")
    run(args, 2, ["--quiet", "--output", restarted, "--steps", "20", "--set",
                  "output.thermo_every=5", "--set", "output.checkpoint_every=10"])
    run(args, 2, ["--quiet", "--output", restarted, "--set", "output.thermo_every=5",
                  "--restart", os.path.join(restarted, "checkpoint_00000010.h5")])
    expected, got = rows_of(reference), rows_of(restarted)
    if [r["step"] for r in got] != [r["step"] for r in expected]:
        fail(f"after the restart: rows of steps {[r['step'] for r in got]}, expected "
             f"{[r['step'] for r in expected]}")
    for a, b in zip(expected, got):
        close(a, b, f"step {a['step']:.0f}, uninterrupted and restarted")


if __name__ == "__main__":
    main()
