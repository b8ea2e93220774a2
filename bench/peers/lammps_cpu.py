#!/usr/bin/python3
"""CPU time (not wall time) of Regolith and LAMMPS for the cases of lammps_compare.py, for a
machine shared with other jobs: `perf stat -e task-clock` of each whole process, minus the same
process run with 0 steps (set-up and output), alternating Regolith and LAMMPS. Descheduling
does not count; cache and memory-bandwidth contention from co-running jobs still does.

usage: lammps_cpu.py [--build build/default] [--case sparse|mesapd|ramp] [--box 30] [--steps 300]
                     [--repeats 3] [--set KEY=VALUE ...]
"""
import argparse
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lammps_compare as lc  # noqa: E402  (same decks, parameters and initial state)


def cpu_seconds(command, cwd=None):
    done = subprocess.run(["perf", "stat", "-x,", "-e", "task-clock", *command],
                          capture_output=True, text=True, env=lc.ENV, cwd=cwd, check=False)
    if done.returncode != 0:
        sys.exit(f"lammps_cpu: {' '.join(command)} failed\n{done.stdout}\n{done.stderr}")
    for line in done.stderr.splitlines():
        if "task-clock" in line:
            return float(line.split(",")[0]) / 1000.0
    sys.exit(f"lammps_cpu: no task-clock from perf stat\n{done.stderr}")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default=os.path.join(lc.ROOT, "build", "default"))
    p.add_argument("--case", default="mesapd", choices=["sparse", "mesapd", "ramp"])
    p.add_argument("--box", type=int, default=30)
    p.add_argument("--steps", type=int, default=300)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--skin", type=float, default=0.1)
    p.add_argument("--set", action="append", default=[], dest="overrides")
    a = p.parse_args()
    app = os.path.join(a.build, "bin", "regolith")
    case = lc.make_case(a.case, a.box)
    args = case.regolith_args(a.overrides)
    with tempfile.TemporaryDirectory() as tmp:
        dump = os.path.join(tmp, "init.csv")
        lc.regolith(app, case, args, os.path.join(tmp, "init.json"),
                    ["--steps", "0", "--dump", dump])
        data = os.path.join(tmp, "grains.data")
        grains = lc.write_data(dump, case.extent, data)
        params = lc.lammps_params(case, float(grains[0]["mass"]))

        def ours(steps):
            return cpu_seconds([app, case.scene, *args, "--quiet", "--steps", str(steps),
                                "--json", os.path.join(tmp, "run.json")])

        def theirs(steps):
            return cpu_seconds(lc.lammps_command(case, data, params, steps, a.skin,
                                                 os.path.join(tmp, "lmp.log")), cwd=tmp)

        print(f"case {a.case}, {len(grains)} grains, {a.steps} steps, overrides {a.overrides}")
        for repeat in range(a.repeats):
            reg = ours(a.steps) - ours(0)
            lmp = theirs(a.steps) - theirs(0)
            print(f"repeat {repeat}: CPU s (loop) Regolith {reg:.3f}, LAMMPS {lmp:.3f}, "
                  f"Regolith / LAMMPS speed {lmp / reg:.2f}", flush=True)


if __name__ == "__main__":
    main()
