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

What each column of each ``bbb reduce`` table means: :data:`TABLE_COLUMNS` (names or patterns
with placeholders such as ``D_<family>``), read by :func:`describe`; docs/tables.md is
generated from it and this module's units (``python -m pipeline.tables --reference --write``,
:mod:`pipeline.tables.reference`).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping

from ..workflow.keys import PARAM_UNITS
from ..workflow.observables.registry import own_tables

__all__ = ["DIMENSIONLESS", "NOT_A_QUANTITY", "UNKNOWN", "D_UNIT", "V_UNIT", "UNITS",
           "FAMILIES", "CI_SUFFIXES", "unit", "column_unit", "units", "PLACEHOLDERS",
           "TABLE_COLUMNS", "describe", "row_unit"]

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
    "dv_tol": V_UNIT, "steady": _NQ, "msd_slope_ratio": _1, "diffusive": _NQ, "v_status": _NQ,
    "a": "mm/s^2",
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
    # the observables' own tables: their columns as each declares them (patterns: _OWN)
    **{name: u for o in own_tables() for name, _, u, _ in o.columns if "<" not in name},
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
    for pattern, u in _FAMILIES + _OWN:
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


# -- what each column means: docs/tables.md is generated from these rows ----------------------
#: placeholders of the rows' names, and what they stand for (a regex)
PLACEHOLDERS: dict[str, str] = {
    "<axis>": "|".join(k for k in PARAM_UNITS), "<family>": r"[A-Za-z][A-Za-z0-9_-]*",
    "<n>": r"\d+|inf", "<counter>": r"[a-z]+", "<s>": r"(?:_coll)?", "<side>": r"(?:dn|up)",
    "<sub>": r"(?:_move|_conf)?",
    "<state>": r"stuck|locked_1|locked_k|chaotic|diffusing|unknown",
    "<class>": r"stuck|locked_1|locked_k|irregular",
}
#: a placeholder's stand-in when the row's unit is looked up (:func:`row_unit`)
_EXAMPLES = {"<family>": "rest", "<n>": "0", "<counter>": "collisions", "<s>": "",
             "<side>": "dn", "<sub>": "", "<state>": "stuck", "<class>": "stuck"}
_AXIS = ("a [grid] scene's axis: the point's value of that [params] key (the long table has "
         "one column per axis, after f)")
_WHICH = (("f", "floor frequency"), ("<axis>", _AXIS))
_FAMILY = (("family", "initial-condition family"),
           ("initial", "its initial condition: rest, dropped or launched"))
_NEIGHBOUR = ("ln of the ratio to the grid neighbour below (dn) or above (up), per period or "
              "per collision (_coll)")

