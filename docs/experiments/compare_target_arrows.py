#!/usr/bin/env python3
"""Compares the arrows of two "Target points" figures (SVGs written by `splinecal intrinsics`'
report.html): matched by their start, the correlation of their components, the cosine between
matched arrows and their RMS lengths. docs/intrinsics.md, "Is the target where its file says?":

    python3 docs/experiments/compare_target_arrows.py \
        docs/intrinsics_euroc_target_check.svg docs/intrinsics_euroc_target_points.svg
"""
import math
import re
import sys

ARROW = re.compile(r'<polyline points="([\d.]+),([\d.]+) ([\d.]+),([\d.]+)" fill="none" '
                   r'stroke="#000000"')


def arrows(path):
    with open(path) as f:
        return {(round(float(a)), round(float(b))): (float(c) - float(a), float(d) - float(b))
                for a, b, c, d in ARROW.findall(f.read())}


def correlation(x, y):
    mx, my = sum(x) / len(x), sum(y) / len(y)
    sxy = sum((a - mx) * (b - my) for a, b in zip(x, y))
    return sxy / math.sqrt(sum((a - mx) ** 2 for a in x) * sum((b - my) ** 2 for b in y))


def main():
    a, b = arrows(sys.argv[1]), arrows(sys.argv[2])
    keys = [k for k in a if k in b]
    print(f"{len(a)} and {len(b)} arrows, {len(keys)} matched")
    for axis, name in ((0, "x"), (1, "y")):
        print(f"correlation {name}: {correlation([a[k][axis] for k in keys], [b[k][axis] for k in keys]):.3f}")
    cosines = sorted((a[k][0] * b[k][0] + a[k][1] * b[k][1]) /
                     (math.hypot(*a[k]) * math.hypot(*b[k])) for k in keys)
    median = cosines[len(cosines) // 2] if len(cosines) % 2 else \
        0.5 * (cosines[len(cosines) // 2 - 1] + cosines[len(cosines) // 2])
    within = sum(c > math.cos(math.radians(30)) for c in cosines) / len(cosines)
    print(f"median cosine {median:.3f}, share within 30 deg {within:.2f}")
    for name, arrows_of in ((sys.argv[1], a), (sys.argv[2], b)):
        rms = math.sqrt(sum(math.hypot(*arrows_of[k]) ** 2 for k in keys) / len(keys))
        print(f"RMS length {rms:.2f} px: {name}")


if __name__ == "__main__":
    main()
