"""Checks a run summary (--json) against the contract in docs/design.md, "Run summary".

usage: check_summary.py summary.json [key=value | key>number | key<number ...]
Every contract key must be present with the right type; each key=value compares a value, the
key a top-level one or a dotted path into the objects (neighbour_list.skin) and lists
(balance.history.step.0), numbers compared as numbers, the rest as strings; key>number
requires a number above it, key<number one below it. Exit code 1 with a reason if not.
"""
import json
import re
import sys

NUMBER = (int, float)
SCHEMA = {
    "scene": str, "ranks": int, "blocks": int, "sync": str, "particles": int, "shadows": int,
    "left_domain": int, "left_through_walls": int, "steps": int, "wall_s": NUMBER, "pupcs": NUMBER,
    "peak_rss_bytes": int,
    "timing_s": {"sync": NUMBER, "contact": NUMBER, "gravity": NUMBER, "integrate": NUMBER},
    "comm": {"messages_per_step": NUMBER, "bytes_per_step": NUMBER, "max_peers": int},
    "neighbour_list": {"skin": NUMBER, "rebuilds": int, "shifts": int},
    "time": NUMBER,
    "conserved": {"momentum": list, "angular_momentum": list, "kinetic_energy": NUMBER,
                  "potential_energy": NUMBER, "center_of_mass": list},
    "conserved_initial": {"momentum": list, "angular_momentum": list, "kinetic_energy": NUMBER,
                          "potential_energy": NUMBER, "center_of_mass": list},
    "checksum": str,
}


def check(obj, schema, where):
    for key, kind in schema.items():
        if key not in obj:
            sys.exit(f"missing key {where}{key}")
        value = obj[key]
        if isinstance(kind, dict):
            check(value, kind, f"{where}{key}.")
        elif isinstance(value, bool) or not isinstance(value, kind):
            sys.exit(f"{where}{key} has the wrong type: {value!r}")
        elif kind is list and (len(value) != 3 or not all(isinstance(x, NUMBER) for x in value)):
            sys.exit(f"{where}{key} is not 3 numbers: {value!r}")


def main():
    with open(sys.argv[1], encoding="utf-8") as f:
        summary = json.load(f)
    check(summary, SCHEMA, "")
    if not summary["checksum"] or any(c not in "0123456789abcdef" for c in summary["checksum"]):
        sys.exit(f"checksum is not hex: {summary['checksum']!r}")
    if summary["peak_rss_bytes"] <= 0:
        sys.exit("peak_rss_bytes must be positive")
    for expectation in sys.argv[2:]:
        key, op, expected = re.fullmatch(r"([\w.]+)([=<>])(.*)", expectation).groups()
        actual = summary
        for part in key.split("."):
            if isinstance(actual, list) and part.isdigit() and int(part) < len(actual):
                actual = actual[int(part)]  # an entry of a list (balance.history.step.0)
                continue
            if not isinstance(actual, dict) or part not in actual:
                sys.exit(f"{key}: not in the summary")
            actual = actual[part]
        if op in "<>":
            above = op == ">"
            if not isinstance(actual, NUMBER) or not (
                    actual > float(expected) if above else actual < float(expected)):
                sys.exit(f"{key}: expected {'above' if above else 'below'} {expected}, "
                         f"got {actual!r}")
            continue
        if isinstance(actual, NUMBER):
            same = actual == float(expected)
        else:
            same = str(actual) == expected
        if not same:
            sys.exit(f"{key}: expected {expected}, got {actual!r}")


if __name__ == "__main__":
    main()
