"""The ``bbb`` command line: ``bbb run``, ``bbb reduce``, ``bbb status``, ``bbb verify``,
``bbb plot``, ``bbb accuracy``, ``bbb plan``, ``bbb scenes``, ``bbb new``, ``bbb --version``.

This module builds the parser and runs a command; the commands are in pipeline/commands/,
one module per group (run and accuracy; the store's reduce, status, verify, plot; plan and
scenes; a scene as a template: ``scenes --show``, ``new``).  Wherever a WORKFLOW is asked
for, a file path or the name of a shipped scene (``bbb run smoke``; ``bbb scenes`` lists
them) is accepted; a path that exists wins.

Usage errors (bad arguments, a malformed workflow, a store of another workflow, a damaged
store) print one line ``bbb: error: ...`` to stderr and exit with status 2, without a
traceback; so does any other exception (naming its type; ``BBB_DEBUG=1`` shows the
traceback).  Output into a pipe whose reader has gone (``bbb status X | head -1``) ends
quietly with status 141, as a process ended by SIGPIPE.  A failed task exits
with status 1 and names the frequency, family and chunk.  ``bbb run`` stopped by Ctrl-C exits
with status 130, by SIGTERM with 143 (pipeline/commands/run_accuracy.py).
"""

from __future__ import annotations

import argparse
import os
import sys

from .commands import plan_scenes, run_accuracy, store, templates
from .commands.common import (
    DEBUG_ENV,
    EXIT_PIPE,
    EXIT_TERMINATED,
    EXIT_USAGE,
    Parser,
    UsageError,
    error,
    version,
)
from .execute.interrupt import Terminated

__all__ = ["main", "UsageError"]


def _build_parser() -> argparse.ArgumentParser:
    p = Parser(prog="bbb", description="Bouncing ball billiard study pipeline.")
    p.add_argument("--version", action="version", version=f"bbb {version()}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", parser_class=Parser)
    sub.required = True
    run_accuracy.add_parsers(sub)
    store.add_parsers(sub)
    plan_scenes.add_parsers(sub)
    templates.add_parsers(sub)  # after plan_scenes: it adds --show to `bbb scenes`
    return p


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``bbb`` script and of ``python -m pipeline``; returns the exit code."""
    try:
        code = _main(argv)
        sys.stdout.flush()  # output a closed pipe refuses fails here, not at exit
        return code
    except SystemExit as e:  # --help, or argparse's own exits
        return int(e.code or 0) if isinstance(e.code, int) or e.code is None else EXIT_USAGE
    except UsageError as e:
        error(str(e).removeprefix("bbb: "))
        _quiet_shutdown()
        return EXIT_USAGE
    except Terminated:
        error("terminated (SIGTERM); re-run the same command to resume")
        return EXIT_TERMINATED
    except KeyboardInterrupt:
        error("interrupted; re-run the same command to resume")
        return 130
    except BrokenPipeError:  # `bbb status X | head -1`: the reader has all it wanted
        return _closed_pipe()
    except Exception as e:  # a bug, or a fault no check names: one line, never a traceback
        if os.environ.get(DEBUG_ENV):
            raise
        error(_unexpected(e))
        return EXIT_USAGE


def _unexpected(e: Exception) -> str:
    _quiet_shutdown()
    return f"{type(e).__name__}: {e} (unexpected; {DEBUG_ENV}=1 shows the traceback)"


def _quiet_shutdown() -> None:
    """A read that failed inside Zarr leaves its other reads pending on Zarr's event loop;
    at exit asyncio would report each ("Task was destroyed but it is pending!") after the
    one line that said what failed."""
    import logging
    import warnings

    logging.getLogger("asyncio").setLevel(logging.CRITICAL)
    warnings.filterwarnings("ignore", message="coroutine .* was never awaited")


def _closed_pipe() -> int:
    """End quietly when stdout or stderr is a pipe whose reader has gone: what remains
    buffered goes nowhere (else Python reports the failed flush at exit), and the exit
    status is a process's ended by SIGPIPE.  (SIGPIPE itself stays ignored, as Python sets
    it: restored to its default it would kill a `bbb run` whose Dask connection breaks.)"""
    devnull = os.open(os.devnull, os.O_WRONLY)
    for stream in (sys.stdout, sys.stderr):
        try:
            os.dup2(devnull, stream.fileno())
        except (OSError, ValueError):  # no file descriptor (a test's captured stream)
            pass
    return EXIT_PIPE


def _main(argv: list[str] | None) -> int:
    from .store.study_store import StoreError
    from .workflow.load import WorkflowError

    args = _build_parser().parse_args(argv)
    try:
        return args.handler(args)
    except (WorkflowError, StoreError) as e:
        raise UsageError(str(e)) from None
    except (UsageError, Terminated, BrokenPipeError):
        raise
    except Exception as e:  # e.g. a chunk no check foresaw failing to decode: name the store
        if os.environ.get(DEBUG_ENV) or not getattr(args, "store", None):
            raise
        raise UsageError(f"{args.store}: {_unexpected(e)}") from None


if __name__ == "__main__":
    sys.exit(main())
