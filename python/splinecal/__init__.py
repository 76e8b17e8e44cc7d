"""splinecal: continuous-time spline calibration from Python (docs/python.md).

Time is int64 nanoseconds, every other quantity SI; frames and names follow
docs/conventions.md. The functions that mirror a command (detect, intrinsics, evaluate,
simulate, integrate, allan, align, fit, calibrate) take the command's flags as keywords (dashes
become underscores, same defaults and units) and return the command's result.yaml as a dict,
plus numpy arrays where natural; `out=` writes the command's files.

Every function is wrapped so that a keyword it does not take raises TypeError naming it and the
closest valid keyword, and so that inspect.signature() and help() show its parameters.
"""
import ast
import difflib
import functools
import inspect

from . import _splinecal
from ._splinecal import Error, SE3Spline

# The command each function mirrors, in `splinecal help`'s order.
COMMANDS = ("detect", "intrinsics", "evaluate", "simulate", "integrate", "correct", "allan",
            "align", "fit", "calibrate", "export", "bag_info", "bag_extract")


def _split_top_level(text):
    """Splits at the commas outside brackets and quotes (pybind11 signature text)."""
    parts, depth, quote, start = [], 0, None, 0
    for i, c in enumerate(text):
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif c == "," and depth == 0:
            parts.append(text[start:i].strip())
            start = i + 1
    parts.append(text[start:].strip())
    return [p for p in parts if p]


def _signature(function):
    """The inspect.Signature of a pybind11 function, from the first line of its docstring:
    `name(a: object, *, b: float = 0.05) -> dict` (pybind11 writes it from its py::arg list)."""
    first = function.__doc__.splitlines()[0]
    inner = first[first.index("(") + 1:first.rindex(")")]
    parameters, kind = [], inspect.Parameter.POSITIONAL_OR_KEYWORD
    for part in _split_top_level(inner):
        if part == "*":
            kind = inspect.Parameter.KEYWORD_ONLY
            continue
        name_and_type, _, default_text = part.partition("=")
        name = name_and_type.split(":")[0].strip()
        default = inspect.Parameter.empty
        if default_text:
            try:
                default = ast.literal_eval(default_text.strip())
            except (ValueError, SyntaxError):
                default = default_text.strip()
        parameters.append(inspect.Parameter(name, kind, default=default))
    return inspect.Signature(parameters)


def _checked(function):
    """`function` with its keywords checked: an unknown one is a TypeError naming it."""
    signature = _signature(function)
    names = list(signature.parameters)

    @functools.wraps(function)
    def call(*args, **kwargs):
        for key in kwargs:
            if key not in signature.parameters:
                close = difflib.get_close_matches(key.replace("-", "_"), names, n=1)
                hint = f"; did you mean '{close[0]}'?" if close else ""
                raise TypeError(f"{function.__name__}() got an unexpected keyword argument "
                                f"'{key}'{hint} (valid: {', '.join(names)})")
        return function(*args, **kwargs)

    call.__signature__ = signature
    return call


allan_deviation = _checked(_splinecal.allan_deviation)
detect = _checked(_splinecal.detect)
intrinsics = _checked(_splinecal.intrinsics)
evaluate = _checked(_splinecal.evaluate)
simulate = _checked(_splinecal.simulate)
integrate = _checked(_splinecal.integrate)
correct = _checked(_splinecal.correct)
allan = _checked(_splinecal.allan)
align = _checked(_splinecal.align)
fit = _checked(_splinecal.fit)
calibrate = _checked(_splinecal.calibrate)
export = _checked(_splinecal.export)
bag_info = _checked(_splinecal.bag_info)
bag_extract = _checked(_splinecal.bag_extract)

__all__ = ["COMMANDS", "Error", "SE3Spline", "align", "allan", "allan_deviation", "bag_extract",
           "bag_info", "calibrate", "correct", "detect", "evaluate", "export", "fit", "integrate",
           "intrinsics", "simulate"]
