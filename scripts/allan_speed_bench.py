#!/usr/bin/python3
"""Issue 16's speed target, measured in one run: the whole `splinecal allan` command on a 10^7-row,
6-axis EuRoC CSV (about 1.4 GB, generated once in /tmp, not in the repository) against a numpy
implementation of allantools' cumulative-sum overlapping ADEV (the same arithmetic as
allantools.oadev: phase by cumulative sum, then one vectorised second difference per averaging
time) on ONE axis of the same data already in memory, both at 10 averaging times per decade.
allantools itself is not a Debian package; this is its method written from the formula, not its
code. Target: splinecal / numpy <= 0.6.

With --per-decade LIST (e.g. 3,10,30,100,1000) it times instead the whole command at each number
of averaging times per decade (docs/performance.md: the time nearly independent of it, under the
default work budget of --max-passes 100), ROUNDS rounds taken in turn, and prints a table: median
wall time, the command's CPU time, the averaging times, the passes over each axis they would take
fully overlapping and the passes used, and the Kalibr keys (the same within their intervals).

Usage: scripts/allan_speed_bench.py BUILD_DIR/splinecal [ROUNDS] [--per-decade LIST]
       (needs python3-numpy)
"""
import os
import resource
import statistics
import subprocess
import sys
import time

import numpy as np

ROWS = 10_000_000
RATE_HZ = 200.0
PATH = "/tmp/splinecal_allan_speed_1e7.csv"
SEED = 11


def axes():
    """Six static axes (white noise plus a bias random walk), the same at every call."""
    rng = np.random.default_rng(SEED)
    white = [2.4e-3] * 3 + [2.8e-2] * 3
    step = [1.4e-6] * 3 + [2.1e-4] * 3
    offset = [0.01, -0.02, 0.003, 0.1, -0.2, 9.81]
    y = np.empty((ROWS, 6))
    for a in range(6):
        y[:, a] = (offset[a] + np.cumsum(step[a] * rng.standard_normal(ROWS))
                   + white[a] * rng.standard_normal(ROWS))
    return y


def write_euroc(y):
    t = 1403636579758555392 + 5000000 * np.arange(ROWS, dtype=np.int64)
    with open(PATH + ".tmp", "w") as f:
        f.write("#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
                "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n")
        for start in range(0, ROWS, 200000):
            f.write("".join("%d,%r,%r,%r,%r,%r,%r\n" % (t[i], *y[i])
                            for i in range(start, min(ROWS, start + 200000))))
    os.replace(PATH + ".tmp", PATH)


def cluster_sizes(n, per_decade=10, max_fraction=0.1):
    """splinecal's averaging times: round(10^(j / per_decade)), de-duplicated, up to n / 10."""
    sizes, j = [], 0
    while True:
        m = int(round(10 ** (j / per_decade)))
        if m > int(max_fraction * n):
            return sizes
        if not sizes or m != sizes[-1]:
            sizes.append(m)
        j += 1


def oadev_cumsum(y, rate, sizes):
    """Overlapping ADEV the allantools way: x = cumulative sum of y / rate (phase), then for each m
    sqrt(sum (x[k+2m] - 2 x[k+m] + x[k])^2 / (2 (N - 2m + 1))) / tau."""
    x = np.concatenate(([0.0], np.cumsum(y))) / rate
    out = []
    for m in sizes:
        d = x[2 * m:] - 2.0 * x[m:-m] + x[:-2 * m]
        out.append(np.sqrt(np.sum(d * d) / (2.0 * len(d))) / (m / rate))
    return np.array(out)


