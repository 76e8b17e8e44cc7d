"""Ctrl-C during a solve: KeyboardInterrupt at the next iteration, the interpreter still usable.

Deterministic: the module's test hook (python/interruptible.h) raises a real SIGINT in the solving
thread at the second poll of the solve, instead of a timer that on two loaded cores may fire
before the solve starts or after it has ended. The signal then goes the way a Ctrl-C goes:
Python's C-level handler marks it, the solve's next poll runs the Python handler, whose
KeyboardInterrupt stops the solve.
"""
import os
import subprocess
import sys
import textwrap

SCRIPT = textwrap.dedent("""
    import os, signal
    import splinecal
    sim = splinecal.simulate(trajectory="random", duration=20, seed=2)
    handled = []
    def on_sigint(signum, frame):
        handled.append(signum)
        raise KeyboardInterrupt
    signal.signal(signal.SIGINT, on_sigint)
    os.environ["SPLINECAL_TEST_SIGINT_AT_POLL"] = "2"
    try:
        splinecal.fit(sim["imu"], sim["ground_truth"], knot_spacing=0.02)
        print("not interrupted")
    except KeyboardInterrupt:
        print(f"interrupted, handler ran {len(handled)} time(s)")
    del os.environ["SPLINECAL_TEST_SIGINT_AT_POLL"]
    result = splinecal.fit(sim["imu"], sim["ground_truth"], knot_spacing=0.02)
    print("fit after the interrupt:", type(result).__name__, "handler ran", len(handled))
    print("still alive", splinecal.allan_deviation([0.0, 1.0] * 50, 10.0)[0].shape)
""")


def test_ctrl_c_stops_a_fit():
    done = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True,
                          timeout=120, env=os.environ)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0] == "interrupted, handler ran 1 time(s)", done.stdout
    # The next solve polls too but no signal is pending: it runs to its end.
    assert lines[1].startswith("fit after the interrupt:"), done.stdout
    assert lines[1].endswith("handler ran 1"), done.stdout
    assert lines[2].startswith("still alive"), done.stdout
