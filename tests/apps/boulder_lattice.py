"""A lattice generated around boulders listed before it: `regolith` must keep exactly the
lattice sites that a brute force over all sites keeps, on every rank count.

usage: boulder_lattice.py --mpiexec M --app APP --out DIR --np 1 4

For each case below the script writes a scene, counts the expected grains itself (every site
of the documented lattice, the region rule per axis, the skip rule "overlaps a boulder or a
periodic image of one", in plain Python), runs the scene with --json and --dump on each rank
count, and compares the particle count and the set of lattice-grain centres. The cases avoid
near-ties (a decision within 1e-9 of its threshold) so that rounding cannot matter; the
script refuses a case that has one.
Exit code 1 with the reason on the first failed check.
"""
import argparse
import itertools
import json
import math
import os
import subprocess
import sys

TIE = 1e-9

# Each case: domain, periodic axes, blocks (+ optional refinement), boulders (centre, radius)
# listed first, then one lattice filling the domain.
CASES = [
    {   # MESA-PD GranularGas geometry (sc, spacing 1, radius 0.6: neighbours overlap); the
        # boulder crosses the periodic x boundary; z is walled, so the outer layers drop out.
        "name": "sc_overlapping",
        "min": [0.0, 0.0, 0.0], "max": [10.0, 8.0, 6.0], "periodic": [True, True, False],
        "blocks": [2, 2, 1], "refine": "[{ min = [0, 0, 0], max = [5, 4, 3], level = 1 }]",
        "boulders": [([0.7, 4.3, 3.1], 2.2)],
        "lattice": "sc", "spacing": 1.0, "radius": 0.6,
    },
    {   # hcp around two boulders, one across the periodic z boundary; y is walled.
        "name": "hcp_two_boulders",
        "min": [0.0, 0.0, 0.0], "max": [9.25, 8.0, 7.0], "periodic": [True, False, True],
        "blocks": [3, 2, 2], "refine": "[]",
        "boulders": [([4.4, 3.9, 6.5], 1.8), ([1.3, 6.1, 2.2], 1.1)],
        "lattice": "hcp", "spacing": 1.0, "radius": 0.45,
    },
]


def fail(message):
    sys.exit(f"boulder_lattice: {message}")


def toml_vec(v):
    return "[" + ", ".join(repr(float(x)) for x in v) + "]"


def scene_text(case):
    bools = ", ".join("true" if p else "false" for p in case["periodic"])
    boulders = case["boulders"]
    return f"""name = "{case['name']}"
[domain]
min = {toml_vec(case['min'])}
max = {toml_vec(case['max'])}
blocks = {list(case['blocks'])}
periodic = [{bools}]
refine = {case['refine']}
[time]
dt = 0.01
steps = 0
allow_unstable = true   # a count of generated grains: no step is taken
[contact]
initial_overlap = 0.5   # the GranularGas case overlaps its neighbours by design
[[particles]]
kind = "list"
radius = {toml_vec([r for _, r in boulders])}
position = [{", ".join(toml_vec(c) for c, _ in boulders)}]
density = 1.0
[[particles]]
kind = "lattice"
lattice = "{case['lattice']}"
spacing = {case['spacing']}
radius = {case['radius']}
density = 1.0
"""


def site(case, i, j, k):
    """Centre of site (i, j, k) as documented in particles/generators/GeneratorSpec.hpp."""
    s = case["spacing"]
    o = [m + s / 2 for m in case["min"]]
    if case["lattice"] == "sc":
        return [o[0] + s * i, o[1] + s * j, o[2] + s * k]
    shifted = (j + k) % 2 == 1
    # On a periodic x the shifted rows start at min, with the other rows' indices i.
    if shifted and case["periodic"][0]:
        x = case["min"][0] + s * i if o[0] + s * i < case["max"][0] else math.inf
    else:
        x = o[0] + s * (i + (0.5 if shifted else 0.0))
    return [x, o[1] + s * math.sqrt(3) / 2 * (j + (k % 2) / 3),
            o[2] + s * math.sqrt(2 / 3) * k]


