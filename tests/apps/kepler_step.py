"""One step of the Kepler pair of scenes/kepler.toml through the driver, for the force checks
(mesh_force_check.py, p3m_force_check.py): grain 1's velocity change, which over one step is
its force per mass up to a constant factor."""
import csv
import os
import subprocess
import sys

V0 = 0.7071067811865476  # grain 1's initial velocity along y


def velocity_change(a, tag, name, extra):
    """Runs a.app on a.scene with a.np ranks for one step with the extra arguments; returns
    grain 1's (Δvx, Δvy). Exits naming the command if the run fails."""
    dump = os.path.join(a.out, f"{tag}_{name}.csv")
    command = [a.mpiexec, "-n", str(a.np), "--oversubscribe", a.app, a.scene, "--quiet",
               "--steps", "1", "--dump", dump, *extra]
    done = subprocess.run(command, capture_output=True, text=True, timeout=240, check=False)
    if done.returncode != 0:
        sys.exit(f"{tag}_check: {' '.join(command)} exited with {done.returncode}\n"
                 f"{done.stdout}\n{done.stderr}")
    with open(dump, encoding="utf-8") as f:
        grain = next(r for r in csv.DictReader(f) if r["uid"] == "1")
    return float(grain["vx"]), float(grain["vy"]) - V0
