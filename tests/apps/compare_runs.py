"""Runs one scene with `regolith` on several rank counts and layouts and checks that the runs
agree.

usage: compare_runs.py --mpiexec M --app APP --out DIR --name NAME [--np 1 4]
                       [--case "NP [ARGS...]" ...] [--reference STEM]
                       [--same KEY ...] [--expect KEY=VALUE|KEY>NUMBER ...] [--dump]
                       [--final "UID COLUMN OP VALUE" ...] [--reload SCENE] [--close TOL]
                       -- [app arguments]

Every run must exit 0 and write a summary (--json); the summaries must agree on every --same
key (e.g. particles, checksum) and satisfy every --expect (a nested key as a.b). Runs: one per --np value with the
app arguments, then one per --case, a string holding the rank count and further arguments
for that run only (split like a shell would), e.g. --case "4 --set domain.blocks=[2,2,1]".
With --reference STEM the runs are compared with STEM.json (and STEM.csv with --dump), the
output of an earlier run, instead of with the first run of this call; a call that makes the
reference for others lists it as its first run.
With --dump every run also writes the dump, which must be byte-identical across the runs,
follow the contract (header, one line per particle sorted by uid, 12 fields) and hash to the
summary's checksum (the checksum is recomputed here from the dumped numbers: the
MSet-Add-Hash of apps/common/StateChecksum.hpp). --final checks a value of the dumped final
state, e.g. --final "0 x < 5" (OP one of < <= > >= ==; needs --dump).
--close TOL (needs --dump) replaces the byte comparison of the dumps: the runs must hold the same
uids, and every grain's position may differ from the first run's by at most TOL per axis (for
methods equal across rank counts only to a tolerance: the parallel tree, the PETSc solve).
--reload SCENE (needs --dump) runs SCENE, whose first [[particles]] entry is a `kind = "file"`
entry, on the largest rank count with its path set to the dump: the state read back must
have the same particle count and checksum (the dump is a lossless restart).
Exit code 1 with the reason on the first failed check.
"""
import argparse
import json
import operator
import os
import re
import shlex
import struct
import subprocess
import sys

HEADER = "uid,x,y,z,vx,vy,vz,wx,wy,wz,radius,mass"
MASK = (1 << 64) - 1


def fail(message):
    sys.exit(f"compare_runs: {message}")


def run(mpiexec, np, app, app_args, json_path, dump_path=None):
    command = [mpiexec, "-n", str(np), "--oversubscribe", app, *app_args, "--quiet",
               "--json", json_path]
    if dump_path:
        command += ["--dump", dump_path]
    for path in (json_path, dump_path):
        if path and os.path.exists(path):
            os.remove(path)
    done = subprocess.run(command, capture_output=True, text=True, timeout=60, check=False)
    if done.returncode != 0:
        fail(f"{' '.join(command)} exited with {done.returncode}\n--- stdout:\n{done.stdout}"
             f"\n--- stderr:\n{done.stderr}")
    with open(json_path, encoding="utf-8") as f:
        return json.load(f)


def fnv1a(data):
    h = 0xCBF29CE484222325
    for byte in data:
        h = ((h ^ byte) * 0x100000001B3) & MASK
    return h


def fmix64(k):
    k ^= k >> 33
    k = (k * 0xFF51AFD7ED558CCD) & MASK
    k ^= k >> 33
    k = (k * 0xC4CEB9FE1A85EC53) & MASK
    k ^= k >> 33
    return k


