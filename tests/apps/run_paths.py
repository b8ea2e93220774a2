"""The files a `regolith` run reads and writes, end to end on tests/apps/scenes/small.toml:
special files are refused as inputs, outputs never overwrite an input or each other, and one
output that fails costs no other.

usage: run_paths.py --mpiexec M --app APP --scenes DIR --out DIR --np N --case CASE

Cases (exit 1 with the reason on a failure; every refusal: exit code 2, the message once on
stderr, no crash, within the timeout):
  scene_fifo        a scene file that is a FIFO is refused, not waited on;
  csv_fifo          a [[particles]] path that is a FIFO is refused alike;
  json_is_scene     --json naming the scene file (also through a link) is refused before
                    the first step, the scene kept byte for byte;
  dump_is_restart   --dump naming the --restart checkpoint is refused, the checkpoint kept;
  json_is_dump      --json and --dump naming one file are refused;
  dump_is_vtk       --dump naming the VTK series the run writes in output.dir is refused;
  dump_dir          --dump newdir/ is refused before the run, the directory not created;
  dump_fails        --dump to a full disk (/dev/full) after the run: exit code 2 naming it,
                    and the --json summary is written all the same;
  name_nul          a scene name with a NUL byte prints whole in the report, escaped;
  csv_secret        a CSV path naming a file that is no grain table: the message quotes
                    nothing of it;
  csv_nul           a CSV column name with a NUL byte: the message prints whole, escaped.
"""
import argparse
import hashlib
import os
import shutil
import subprocess
import sys

SECRET = "root:$y$j9T$SECRETHASHVALUE0123456789:19000:0:99999:7:::"


def fail(why):
    print(f"FAIL: {why}")
    sys.exit(1)


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


