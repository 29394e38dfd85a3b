"""What the ``bbb`` commands share: the one-line usage error, the argument parser class,
the argument types, and the workflow argument (a file path, or a shipped scene's name)."""

from __future__ import annotations

import argparse
import math
import signal
import sys
from importlib import metadata

from ..workflow.identity import f_key

__all__ = ["UsageError", "Parser", "EXIT_USAGE", "EXIT_FAILED", "EXIT_TERMINATED", "EXIT_PIPE",
           "DEBUG_ENV", "error",
           "version", "frequency_list", "positive_int", "positive_ints", "jobs",
           "WORKFLOW_HELP", "load"]

EXIT_USAGE = 2
EXIT_FAILED = 1
EXIT_TERMINATED = 128 + signal.SIGTERM
EXIT_PIPE = 128 + signal.SIGPIPE  # output into a closed pipe (pipeline/cli.py)
#: set (to anything) to see the traceback of an unexpected exception instead of one line
DEBUG_ENV = "BBB_DEBUG"

#: the help of every workflow argument
WORKFLOW_HELP = "workflow TOML file, or the name of a shipped scene (`bbb scenes` lists them)"


class UsageError(Exception):
    """Bad command-line input: reported in one line, exit status 2."""


class Parser(argparse.ArgumentParser):
    def error(self, message: str):  # argparse prints usage + message; we want one line
        raise UsageError(f"{self.prog}: {message} (see {self.prog} --help)")


def error(message: str) -> None:
    """``bbb: error: message`` on stderr."""
    print(f"bbb: error: {message}", file=sys.stderr)


def version() -> str:
    """The installed package's version (importlib.metadata), as pip reports it."""
    try:
        return metadata.version("bbb")
    except metadata.PackageNotFoundError:  # a source tree on sys.path, never installed
        return "unknown (not installed)"


def load(workflow: str):
    """The Study of a workflow argument: a file that exists, else a shipped scene's name
    (:func:`pipeline.workflow.scenes.load_named`; WorkflowError, one line, if neither)."""
    from ..workflow.scenes import load_named

    return load_named(workflow)


def frequency_list(text: str) -> tuple[float, ...]:
    """'60,72.5' -> (60.0, 72.5): distinct frequencies within bbb.Params' range, multiples of
    1 mHz (pipeline.workflow.keys.ALLOWED_F)."""
    from ..workflow.keys import ALLOWED_F, F_MAX

    allowed = "allowed: comma-separated frequencies in Hz, e.g. 60,72"
    out = []
    for item in text.split(","):
        try:
            f = float(item)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{item.strip()!r} is not a number; {allowed}") from None
        if not math.isfinite(f) or not 0 < f <= F_MAX or abs(f * 1000 - f_key(f)) > 1e-6 * f:
            raise argparse.ArgumentTypeError(f"{item.strip()} is out of range; allowed: {ALLOWED_F}")
        if f_key(f) in {f_key(g) for g in out}:
            raise argparse.ArgumentTypeError(f"{item.strip()} is repeated; {allowed}")
        out.append(f)
    return tuple(out)


def positive_int(text: str) -> int:
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"{n} is out of range; allowed: an integer >= 1")
    return n


def jobs(text: str) -> int | tuple[int, int]:
    """'4' -> 4; '0:8' -> (0, 8): elastic, 0 <= MIN <= MAX, MAX >= 1."""
    lo, colon, hi = text.partition(":")
    if not colon:
        return positive_int(text)
    if not (lo.isdigit() and hi.isdigit() and int(lo) <= int(hi) and int(hi) >= 1):
        raise argparse.ArgumentTypeError(f"{text!r}; allowed: N, or MIN:MAX, 0 <= MIN <= MAX >= 1")
    return int(lo), int(hi)


def positive_ints(text: str) -> tuple[int, ...]:
    return tuple(positive_int(x.strip()) for x in text.split(","))
