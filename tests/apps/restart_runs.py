"""Checkpoint and restart of `regolith` end to end, on the scene
tests/apps/scenes/restart.toml (1000 grains falling on a floor, reproducible mode, 40 steps).

usage: restart_runs.py --mpiexec M --app APP --scene SCENE --out DIR [--case plain|gravity]

Case "plain" checks, in order (exit 1 with the reason on the first failure):
 1. the reference: 40 steps on 2 ranks;
 2. 20 steps on 2 ranks writing a checkpoint every 5 steps and keeping 3: exactly the
    checkpoints of steps 10, 15, 20 remain, no temporary file; its VTK output (every 10
    steps) is a particles.pvd and blocks.pvd series of steps 0, 10, 20 whose .pvtu files
    name 2 existing pieces holding the 1000 grains (the 8 blocks);
 3. restarts to the scene's 40 steps (a total): from step 20 on 3 ranks and from step 10 on
    1 rank give the reference's checksum, having run 20 and 30 steps; the first, into the
    directory of run 2, continues its VTK series (steps 0-10 on 2 ranks, 20-40 on 3); so does
    the restart from step 20 on 3 ranks with a sync skin;
 4. a writer killed on purpose mid-write (REGOLITH_TEST_ABORT_IN_CHECKPOINT=20) exits
    non-zero and leaves the checkpoint of step 10 complete, which restarts to the reference;
 5. one rank's part of the step-20 checkpoint failing (REGOLITH_TEST_FAIL_IN_CHECKPOINT=20:1,
    as a full disk): exit code 2 with the message once, no hang, the checkpoint of step 10 and
    nothing else left, which restarts to the reference; a directory under the name of the
    step-20 checkpoint is refused before the first step (exit code 2, the message once,
    nothing written), and so is a file there that is no HDF5 file (kept as it was);
 6. a truncated file, a flipped byte, a scene with another domain, a step beyond
    time.steps and grains of a material type the scene lacks are refused on 2 ranks: exit
    code 2, the message once on stderr naming the file, no crash, every checkpoint file
    byte-identical before and after;
 7. a restart at the scene's last step runs none with a warning; another scene file (name
    and friction changed, an [output] added) restarts with one
    warning naming the sections that differ (name, contact); so does the same file with a
    --set change of the friction; a checkpoint written with that --set and restarted with
    it does not warn.

Case "gravity", on tests/apps/scenes/restart_gravity.toml (729 grains, direct self-gravity
with update_threshold > 0: the field is recomputed only every few steps; between updates
each grain keeps the field of the last update, which the checkpoint stores with the update
policy's reference positions; grains sit on the block faces and change rank between
updates):
 1. the reference: 40 steps on 2 ranks, with more than one update and fewer than one per
    step, and a checksum other than that of the run without self-gravity;
 2. the same 40 steps on 3 ranks give the same checksum (the policy does not depend on the
    layout: a grain that changes rank brings its reference and field along);
 3. 20 steps on 2 ranks writing checkpoints at steps 10 and 20; restarts to 40 steps from
    step 20 on 2 ranks and from step 10 on 3 ranks give the reference's checksum; the first
    makes exactly the updates the reference made after step 20 (no update forced by the
    restart);
 4. with gravity.self = "pm" (the PETSc Poisson solve): 20 + 20 steps give the 40-step
    run's checksum, on 2 and on 4 ranks, the restart writing VTK output with the grid fields
    at steps 20, 30 and 40.

Case "auto", on scenes/default.toml (time.dt, gravity.self and gravity.update_threshold
"auto"; 16 steps, a checkpoint at step 8):
 1. the restart from step 8 with the same scene reuses what "auto" chose (printed "from the
    checkpoint"), without a warning, and ends with the uninterrupted run's checksum;
 2. so does the restart that sets those values with --set, as the run summary lists them;
 3. a checkpoint written by a run that set them itself (no "auto" lines) is refused for the
    scene with "auto", naming the keys: exit code 2.
"""
import argparse
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

CRASH_SIGNS = ("internal error", "terminate called", "Segmentation fault", "MPI_ABORT",
               "core dumped", "Sanitizer")


def fail(message):
    sys.exit(f"restart_runs: {message}")