def timed_command(tool, per_decade, out):
    """Runs the whole command; returns (wall, user + system) seconds."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run([tool, "allan", "--imu", PATH, "--out", out, "--taus-per-decade",
                    str(per_decade), "--quiet"], check=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def yaml_number(text, key):
    """The value of a top-level `key: value` line of result.yaml."""
    for line in text.splitlines():
        if line.startswith(key + ":"):
            return float(line.split(":", 1)[1].split("#")[0])
    return float("nan")


def per_decade_table(tool, rounds, settings):
    """The whole command at each number of averaging times per decade."""
    subprocess.run(["cat", PATH], stdout=subprocess.DEVNULL, check=True)  # page cache warm
    times = {p: [] for p in settings}
    for _ in range(rounds):
        for p in settings:  # in turn, so that a change of load hits every setting alike
            times[p].append(timed_command(tool, p, "/tmp/splinecal_allan_speed_out_%d" % p))
    reference = statistics.median(w for w, _ in times[10]) if 10 in settings else None
    print("| per decade | averaging times | passes fully overlapping | passes used | wall (median) "
          "| user + system (median) | vs 10 per decade | gyro N | gyro K | accel N | accel K |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for p in settings:
        out = "/tmp/splinecal_allan_speed_out_%d" % p
        result = open(os.path.join(out, "result.yaml")).read()
        rows = sum(1 for line in open(os.path.join(out, "allan.csv")) if not line.startswith("#"))
        wall = statistics.median(w for w, _ in times[p])
        cpu = statistics.median(c for _, c in times[p])
        print("| %d | %d | %.4g | %.4g | %.3f s (%s) | %.2f s | %s | %.4g | %.4g | %.4g | %.4g |" % (
            p, rows, yaml_number(result, "overlapping_passes"), yaml_number(result, "passes_used"),
            wall, " ".join("%.2f" % w for w, _ in times[p]), cpu,
            "%.2f" % (wall / reference) if reference else "-",
            yaml_number(result, "gyroscope_noise_density"),
            yaml_number(result, "gyroscope_random_walk"),
            yaml_number(result, "accelerometer_noise_density"),
            yaml_number(result, "accelerometer_random_walk")))
    print("load average at the end: %s" % " ".join("%.2f" % v for v in os.getloadavg()))


def main():
    args = sys.argv[1:]
    settings = None
    if "--per-decade" in args:
        at = args.index("--per-decade")
        settings = [int(v) for v in args[at + 1].split(",")]
        del args[at:at + 2]
    tool = args[0]
    rounds = int(args[1]) if len(args) > 1 else 3
    if settings is not None and os.path.exists(PATH):
        per_decade_table(tool, rounds, settings)
        return
    y = axes()
    if not os.path.exists(PATH):
        print("writing %s (once)" % PATH, file=sys.stderr)
        write_euroc(y)
    if settings is not None:
        del y
        per_decade_table(tool, rounds, settings)
        return
    gyro_x = np.ascontiguousarray(y[:, 0])
    del y
    sizes = cluster_sizes(ROWS)
    subprocess.run(["cat", PATH], stdout=subprocess.DEVNULL, check=True)  # page cache warm
    numpy_times, tool_times = [], []
    for _ in range(rounds):
        start = time.perf_counter()
        reference = oadev_cumsum(gyro_x, RATE_HZ, sizes)
        numpy_times.append(time.perf_counter() - start)
        start = time.perf_counter()
        subprocess.run([tool, "allan", "--imu", PATH, "--out", "/tmp/splinecal_allan_speed_out",
                        "--taus-per-decade", "10", "--quiet"], check=True)
        tool_times.append(time.perf_counter() - start)
    # The same numbers: splinecal's gyro_x column against the numpy reference.
    table = np.loadtxt("/tmp/splinecal_allan_speed_out/allan.csv", delimiter=",", comments="#")
    worst = np.max(np.abs(table[:, 1] / reference - 1.0))
    numpy_s, tool_s = statistics.median(numpy_times), statistics.median(tool_times)
    print("averaging times: %d (10 per decade, up to a tenth of the record)" % len(sizes))
    print("numpy cumulative-sum oadev, one axis in memory: median %.3f s  (%s)"
          % (numpy_s, " ".join("%.3f" % t for t in numpy_times)))
    print("splinecal allan, whole command, 6 axes from %s (%.2f GB): median %.3f s  (%s)"
          % (PATH, os.path.getsize(PATH) / 1e9, tool_s, " ".join("%.3f" % t for t in tool_times)))
    print("ratio splinecal / numpy: %.2f (target <= 0.6); per axis numpy is %.1f times slower"
          % (tool_s / numpy_s, 6 * numpy_s / tool_s))
    print("largest relative difference of gyro_x deviations: %.2e" % worst)
    print("load average at the end: %s" % " ".join("%.2f" % v for v in os.getloadavg()))


if __name__ == "__main__":
    main()
