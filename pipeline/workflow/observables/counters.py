"""Counters, always recorded: per particle the collisions, sticks, lift-offs and anomalies
(non-finite velocities repaired) up to t_max (bbb.record.COUNTER_NAMES; 'recorded' is the
collisions' n_recorded)."""

from __future__ import annotations

from bbb.record import COUNTER_NAMES

from .contract import Array, Chunk, Observable

__all__ = ["Counters", "COUNTERS"]

#: per-particle counters kept from bbb's SimRun.counters, in storage order
COUNTERS = tuple(c for c in COUNTER_NAMES if c != "recorded")


class Counters(Observable):
    name = "counters"
    tables = ("counters",)

    def on(self, obs) -> bool:
        return True

    def arrays(self, study):
        return tuple(Array(f"n_{c}", (), "int64", 0, "", f"number of {c} up to t_max")
                     for c in COUNTERS)

    def compute(self, chunk: Chunk):
        return {f"n_{c}": chunk.run.counters[c] for c in COUNTERS}
