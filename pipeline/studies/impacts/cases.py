"""Synthetic impacts tables with known answers, and each impacts claim's synthetic cases
(:class:`~pipeline.claims.claim.Case`), named by the claim records of :mod:`.claims`.

A table holds the frequencies 50, 60, 80 Hz for the families rest and launched; a column's
value is set directly with an interval of ± 0.02 (the rule reads only the value, its interval
and the status).  50 Hz lies below the claims' frequencies: its value never counts."""

from __future__ import annotations

import math

import pandas as pd

from ...claims.claim import Case

__all__ = ["impacts_table", "phase_cases", "lag_cases"]

_HW = 0.02
_F = (50.0, 60.0, 80.0)
_FAMILIES = ("rest", "launched")


def impacts_table(column: str, value: float, below: float | None = None,
                  at: dict | None = None) -> pd.DataFrame:
    """Rows (f, family) for f in 50, 60, 80 Hz with ``column`` = ``value`` ± 0.02; ``below``:
    the value at 50 Hz (default ``value``); ``at``: {(f, family): value} overriding single
    rows (NaN: blank, its status says so)."""
    rows = []
    for f in _F:
        for fam in _FAMILIES:
            v = (at or {}).get((f, fam), below if f < 60 and below is not None else value)
            blank = math.isnan(v)
            rows.append({"f": f, "family": fam, column: v,
                         f"{column}_lo": math.nan if blank else v - _HW,
                         f"{column}_hi": math.nan if blank else v + _HW,
                         "impacts_status": f"{column}: fewer than two pairs" if blank else ""})
    return pd.DataFrame(rows)


def _ctx(t: pd.DataFrame | None) -> dict:
    return {"tables": {"impacts": t}}


def _cases(column: str, holds: float, fails: float) -> list[Case]:
    base = "holds at every f and family"
    return [
        Case(base, _ctx(impacts_table(column, holds, below=fails)), "agrees"),
        Case("fails at every f and family", _ctx(impacts_table(column, fails)), "disagrees",
             perturbs=base),
        Case("fails at 80 Hz from rest only", _ctx(impacts_table(column, holds,
                                                                 at={(80.0, "rest"): fails})),
             "partly", perturbs=base),
        Case("interval reaches the edge at 60 Hz launched",
             _ctx(impacts_table(column, holds, at={(60.0, "launched"): _edge(holds, fails)})),
             "agrees within the CI", perturbs=base),
        Case("blank at 60 Hz launched", _ctx(impacts_table(column, holds,
                                                           at={(60.0, "launched"): math.nan})),
             "not measured", perturbs=base),
        Case("no table", _ctx(None), "not measured", perturbs=base),
        # the claims' frequencies moved above the table's: nothing in scope
        Case("scope above the table", _ctx(impacts_table(column, holds)), "not measured",
             perturbs=base, options={"f_from": 90.0}),
        # the claims' frequencies moved down to 50 Hz, where the value fails: one part flips
        Case("scope down to 50 Hz", _ctx(impacts_table(column, holds, below=fails)), "partly",
             perturbs=base, options={"f_from": 50.0}),
    ]


def _edge(holds: float, fails: float) -> float:
    """A value on the holding side of the band edge whose ± 0.02 interval crosses it."""
    edge = 0.5 if holds > 0.5 or fails > 0.5 else 0.0
    return edge + math.copysign(0.01, holds - edge)


def phase_cases() -> list[Case]:
    """I1's rule: up_share above 0.5 with its interval, at every (f, family) with f ≥ 60 Hz."""
    return _cases("up_share", 0.62, 0.41)


def lag_cases() -> list[Case]:
    """I2's rule: vx_within_1 below 0 with its interval, at every (f, family) with f ≥ 60 Hz."""
    return _cases("vx_within_1", -0.3, 0.2)
