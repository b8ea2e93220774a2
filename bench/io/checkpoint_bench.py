"""Checkpoint write and read time and size per grain (docs/results.md, "Checkpoints
and output"), on scenes/checkpoint-bench.toml (103,823 grains; checkpoints at steps 10 and
20, the second with ~34,000 contact-history entries).

usage: python3 bench/io/checkpoint_bench.py [--app build/default/bin/regolith]
                                            [--np 1 2 4] [--repeats 3] [--out out/ckpt-bench]
                                            [--set section.key=value ...]

For each rank count and repeat: one run of 20 steps writing both checkpoints (the write time
is the one `regolith` logs: collect the masters, write the temporary file collectively with
parallel HDF5, flush, fsync, rename), then a restart from the step-20 file that runs no step
(the read time it logs: every rank reads its slice, the checksum is verified, the grains are
routed to their blocks, the state checksum is compared). Prints a Markdown table of medians.
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys

# The repository (this file is bench/<part>/<script>.py): defaults that work from any directory.
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

WRITE = re.compile(r"checkpoint (\S+): (\d+) grains, (\d+) history entries, ([\d.e+-]+) MB in "
                   r"([\d.e+-]+) s")
READ = re.compile(r"read and distributed in ([\d.e+-]+) s")


def run(command):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    done = subprocess.run(command, capture_output=True, text=True, check=False, env=env)
    if done.returncode != 0: # the run's own message, not a traceback
        sys.exit(f"checkpoint_bench: {' '.join(command)} exited with {done.returncode}\n"
                 f"{done.stdout[-2000:]}{done.stderr[-2000:]}")
    return done.stdout


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--app", default=os.path.join(ROOT, "build", "default", "bin", "regolith"))
    parser.add_argument("--scene", default=os.path.join(ROOT, "scenes", "checkpoint-bench.toml"))
    parser.add_argument("--np", type=int, nargs="+", default=[1, 2, 4])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--out", default="out/ckpt-bench")
    parser.add_argument("--set", action="append", default=[], dest="overrides",
                        metavar="KEY=VALUE", help="a scene key for every run; repeatable")
    a = parser.parse_args()
    print("| ranks | grains | history entries | file [MB] | bytes / grain | write [s] | "
          "read [s] |")
    print("|---|---|---|---|---|---|---|")
    for np in a.np:
        writes, reads, last = [], [], None
        for _ in range(a.repeats):
            shutil.rmtree(a.out, ignore_errors=True)
            base = ["mpiexec", "--oversubscribe", "-n", str(np), a.app, a.scene,
                    "--output", a.out] + [x for kv in a.overrides for x in ("--set", kv)]
            lines = WRITE.findall(run(base))
            last = lines[-1]
            writes.append(float(last[4]))
            reads.append(float(READ.findall(run(base + ["--restart", last[0]]))[0]))
        grains, entries, mb = int(last[1]), int(last[2]), float(last[3])
        print(f"| {np} | {grains} | {entries} | {mb:.1f} | {mb * 1e6 / grains:.0f} | "
              f"{statistics.median(writes):.3f} | {statistics.median(reads):.3f} |")


if __name__ == "__main__":
    main()
