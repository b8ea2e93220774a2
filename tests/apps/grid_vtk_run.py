"""Grid fields in the driver's VTK output: scenes/kepler.toml with particle-mesh
self-gravity (4 blocks of 8 x 8 x 16 cells over [-4, 4]^3) for 20 steps with
output.vtk_every = 10, on --np ranks. Checks from the XML headers: out/grid.pvd lists steps
0, 10, 20; each .vtm names the 4 blocks' .vti pieces, which exist; each piece has 8 x 8 x 16
cells of spacing 0.5 at its block's corner (the 4 corners distinct, ghost layers excluded)
and the cell arrays density, potential (negative throughout) and acceleration (3
components). The values are read back with VTK's readers by tests/io/GridOutputTest.cpp.

usage: grid_vtk_run.py --mpiexec M --app APP --scene kepler.toml --out DIR --np N
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET


def fail(message):
    sys.exit(f"grid_vtk_run: {message}")


def header(path):
    with open(path, "rb") as f:
        text = f.read(4000).decode("latin-1")
    return text.split("<AppendedData")[0]


def main():
    p = argparse.ArgumentParser()
    for k in ("--mpiexec", "--app", "--scene", "--out"):
        p.add_argument(k, required=True)
    p.add_argument("--np", type=int, required=True)
    a = p.parse_args()
    out = os.path.join(a.out, f"grid_vtk_np{a.np}")
    shutil.rmtree(out, ignore_errors=True)
    command = [a.mpiexec, "-n", str(a.np), "--oversubscribe", a.app, a.scene, "--quiet",
               "--steps", "20", "--output", out, "--set", "gravity.self=pm",
               "--set", "domain.cells_per_block=[8,8,16]", "--set", "output.vtk_every=10"]
    done = subprocess.run(command, capture_output=True, text=True, timeout=120, check=False)
    if done.returncode != 0:
        fail(f"{' '.join(command)} exited with {done.returncode}\n{done.stderr}")
    sets = ET.parse(os.path.join(out, "grid.pvd")).getroot().find("Collection").findall("DataSet")
    files = [d.get("file") for d in sets]
    if files != [f"vtk/grid_{s:08d}.vtm" for s in (0, 10, 20)]:
        fail(f"grid.pvd lists {files}")
    for index in files:
        vtm = os.path.join(out, index)
        root = ET.parse(vtm).getroot()
        pieces = [d.get("file") for d in root.iter("DataSet")]
        if len(pieces) != 4:
            fail(f"{vtm} names {len(pieces)} pieces, expected 4")
        corners = set()
        for piece in pieces:
            path = os.path.join(os.path.dirname(vtm), piece)
            if not os.path.exists(path):
                fail(f"{vtm} names {piece}, which does not exist")
            h = header(path)
            image = re.search(r'<ImageData WholeExtent="([^"]*)" Origin="([^"]*)" '
                              r'Spacing="([^"]*)"', h)
            if image is None or image.group(1) != "0 8 0 8 0 16" or image.group(3) != "0.5 0.5 0.5":
                fail(f"{path}: image header {image and image.groups()}")
            corners.add(image.group(2))
            arrays = dict(re.findall(r'Name="(\w+)"( NumberOfComponents="3")?', h))
            if sorted(arrays) != ["acceleration", "density", "potential"] or \
                    not arrays["acceleration"]:
                fail(f"{path}: cell arrays {arrays}")
            top = float(re.search(r'Name="potential"[^>]*RangeMax="([^"]*)"', h).group(1))
            if not top < 0.0:
                fail(f"{path}: potential up to {top}, expected negative everywhere")
        if corners != {"-4 -4 -4", "0 -4 -4", "-4 0 -4", "0 0 -4"}:
            fail(f"{vtm}: block corners {sorted(corners)}")
    print(f"grid_vtk_run: {a.np} ranks, all checks passed")


if __name__ == "__main__":
    main()
