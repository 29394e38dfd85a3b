"""SIGTERM handled as Ctrl-C while ``bbb run`` runs (pipeline/commands/run_accuracy.py)."""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager

__all__ = ["Terminated", "sigterm_as_interrupt"]


class Terminated(KeyboardInterrupt):
    """SIGTERM during ``bbb run``: unwinds the run as Ctrl-C's KeyboardInterrupt does."""


@contextmanager
def sigterm_as_interrupt() -> Iterator[None]:
    """While ``bbb run`` runs, SIGTERM raises Terminated (a KeyboardInterrupt) in the main
    thread, so it unwinds like Ctrl-C: the ``finally`` blocks release the store's lock and
    cancel a --cluster's jobs (Python's default for SIGTERM ends the process at once, leaving
    SLURM jobs running).  Further SIGTERMs are ignored while that clean-up runs; the previous
    handler is restored on exit (tests call main() in-process)."""
    if threading.current_thread() is not threading.main_thread():
        yield  # signal handlers can only be set from the main thread
        return

    def handler(signum, frame):
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        raise Terminated

    before = signal.signal(signal.SIGTERM, handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, before)
