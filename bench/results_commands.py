#!/usr/bin/python3
"""The commands of docs/results.md: list them, run them (`make bench`), or check them in a
small mode (ctest `results_commands`).

The page lists its commands in ```sh blocks, each after a label line

    # [c7] needs: lmp matplotlib (optional words after the requirements)
    /usr/bin/python3 bench/dem/dem_timestep.py sweep

and its tables name them in a column `cmd` (`c7`, or `c16, c17`). A command is one line, or
several joined by a trailing backslash; `build/default` in it stands for the build folder.

  list   print the commands with their labels and requirements
  run    run every command in page order from the repository's root, each one's output to
         bench/out/<label>.log (the raw CSV files go where the command says, bench/out/)
  check  run every command in a small mode: the arguments in SMALL are appended (the last
         value of an option wins, in the Python scripts and in the C++ benchmarks alike; a
         command's own --out is kept), paths under bench/out/ and docs/images/ are moved to a
         temporary folder, so the check writes nothing into the repository, and `ctest`
         commands only list their tests. Fails on a command that exits non-zero, runs longer
         than --timeout, names a missing script or executable, a `ctest` selection with no
         test, or a table that names a label no block defines.

A command whose requirement is missing (`lmp`: LAMMPS's executable on PATH; `matplotlib`, `vtk`:
the Python modules matplotlib and vtkmodules; `pvbatch`: ParaView's pvbatch and xvfb-run;
`valgrind`: valgrind on PATH) is skipped with a message, in both modes.

usage: results_commands.py {list,run,check} [--build build/default] [--page docs/results.md]
                           [--only c1 c7 ...] [--timeout 60]
"""
import argparse
import importlib.util
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LABEL = re.compile(r"^#\s*\[(c\d+)\]\s*(?:needs:\s*([a-z0-9 ]*?))?\s*(\(.*\))?\s*$")
KNOWN_NEEDS = {"lmp", "matplotlib", "vtk", "pvbatch", "valgrind"}

