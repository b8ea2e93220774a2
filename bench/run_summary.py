"""Shared by the benchmark scripts: run a Regolith app under mpiexec and return its run summary
(docs/design.md, "Run summary")."""
import json
import os
import subprocess
import sys
import tempfile

MPI_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}


def mpiexec(ranks):
    """The mpiexec prefix for `ranks` ranks: each bound to a core while this process may use
    enough (on this 2-core VM, unbound ranks share a core at times: 2-rank gas runs then spread
    2.0e7 to 3.2e7 PUpCS against 2.7e7 to 3.2e7 bound), unbound and oversubscribed beyond.
    Bound runs of two benchmarks started together would share the same cores: run one alone."""
    bind = "core" if ranks <= len(os.sched_getaffinity(0)) else "none"
    return ["mpiexec", "-n", str(ranks), "--oversubscribe", "--bind-to", bind]


def run_app(app, ranks, args, refusal=None):
    """Runs `app` (a path) on `ranks` ranks with `args`; returns the summary (--json), or None
    when the app refused the scene with a message containing `refusal` (exit code 2; e.g. NNS
    refusing a grain too large for it). Any other failure, a refusal for another reason (a typo
    in a key exits 2 too) included, ends the calling script with the command and its output."""
    with tempfile.TemporaryDirectory() as tmp:
        summary = os.path.join(tmp, "summary.json")
        command = [*mpiexec(ranks), app, *args, "--quiet", "--json", summary]
        done = subprocess.run(command, capture_output=True, text=True, check=False,
                              env={**os.environ, **MPI_ENV})
        if done.returncode == 2 and refusal is not None and refusal in done.stderr:
            return None
        return summary_or_exit(command, done.returncode, f"{done.stdout}\n{done.stderr}",
                               summary)


def summary_or_exit(command, returncode, output, summary):
    """The run summary written to `summary` by `command`, which exited with `returncode`; a
    failed run ends the calling script with the command and its `output`."""
    if returncode != 0:
        sys.exit(f"{os.path.basename(sys.argv[0])}: {' '.join(command)} exited with "
                 f"{returncode}\n{output}")
    with open(summary, encoding="utf-8") as f:
        return json.load(f)
