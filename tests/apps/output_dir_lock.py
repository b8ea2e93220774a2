#!/usr/bin/python3
"""A run stops before its first step, with one message, while another process holds the lock
of its output folder (flock of the folder, as a running run holds it), and runs once the lock
is free; the folder's files are untouched and the refused run adds none.

usage: output_dir_lock.py --mpiexec MPIEXEC --app REGOLITH --scene TOML --out DIR
"""
import argparse
import fcntl
import os
import shutil
import subprocess
import sys


def run(args, np, expect_ok):
    cmd = [args.mpiexec, "--oversubscribe", "-n", str(np), args.app, args.scene, "--quiet",
           "--output", args.out, "--steps", "5"]
    result = subprocess.run(cmd, capture_output=True, text=True, check=False, timeout=120)
    if (result.returncode == 0) != expect_ok:
        sys.exit(f"{' '.join(cmd)}: exit code {result.returncode}, expected "
                 f"{'0' if expect_ok else 'a failure'}:\n{result.stdout}{result.stderr}")
    return result.stdout + result.stderr


def main():
    p = argparse.ArgumentParser()
    for key in ("--mpiexec", "--app", "--scene", "--out"):
        p.add_argument(key, required=True)
    args = p.parse_args()
    shutil.rmtree(args.out, ignore_errors=True)
    os.makedirs(args.out)
    kept = os.path.join(args.out, "summary.json")
    with open(kept, "w", encoding="utf-8") as f:
        f.write("a file of an earlier run\n")
    folder = os.open(args.out, os.O_RDONLY | os.O_DIRECTORY)
    fcntl.flock(folder, fcntl.LOCK_EX | fcntl.LOCK_NB)  # as a running run holds it
    for np in (1, 2):
        text = run(args, np, expect_ok=False)
        expected = f'output.dir = "{args.out}": another run is writing there'
        if text.count(expected) != 1:
            sys.exit(f"expected one message '{expected}', got:\n{text}")
        if "Segmentation" in text or "core dumped" in text:
            sys.exit(f"the refused run crashed:\n{text}")
    if os.listdir(args.out) != ["summary.json"]:
        sys.exit(f"the refused runs wrote into the folder: {sorted(os.listdir(args.out))}")
    with open(kept, encoding="utf-8") as f:
        if f.read() != "a file of an earlier run\n":
            sys.exit("the refused run changed the folder's summary.json")
    os.close(folder)  # releases the lock
    run(args, 2, expect_ok=True)
    print("refused while the folder was locked, ran once it was free")


if __name__ == "__main__":
    main()
