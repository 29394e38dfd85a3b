"""The ``bbb`` command line: ``bbb run``, ``bbb reduce``, ``bbb status``, ``bbb verify``,
``bbb plot``, ``bbb accuracy``, ``bbb plan``, ``bbb scenes``, ``bbb --version``.

This module builds the parser and runs a command; the commands are in pipeline/commands/,
one module per group (run and accuracy; the store's reduce, status, verify, plot; plan and
scenes).  Wherever a WORKFLOW is asked for, a file path or the name of a shipped scene
(``bbb run smoke``; ``bbb scenes`` lists them) is accepted; a path that exists wins.

Usage errors (bad arguments, a malformed workflow, a store of another workflow) print one line
``bbb: error: ...`` to stderr and exit with status 2, without a traceback.  A failed task exits
with status 1 and names the frequency, family and chunk.  ``bbb run`` stopped by Ctrl-C exits
with status 130, by SIGTERM with 143 (pipeline/commands/run.py).
"""

from __future__ import annotations

import argparse
import sys

from .commands import plan, run, store
from .commands.common import EXIT_TERMINATED, EXIT_USAGE, Parser, UsageError, error, version
from .execute.interrupt import Terminated
from .store.layout import default_store_path  # importable from here as before

__all__ = ["main", "default_store_path", "UsageError"]


def _build_parser() -> argparse.ArgumentParser:
    p = Parser(prog="bbb", description="Bouncing ball billiard study pipeline.")
    p.add_argument("--version", action="version", version=f"bbb {version()}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", parser_class=Parser)
    sub.required = True
    run.add_parsers(sub)
    store.add_parsers(sub)
    plan.add_parsers(sub)
    return p


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``bbb`` script and of ``python -m pipeline``; returns the exit code."""
    try:
        return _main(argv)
    except SystemExit as e:  # --help, or argparse's own exits
        return int(e.code or 0) if isinstance(e.code, int) or e.code is None else EXIT_USAGE
    except UsageError as e:
        error(str(e).removeprefix("bbb: "))
        return EXIT_USAGE
    except Terminated:
        error("terminated (SIGTERM); re-run the same command to resume")
        return EXIT_TERMINATED
    except KeyboardInterrupt:
        error("interrupted; re-run the same command to resume")
        return 130


def _main(argv: list[str] | None) -> int:
    from .store.study_store import StoreError
    from .workflow.load import WorkflowError

    args = _build_parser().parse_args(argv)
    try:
        return args.handler(args)
    except (WorkflowError, StoreError) as e:
        raise UsageError(str(e)) from None


if __name__ == "__main__":
    sys.exit(main())