class Runner:
    def __init__(self, args):
        self.args = args

    def run(self, *argv, cwd=None):
        cmd = [self.args.mpiexec, "-n", str(self.args.np), "--oversubscribe", self.args.app,
               *argv]
        try:
            p = subprocess.run(cmd, capture_output=True, text=True, timeout=60, cwd=cwd,
                               errors="replace")
        except subprocess.TimeoutExpired:
            fail(f"timed out (a hang): {' '.join(cmd)}")
        for crash in ("internal error", "MPI_ABORT", "terminate called", "Segmentation fault"):
            if crash in p.stderr:
                fail(f"crashed ('{crash}'): {' '.join(cmd)}\n{p.stderr}")
        return p

    def refused(self, message, *argv, cwd=None):
        p = self.run(*argv, cwd=cwd)
        if p.returncode != 2:
            fail(f"expected exit code 2, got {p.returncode}: {' '.join(argv)}\n"
                 f"stdout:\n{p.stdout}\nstderr:\n{p.stderr}")
        if p.stderr.count(message) != 1:
            fail(f"expected once on stderr: {message}\nstderr:\n{p.stderr}")
        if "step 1" in p.stdout or " steps in " in p.stdout:
            fail(f"the run started before refusing:\n{p.stdout}")
        return p


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--mpiexec", required=True)
    ap.add_argument("--app", required=True)
    ap.add_argument("--scenes", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--case", required=True)
    args = ap.parse_args()
    r = Runner(args)
    work = os.path.abspath(os.path.join(args.out, f"run_paths_{args.case}_np{args.np}"))
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    small = os.path.join(args.scenes, "small.toml")
    scene = os.path.join(work, "scene.toml")
    shutil.copy(small, scene)
    c = args.case

    if c == "scene_fifo":
        fifo = os.path.join(work, "scene.fifo")
        os.mkfifo(fifo)
        r.refused(f"cannot read '{fifo}': it is a FIFO, not a regular file", fifo)
    elif c == "csv_fifo":
        fifo = os.path.join(work, "grains.csv")
        os.mkfifo(fifo)
        r.refused(f"particles[0].path: '{fifo}' is a FIFO, not a regular file",
                  os.path.join(args.scenes, "missing_particle_file.toml"),
                  "--set", f"particles.0.path=\"{fifo}\"")
    elif c == "json_is_scene":
        before = digest(scene)
        r.refused("--json scene.toml: names the scene file ('scene.toml'), an input of the "
                  "run, which the run would overwrite", "scene.toml", "--json", "scene.toml",
                  cwd=work)
        os.symlink("scene.toml", os.path.join(work, "link.json"))
        r.refused("--json link.json: names the scene file", "scene.toml", "--json",
                  "link.json", cwd=work)
        if digest(scene) != before:
            fail("the scene file changed")
    elif c == "dump_is_restart":
        p = r.run(scene, "--steps", "10", "--quiet", "--output", "out", "--set",
                  "output.checkpoint_every=10", cwd=work)
        if p.returncode != 0:
            fail(f"the checkpoint run failed:\n{p.stderr}")
        ck = os.path.join("out", "checkpoint_00000010.h5")
        before = digest(os.path.join(work, ck))
        r.refused(f"--dump {ck}: names the --restart checkpoint ('{ck}'), an input of the run",
                  scene, "--restart", ck, "--dump", ck, cwd=work)
        if digest(os.path.join(work, ck)) != before:
            fail("the checkpoint changed")
    elif c == "json_is_dump":
        r.refused("--dump same.out: names the --json file too, which the run would overwrite",
                  scene, "--json", "same.out", "--dump", "same.out", cwd=work)
        if os.path.exists(os.path.join(work, "same.out")):
            fail("same.out was written")
    elif c == "dump_is_vtk":
        r.refused("--dump out/particles.pvd: names the VTK series particles.pvd in output.dir "
                  "= \"out\"", scene, "--output", "out", "--set", "output.vtk_every=10",
                  "--dump", "out/particles.pvd", cwd=work)
    elif c == "dump_dir":
        r.refused("--dump newdir/: names a directory, expected a file name", scene, "--dump",
                  "newdir/", cwd=work)
        if os.path.exists(os.path.join(work, "newdir")):
            fail("newdir was created")
    elif c == "dump_fails":
        p = r.run(scene, "--quiet", "--dump", "/dev/full", "--json", "summary.json", cwd=work)
        if p.returncode != 2 or p.stderr.count("cannot write '/dev/full': No space left") != 1:
            fail(f"expected exit code 2 naming /dev/full once, got {p.returncode}:\n{p.stderr}")
        summary = os.path.join(work, "summary.json")
        if not os.path.exists(summary) or "checksum" not in open(summary).read():
            fail("the summary was not written")
    elif c == "name_nul":
        p = r.run(scene, "--steps", "1", "--set", 'name="before\\u0000after"', cwd=work)
        if p.returncode != 0 or "scene 'before\\x00after' (" not in p.stdout:
            fail(f"expected the name escaped in the report:\n{p.stdout}\n{p.stderr}")
    elif c == "csv_secret":
        secret = os.path.join(work, "shadow")
        with open(secret, "w") as f:
            f.write(SECRET + "\n")
        p = r.refused("line 1: not a header of grain columns",
                      os.path.join(args.scenes, "missing_particle_file.toml"),
                      "--set", f"particles.0.path=\"{secret}\"")
        if "SECRET" in p.stderr or "root" in p.stderr:
            fail(f"the message quotes the file:\n{p.stderr}")
    elif c == "csv_nul":
        binary = os.path.join(work, "binary.csv")
        with open(binary, "wb") as f:
            f.write(b"x,y,z,radius,ab\0cd\n1,1,1,0.5,0\n")
        r.refused("unknown column 'ab\\x00cd' (known: x,y,z,",
                  os.path.join(args.scenes, "missing_particle_file.toml"),
                  "--set", f"particles.0.path=\"{binary}\"")
    else:
        fail(f"unknown case {c}")
    shutil.rmtree(work, ignore_errors=True)
    print(f"ok: {c}")


if __name__ == "__main__":
    main()
