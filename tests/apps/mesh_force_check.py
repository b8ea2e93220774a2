"""The particle-mesh self-gravity in the coupled time step: the Kepler pair of
scenes/kepler.toml (separation 1, G = 1) takes one step with gravity.self = "pm" on grids of
spacing h = 1, 1/2, 1/4 (cells_per_block doubled each time; 4th-order gradient) and with the
direct sum; the relative error of the velocity change of grain 1 against the direct sum is the
relative force error. It must fall as h falls and be below --finest-tol (2 %) at h = 1/4
(separation 4 h: the mesh force is good from ~4 h on). Prints the errors (the figures quoted in
docs/results.md).

usage: mesh_force_check.py --mpiexec M --app APP --scene kepler.toml --out DIR [--np 2]
"""
import argparse
import math
import sys

from kepler_step import velocity_change


def main():
    p = argparse.ArgumentParser()
    for k in ("--mpiexec", "--app", "--scene", "--out"):
        p.add_argument(k, required=True)
    p.add_argument("--np", type=int, default=2)
    p.add_argument("--finest-tol", type=float, default=0.02)
    a = p.parse_args()
    reference = velocity_change(a, "mesh_force", "direct", ["--set", "gravity.self=direct"])
    errors = []
    for cells in (4, 8, 16):  # the domain is 8 wide over 2 blocks in x and y, 1 in z
        dv = velocity_change(a, "mesh_force", f"pm{cells}", [
            "--set", "gravity.self=pm", "--set", "gravity.gradient_order=4",
            "--set", f"domain.cells_per_block=[{cells},{cells},{2 * cells}]"])
        errors.append(math.dist(dv, reference) / math.hypot(*reference))
        print(f"pm, h = {4.0 / cells:g}: relative force error {errors[-1]:.3g}")
    if not all(x > y for x, y in zip(errors, errors[1:])):
        sys.exit(f"mesh_force_check: the error does not fall with the grid spacing: {errors}")
    if not errors[-1] < a.finest_tol:
        sys.exit(f"mesh_force_check: error {errors[-1]:.3g} at h = 1/4, expected < "
                 f"{a.finest_tol}")


if __name__ == "__main__":
    main()
