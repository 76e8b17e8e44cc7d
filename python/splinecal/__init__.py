"""splinecal: continuous-time spline calibration from Python (docs/python.md).

Time is int64 nanoseconds, every other quantity SI; frames and names follow
docs/conventions.md. Functions that mirror a command (allan, simulate, fit, calibrate) return
a dict with the keys of that command's result.yaml, plus numpy arrays where natural.
"""
from ._splinecal import (Error, SE3Spline, allan, allan_deviation, calibrate, detect, fit,
                         simulate)

__all__ = ["Error", "SE3Spline", "allan", "allan_deviation", "calibrate", "detect", "fit",
           "simulate"]