# Small mode: arguments appended to a command, by the script's or executable's file name. Every
# program a command of the page runs must be here (a missing one fails the check), so a new
# figure comes with its small mode. `{tmp}` is the check's temporary folder.
SMALL = {
    "lammps_compare.py": ["--box", "6", "--steps", "10", "--repeats", "1",
                          "--out", "{tmp}/bench/out"],
    "blocks_per_rank.py": ["--steps", "5", "--repeats", "1", "--blocks", "1", "--small",
                           "--out", "{tmp}/bench/out"],
    "particles_bench": ["--benchmark_filter=springDashpotBatch/0/1", "--benchmark_min_time=0.01"],
    "dem_timestep.py": ["--sweep-box", "4", "--sweep-time", "0.5", "--repeats", "1",
                        "--fractions", "20", "10", "--map-box", "3", "--map-time", "0.2",
                        "--stiffness", "10", "50", "--map-dt-count", "2", "--no-docs",
                        "--out", "{tmp}/bench/out"],
    "sync_bench.py": ["--repeats", "1", "--steps", "5", "--box", "8", "--comm-ranks", "1", "2",
                      "--comm-steps", "5", "--out", "{tmp}/bench/out"],
    "dem_bench.py": ["--repeats", "1", "--ranks", "1", "--steps", "5",
                     "--set", "granular_gas.per_rank=[6,6,6]",
                     "--set", "dense_ramp.per_rank=[6,5.196152422706632,4]",
                     "--radii", "4", "--radius-steps", "2", "--edge", "20", "--radius-ranks", "1",
                     "--memory-boxes", "10", "--no-docs", "--out", "{tmp}/bench/out"],
    "nns_radius_map.py": ["--edge", "8", "--splits", "2", "--ratios", "0.5", "1.0", "--steps", "1",
                          "--no-docs", "--out", "{tmp}/bench/out"],
    "gravity_bench": ["--instances", "agg3866", "--samples", "100", "--repeat", "1"],
    "gravity_pareto.py": ["--instance", "agg3866", "--methods", "direct,tree,pm,stale-tree",
                          "--thetas", "0.5,0.9", "--spacings", "4",
                          "--node-spacings", "2.5", "--thresholds", "1", "--samples", "100",
                          "--repeat", "1", "--no-docs", "--out", "{tmp}/bench/out"],
    "grid_bench": ["--min-cells", "16", "--max-cells", "16"],
    "wall_work_check.py": [],
    "drum_picture.py": ["--steps", "5000"],
    "grid_matched_bench": ["--min-cells", "16", "--max-cells", "16", "--rtols", "1e-3"],
    "grid_agglomerate_bench": ["--grains", "2000", "--cells", "16", "--cutoffs", "2",
                               "--repeat", "1"],
    "default_scene_gravity.py": ["--steps", "20", "--repeats", "1", "--ranks", "1",
                                 "--stale", "0.002", "--every", "10",
                                 "--out", "{tmp}/bench/out"],
    "agglomerates_policies.py": ["--instances", "small", "--steps", "5", "--ranks", "1",
                                 "--repeats", "1", "--max-seconds", "0",
                                 "--out", "{tmp}/bench/out"],
    "agglomerates_bench.py": ["--steps", "5", "--instances", "small", "--ranks", "1",
                              "--methods", "direct", "--out", "{tmp}/bench/out"],
    "checkpoint_bench.py": ["--np", "1", "--repeats", "1", "--set",
                            "particles[0].region={min=[0.0,0.0,0.0],max=[8.0,8.0,8.0]}"],
    "load_balance.py": ["--ranks", "2", "--steps", "5", "--repeats", "1",
                        "--out", "{tmp}/bench/out"],
    "regolith": ["--output", "{tmp}/out"],
    "collectives_per_step.py": ["--steps", "2", "--blocks", "1", "--small",
                                "--out", "{tmp}/bench/out"],
    "instruction_counts.py": ["--steps", "1", "--sync-steps", "1",
                              "--set", "domain.max=[8.0,8.0,8.0]", "--out", "{tmp}/bench/out"],
    "tutorial_figures.py": ["--pull-steps", "2000", "--spin-sites", "6", "--spin-steps", "600",
                            "--out", "{tmp}/bench/out"],
    "grid_fields_figure.py": ["--np", "1", "--steps", "2", "--png", "{tmp}/docs/images/g.png"],
    "rubble_piles.py": ["--ranks", "1", "--rates", "0.05", "--steps", "150", "--periapses", "1.0",
                        "--grains", "50", "--cost-steps", "10", "20", "--repeats", "1",
                        "--set", "time.steps=150", "--set", "pile.settle_steps=50",
                        "--set", "pile.record_every=50",
                        "--set", "particles[0].count=30", "--out", "{tmp}/bench/out"],
    "cohesive_spin_up.py": ["--ranks", "1", "--pull-offs", "8", "--repeats", "1",
                            "--steps", "150", "--set", "pile.settle_steps=50",
                            "--set", "pile.record_every=50", "--set", "particles[0].count=30",
                            "--out", "{tmp}/bench/out"],
    "spin_up": ["--set", "particles[0].count=300", "--set", "particles[0].radius=6",
                "--set", "time.steps=20", "--set", "pile.settle_steps=10",
                "--set", "pile.record_every=10"],
}
# Options a program refuses to see twice (CLI11): small mode replaces their value in place.
SMALL_REPLACE = {"regolith": {"--steps": "2"}}
MPI_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}


class Command:
    def __init__(self, label, needs, text, line):
        self.label, self.needs, self.text, self.line = label, needs, text, line


def parse(page):
    """The page's commands (in order) and the labels its tables' `cmd` columns name."""
    commands, named, errors = [], set(), []
    lines = open(page, encoding="utf-8").read().splitlines()
    in_sh, current, cmd_col = False, None, None
    for number, line in enumerate(lines, 1):
        if line.startswith("```"):
            in_sh = line.strip() == "```sh" and not in_sh
            current = None
            continue
        if in_sh:
            if not line.strip():
                continue
            m = LABEL.match(line.strip())
            if m:
                needs = set((m.group(2) or "").split())
                if needs - KNOWN_NEEDS:
                    errors.append(f"line {number}: unknown requirement "
                                  f"{' '.join(sorted(needs - KNOWN_NEEDS))}")
                current = Command(m.group(1), needs, "", number)
                commands.append(current)
            elif line.lstrip().startswith("#"):
                continue
            elif current is None:
                errors.append(f"line {number}: a command without a label line `# [cN]`")
            elif current.text and not current.text.endswith("\\"):
                errors.append(f"line {number}: [{current.label}] holds two commands")
            else:
                current.text = (current.text[:-1] + " " if current.text else "") + line.strip()
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")] if line.startswith("|") \
            else None
        if cells is None:
            cmd_col = None
        elif "cmd" in cells:
            cmd_col = cells.index("cmd")
        elif cmd_col is not None and cmd_col < len(cells) and not set(cells[0]) <= set("-"):
            named.update(re.findall(r"\bc\d+\b", cells[cmd_col]))
    labels = [c.label for c in commands]
    for label in sorted({x for x in labels if labels.count(x) > 1}):
        errors.append(f"[{label}] is defined twice")
    for label in sorted(named - set(labels)):
        errors.append(f"a table names {label}, which no ```sh block defines")
    for c in commands:
        if not c.text:
            errors.append(f"line {c.line}: [{c.label}] has no command")
    return commands, errors


