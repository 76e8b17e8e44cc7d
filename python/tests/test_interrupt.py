"""Ctrl-C during a solve: KeyboardInterrupt soon after, the interpreter still usable."""
import os
import subprocess
import sys
import textwrap

SCRIPT = textwrap.dedent("""
    import os, signal, threading, time
    import splinecal
    sim = splinecal.simulate(trajectory="random", duration=60, seed=2)
    start = time.monotonic()
    splinecal.fit(sim["imu"], sim["ground_truth"], knot_spacing=0.02)
    full = time.monotonic() - start
    threading.Timer(0.2, os.kill, (os.getpid(), signal.SIGINT)).start()
    start = time.monotonic()
    try:
        splinecal.fit(sim["imu"], sim["ground_truth"], knot_spacing=0.02)
        print("not interrupted")
    except KeyboardInterrupt:
        print(f"interrupted after {time.monotonic() - start:.2f} s of {full:.2f} s")
    print("still alive", splinecal.allan_deviation([0.0, 1.0] * 50, 10.0)[0].shape)
""")


def test_ctrl_c_stops_a_fit():
    done = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True,
                          timeout=120, env=os.environ)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0].startswith("interrupted after"), done.stdout
    interrupted_s, full_s = float(lines[0].split()[2]), float(lines[0].split()[5])
    assert interrupted_s < 0.2 + 0.5 * full_s, done.stdout
    assert lines[1].startswith("still alive")
