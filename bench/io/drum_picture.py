"""The rotating drum in ParaView (docs/guide/walls.md): runs scenes/rotating-drum.toml (or reads
an existing run with --no-run) and renders its last frame with ParaView's pvbatch as a user
would set it up: the grains as Point Gaussian spheres of their radius (Scale by array `radius`,
Use Scale Function off, Gaussian Radius 1: ParaView 5.11), coloured by speed, and walls.pvd as
a half-transparent surface, seen along the drum's axis. Checks what the picture must show: the
drum's wall polygons lie on its radius, its three walls are in walls.pvd in the frame of the
grains, and the grains lie inside the drum (overlapping it by less than a tenth of their
radius), from 1 s on (poured and settled) as a bed in its lower half, not a floating cloud.
Prints the run's particle updates per core-second.

Debian 12's python3-paraview (pvbatch's Python modules) conflicts with python3-vtk9, which
the build needs: unpack it beside instead (apt-get download python3-paraview; dpkg -x it into
DIR) and run pvbatch with PYTHONPATH=DIR/usr/lib/python3/dist-packages.

usage: pvbatch bench/io/drum_picture.py [--app build/default/bin/regolith] [--np 1]
           [--steps 75000] [--out out/rotating-drum] [--png docs/images/rotating-drum.png]
           [--no-run]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

from paraview import simple as pv
from paraview import servermanager as sm
from vtkmodules.util.numpy_support import vtk_to_numpy

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DRUM_RADIUS = 0.05  # scenes/rotating-drum.toml


def entries(pvd):
    return ET.parse(pvd).getroot().find("Collection").findall("DataSet")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--app", default=os.path.join(ROOT, "build", "default", "bin", "regolith"))
    p.add_argument("--scene", default=os.path.join(ROOT, "scenes", "rotating-drum.toml"))
    p.add_argument("--np", type=int, default=1)
    p.add_argument("--steps", type=int, default=75000)
    p.add_argument("--out", default="out/rotating-drum")
    p.add_argument("--png", default=os.path.join(ROOT, "docs", "images", "rotating-drum.png"))
    p.add_argument("--no-run", action="store_true")
    a = p.parse_args()
    if not a.no_run:
#pvbatch is an MPI process itself : its Open MPI variables must not reach mpiexec.
        env = {
k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_"))}
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
        os.makedirs(a.out, exist_ok=True)
        summary = os.path.join(a.out, "summary.json")
        subprocess.run(["mpiexec", "-n", str(a.np), "--oversubscribe", a.app, a.scene, "--quiet",
                        "--steps", str(a.steps), "--output", a.out, "--json", summary],
                       check=True, env=env)
        with open(summary, encoding="utf-8") as f:
            s = json.load(f)
        print(f"{s['particles']} grains ({s['inserted']} inserted), {s['steps']} steps on "
              f"{s['ranks']} rank(s) in {s['wall_s']:.3g} s: {s['pupcs']:.3g} particle updates "
              f"per core-second; drum torque {s['walls'][0]['torque']}")
    grains_pvd = os.path.join(a.out, "particles.pvd")
    walls_pvd = os.path.join(a.out, "walls.pvd")
    times = [float(e.get("timestep")) for e in entries(grains_pvd)]
    if times != [float(e.get("timestep")) for e in entries(walls_pvd)]:
        sys.exit("walls.pvd and particles.pvd have different frames")

    grains = pv.PVDReader(FileName=grains_pvd)
    walls = pv.PVDReader(FileName=walls_pvd)
    t = times[-1]
    for reader in (grains, walls):
        reader.UpdatePipeline(t)
    g = sm.Fetch(grains)
    w = sm.Fetch(walls)
    xyz = vtk_to_numpy(g.GetPoints().GetData())
    radius = vtk_to_numpy(g.GetPointData().GetArray("radius"))
    rho = (xyz[:, 0] ** 2 + xyz[:, 2] ** 2) ** 0.5
    wall_ids = set(vtk_to_numpy(w.GetCellData().GetArray("wall")).tolist())
    if wall_ids != {0, 1, 2}:
        sys.exit(f"walls.pvd holds walls {sorted(wall_ids)}, expected 0, 1, 2")
#The drum's polygons (wall 0) lie on its radius.
    points = vtk_to_numpy(w.GetPoints().GetData())
    ids = vtk_to_numpy(w.GetCellData().GetArray("wall"))
    drum_points = set()
    for c in range(w.GetNumberOfCells()):
        if ids[c] == 0:
            cell = w.GetCell(c)
            drum_points.update(cell.GetPointId(k) for k in range(cell.GetNumberOfPoints()))
    worst = max(abs(math.hypot(points[k][0], points[k][2]) - DRUM_RADIUS) for k in drum_points)
    if worst > 1e-12:
        sys.exit(f"a drum vertex lies {worst} off its radius")
    if not (rho + 0.9 * radius <= DRUM_RADIUS).all():  # a contact overlaps a few per cent
        sys.exit("a grain lies outside the drum")
    below = (xyz[:, 2] < 0).mean() if len(xyz) else 0.0
    print(f"t = {t:.4g}: {len(xyz)} grains, {below:.0%} below the axis; "
          f"{w.GetNumberOfCells()} wall polygons, drum vertices on r = {DRUM_RADIUS}")
    if t >= 1.0 and below < 0.8:
        sys.exit("the grains do not lie as a bed in the drum's lower half")

    view = pv.CreateRenderView()
    view.ViewSize = [600, 600]
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    try:  # ParaView 5.11 draws a palette background unless told to use its own colour
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    shown = pv.Show(grains, view)
    shown.SetRepresentationType("Point Gaussian")
    shown.ShaderPreset = "Sphere"
    shown.ScaleByArray = 1
    shown.SetScaleArray = ["POINTS", "radius"]
    shown.UseScaleFunction = 0
    shown.GaussianRadius = 1.0
    pv.ColorBy(shown, ("POINTS", "velocity", "Magnitude"))
    shown.RescaleTransferFunctionToDataRange(True)
    lut = pv.GetColorTransferFunction("velocity")
    lut.ApplyPreset("Turbo", True)
    shown.SetScalarBarVisibility(view, True)
    bar = pv.GetScalarBar(lut, view)
    bar.Title = "speed [m/s]"
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
    drum = pv.Show(walls, view)
    drum.SetRepresentationType("Surface With Edges")
    drum.ColorArrayName = [None, ""]
    drum.DiffuseColor = [0.55, 0.55, 0.6]
    drum.Opacity = 0.25
    view.ViewTime = t
    view.CameraPosition = [0, -0.4, 0]
    view.CameraFocalPoint = [0, 0.02, 0]
    view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    os.makedirs(os.path.dirname(os.path.abspath(a.png)), exist_ok=True)
    pv.SaveScreenshot(a.png, view, ImageResolution=[600, 600])
    print(f"wrote {a.png}")


if __name__ == "__main__":
    main()