def pvbatch_works():
    """Whether pvbatch runs a script that imports paraview.simple under xvfb-run (Debian's
    python3-paraview may be missing: it conflicts with python3-vtk9)."""
    if not (shutil.which("pvbatch") and shutil.which("xvfb-run")):
        return False
    with tempfile.NamedTemporaryFile("w", suffix=".py") as script:
        script.write("import paraview.simple\n")
        script.flush()
        return subprocess.run(["xvfb-run", "-a", "pvbatch", script.name],
                              capture_output=True, check=False).returncode == 0


def missing_needs(needs):
    missing = []
    if "lmp" in needs and not shutil.which("lmp"):
        missing.append("lmp (LAMMPS)")
    if "valgrind" in needs and not shutil.which("valgrind"):
        missing.append("valgrind")
    if "pvbatch" in needs and not pvbatch_works():
        missing.append("pvbatch with its Python modules, and xvfb-run (ParaView, a display)")
    for module, name in (("matplotlib", "matplotlib"), ("vtk", "vtkmodules")):
        if module in needs and importlib.util.find_spec(name) is None:
            missing.append(f"{module} (Python module {name})")
    return missing


def program_of(argv):
    """The argv index of the program a command runs (past xvfb-run, mpiexec and the
    interpreter: python or ParaView's pvbatch)."""
    i = 0
    if os.path.basename(argv[0]) == "xvfb-run":
        i = 1
        while i < len(argv) and argv[i].startswith("-"):
            i += 1
        argv = argv[i:]
        return i + program_of(argv)
    if os.path.basename(argv[0]) == "mpiexec":
        i = 1
        while i < len(argv) and argv[i].startswith("-"):
            i += 2 if argv[i] in ("-n", "-np") else 1
    if i < len(argv) and (os.path.basename(argv[i]).startswith("python") or
                          os.path.basename(argv[i]) == "pvbatch"):
        i += 1
    return i


def prepare(c, build, small, tmp):
    """argv for command c: the build folder substituted, mpiexec made to run as root and
    oversubscribed; in small mode SMALL's arguments appended and outputs moved to tmp."""
    argv = shlex.split(c.text.replace("build/default", build))
    if argv[0] == "mpiexec" and "--oversubscribe" not in argv:
        argv.insert(1, "--oversubscribe")
    p = program_of(argv)
    if p >= len(argv):
        raise ValueError("no program")
    path = argv[p] if os.path.isabs(argv[p]) else os.path.join(ROOT, argv[p])
    if argv[0] != "ctest" and not os.path.exists(path):
        raise ValueError(f"{argv[p]} does not exist")
    if small:
        def moved(arg):
            for prefix in ("bench/out", "docs/images"):
                for form in (prefix, os.path.join(ROOT, prefix)):
                    if arg == form or arg.startswith(form + "/"):
                        return os.path.join(tmp, prefix) + arg[len(form):]
                    if "=" in arg and arg.split("=", 1)[1].startswith(form):
                        key, value = arg.split("=", 1)
                        return key + "=" + moved(value)
            return arg
        argv = [moved(a) for a in argv]
        name = os.path.basename(argv[p])
        if argv[0] != "ctest":
            if name not in SMALL:
                raise ValueError(f"no small mode for {name} (bench/results_commands.py, SMALL)")
            for option, value in SMALL_REPLACE.get(name, {}).items():
                if option in argv[p + 1:]:
                    argv[argv.index(option, p + 1) + 1] = value
                else:
                    argv += [option, value]
            extra = [a.replace("{tmp}", tmp) for a in SMALL[name]]
            if "--out" in extra and "--out" in argv[p + 1:]: # the command's own, moved to tmp
                i = extra.index("--out")
                del extra[i:i + 2]
            argv += extra
    return argv


