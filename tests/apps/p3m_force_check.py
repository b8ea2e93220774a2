"""P3M in the coupled time step through the whole driver: the Kepler pair of
scenes/kepler.toml (separation 1, G = 1) takes one step with gravity.self = "pm" and "p3m" on
grids where the pair is only 1 and 2 cells apart (h = 1 with a 2-cell cut-off, h = 1/2 with the
default 4 cells; 4th-order gradient), and with the direct sum. The relative error of grain 1's
velocity change against the direct sum is the relative force error: the bare mesh's must be
large (softened over the kernel width), P3M's small. Prints the errors (quoted in
docs/results.md).

usage: p3m_force_check.py --mpiexec M --app APP --scene kepler.toml --out DIR [--np 2]
"""
import argparse
import math
import sys

from kepler_step import velocity_change

# (cells per block on x and y, cut-off in cells, the least mesh error, the largest P3M error)
CASES = ((4, 2, 0.3, 0.06), (8, 4, 0.08, 0.02))


def main():
    p = argparse.ArgumentParser()
    for k in ("--mpiexec", "--app", "--scene", "--out"):
        p.add_argument(k, required=True)
    p.add_argument("--np", type=int, default=2)
    a = p.parse_args()
    reference = velocity_change(a, "p3m_force", "direct", ["--set", "gravity.self=direct"])
    failures = []
    for cells, cutoff, mesh_least, p3m_most in CASES:
        grid = ["--set", "gravity.gradient_order=4",
                "--set", f"domain.cells_per_block=[{cells},{cells},{2 * cells}]"]
        errors = {}
        for method in ("pm", "p3m"):
            extra = ["--set", f"gravity.self={method}", *grid]
            if method == "p3m":
                extra += ["--set", f"gravity.p3m_cutoff={cutoff}"]
            dv = velocity_change(a, "p3m_force", f"{method}{cells}", extra)
            errors[method] = math.dist(dv, reference) / math.hypot(*reference)
        h = 4.0 / cells  # the domain is 8 wide over 2 blocks in x and y
        print(f"h = {h:g} (pair {1 / h:g} h apart): pm error {errors['pm']:.3g}, "
              f"p3m (cut-off {cutoff} cells) error {errors['p3m']:.3g}")
        if not errors["pm"] > mesh_least:
            failures.append(f"pm error {errors['pm']:.3g} at h = {h:g}, expected > {mesh_least}")
        if not errors["p3m"] < p3m_most:
            failures.append(f"p3m error {errors['p3m']:.3g} at h = {h:g}, expected < {p3m_most}")
    if failures:
        sys.exit("p3m_force_check: " + "; ".join(failures))


if __name__ == "__main__":
    main()
