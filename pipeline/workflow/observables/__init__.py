"""Observables as plug-ins: what a chunk records, its store arrays, how a chunk computes them
from its run and how they reduce (:mod:`.contract`); every observable is listed once, in
:mod:`.registry`."""
