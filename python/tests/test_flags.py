"""Every command has a Python function and every flag of it is a keyword of that function, with
the same default. Generated from the tool itself (`splinecal help`, `splinecal COMMAND --help`),
so a command or flag added later fails here until Python has it too. And a keyword the function
does not take is a TypeError naming it, for every function."""
import functools
import inspect
import re
import subprocess

import pytest

import splinecal
from conftest import TOOL

# Flags that make no sense in Python, for every command. Nothing else is left out.
NOT_IN_PYTHON = {
    # The command prints progress lines on stderr unless --quiet; the module prints nothing.
    "quiet",
}

# Flags whose keyword is spelled differently, with the reason.
KEYWORD_NAME = {
    # `from` is a Python keyword: splinecal.export(from_=...) is `export --from`.
    ("export", "from"): "from_",
}

# Keywords whose Python default differs from the flag's in form only, with the reason.
DEFAULT_FORM = {
    # The command's 20 s is its default for the analytic trajectories; with --trajectory-file it
    # means the whole file. None says both in Python (as the command does by is_default).
    ("simulate", "duration"),
    # 0 Hz means "not given" on the command line (EuRoC files carry timestamps); None in Python.
    ("allan", "rate"),
    # Not a flag default: calibrate's help text for --imu-yaml ends in "(default: ADIS16448)",
    # the densities used when no file is given; None (no file) in Python, as "" on the command
    # line.
    ("calibrate", "imu_yaml"),
}


def tool_help(*args):
    done = subprocess.run([TOOL, *args], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout + done.stderr


# Commands without a Python function yet. An exact list, not a skip: the test fails when one
# gets a function (remove it here) and when another command lacks one.
COMMANDS_NOT_YET = set()


def commands():
    """The command names `splinecal help` lists (help and version are the front end's), a command
    group's two words joined by a space ("bag info")."""
    names = [m.group(1) or m.group(2) for m in re.finditer(
        r"^  (?:(bag \w+)|(\w+)) ", tool_help("help"), re.MULTILINE)]
    missing = COMMANDS_NOT_YET - set(names)
    assert not missing, f"COMMANDS_NOT_YET names commands that are gone: {sorted(missing)}"
    return [n for n in names if n not in ("help", "version") and n not in COMMANDS_NOT_YET]


def function_name(command):
    """A command group's function: `bag info` is splinecal.bag_info."""
    return command.replace(" ", "_")


@functools.lru_cache(maxsize=None)
def flags(command):
    """{keyword: default text or None} of `splinecal COMMAND --help` (dashes -> underscores)."""
    text = tool_help(*command.split(), "--help").split("\nflags:\n", 1)[1]
    found = {}
    for block in re.split(r"^  --", text, flags=re.MULTILINE)[1:]:
        name, _, help_text = block.partition("\n")
        default = re.search(r"\(default: (.*)\)\s*$", help_text)
        found[name.strip().replace("-", "_")] = default.group(1) if default else None
    assert found, f"no flags parsed from `splinecal {command} --help`"
    return found


def test_every_command_has_a_function():
    listed = commands()
    assert len(listed) >= 9, listed
    assert sorted(map(function_name, listed)) == sorted(splinecal.COMMANDS)
    for name in listed:
        assert callable(getattr(splinecal, function_name(name))), name


def same_default(cli, python):
    """The flag's default text (None: empty string) against the keyword's default."""
    if python is inspect.Parameter.empty:  # a required argument: the command requires it too
        return True
    if cli is None:
        return python in (None, "")
    if isinstance(python, bool):
        return cli == str(python).lower()
    if isinstance(python, (int, float)):
        return float(cli) == pytest.approx(python, rel=1e-9)
    if isinstance(python, (list, tuple)):
        return [float(x) for x in cli.split(",")] == [float(x) for x in python]
    return cli == python


@pytest.mark.parametrize("command", commands())
def test_every_flag_is_a_keyword_with_the_same_default(command):
    signature = inspect.signature(getattr(splinecal, function_name(command))).parameters
    keyword = {flag: KEYWORD_NAME.get((command, flag), flag) for flag in flags(command)}
    parameters = {flag: signature[name] for flag, name in keyword.items() if name in signature}
    missing = {f for f in flags(command) if f not in parameters} - NOT_IN_PYTHON
    assert not missing, f"splinecal.{command} lacks the keywords {sorted(missing)}"
    for flag, cli_default in flags(command).items():
        if flag in missing or flag in NOT_IN_PYTHON or (command, flag) in DEFAULT_FORM:
            continue
        python_default = parameters[flag].default
        assert same_default(cli_default, python_default), \
            f"{command} --{flag}: default {cli_default!r}, Python {python_default!r}"


@pytest.mark.parametrize("command", list(splinecal.COMMANDS) + ["allan_deviation"])
def test_an_unknown_keyword_is_a_type_error_naming_it(command):
    function = getattr(splinecal, command)
    with pytest.raises(TypeError, match="'definitely_not_a_flag'"):
        function(definitely_not_a_flag=1)


def test_a_misspelled_keyword_names_the_closest_one():
    with pytest.raises(TypeError, match=r"'knot_spaceing'; did you mean 'knot_spacing'\?"):
        splinecal.fit("imu.csv", "poses.csv", knot_spaceing=0.05)
    with pytest.raises(TypeError, match=r"'hold-camera-chain'; did you mean 'hold_camera_chain'"):
        splinecal.calibrate("imu.csv", "obs.csv", "camchain.yaml", **{"hold-camera-chain": True})