#: table -> its columns in order: (name or pattern, whether ``_lo``/``_hi`` follow, meaning)
TABLE_COLUMNS: dict[str, tuple[tuple[str, bool, str], ...]] = {
    "counters": tuple((n, False, d) for n, d in (*_WHICH, *_FAMILY)) + (
        ("n_particles", False, "particles of done chunks"),
        ("t_max", False, "simulated time per particle"),
        ("<counter>_per_s", False, "a bbb counter (collisions, sticks, liftoffs, anomalies) "
         "per particle per second of simulated time"),
        ("task_seconds", False, "summed simulation time of the done chunks' tasks"),
    ),
    "diffusion": tuple((n, False, d) for n, d in _WHICH) + (
        ("Gamma", False, "peak floor acceleration Γ = A (2π f)² / g"),
        ("D", True, "diffusion coefficient, all families pooled: half the slope of the fit "
         "MSD(lag) = 2 D lag + c to the time-and-ensemble averaged MSD over the fit lags, with "
         "its bootstrap CI over particles (the CI a target-driven run stopped on); blank where "
         "the estimator failed (CI below 0: see D_status); D_hi blank where no particle moved. "
         "On a tilted or thrown floor this is the raw MSD's slope, drift included (it grows "
         "with v²): the diffusion coefficient there is D_drift"),
        ("D_status", False, "what D's CI means: \"ok\", \"rare movers\" (calibrated coverage), "
         "\"no mover\" (with the mover-share bound) or \"estimator failed\" (D < 0 "
         "significantly: the fit's numbers; D left blank), per family where they differ; "
         "\"no mover\" where no particle left its cell (n_moving); and, where v is "
         "significant, \"drift included (v significant): read D_drift\", where the drift "
         "accelerates, \"accelerating (v_status): D includes the acceleration\""),
        ("D_cover", False, "the coverage of D's CI: the nominal level, or the rare-mover "
         "rule's calibrated coverage; blank with no mover or a failed estimator"),
        ("mover_share_hi", False, "no mover only: one-sided upper bound on the share of "
         "particles that move"),
        ("D_last", False, "single-origin MSD(t_end) / (2 t_end) over the whole run (the "
         "paper's Eq. 10)"),
        ("n_particles", False, "particles analysed (of done chunks)"),
        ("n_moving", False, "particles that left their cell: farther than S from their "
         "position at the start of the analysed part at some time of it (a change of x by "
         "rounding, or rocking on an arc, never counts)"),
        ("t_max", False, "simulated time per particle"),
        ("fit_from", False, "first lag of the MSD fit"), ("fit_to", False, "last lag of the MSD fit"),
        ("eb_lag", False, "lag of EB"),
        ("EB", False, "ergodicity-breaking parameter Var(δ²)/<δ²>² at eb_lag, pooled"),
        ("EB_threshold", False, "eb_tolerance × the Brownian EB at that lag and run length"),
        ("EB_decay", False, "EB of the analysed run's first half / EB of all of it: ~2 "
         "ergodic, ~1 a population mixing different D"),
        ("EB_decay_threshold", False, "the smallest passing EB_decay"),
        ("ergodic", False, "the ergodicity verdict under its rule (docs/statistics.md); blank, "
         "with its components, where no particle left its cell"),
        ("families_agree", False, "the families' D agree within their CIs (true with one family)"),
        ("eb_ok", False, "the rule's EB part passes"), ("rule", False, "the verdict rule's name"),
        ("level_ok", False, "EB <= EB_threshold"), ("decay_ok", False, "EB_decay passes"),
        ("spread_ok", False, "CV_D <= cv_max"),
        ("CV2_D", True, "estimated squared CV of the per-particle D, 2 EB − EB(T/2), pooled, "
         "signed (noise takes it below 0)"),
        ("CV_D", False, "sqrt(CV2_D) where CV2_D > 0"),
        ("CV_D_upper", False, "sqrt of CV2_D's one-sided 95 % upper bound"),
        ("cv_max", False, "the rule's limit on CV_D"),
        ("rule_fp", False, "the rule's worst measured false-positive rate at this size"),
        ("rule_fn", False, "the rule's worst measured false-negative rate at this size"),
        ("D_<family>", True, "D of one family, as D (blank where its estimator failed)"),
        ("EB_<family>", False, "EB of one family"),
        ("EB_decay_<family>", False, "EB_decay of one family"),
        ("verdict", False, "the ergodicity verdict's reasons, '; '-joined"),
        ("stop", False, "target-driven stores only: why sampling stopped (target met, "
         "resolved to ±d_resolved, cap, open), per family"),
        ("D_half1", False, "D of the analysed run's first half (pooled)"),
        ("D_half2", False, "D of its second half"),
        ("dD", True, "D_half2 − D_half1, paired bootstrap CI over particles"),
        ("dD_tol", False, "what dD's CI must clear to flag: 5 % of D + 1e-6 mm²/s"),
        ("stationary", False, "false where D depends on the run length (dD's CI beyond ±dD_tol)"),
        ("v", True, "tilted or thrown floors: drift velocity, slope of the mean displacement "
         "over the fit lags; v_lo, v_hi blank unless v_status is ok or by construction (on an "
         "accelerating row v is the mean velocity over the analysed run, not a drift)"),
        ("v_status", False, "what v means: ok (a steady drift), accelerating (read a), no "
         "mover (no particle left its cell: no drift, D_drift or Pe measured), by "
         "construction (mirror symmetry: v = 0 exactly), not measured (dv unknown)"),
        ("a", True, "acceleration 2 dv / T_a (T_a the analysed duration) with dv's CI scaled "
         "alike: exact for a uniform acceleration"),
        ("v_by", False, "how particles count: mirror symmetry (v = 0 exactly), pairs, independent"),
        ("D_drift", True, "tilted or thrown floors: diffusion coefficient about the drift (MSD "
         "of x − v t); blank where its estimator failed"),
        ("D_drift_status", False, "\"ok\", the failed fit's numbers, or \"no mover\""),
        ("Pe", False, "Péclet number v S / D_drift; blank unless v_status is ok or by construction"),
        ("dv", True, "v of the second half − v of the first half"),
        ("dv_tol", False, "the band dv's CI must leave to flag"),
        ("steady", False, "false where dv's CI lies beyond ±dv_tol: an acceleration, not a drift; "
         "blank where untested (no mover, dv unknown)"),
        ("msd_slope_ratio", True, "slope of the MSD about the drift, upper / lower half of "
         "the fit lags: 1 for diffusion"),
        ("diffusive", False, "false where that ratio's CI lies above 1 + a calibrated "
         "tolerance: D_drift is then a window slope"),
    ),
    "contact": tuple((n, False, d) for n, d in (*_WHICH, *_FAMILY)) + (
        ("n_particles", False, "particles of done chunks"),
        ("held_frac", True, "mean share of the run a particle is held at rest on the floor"),
        ("slide_frac", True, "mean share of the run a particle slides on an arc (0 under stick)"),
        ("contact_frac", False, "held_frac + slide_frac"),
    ),
    "mechanisms": tuple((n, False, d) for n, d in _WHICH) + (
        ("Gamma", False, "peak floor acceleration Γ = A (2π f)² / g"),
        ("n_jump_particles", False, "particles in the per-period expansion"),
        ("D_<n>", True, "Taylor–Green–Kubo sum D_n per floor period; D_inf the converged sum"),
        ("lag", False, "first lag from which |C(k)| stays in its noise, floor periods"),
        ("lag_s", False, "that lag in seconds"),
        ("converged", False, "false: |C| never fell into the noise below max_lag"),
        ("max_lag", False, "largest lag summed, floor periods"),
        ("n_left_cell", False, "particles whose x spans ≥ S over the analysed window"),
        ("n_coll_particles", False, "particles kept in the per-collision expansion"),
        ("n_coll_excluded", False, "left out for recording under half the median jumps"),
        ("n_coll_jumps", False, "jumps per particle used"),
        ("D_<n>_coll", True, "the same sums per collision"),
        ("tau_coll", False, "mean time between collisions of the jumps used"),
        ("lag_coll", False, "lag per collision"), ("converged_coll", False, "converged per collision"),
        ("max_lag_coll", False, "max_lag per collision"),
        ("n_lyapunov", False, "particles with a Lyapunov exponent"),
        ("n_collapsed", False, "of them, those whose separation became 0 (left out)"),
        ("n_lam_move", False, "moving particles (x spans ≥ S)"),
        ("n_lam_conf", False, "confined particles (spans < S)"),
        ("lam", True, "largest Lyapunov exponent, mean over particles"),
        ("lam_coll", True, "the same per collision"),
        ("lam_move", True, "λ of the moving particles"), ("lam_conf", True, "λ of the confined ones"),
        ("lam<sub>_distinct", False, "distinct per-particle values of λ (equal to 1e-4 relative)"),
        ("lam<sub>_tie", False, "size of the largest group of equal values"),
        ("lam<sub>_degenerate", False, "true where that CI is degenerate (its _lo, _hi blank)"),
        ("frac_creep", False, "share of post-collision states in the creeping band, pooled"),
        ("f_dn", False, "grid neighbour below f"), ("f_up", False, "grid neighbour above f"),
        ("ln_D<s>_<side>", True, f"{_NEIGHBOUR} of D_inf"),
        ("ln_walk<s>_<side>", True, f"{_NEIGHBOUR} of D_0 (random walk)"),
        ("ln_mem<s>_<side>", True, f"{_NEIGHBOUR} of D_inf / D_0 (memory)"),
        ("share_mem<s>_<side>", True, "ln_mem / ln_D: memory's share of the contrast"),
        ("still", False, "true where no particle left its cell or every state creeps"),
    ),
    "locking": tuple((n, False, d) for n, d in (*_WHICH, *_FAMILY)) + (
        ("n_states", False, "finite post-collision states"),
        ("frac_creep", False, "share of them in the creeping band v_y⁺ <= v_creep"),
        ("v_creep", False, "upper edge of the creeping band, 1.1 A 2π f"),
        ("v_max", True, "maximal v_y⁺ of the spiral: 0.99 quantile above the band"),
        ("k_max", True, "2 v_max f / g"),
        ("v_peak", True, "dominant peak (KDE mode) of v_y⁺ above the band"),
        ("k_peak", True, "2 v_peak f / g"),
        ("t_max", False, "0.99 quantile of the free-flight times (not the run's length)"),
        ("n_flights", False, "free flights t_max was computed from"),
        ("loops", False, "f t_max: turns of the spiral approximation"),
    ),
    **{o.name: tuple((n, False, d) for n, d in (*_WHICH, *_FAMILY))
       + tuple((name, ci, doc) for name, ci, _, doc in o.columns) for o in own_tables()},
}


def _pattern(name: str, ci: bool) -> re.Pattern:
    rx = re.escape(name)
    for ph, sub in PLACEHOLDERS.items():
        rx = rx.replace(re.escape(ph), f"(?:{sub})")
    return re.compile(rx + ("(?:_lo|_hi)?" if ci else ""))


#: the observables' own column families (names with placeholders, as they declare them)
_OWN = tuple((_pattern(name, False), u) for o in own_tables() for name, _, u, _ in o.columns
             if "<" in name)


def describe(table: str, column: str) -> str | None:
    """The meaning of ``column`` in ``table`` (:data:`TABLE_COLUMNS`; an exact name before a
    pattern), None if it has no row there."""
    rows = TABLE_COLUMNS[table]
    for exact in (True, False):
        for name, ci, doc in rows:
            if ("<" not in name) == exact and _pattern(name, ci).fullmatch(column):
                return doc
    return None


def row_unit(name: str) -> str | None:
    """The unit of a row of :data:`TABLE_COLUMNS` (None for ``<axis>``: each axis has its
    [params] key's)."""
    if name == "<axis>":
        return None
    for ph, ex in _EXAMPLES.items():
        name = name.replace(ph, ex)
    return unit(name)
