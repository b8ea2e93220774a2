#!/usr/bin/python3
"""The tutorials' physics figures: runs the tutorials of the build (build/<preset>/examples/;
tests/install builds the same programs against an installed prefix)

  02-contact-law  the pull-off force of Hertz + DMT adhesion against 2 pi w R*
  03-spin-up      the spin at which a cohesionless pile's equator lifts off, over omega_c

writing bench/out/framework/tutorial_figures.csv (figure, value, the tutorial's verdict). A
tutorial that exits 1 judged its figure outside its bound (recorded, not an error here); any
other failure stops the script.

usage: tutorial_figures.py [--build build/default] [--out bench/out/framework] [--ranks 2]
                           [--pull-steps 20000] [--spin-sites 16] [--spin-steps 40000]
"""
import argparse
import csv
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MPI_ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def run(cmd, cwd, log):
    with open(log, "w", encoding="utf-8") as out:
        return subprocess.run(cmd, cwd=cwd, env=MPI_ENV, stdout=out, stderr=subprocess.STDOUT,
                              check=False).returncode


def tutorial(args, work, name, params):
    log = os.path.join(work, name + ".log")
    program = os.path.join(os.path.abspath(args.build), "examples", name)
    if not os.path.exists(program):
        sys.exit(f"{program} is missing: build first (make build)")
    code = run(["mpiexec", "--oversubscribe", "-n", str(args.ranks), program] +
               [str(p) for p in params], work, log)
    text = open(log, encoding="utf-8").read()
    if code not in (0, 1):
        sys.exit(f"{name} failed (exit {code}); see {log}")
    return text, "within its bound" if code == 0 else "outside its bound"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--build", default="build/default")
    p.add_argument("--out", default="bench/out/framework")
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--pull-steps", type=int, default=20000)
    p.add_argument("--spin-sites", type=int, default=16)
    p.add_argument("--spin-steps", type=int, default=40000)
    args = p.parse_args()
    work = os.path.abspath(args.out)
    os.makedirs(work, exist_ok=True)

    rows = []
    text, verdict = tutorial(args, work, "02-contact-law", [args.pull_steps])
    m = re.search(r"measured ([0-9.eE+-]+), DMT 2 pi w R\* = ([0-9.eE+-]+)", text)
    rows.append(("pull-off force / 2 pi w R*", float(m.group(1)) / float(m.group(2)), verdict))
    text, verdict = tutorial(args, work, "03-spin-up", [args.spin_sites, args.spin_steps])
    grains = re.search(r"^(\d+) grains", text, re.M).group(1)
    m = re.search(r"lifted off at omega = ([0-9.]+) omega_c; ([0-9.]+) % of the mass shed", text)
    rows.append((f"lift-off spin / omega_c ({grains} grains)", float(m.group(1)), verdict))
    rows.append((f"mass shed ({grains} grains) [%]", float(m.group(2)), verdict))

    path = os.path.join(work, "tutorial_figures.csv")
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(["figure", "value", "verdict"])
        w.writerows(rows)
    for r in rows:
        print(f"{r[0]}: {r[1]:.4g} ({r[2]})")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
