#!/usr/bin/python3
"""Instructions executed by the time step and by the synchronisation, counted by valgrind's
callgrind (machine-independent: the figure for "no loss of speed" on a shared machine)

  step  inclusive in DemStep::step: scene A (bench/peers/scenes/scene-a.toml) with Hertz
        contacts (E = 60.1936, nu = 0.3: the spring-dashpot's k_n as the effective modulus),
        one block, --steps steps
  sync  inclusive in ParticleSync::sync: the same scene in 8 x 8 x 8 blocks on one rank (every
        grain has shadows), --sync-steps steps

writing bench/out/framework/instruction_counts.csv (case, steps, instructions, checksum). The
spring-dashpot's batch kernel uses AVX-512, which valgrind cannot run: hence Hertz. Run it on
two builds (--bin) to compare commits.

usage: instruction_counts.py [--bin build/default/bin/regolith] [--out bench/out/framework]
                             [--steps 200] [--sync-steps 100] [--set KEY=VALUE ...]
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE_A = os.path.join(ROOT, "bench", "peers", "scenes", "scene-a.toml")
HERTZ = ['model = "hertz"', "youngs_modulus = 60.1936", "poisson_ratio = 0.3"]


def hertz_scene(work):
    """Scene A with its [contact] stiffness replaced by Hertz's elasticity."""
    text = open(SCENE_A, encoding="utf-8").read()
    text, n = re.subn(r"^stiffness = .*$", "\n".join(HERTZ), text, flags=re.M)
    if n != 1:
        sys.exit(f"{SCENE_A}: no [contact] stiffness line to replace")
    path = os.path.join(work, "scene-a-hertz.toml")
    with open(path, "w", encoding="utf-8") as out:
        out.write(text)
    return path


def count(binary, scene, work, name, toggle, steps, extra):
    """(instructions, checksum) of one run under callgrind."""
    profile = os.path.join(work, name + ".callgrind")
    summary = os.path.join(work, name + ".json")
    cmd = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={profile}",
           f"--toggle-collect={toggle}", binary, scene, "--steps", str(steps), "--quiet",
           "--output", os.path.join(work, "out"), "--set", "sync.reproducible=true",
           "--json", summary] + extra
    run = subprocess.run(cmd, capture_output=True, text=True, check=False)
    found = re.search(r"Collected : (\d+)", run.stderr)
    if run.returncode != 0 or not found:
        sys.exit(f"{name} failed (exit {run.returncode}):\n{run.stderr[-2000:]}")
    return int(found.group(1)), json.load(open(summary, encoding="utf-8"))["checksum"]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--bin", default="build/default/bin/regolith")
    p.add_argument("--out", default="bench/out/framework")
    p.add_argument("--steps", type=int, default=200)
    p.add_argument("--sync-steps", type=int, default=100)
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="a scene key for both cases (e.g. a smaller domain.max)")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    binary = os.path.abspath(args.bin)
    rows = []
    with tempfile.TemporaryDirectory() as work:
        scene = hertz_scene(work)
        cases = [("step", "regolith::particles::DemStep::step*", args.steps, []),
                 ("sync", "regolith::particles::ParticleSync::sync*", args.sync_steps,
                  ["--set", "domain.blocks=[8,8,8]"])]
        keys = [a for kv in args.set for a in ("--set", kv)]
        for name, toggle, steps, extra in cases:
            instructions, checksum = count(binary, scene, work, name, toggle, steps, keys + extra)
            rows.append({"case": name, "steps": steps, "instructions": instructions,
                         "checksum": checksum})
            print(f"{name}: {instructions:,} instructions in {steps} steps, checksum {checksum}")
    path = os.path.join(args.out, "instruction_counts.csv")
    with open(path, "w", newline="", encoding="utf-8") as out:
        writer = csv.DictWriter(out, fieldnames=["case", "steps", "instructions", "checksum"])
        writer.writeheader()
        writer.writerows(rows)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