def check_ctest(argv, build):
    """A ctest command of the page: its selection must name at least one test."""
    listed = subprocess.run(argv + ["-N"], cwd=ROOT, capture_output=True, text=True)
    found = re.search(r"Total Tests:\s*(\d+)", listed.stdout)
    if listed.returncode != 0 or not found or int(found.group(1)) == 0:
        return f"selects no test in {build}"
    return None


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("mode", choices=("list", "run", "check"))
    p.add_argument("--build", default="build/default")
    p.add_argument("--page", default=os.path.join(ROOT, "docs", "results.md"))
    p.add_argument("--only", nargs="*", help="labels to run (default: all)")
    p.add_argument("--timeout", type=float, default=None,
                   help="seconds per command (check: 60 by default)")
    a = p.parse_args()
    commands, errors = parse(a.page)
    for e in errors:
        print(f"results_commands: {a.page}: {e}", file=sys.stderr)
    if a.only:
        commands = [c for c in commands if c.label in a.only]
    if a.mode == "list":
        for c in commands:
            needs = f" (needs {' '.join(sorted(c.needs))})" if c.needs else ""
            print(f"[{c.label}]{needs} {c.text}")
        return 1 if errors else 0
    build = os.path.relpath(os.path.abspath(a.build), ROOT) \
        if os.path.abspath(a.build).startswith(ROOT + os.sep) else os.path.abspath(a.build)
    small = a.mode == "check"
    timeout = a.timeout if a.timeout is not None else (60.0 if small else None)
    env = {**os.environ, **MPI_ENV}
    out = os.path.join(ROOT, "bench", "out")
    os.makedirs(out, exist_ok=True)
    failed = list(errors)
    with tempfile.TemporaryDirectory(prefix="results-check-") as tmp:
        for sub in ("bench/out", "docs/images"):
            os.makedirs(os.path.join(tmp, sub), exist_ok=True)
        for c in commands:
            missing = missing_needs(c.needs)
            if missing:
                print(f"[{c.label}] skipped: {', '.join(missing)} not installed", flush=True)
                continue
            try:
                argv = prepare(c, build, small, tmp)
            except ValueError as e:
                failed.append(f"[{c.label}] {e}")
                print(f"[{c.label}] FAILED: {e}", flush=True)
                continue
            start = time.monotonic()
            if argv[0] == "ctest":
                problem = check_ctest(argv, build) if small else None
                if not small:
                    problem = None if subprocess.run(argv, cwd=ROOT, env=env).returncode == 0 \
                        else "failed"
            else:
                log = os.path.join(tmp if small else out, f"{c.label}.log")
                print(f"[{c.label}] {shlex.join(argv)}", flush=True)
                with open(log, "w", encoding="utf-8") as f:
                    try:
                        if small:
                            done = subprocess.run(argv, cwd=ROOT, env=env, stdout=f,
                                                  stderr=subprocess.STDOUT, timeout=timeout)
                        else: # `make bench`: the output to the terminal and to the log
                            proc = subprocess.Popen(argv, cwd=ROOT, env=env, text=True,
                                                    stdout=subprocess.PIPE,
                                                    stderr=subprocess.STDOUT)
                            for chunk in proc.stdout:
                                sys.stdout.write(chunk)
                                f.write(chunk)
                            done = proc
                            proc.wait(timeout=timeout)
                        problem = None if done.returncode == 0 \
                            else f"exit code {done.returncode}"
                    except subprocess.TimeoutExpired:
                        problem = f"longer than {timeout:.0f} s"
                if problem and small:
                    with open(log, encoding="utf-8", errors="replace") as f:
                        tail = f.read()[-3000:]
                    print(tail, flush=True)
            seconds = time.monotonic() - start
            if problem:
                failed.append(f"[{c.label}] {problem}")
                print(f"[{c.label}] FAILED: {problem} ({seconds:.1f} s)", flush=True)
            else:
                print(f"[{c.label}] ok ({seconds:.1f} s)", flush=True)
    if failed:
        print("results_commands: " + "; ".join(failed), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
