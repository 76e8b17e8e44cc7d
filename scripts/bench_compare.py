#!/usr/bin/env python3
"""Median of each benchmark over the rounds of `scripts/bench.sh --against REV`, before (REV) and
after (this tree), and their ratio. Usage: bench_compare.py RESULTS_DIR REV."""
import glob
import json
import os
import statistics
import sys


def load(directory, side):
    times = {}  # (bench program, benchmark name) -> [real time in its unit]
    units = {}
    for path in sorted(glob.glob(os.path.join(directory, "*.%s.*.json" % side))):
        program = os.path.basename(path).split(".")[0]
        with open(path) as f:
            data = json.load(f)
        for b in data["benchmarks"]:
            if b.get("run_type") == "aggregate":
                continue
            key = (program, b["name"])
            times.setdefault(key, []).append(b["real_time"])
            units[key] = b["time_unit"]
    return times, units


def main():
    directory, rev = sys.argv[1], sys.argv[2]
    before, units = load(directory, "before")
    after, _ = load(directory, "after")
    print("median real time over %d rounds; before = %s, after = this tree"
          % (max((len(v) for v in before.values()), default=0), rev))
    print("%-62s %14s %14s %7s" % ("benchmark", "before", "after", "ratio"))
    for key in sorted(before):
        if key not in after:
            continue
        b = statistics.median(before[key])
        a = statistics.median(after[key])
        unit = units[key]
        print("%-62s %11.4g %-2s %11.4g %-2s %7.3f"
              % (key[0] + "/" + key[1], b, unit, a, unit, a / b))


if __name__ == "__main__":
    main()
