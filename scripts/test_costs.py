#!/usr/bin/env python3
"""Writes tests/test_costs.txt: each test's measured seconds, its ctest COST.

A fresh build folder (every CI clone) has no Testing/Temporary/CTestCostData.txt, so without
COST ctest -j starts tests in declaration order. The table gives it the costs of a real run, so
it starts the longest first and the short ones fill the other core around them. The figures only
order the tests: a stale or missing entry changes when a test starts, never whether it runs
(ctest ignores set_tests_properties on a name it does not have).

  scripts/test_costs.py RELEASE_BUILD SANITIZE_BUILD [--min-seconds S]

reads RELEASE_BUILD/Testing/Temporary/CTestCostData.txt (after scripts/test.sh) and
SANITIZE_BUILD/Testing/... (after scripts/test.sh --sanitize) and rewrites
tests/test_costs.txt. Tests shorter than --min-seconds (default 1) are left out: they are the
filling, their order does not matter.
"""
import argparse
import os
import sys

HEADER = """\
# Written by scripts/test_costs.py from the CTestCostData.txt files of
# {source}
# (docs/reliability.md, "The cold and warm figures": how to regenerate); read by
# tests/test_costs.cmake. A row a test: the build (release or sanitize), its measured seconds, its
# name. Tests shorter than {min_seconds:g} s are left out.
"""


def read_costs(build_dir):
    """{test name: average seconds} from a build folder's CTestCostData.txt."""
    return read_cost_file(os.path.join(build_dir, "Testing", "Temporary", "CTestCostData.txt"))


def read_cost_file(path):
    """{test name: average seconds} from a CTestCostData.txt file."""
    costs = {}
    with open(path) as f:
        for line in f:
            line = line.rstrip("\n")
            if line.startswith("---"):
                break  # the failed tests' list follows
            # "name runs seconds"; a parametrised test's name has spaces ("a/b  # GetParam() = b").
            parts = line.rsplit(" ", 2)
            if len(parts) != 3:
                continue
            try:
                costs[parts[0]] = float(parts[2])
            except ValueError:
                continue
    if not costs:
        sys.exit(f"{path}: no test costs")
    return costs


def rows(build, costs, min_seconds):
    """The rows "BUILD SECONDS NAME" of one build, longest first."""
    lines = []
    for name, seconds in sorted(costs.items(), key=lambda item: (-item[1], item[0])):
        if seconds < min_seconds:
            break
        # test_costs.cmake passes the name through a CMake list and a quoted argument.
        if any(c in name for c in ';\\"$[]\n'):
            sys.exit(f"cannot pass test name {name!r} to set_tests_properties")
        lines.append(f"{build} {seconds:.1f} {name}\n")
    return "".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("release_build")
    parser.add_argument("sanitize_build")
    parser.add_argument("--min-seconds", type=float, default=1.0)
    parser.add_argument("--source", default="", help="where the run came from, for the header")
    args = parser.parse_args()
    release = read_costs(args.release_build)
    sanitize = read_costs(args.sanitize_build)
    source = args.source or f"{args.release_build} and {args.sanitize_build}"
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                       "test_costs.txt")
    with open(out, "w") as f:
        f.write(HEADER.format(source=source, min_seconds=args.min_seconds))
        f.write(rows("sanitize", sanitize, args.min_seconds))
        f.write(rows("release", release, args.min_seconds))


if __name__ == "__main__":
    main()