def near(a, b):
    return abs(a - b) < TIE


def used(case, c):
    r = case["radius"]
    for a in range(3):
        lo, hi = case["min"][a], case["max"][a]
        if case["periodic"][a]:
            # (the shifted hcp rows' first site is exactly min: no tie)
            if (near(c[a], lo) and c[a] != lo) or near(c[a], hi):
                fail(f"{case['name']}: site {c} is a near-tie on axis {a}")
            if not lo <= c[a] < hi:
                return False
        else:
            if near(c[a] - r, lo) or near(c[a] + r, hi):
                fail(f"{case['name']}: site {c} is a near-tie on axis {a}")
            if c[a] - r < lo or c[a] + r > hi:
                return False
    return True


def distance(case, a, b):
    """Minimum-image distance."""
    d2 = 0.0
    for k in range(3):
        d = a[k] - b[k]
        if case["periodic"][k]:
            length = case["max"][k] - case["min"][k]
            d -= length * round(d / length)
        d2 += d * d
    return math.sqrt(d2)


def expected_sites(case):
    steps = [1.0, 1.0, 1.0] if case["lattice"] == "sc" else [1.0, math.sqrt(3) / 2,
                                                            math.sqrt(2 / 3)]
    n = [int((case["max"][a] - case["min"][a]) / (case["spacing"] * steps[a])) + 2
         for a in range(3)]
    kept, sites = [], 0
    for i, j, k in itertools.product(range(n[0]), range(n[1]), range(n[2])):
        c = site(case, i, j, k)
        if not used(case, c):
            continue
        sites += 1
        overlaps = False
        for centre, radius in case["boulders"]:
            d, reach = distance(case, c, centre), radius + case["radius"]
            if near(d, reach):
                fail(f"{case['name']}: site {c} is a near-tie with the boulder at {centre}")
            overlaps = overlaps or d < reach
        if not overlaps:
            kept.append(c)
    if len(kept) == sites:
        fail(f"{case['name']}: the boulders skip no site; the case tests nothing")
    return kept, sites


def key(c):
    return tuple(round(x, 6) for x in c)


def run_case(case, args):
    scene = os.path.join(args.out, f"boulder_{case['name']}.toml")
    with open(scene, "w", encoding="utf-8") as f:
        f.write(scene_text(case))
    expected, sites = expected_sites(case)
    want = sorted(key(c) for c in expected)
    total = len(expected) + len(case["boulders"])
    for np in args.np:
        stem = os.path.join(args.out, f"boulder_{case['name']}.np{np}")
        command = [args.mpiexec, "-n", str(np), "--oversubscribe", args.app, scene, "--quiet",
                   "--json", stem + ".json", "--dump", stem + ".csv"]
        done = subprocess.run(command, capture_output=True, text=True, timeout=60, check=False)
        if done.returncode != 0:
            fail(f"{' '.join(command)} exited with {done.returncode}:\n{done.stderr}")
        with open(stem + ".json", encoding="utf-8") as f:
            particles = json.load(f)["particles"]
        if particles != total:
            fail(f"{case['name']} on {np} ranks: {particles} particles, expected {total} "
                 f"({len(expected)} lattice sites + {len(case['boulders'])} boulders)")
        with open(stem + ".csv", encoding="utf-8") as f:
            rows = [line.split(",") for line in f.read().splitlines()[1:]]
        got = sorted(key([float(x) for x in row[1:4]]) for row in rows
                     if float(row[10]) == case["radius"])
        if got != want:
            missing = sorted(set(want) - set(got))[:5]
            extra = sorted(set(got) - set(want))[:5]
            fail(f"{case['name']} on {np} ranks: lattice centres differ; missing {missing}, "
                 f"extra {extra}")
    print(f"{case['name']}: {total} particles ({len(expected)} of {sites} lattice sites kept) "
          f"on {args.np} ranks, as the brute force says")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--mpiexec", required=True)
    parser.add_argument("--app", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--np", type=int, nargs="+", required=True)
    args = parser.parse_args()
    for case in CASES:
        run_case(case, args)


if __name__ == "__main__":
    main()
