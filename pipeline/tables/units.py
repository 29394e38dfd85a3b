"""The unit of every column of every table the pipeline writes: one map, read by the Parquet
metadata of ``bbb reduce`` (:func:`pipeline.tables.reduce.write_table`) and by the xarray
attributes of ``open_study(reduced=True)`` (:mod:`pipeline.api`).

Conventions (UDUNITS / CF): lengths in mm, times in s, frequencies in Hz, so D is ``mm^2/s``
and a velocity ``mm/s``; a dimensionless number (a ratio, a fraction, a count, a rate per
collision, a log-ratio) has the unit ``"1"``; a column that is not a quantity (a name, a
flag, a verdict or status text, or a number whose unit depends on another column, such as the
accuracy study's knob ``value``) has ``""``.  A CI bound ``<col>_lo`` / ``<col>_hi`` has the
unit of ``<col>``.

How a column's unit is found (:func:`unit`): its exact name in :data:`UNITS` (or in a study's
own map, ``extra``); else, for ``<col>_lo`` / ``<col>_hi``, the unit of ``<col>``; else the
first rule of :data:`FAMILIES` whose pattern the whole name matches (column families such as
the per-family ``D_<family>``); else it is unknown (None; written as ``"?"``, and
tests/pipeline/tables/test_units.py fails on every committed table with such a column).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping

from ..workflow.keys import PARAM_UNITS

__all__ = ["DIMENSIONLESS", "NOT_A_QUANTITY", "UNKNOWN", "D_UNIT", "V_UNIT", "UNITS",
           "FAMILIES", "CI_SUFFIXES", "unit", "column_unit", "units"]

DIMENSIONLESS = "1"
NOT_A_QUANTITY = ""
UNKNOWN = "?"
D_UNIT = "mm^2/s"
V_UNIT = "mm/s"
CI_SUFFIXES = ("_lo", "_hi")

_1, _NQ = DIMENSIONLESS, NOT_A_QUANTITY

#: exact column names (CI bounds follow their column)
UNITS: dict[str, str] = {
    # every table: the point and its family
    "f": "Hz", "family": _NQ, "initial": _NQ, "n_particles": _1, "t_max": "s",
    # diffusion (pipeline.tables.diffusion): D(f), its CI and what the CI means
    "Gamma": _1, "D": D_UNIT, "D_status": _NQ, "D_cover": _1, "mover_share_hi": _1,
    "D_last": D_UNIT, "n_moving": _1, "fit_from": "s", "fit_to": "s", "eb_lag": "s",
    # ... ergodicity
    "EB": _1, "EB_threshold": _1, "EB_decay": _1, "EB_decay_threshold": _1, "ergodic": _NQ,
    "families_agree": _NQ, "eb_ok": _NQ, "rule": _NQ, "level_ok": _NQ, "decay_ok": _NQ,
    "spread_ok": _NQ, "CV2_D": _1, "CV_D": _1, "CV_D_upper": _1, "cv_max": _1, "rule_fp": _1,
    "rule_fn": _1, "verdict": _NQ, "stop": _NQ,
    # ... stationarity: D of the run's two halves and their difference, a D too
    "D_half1": D_UNIT, "D_half2": D_UNIT, "dD": D_UNIT, "dD_tol": D_UNIT, "stationary": _NQ,
    # ... transport (conveyor scenes)
    "v": V_UNIT, "v_by": _NQ, "D_drift": D_UNIT, "D_drift_status": _NQ, "Pe": _1, "dv": V_UNIT,
    "dv_tol": V_UNIT, "steady": _NQ, "msd_slope_ratio": _1, "diffusive": _NQ,
    # counters (pipeline.tables.counters): <counter>_per_s in FAMILIES
    "task_seconds": "s",
    # contact (pipeline.tables.contact): shares of the run
    "held_frac": _1, "slide_frac": _1, "contact_frac": _1,
    # mechanisms (pipeline.tables.mechanisms): D_<n>, D_inf... in FAMILIES
    "n_jump_particles": _1, "lag": _1, "lag_s": "s", "converged": _NQ, "max_lag": _1,
    "lag_coll": _1, "converged_coll": _NQ, "max_lag_coll": _1, "tau_coll": "s",
    "f_dn": "Hz", "f_up": "Hz", "lam": "1/s", "lam_coll": _1, "lam_move": "1/s",
    "lam_conf": "1/s", "frac_creep": _1, "still": _NQ,
    # locking (pipeline.tables.collisions)
    "n_states": _1, "v_creep": V_UNIT, "v_max": V_UNIT, "k_max": _1, "v_peak": V_UNIT,
    "k_peak": _1, "n_flights": _1, "loops": _1,
    # a grid's axis columns: the [params] keys, in the workflow's own map
    **{k: u for k, u in PARAM_UNITS.items() if k != "Gamma"},
}

#: (pattern of the whole name, unit) for column families, first match wins
FAMILIES: tuple[tuple[str, str], ...] = (
    (r"D_.+", D_UNIT),  # D_<family>, D_<n> and D_inf (+ _coll) of the expansion
    (r"EB_.+", _1),  # EB_<family>, EB_decay_<family>
    (r".+_per_s", "1/s"),  # counters per particle per second
    (r"(ln_(D|mem|walk)|share_mem)(_coll)?_(dn|up)", _1),  # contrasts with the neighbours
    (r"lam(_move|_conf)?_(distinct|tie)", _1),
    (r"lam(_move|_conf)?_degenerate", _NQ),
    (r"n_.+", _1),  # counts
)
_FAMILIES = tuple((re.compile(p), u) for p, u in FAMILIES)


def unit(column: str, extra: Mapping[str, str] | None = None) -> str | None:
    """The unit of ``column`` (module docstring), None if unknown; ``extra``: a study's own
    columns, looked up first."""
    for table in (extra or {}, UNITS):
        if column in table:
            return table[column]
    for suffix in CI_SUFFIXES:
        if column.endswith(suffix) and len(column) > len(suffix):
            found = unit(column[: -len(suffix)], extra)
            if found is not None:
                return found
    for pattern, u in _FAMILIES:
        if pattern.fullmatch(column):
            return u
    return None


def column_unit(column: str, extra: Mapping[str, str] | None = None) -> str:
    """:func:`unit`, with ``"?"`` for a column the map does not know."""
    found = unit(column, extra)
    return UNKNOWN if found is None else found


def units(columns: Iterable[str], extra: Mapping[str, str] | None = None) -> dict[str, str]:
    """{column: :func:`column_unit`} for ``columns``."""
    return {c: column_unit(c, extra) for c in columns}
