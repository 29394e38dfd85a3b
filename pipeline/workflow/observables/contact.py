"""Contact: per particle the time held at rest on the floor and the time sliding on an arc, s
(bbb.record.CONTACT_TIME_NAMES)."""

from __future__ import annotations

import numpy as np

from bbb.record import CONTACT_TIME_NAMES

from .contract import Array, Chunk, Observable


class Contact(Observable):
    name = "contact"
    tables = ("contact",)

    def on(self, obs) -> bool:
        return bool(obs.contact)

    def arrays(self, study):
        return tuple(Array(f"{c}_time", (), "float64", np.nan, "s",
                           f"time {c} in sustained contact up to t_max") for c in CONTACT_TIME_NAMES)

    def compute(self, chunk: Chunk):
        return {f"{c}_time": chunk.run.contact_time[c] for c in CONTACT_TIME_NAMES}
