"""Total energy of an elastic spring-dashpot gas (restitution 1, no friction) from a run's
summary and its final dump: kinetic energy (summary, `conserved`) plus the normal springs'
energy 1/2 k δ² of every overlapping pair (dump). Without damping and friction these two are
all the energy there is, so their drift is the integrator's error."""
import csv
import json
import os
import subprocess
import tempfile

import numpy as np
from scipy.spatial import cKDTree

from run_summary import MPI_ENV, mpiexec


def run_with_dump(app, ranks, args, timeout=900):
    """Runs `app` with `args` and --json / --dump; returns (summary or None, dump rows or
    None, exit code, last output line). A failed or timed-out run is a result here (the
    charts map where runs fail), not an error."""
    with tempfile.TemporaryDirectory() as tmp:
        summary = os.path.join(tmp, "summary.json")
        dump = os.path.join(tmp, "final.csv")
        command = [*mpiexec(ranks), app, *args, "--quiet", "--json", summary, "--dump", dump]
        try:
            done = subprocess.run(command, capture_output=True, text=True, check=False,
                                  timeout=timeout, env={**os.environ, **MPI_ENV})
        except subprocess.TimeoutExpired:
            return None, None, "timeout", f"no result within {timeout} s"
        lines = (done.stderr + "\n" + done.stdout).splitlines()
        said = [l for l in lines if l.startswith(os.path.basename(app) + ":")]
        errors = [l for l in said if "error" in l.lower()]
        message = (errors or said or [l for l in lines if l.strip()] or [""])[0]
        if done.returncode != 0 or not os.path.exists(summary):
            return None, None, done.returncode, message
        with open(summary, encoding="utf-8") as f:
            s = json.load(f)
        with open(dump, newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
        return s, rows, 0, message


def spring_energy(rows, stiffness, box):
    """(Σ 1/2 k δ² over overlapping pairs, deepest overlap / smaller radius) for the dumped
    grains in a periodic cube of edge `box` with its corner at the origin."""
    if not rows:
        return 0.0, 0.0
    pos = np.array([[float(r["x"]), float(r["y"]), float(r["z"])] for r in rows]) % box
    rad = np.array([float(r["radius"]) for r in rows])
    tree = cKDTree(pos, boxsize=box)
    pairs = tree.query_pairs(2.0 * rad.max(), output_type="ndarray")
    if len(pairs) == 0:
        return 0.0, 0.0
    d = pos[pairs[:, 0]] - pos[pairs[:, 1]]
    d -= box * np.round(d / box)
    dist = np.linalg.norm(d, axis=1)
    overlap = rad[pairs[:, 0]] + rad[pairs[:, 1]] - dist
    touching = overlap > 0.0
    if not touching.any():
        return 0.0, 0.0
    energy = 0.5 * stiffness * float(np.sum(overlap[touching] ** 2))
    smaller = np.minimum(rad[pairs[:, 0]], rad[pairs[:, 1]])
    deepest = float(np.max(overlap[touching] / smaller[touching]))
    return energy, deepest


def total_energy(summary, rows, stiffness, box):
    """(kinetic + external potential + spring energy, deepest overlap / radius)."""
    spring, deepest = spring_energy(rows, stiffness, box)
    c = summary["conserved"]
    return c["kinetic_energy"] + c["potential_energy"] + spring, deepest
