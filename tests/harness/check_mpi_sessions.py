#!/usr/bin/env python3
"""Checks that every registered test that starts Open MPI has a session directory of its own.

Open MPI 4 removes the shared /tmp/ompi.<host>.<uid> when its last job ends, and a job that
ctest -j starts in that moment fails (open-mpi/ompi#8510); regolith_isolate_mpi_sessions()
gives each test its own OMPI_MCA_orte_tmpdir_base. A directory whose CMakeLists.txt adds tests
but forgets that call fails here, naming the tests.

Usage: check_mpi_sessions.py CTEST BUILD_DIR
"""
import json
import subprocess
import sys

KEY = "OMPI_MCA_orte_tmpdir_base="


def main() -> int:
    ctest, build = sys.argv[1], sys.argv[2]
    listing = subprocess.run([ctest, "--show-only=json-v1"], cwd=build, check=True,
                             capture_output=True, text=True).stdout
    tests = json.loads(listing)["tests"]
    missing, owners = [], {}
    for test in tests:
        env = next((p["value"] for p in test.get("properties", [])
                    if p["name"] == "ENVIRONMENT"), [])
        bases = [e[len(KEY):] for e in env if e.startswith(KEY)]
        if not bases:
            missing.append(test["name"])
            continue
        owners.setdefault(bases[-1], []).append(test["name"])
    shared = {base: names for base, names in owners.items() if len(names) > 1}
    for name in missing:
        print(f"{name}: no {KEY[:-1]} (call regolith_isolate_mpi_sessions() at the end of "
              "the CMakeLists.txt that adds it)")
    for base, names in shared.items():
        print(f"{', '.join(names)}: share the session directory {base}")
    if len(tests) < 2:
        print(f"ctest listed {len(tests)} tests in {build}; expected the whole suite")
        return 1
    if missing or shared:
        return 1
    print(f"{len(tests)} tests, each with a session directory of its own")
    return 0


if __name__ == "__main__":
    sys.exit(main())