class Runner:
    def __init__(self, mpiexec, app, scene, out):
        self.mpiexec, self.app, self.scene, self.out = mpiexec, app, scene, out

    def path(self, name):
        return os.path.join(self.out, name)

    def run(self, np, args, env_extra=None):
        command = [self.mpiexec, "-n", str(np), "--oversubscribe", self.app, self.scene,
                   "--quiet", *args]
        env = dict(os.environ, **(env_extra or {}))
        done = subprocess.run(command, capture_output=True, text=True, timeout=60, check=False,
                              env=env)
        return command, done

    def summary(self, np, name, args):
        json_path = self.path(name + ".json")
        command, done = self.run(np, [*args, "--json", json_path])
        if done.returncode != 0:
            fail(f"{' '.join(command)} exited with {done.returncode}\n{done.stderr}")
        with open(json_path, encoding="utf-8") as f:
            return json.load(f)


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def check_vtk(directory, steps, nps, dt=0.01):
    """The driver's VTK series (io/vtk): counts from the XML headers of the pieces."""
    for kind, total, what in (("particles", 1000, "NumberOfPoints"), ("blocks", 8, "NumberOfCells")):
        root = ET.parse(os.path.join(directory, f"{kind}.pvd")).getroot()
        sets = root.find("Collection").findall("DataSet")
        if [(round(float(d.get("timestep")), 9), d.get("file")) for d in sets] != [
                (round(s * dt, 9), f"vtk/{kind}_{s:08d}.pvtu") for s in steps]:
            fail(f"{directory}/{kind}.pvd lists {[d.attrib for d in sets]}")
        for d, np in zip(sets, nps):
            index = os.path.join(directory, d.get("file"))
            pieces = [p.get("Source") for p in ET.parse(index).getroot().iter("Piece")]
            if len(pieces) != np:
                fail(f"{index} names {len(pieces)} pieces, expected {np}")
            count = 0
            for piece in pieces:
                with open(os.path.join(os.path.dirname(index), piece), "rb") as f:
                    header = f.read(2000).decode("latin-1")
                count += int(re.search(what + r'="\s*(\d+)', header).group(1))
            if count != total:
                fail(f"{index}: {count} {what} in its pieces, expected {total}")


def expect_refused(runner, np, args, message, files):
    before = {f: digest(f) for f in files}
    command, done = runner.run(np, args)
    line = f"{' '.join(command)}\n--- stderr:\n{done.stderr}"
    if done.returncode != 2:
        fail(f"expected exit code 2, got {done.returncode}: {line}")
    if done.stderr.count(message) != 1:
        fail(f"expected the message {message!r} once on stderr: {line}")
    if any(sign in done.stderr for sign in CRASH_SIGNS):
        fail(f"a crash sign on stderr: {line}")
    if {f: digest(f) for f in files} != before:
        fail(f"a checkpoint file changed: {line}")


def auto_case(runner):
    # The checksums are compared: the blocks must not split (a restart cuts the scene's blocks;
    # the tree's sums follow the ranks' blocks).
    steps = ["--steps", "16", "--set", "output.vtk_every=0", "--set", "balance.split_levels=0"]
    reference = runner.summary(2, "reference", steps)
    first = runner.path("first")
    runner.summary(2, "first", [*steps, "--output", first, "--set", "output.checkpoint_every=8"])
    step8 = os.path.join(first, "checkpoint_00000008.h5")
    chosen = {c["key"]: c["value"] for c in reference["auto"]} if isinstance(
        reference["auto"], list) else {k: v["value"] for k, v in reference["auto"].items()}
    for key in ("time.dt", "gravity.self", "gravity.theta", "gravity.update_threshold"):
        if key not in chosen:
            fail(f"the run summary's auto lists {sorted(chosen)}: expected {key} among them")
    explicit = [arg for key, value in chosen.items() for arg in ("--set", f"{key}={value}")]
    for name, extra in (("same scene", []), ("--set as the summary lists", explicit)):
        command, done = runner.run(2, [*steps, "--restart", step8, "--output",
                                       runner.path("r" + str(len(extra))), *extra, "--json",
                                       runner.path(f"r{len(extra)}.json")])
        line = f"{' '.join(command)}\n--- output:\n{done.stdout}{done.stderr}"
        if done.returncode != 0 or "[warn]" in done.stdout + done.stderr:
            fail(f"restart ({name}): exit code {done.returncode}, expected 0 without a warning: "
                 f"{line}")
        with open(runner.path(f"r{len(extra)}.json"), encoding="utf-8") as f:
            checksum = json.load(f)["checksum"]
        if checksum != reference["checksum"]:
            fail(f"restart ({name}): checksum {checksum}, the uninterrupted run "
                 f"{reference['checksum']}")
    set_dir = runner.path("set")
    runner.summary(2, "set", [*steps, *explicit, "--output", set_dir,
                              "--set", "output.checkpoint_every=8"])
    expect_refused(runner, 2, [*steps, "--restart", os.path.join(set_dir, "checkpoint_00000008.h5"),
                               "--output", runner.path("refused")],
                   'the checkpoint does not say what "auto" chose for time.dt gravity.self '
                   'gravity.update_threshold', [])