def check_dump(path, summary):
    """Checks the dump's format and returns the checksum recomputed from it."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    if lines[0] != HEADER or lines[-1] != "":
        fail(f"{path}: expected the header line {HEADER!r} and a final newline")
    rows = lines[1:-1]
    if len(rows) != summary["particles"]:
        fail(f"{path}: {len(rows)} particles, the summary says {summary['particles']}")
    total, previous = 0, -1
    for number, row in enumerate(rows, start=2):
        fields = row.split(",")
        if len(fields) != 12:
            fail(f"{path}:{number}: expected 12 fields, got {len(fields)}")
        uid = int(fields[0])
        if uid <= previous:
            fail(f"{path}:{number}: uid {uid} after {previous}: not sorted by uid")
        previous = uid
        data = struct.pack("<Q", uid) + b"".join(struct.pack("<d", float(x)) for x in fields[1:])
        total = (total + fmix64(fnv1a(data))) & MASK
    return f"{fnv1a(struct.pack('<QQ', len(rows), total)):016x}"


def positions(path):
    with open(path, encoding="utf-8") as f:
        rows = [line.split(",") for line in f.read().splitlines()[1:]]
    return {int(r[0]): tuple(float(v) for v in r[1:4]) for r in rows}


def check_close(path_a, path_b, tol, labels):
    a, b = positions(path_a), positions(path_b)
    if a.keys() != b.keys():
        fail(f"{labels}: different grains ({len(a)} and {len(b)}; uids differ)")
    worst = max(((max(abs(p - q) for p, q in zip(a[u], b[u])), u) for u in a), default=(0, 0))
    if not worst[0] <= tol:
        fail(f"{labels}: grain uid {worst[1]} differs by {worst[0]:.3e} in position, more than "
             f"{tol:g}")
    print(f"{labels}: positions within {worst[0]:.3e} (tolerance {tol:g})")


def check_final(path, check):
    """One --final check "UID COLUMN OP VALUE" against the dump at `path`."""
    ops = {"<": operator.lt, "<=": operator.le, ">": operator.gt, ">=": operator.ge,
           "==": operator.eq}
    parts = check.split()
    if len(parts) != 4 or parts[2] not in ops:
        fail(f"--final {check!r}: expected 'UID COLUMN OP VALUE' with OP one of {list(ops)}")
    uid, column, op, value = parts
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    header = lines[0].split(",")
    if column not in header:
        fail(f"--final {check!r}: no column {column!r} in {HEADER!r}")
    for row in lines[1:]:
        fields = row.split(",")
        if fields[0] == uid:
            actual = float(fields[header.index(column)])
            if not ops[op](actual, float(value)):
                fail(f"final state of uid {uid}: {column} = {actual!r}, expected {op} {value}")
            return
    fail(f"--final {check!r}: uid {uid} is not in the final state {path}")


def check_expectation(summary, expectation, label):
    """KEY=VALUE (the value's text) or KEY>NUMBER; KEY may name a nested key, a.b."""
    match = re.fullmatch(r"([\w.]+)(=|>)(.*)", expectation)
    if not match:
        fail(f"--expect {expectation!r}: expected KEY=VALUE or KEY>NUMBER")
    key, op, expected = match.groups()
    value = summary
    for part in key.split("."):
        if not isinstance(value, dict) or part not in value:
            fail(f"{label}: the summary has no {key}")
        value = value[part]
    if op == "=" and str(value) != expected:
        fail(f"{label}: {key} = {value!r}, expected {expected}")
    if op == ">" and not value > float(expected):
        fail(f"{label}: {key} = {value!r}, expected more than {expected}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--mpiexec", required=True)
    parser.add_argument("--app", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--name", required=True)
    parser.add_argument("--np", type=int, nargs="*", default=[])
    parser.add_argument("--case", action="append", default=[])
    parser.add_argument("--reference")
    parser.add_argument("--same", nargs="*", default=[])
    parser.add_argument("--expect", nargs="*", default=[])
    parser.add_argument("--dump", action="store_true")
    parser.add_argument("--final", action="append", default=[])
    parser.add_argument("--reload")
    parser.add_argument("--close", type=float)
    parser.add_argument("app_args", nargs="*")
    args = parser.parse_args()

    plan = [(np, [], f"{args.name}.np{np}") for np in args.np]
    for k, case in enumerate(args.case):
        words = shlex.split(case)
        if not words or not words[0].isdigit():
            fail(f"--case {case!r}: expected the rank count first")
        np = int(words[0])
        plan.append((np, words[1:], f"{args.name}.case{k}.np{np}"))
    if not plan:
        fail("nothing to run: give --np or --case")

    runs = []
    if args.reference:
        with open(args.reference + ".json", encoding="utf-8") as f:
            reference = json.load(f)
        runs.append((f"the reference {args.reference}", reference,
                     args.reference + ".csv" if args.dump else None))
    for np, extra, name in plan:
        stem = os.path.join(args.out, name)
        dump = stem + ".csv" if args.dump else None
        summary = run(args.mpiexec, np, args.app, [*args.app_args, *extra], stem + ".json",
                      dump)
        label = f"np {np}" + (f" ({' '.join(extra)})" if extra else "")
        if summary["ranks"] != np:
            fail(f"{label}: the summary says ranks = {summary['ranks']}")
        for expectation in args.expect:
            check_expectation(summary, expectation, label)
        if dump:
            recomputed = check_dump(dump, summary)
            if recomputed != summary["checksum"]:
                fail(f"{label}: the checksum recomputed from the dump is {recomputed}, the "
                     f"summary says {summary['checksum']}")
            for check in args.final:
                check_final(dump, check)
        runs.append((label, summary, dump))

    first_label, first, first_dump = runs[0]
    for label, summary, dump in runs[1:]:
        for key in args.same:
            if summary[key] != first[key]:
                fail(f"{key}: {first[key]!r} on {first_label} but {summary[key]!r} on {label}")
        if dump and args.close is not None:
            check_close(first_dump, dump, args.close, f"{first_label} and {label}")
        elif dump:
            with open(first_dump, "rb") as a, open(dump, "rb") as b:
                if a.read() != b.read():
                    fail(f"the dumps of {first_label} and {label} differ: {first_dump} {dump}")
    print(f"{args.name}: " + ", ".join(f"{k} = {first[k]}" for k in args.same) +
          " on " + "; ".join(label for label, _, _ in runs))

    if args.reload:
        label, summary, dump = runs[-1]
        np = plan[-1][0]
        stem = os.path.join(args.out, f"{args.name}.reload.np{np}")
        again = run(args.mpiexec, np, args.app,
                    [args.reload, "--set", f'particles.0.path="{os.path.abspath(dump)}"'],
                    stem + ".json")
        for key in ("particles", "checksum"):
            if again[key] != summary[key]:
                fail(f"reloaded dump: {key} = {again[key]!r}, the dumped state had "
                     f"{summary[key]!r}")
        print(f"{args.name}: the dump read back as a particle file gives the same state")


if __name__ == "__main__":
    main()
