#!/usr/bin/env python3
"""What ctest -j2 would take for a build's tests, from the seconds a real run measured.

  scripts/ctest_schedule.py BUILD_DIR COSTDATA [CTEST_FILTERS ...]
  e.g. scripts/ctest_schedule.py build-sanitize build-sanitize/Testing/Temporary/CTestCostData.txt \
         -LE "slow|sanitize_skip"

Lists BUILD_DIR's tests (ctest --show-only, with their COST from tests/test_costs.cmake), gives
each the time COSTDATA measured, and plays 2-slot list scheduling three ways: declaration order
(a fresh folder without COST), by COST (a fresh CI clone), by the measured times (ctest's own
order once CTestCostData exists). A makespan near sum/2 means the order wastes no core.
COSTDATA's names with spaces (parametrised tests, "a/b  # GetParam() = b") count too.
"""
import heapq
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_costs import read_cost_file  # noqa: E402  (the one CTestCostData reader)

build, costdata = sys.argv[1], sys.argv[2]
extra = sys.argv[3:]
j = json.loads(subprocess.run(["ctest", "--test-dir", build, "--show-only=json-v1", *extra],
                              capture_output=True, text=True).stdout)
measured = read_cost_file(costdata)
tests = []
for i, t in enumerate(j["tests"]):
    props = {p["name"]: p["value"] for p in t.get("properties", [])}
    if props.get("DISABLED"): continue
    name = t["name"]
    tests.append((name, float(props.get("COST", 0)), measured.get(name)))
run = [t for t in tests if t[2] is not None]
def makespan(order):
    cores = [0.0, 0.0]
    for name, _, m in order:
        c = heapq.heappop(cores); heapq.heappush(cores, c + m)
    return max(cores), min(cores)
# Python's sort is stable: ties keep declaration order.
s = sum(t[2] for t in run)
print("tests run %d (of %d listed, %d unmeasured), sum %.1f s, sum/2 %.1f" % (len(run), len(tests), len(tests)-len(run), s, s/2))
print("declaration order: makespan %.1f (other core idle from %.1f)" % makespan(run))
print("by COST property:  makespan %.1f (other core idle from %.1f)" % makespan(sorted(run, key=lambda t: -t[1])))
print("by measured time:  makespan %.1f (other core idle from %.1f)" % makespan(sorted(run, key=lambda t: -t[2])))
