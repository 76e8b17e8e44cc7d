#!/usr/bin/python3
"""compare_results.py A B [N]: the largest relative difference between the numeric leaves of two
result.yaml files (same keys) and where it occurs; with N, also the N largest. Differences below
1e-14 absolute (a gravity component of 1e-18) and timing keys are left out. Used to check that a
speed change leaves results unchanged (docs/performance.md):
    scripts/compare_results.py before/result.yaml after/result.yaml 5
"""
import sys, math, yaml
def leaves(node, path=""):
    if isinstance(node, dict):
        for k, v in node.items(): yield from leaves(v, f"{path}/{k}")
    elif isinstance(node, list):
        for i, v in enumerate(node): yield from leaves(v, f"{path}[{i}]")
    elif isinstance(node, (int, float)) and not isinstance(node, bool):
        yield path, float(node)
a = dict(leaves(yaml.safe_load(open(sys.argv[1]))))
b = dict(leaves(yaml.safe_load(open(sys.argv[2]))))
worst, where = 0.0, None
rows = []
for k in a:
    if k not in b: print("missing in B:", k); continue
    if any(s in k for s in ("solve_time", "time_s", "seconds")): continue
    x, y = a[k], b[k]
    if math.isnan(x) and math.isnan(y): continue
    if abs(x - y) < 1e-14: continue  # zero to rounding (e.g. a gravity component of 1e-18)
    d = abs(x - y) / max(abs(x), abs(y), 1e-300)
    rows.append((d, k, x, y))
    if d > worst: worst, where = d, k
print(f"max relative difference {worst:.3e} at {where}")
if len(sys.argv) > 3:
    for d, k, x, y in sorted(rows, reverse=True)[:int(sys.argv[3])]:
        print(f"  {d:.3e} {k}: {x!r} vs {y!r}")