def gravity_case(runner):
    plain = runner.summary(2, "plain", ["--set", "gravity.self=none"])["checksum"]
    ref = runner.summary(2, "reference", [])
    updates = ref["gravity"]["updates"]
    if not 1 < updates < 40:
        fail(f"the reference made {updates} gravity updates in 40 steps; expected more than 1 "
             "and fewer than 40 (the threshold must skip updates for this test to mean anything)")
    if ref["checksum"] == plain:
        fail("self-gravity did not change the final state")
    three = runner.summary(3, "reference_np3", [])
    if three["checksum"] != ref["checksum"]:
        fail(f"40 steps on 3 ranks: checksum {three['checksum']}, on 2 ranks {ref['checksum']} "
             "(the update policy depends on the layout)")

    first_dir = runner.path("first")
    first = runner.summary(2, "first", ["--steps", "20", "--output", first_dir,
                                        "--set", "output.checkpoint_every=10"])
    for np, step, name in ((2, 20, "restart_np2"), (3, 10, "restart_np3")):
        start = os.path.join(first_dir, f"checkpoint_{step:08d}.h5")
        s = runner.summary(np, name, ["--restart", start,
                                      "--output", runner.path(name)])
        if s["checksum"] != ref["checksum"] or s["steps"] != 40 - step:
            fail(f"restart from {start} on {np} ranks: checksum {s['checksum']}, steps "
                 f"{s['steps']}; expected {ref['checksum']}, {40 - step}")
        if step == 20 and first["gravity"]["updates"] + s["gravity"]["updates"] != updates:
            fail(f"updates: {first['gravity']['updates']} before the checkpoint + "
                 f"{s['gravity']['updates']} after the restart, the reference made {updates} "
                 "(the restart did not continue the update policy)")
    # A restart warns about the self-gravity parameters against the grains as a new run does
    # (they ran for new runs only): at G = 2000 a close orbit takes fewer than 20 steps of dt =
    # 0.01 (period 2 pi sqrt(3 / (pi G rho)) = 0.137) and k = 50 is soft (touching grains
    # would overlap by G m^2 / (2r)^2 / k = 16 radii), and an update threshold of 2 exceeds
    # the grain spacing 0.9.
    start = os.path.join(first_dir, "checkpoint_00000020.h5")
    command = [runner.mpiexec, "-n", "2", "--oversubscribe", runner.app, runner.scene,
               "--restart", start, "--output", runner.path("coarse_orbit"), "--steps", "21",
               "--set", "gravity.G=2000", "--set", "gravity.update_threshold=2.0"]
    # (without --quiet, which silences warnings)
    done = subprocess.run(command, capture_output=True, text=True, timeout=60, check=False)
    for warning in ("exceeds the orbital period of two touching grains",
                    "is soft for the grains' own gravity", "exceeds the grain spacing"):
        if done.returncode != 0 or done.stdout.count(warning) != 1:
            fail(f"{' '.join(command)}: exit {done.returncode}, expected 0 and one warning "
                 f"containing {warning!r}\n--- stdout:\n{done.stdout}\n--- stderr:\n"
                 f"{done.stderr}")
    # The PETSc Poisson solve (pm): in reproducible mode each solve starts from zero, so the
    # restart, which has no last solution to warm-start from, repeats the run's bits.
    pm = ["--set", "gravity.self=pm", "--set", "domain.cells_per_block=[8,8,8]",
          "--set", "domain.min=[-2,-2,-2]", "--set", "domain.max=[12,12,14]"]
    # On 4 ranks too: there PETSc's default GAMG gave other bits from run to run.
    pm_refs = []
    for np in (2, 4):
        pm_ref = runner.summary(np, f"pm_reference_np{np}", pm)["checksum"]
        pm_dir = runner.path(f"pm_first_np{np}")
        runner.summary(np, f"pm_first_np{np}", [*pm, "--steps", "20", "--output", pm_dir,
                                                "--set", "output.checkpoint_every=20"])
        start = os.path.join(pm_dir, "checkpoint_00000020.h5")
        # With VTK output: the restart writes the grid fields from its first step on (it has
        # no update before the next due one, so it computes them for the output alone), and
        # that changes nothing else.
        restart_dir = runner.path(f"pm_restart_np{np}")
        s = runner.summary(np, f"pm_restart_np{np}", [*pm, "--restart", start, "--output",
                                                      restart_dir, "--set", "output.vtk_every=10"])
        if s["checksum"] != pm_ref:
            fail(f"pm on {np} ranks: restart from {start}: checksum {s['checksum']}, the run "
                 f"gave {pm_ref}")
        grid_pvd = os.path.join(restart_dir, "grid.pvd")
        outputs = len(list(ET.parse(grid_pvd).getroot().iter("DataSet"))) \
            if os.path.exists(grid_pvd) else 0
        if outputs != 3:
            fail(f"pm on {np} ranks, restart with VTK output every 10 steps from step 20 to 40: "
                 f"{grid_pvd} lists {outputs} grid outputs, expected 3 (steps 20, 30, 40)")
        pm_refs.append(pm_ref)
    print(f"restart_runs: gravity checks passed (reference checksum {ref['checksum']}, "
          f"{updates} updates in 40 steps; pm {pm_refs})")


def main():
    parser = argparse.ArgumentParser()
    for option in ("--mpiexec", "--app", "--scene", "--out"):
        parser.add_argument(option, required=True)
    parser.add_argument("--case", choices=("plain", "gravity", "auto"), default="plain")
    a = parser.parse_args()
    out = os.path.join(a.out, "restart" if a.case == "plain" else "restart_" + a.case)
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    runner = Runner(a.mpiexec, a.app, a.scene, out)
    if a.case != "plain":
        (gravity_case if a.case == "gravity" else auto_case)(runner)
        return

    reference = runner.summary(2, "reference", [])["checksum"]

    first = runner.path("first")
    runner.summary(2, "first", ["--steps", "20", "--output", first,
                                "--set", "output.checkpoint_every=5",
                                "--set", "output.checkpoint_keep=3",
                                "--set", "output.vtk_every=10"])
    check_vtk(first, (0, 10, 20), (2, 2, 2))
    names = sorted(n for n in os.listdir(first) if n.startswith("checkpoint"))
    expected = [f"checkpoint_{s:08d}.h5" for s in (10, 15, 20)]
    if names != expected:
        fail(f"{first} holds {names}, expected {expected} (rotation, no temporary file)")
    step10, step20 = (os.path.join(first, expected[k]) for k in (0, 2))

    # The 3-rank restart writes into the first run's directory: its VTK series continues.
    for np, start, steps, out in ((3, step20, 20, first), (1, step10, 30, runner.path("r1"))):
        s = runner.summary(np, f"restart_np{np}", ["--restart", start, "--output", out,
                                                   "--set", "output.vtk_every=10"])
        if s["checksum"] != reference or s["steps"] != steps or s["particles"] != 1000:
            fail(f"restart from {start} on {np} ranks: checksum {s['checksum']}, steps "
                 f"{s['steps']}, particles {s['particles']}; expected {reference}, {steps}, 1000")

    check_vtk(first, (0, 10, 20, 30, 40), (2, 2, 3, 3, 3))

    # With a sync skin (shadows along fixed lists, remote ones too) the restart on 3 ranks
    # follows the same trajectory: the list is decided afresh from the restored grains.
    s = runner.summary(3, "restart_np3_skin", ["--restart", step20, "--output",
                                               runner.path("skin"), "--set", "sync.skin=0.1"])
    if s["checksum"] != reference or s["steps"] != 20:
        fail(f"restart from {step20} on 3 ranks with sync.skin = 0.1: checksum {s['checksum']}, "
             f"steps {s['steps']}; expected {reference}, 20")

    killed = runner.path("killed")
    command, done = runner.run(2, ["--output", killed, "--set", "output.checkpoint_every=10"],
                               {"REGOLITH_TEST_ABORT_IN_CHECKPOINT": "20"})
    if done.returncode == 0:
        fail(f"{' '.join(command)}: the writer killed at step 20 exited 0")
    if os.path.exists(os.path.join(killed, "checkpoint_00000020.h5")):
        fail("the killed writer left a checkpoint of step 20 under its final name")
    s = runner.summary(2, "after_kill", ["--restart", os.path.join(killed, expected[0]),
                                         "--output", runner.path("after_kill")])
    if s["checksum"] != reference:
        fail(f"restart from the checkpoint before the killed one: checksum {s['checksum']}, "
             f"expected {reference}")

    # One rank's part of a dataset fails (as on a full disk): every rank stops with the
    # message (exit 2, no hang in the next collective write), the checkpoint of step 10 stays
    # and restarts, no temporary is left.
    full = runner.path("full")
    command, done = runner.run(2, ["--output", full, "--set", "output.checkpoint_every=10"],
                               {"REGOLITH_TEST_FAIL_IN_CHECKPOINT": "20:1"})
    line = f"{' '.join(command)}\n--- stderr:\n{done.stderr}"
    message = (f"cannot write checkpoint '{os.path.join(full, 'checkpoint_00000020.h5')}'")
    if done.returncode != 2 or done.stderr.count(message) != 1 or "REGOLITH_TEST_FAIL" not in \
            done.stderr or any(sign in done.stderr for sign in CRASH_SIGNS):
        fail(f"a failed checkpoint write: expected exit code 2 and {message!r} once: {line}")
    left = sorted(f for f in os.listdir(full) if f.startswith("checkpoint"))
    if left != [expected[0]]:
        fail(f"after the failed write {full} holds {left}: expected the checkpoint of step 10 "
             "only (no step 20, no temporary)")
    s = runner.summary(2, "after_full", ["--restart", os.path.join(full, expected[0]),
                                         "--output", runner.path("after_full")])
    if s["checksum"] != reference:
        fail(f"restart from the checkpoint before the failed one: checksum {s['checksum']}, "
             f"expected {reference}")

    # A directory under the name of a checkpoint the run will write is refused before the
    # first step (it was found only by the rename after the whole run, and the run's output
    # was lost), on every rank: exit code 2, the message once, the earlier run's checkpoint
    # beside it untouched, nothing written.
    blocked = runner.path("blocked")
    os.makedirs(os.path.join(blocked, "checkpoint_00000020.h5"))
    shutil.copy(step10, os.path.join(blocked, expected[0]))
    expect_refused(runner, 2, ["--output", blocked, "--set", "output.checkpoint_every=10"],
                   "holds 'checkpoint_00000020.h5', which is not a file",
                   [os.path.join(blocked, expected[0])])
    if sorted(os.listdir(blocked)) != [expected[0], "checkpoint_00000020.h5"]:
        fail(f"a run refused before its first step wrote into {blocked}: "
             f"{sorted(os.listdir(blocked))}")
    # So is a file there that is no HDF5 file (it was replaced without a word), kept as it was.
    notes = runner.path("notes")
    os.makedirs(notes)
    with open(os.path.join(notes, "checkpoint_00000020.h5"), "w", encoding="utf-8") as f:
        f.write("my notes\n")
    expect_refused(runner, 2, ["--output", notes, "--set", "output.checkpoint_every=10"],
                   "holds 'checkpoint_00000020.h5', which is not an HDF5 file",
                   [os.path.join(notes, "checkpoint_00000020.h5")])

    truncated = runner.path("truncated.h5")
    shutil.copy(step20, truncated)
    os.truncate(truncated, os.path.getsize(step20) // 2)
    flipped = runner.path("flipped.h5")
    shutil.copy(step20, flipped)
    with open(flipped, "r+b") as f:  # a byte well inside the datasets (raw data is the bulk)
        f.seek(int(os.path.getsize(flipped) * 0.6))
        byte = f.read(1)
        f.seek(-1, os.SEEK_CUR)
        f.write(bytes([byte[0] ^ 0x01]))
    files = [truncated, flipped, step10, step20]
    refused = runner.path("refused")
    expect_refused(runner, 2, ["--restart", truncated, "--output", refused],
                   f"checkpoint '{truncated}': HDF5 cannot open it (truncated or damaged file)",
                   files)
    expect_refused(runner, 2, ["--restart", flipped, "--output", refused],
                   f"checkpoint '{flipped}': checksum mismatch", files)
    expect_refused(runner, 2, ["--restart", step20, "--output", refused,
                               "--set", "domain.max=[12,10,12]"],
                   f"--restart {step20}: the checkpoint was written for the domain", files)
    expect_refused(runner, 2, ["--restart", step20, "--output", refused, "--steps", "10"],
                   f"--restart {step20}: the checkpoint is at step 20, beyond", files)
    # Grains of a material type the scene does not name (the contact tables are indexed by
    # type unchecked): refused, not read out of bounds.
    typed = runner.path("typed")
    runner.summary(1, "typed", ["--steps", "10", "--output", typed,
                                "--set", "output.checkpoint_every=10", "--set", "particles.0.type=1"])
    typed10 = os.path.join(typed, "checkpoint_00000010.h5")
    expect_refused(runner, 2, ["--restart", typed10, "--output", refused],
                   "has material type 1, but the scene's [[particles]] and [[walls]] name types "
                   "up to 0 only (the checkpoint was written for another scene)", [typed10])
    # Another scene file (its name, friction and output changed) restarts with one warning
    # naming the sections that differ, output and time not among them.
    with open(runner.scene, encoding="utf-8") as f:
        text = f.read()
    other = runner.path("other.toml")
    with open(other, "w", encoding="utf-8") as f:
        f.write(text.replace('name = "restart"', 'name = "other"')
                    .replace("friction = 0.5", "friction = 0.4") + "\n[output]\nvtk_every = 0\n"
                + "# --set (a user's comment: not an override; it once silenced the comparison)\n")
    def loud(scene, args):  # without --quiet, which silences warnings
        command = [runner.mpiexec, "-n", "2", "--oversubscribe", runner.app, scene, *args]
        return command, subprocess.run(command, capture_output=True, text=True, timeout=60,
                                       check=False)
    # A restart at the scene's last step runs none, and says so (--steps is a total, not a
    # remainder).
    command, done = loud(runner.scene, ["--restart", step20, "--output", runner.path("none"),
                                        "--steps", "20"])
    nothing = f"--restart {step20}: the checkpoint is at step 20, the scene's time.steps"
    if done.returncode != 0 or done.stdout.count(nothing) != 1:
        fail(f"{' '.join(command)}: exit {done.returncode}, expected 0 and one warning "
             f"{nothing!r}\n--- stdout:\n{done.stdout}\n--- stderr:\n{done.stderr}")
    command, done = loud(other, ["--restart", step20, "--output", runner.path("other")])
    warning = (f"--restart {step20}: the checkpoint was written by another scene (it differs in "
               "name, contact)")
    if done.returncode != 0 or done.stdout.count(warning) != 1:
        fail(f"{' '.join(command)}: exit {done.returncode}, expected 0 and the warning "
             f"{warning!r} once\n--- stdout:\n{done.stdout}")
    # The banner of a restart: the steps still to run and the grains of the checkpoint (not
    # "40 steps" and "from 1 [[particles]] entries").
    for expected in ("  20 steps (from step 20 to 40) of dt", "1000 particles from the checkpoint"):
        if expected not in done.stdout:
            fail(f"{' '.join(command)}: expected {expected!r} in the banner\n--- stdout:\n"
                 f"{done.stdout}")
    # The scenes compared are the files with their --set overrides: the same file with a
    # --set change of the physics warns (it did not: only the files were compared) ...
    command, done = loud(runner.scene, ["--restart", step20, "--output", runner.path("same"),
                                        "--set", "contact.friction=0.4"])
    warning = warning.replace("name, contact", "contact")
    if done.returncode != 0 or done.stdout.count(warning) != 1:
        fail(f"{' '.join(command)}: exit {done.returncode}, expected 0 and the warning "
             f"{warning!r} once\n--- stdout:\n{done.stdout}")
    # ... and a checkpoint written with that --set, restarted with it, does not.
    changed = runner.path("changed")
    runner.summary(2, "changed", ["--output", changed, "--set", "contact.friction=0.4",
                                  "--set", "output.checkpoint_every=10", "--steps", "10"])
    command, done = loud(runner.scene, ["--restart",
                                        os.path.join(changed, "checkpoint_00000010.h5"),
                                        "--output", runner.path("same"),
                                        "--set", "contact.friction=0.4"])
    if done.returncode != 0 or "another scene" in done.stdout:
        fail(f"{' '.join(command)}: exit {done.returncode}, or the same scene and --set "
             f"warned\n{done.stdout}")
    print(f"restart_runs: all checks passed (reference checksum {reference})")


if __name__ == "__main__":
    main()
