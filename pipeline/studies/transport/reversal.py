"""The transport map ``transport_reversal``: drift v over (throw ψ, f) on a floor tilted by
φ = 2° (downhill towards −x) whose throw carries particles towards +x, uphill, under the stick
model and Coulomb friction -- where the current changes sign, and where the particles start
to hop, against conveyor theory's throw number.

Sign convention (bbb.Params, docs/physics.md): x runs up the slope for φ > 0, and a throw
ψ < 90° moves the floor along (cos ψ, sin ψ), so a hopping particle is carried towards +x:
uphill.  ψ = 90° is the tilted floor vibrated vertically.

throw number     Γ_v = Γ sin ψ / cos φ, Γ = A ω²/g (Sloot & Kruyt 1996): a particle at rest on
                 a flat floor lifts off once Γ_v > 1 (sliding regime below, hopping above);
                 :func:`throw_number_frequency` is the f of Γ_v = 1.
airborne share   1 − (time held + time sliding) / t_max, the mean over particles from the
                 contact table, its CI the conservative one from the two fractions' CIs
                 (lo = 1 − held_hi − slide_hi, hi = 1 − held_lo − slide_lo): :func:`airborne`.
hopping boundary along f at a fixed floor and contact model: the first frequency whose
                 airborne share is significantly above the threshold H (its CI's lower end
                 > H) and the last frequency below it whose share is significantly below H
                 (CI's upper end < H) bound the boundary: :func:`hopping_boundary`.  H is read
                 from ``hopping.json``, written by :mod:`.hopping_calibration`, which checks
                 it on flat floors (R = ∞: lift-off from rest exactly at Γ_v = 1) before any
                 map is looked at.
sign changes     :mod:`pipeline.claims.signs` along f on each line (:func:`f_reversals`) and
                 along ψ at each fixed (floor, contact model, f) (:func:`throw_cuts`,
                 :func:`throw_reversals`), steady points only, Bonferroni over each curve's
                 points.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from importlib import resources

import numpy as np
import pandas as pd

from bbb import Params

from ...claims.claim import Band, Quantity, judge
from ...claims.signs import reversal_intervals, significant_signs, steady_rows

__all__ = ["REVERSAL_MAP", "REVERSAL_TILT", "REVERSAL_THROWS", "REVERSAL_MODELS",
           "REVERSAL_LINES", "MODEL_LABELS", "HOPPING_CALIBRATION", "AIRBORNE_MIN", "F_STEP",
           "reversal_line", "line_label", "floor_label", "f_ranges", "throw_number_frequency", "airborne",
           "hopping_boundary", "liftoff_boundary", "judge_boundary", "f_reversals", "throw_cuts",
           "throw_reversals"]

REVERSAL_MAP = "transport_reversal"
REVERSAL_TILT = 2.0
REVERSAL_THROWS = (90.0, 75.0, 60.0, 45.0, 30.0)
#: (contact model, μ) of the map's lines
REVERSAL_MODELS = (("stick", 0.0), ("coulomb", 0.3))
MODEL_LABELS = {"stick": "stick", "coulomb": "Coulomb, μ = 0.3"}
#: the scene's frequency step (Hz): the resolution of every boundary along f
F_STEP = 2.0


def reversal_line(throw: float, contact: str) -> str:
    """The name of the map's line at (φ = 2°, ``throw``, ``contact``): its tables are
    ``<line>_<table>``."""
    return f"{REVERSAL_MAP}_p{throw:g}_{contact}"


#: {line: its grid values}
REVERSAL_LINES = {reversal_line(p, c): {"tilt": REVERSAL_TILT, "throw": p, "contact": c,
                                        "mu": mu}
                  for c, mu in REVERSAL_MODELS for p in REVERSAL_THROWS}
#: the hopping rule's calibration (hopping_calibration.py): the threshold H and its check
HOPPING_CALIBRATION: dict = json.loads(resources.files(__package__).joinpath("hopping.json")
                                       .read_text(encoding="utf-8"))
AIRBORNE_MIN = float(HOPPING_CALIBRATION["threshold"])


def line_label(values: Mapping) -> str:
    """"φ = 2°, ψ = 60°, stick" from a line's grid values."""
    s = f"φ = {float(values['tilt']):g}°, ψ = {float(values['throw']):g}°"
    return s + (f", {MODEL_LABELS.get(values['contact'], values['contact'])}"
                if "contact" in values else "")


def floor_label(floor: tuple) -> str:
    """"φ = 2°, stick" from a floor key of :func:`throw_cuts` (its (axis, value) pairs)."""
    d = dict(floor)
    return f"φ = {float(d['tilt']):g}°" + (
        f", {MODEL_LABELS.get(d['contact'], d['contact'])}" if "contact" in d else "")


def f_ranges(fs, step: float = F_STEP) -> str:
    """"46–58, 62 Hz": sorted frequencies with runs of neighbours ``step`` apart joined."""
    runs: list[list[float]] = []
    for f in sorted(fs):
        if runs and f - runs[-1][-1] <= step + 1e-9:
            runs[-1].append(f)
        else:
            runs.append([f])
    return ", ".join(f"{r[0]:g}–{r[-1]:g}" if len(r) > 1 else f"{r[0]:g}" for r in runs) + " Hz"


def throw_number_frequency(tilt: float, throw: float, params: Params | None = None) -> float:
    """The frequency (Hz) at which Γ_v = A ω² sin ψ / (g cos φ) = 1 (A, g of ``params``,
    default the paper's preset)."""
    p = Params.preset("klages2004", f=1.0) if params is None else params
    gv1 = p.g * math.cos(math.radians(tilt)) / (p.A * math.sin(math.radians(throw)))
    return math.sqrt(gv1) / (2.0 * math.pi)


def airborne(contact: pd.DataFrame) -> pd.DataFrame:
    """f, air, air_lo, air_hi (the share of the run in flight, module docstring) from a
    contact table's rows, sorted by f."""
    t = contact.sort_values("f")
    return pd.DataFrame({
        "f": t["f"].to_numpy(float),
        "air": (1.0 - t["held_frac"] - t["slide_frac"]).to_numpy(float),
        "air_lo": (1.0 - t["held_frac_hi"] - t["slide_frac_hi"]).to_numpy(float),
        "air_hi": (1.0 - t["held_frac_lo"] - t["slide_frac_lo"]).to_numpy(float)})


def hopping_boundary(f, lo, hi, threshold: float = AIRBORNE_MIN
                     ) -> tuple[float, float] | None:
    """(f_slide, f_hop): f_hop the first frequency whose airborne share's CI lies above
    ``threshold`` (lower end ``lo`` > it), f_slide the last frequency below f_hop whose CI lies
    below it (``hi`` < it); None if no frequency hops or none below the first hop slides."""
    f, lo, hi = (np.asarray(a, dtype=float) for a in (f, lo, hi))
    hop = np.flatnonzero(lo > threshold)
    if hop.size == 0:
        return None
    i = int(hop[0])
    slide = np.flatnonzero(hi[:i] < threshold)
    if slide.size == 0:
        return None
    return float(f[slide[-1]]), float(f[i])


def liftoff_boundary(f, per_period, threshold: float) -> tuple[float, float] | None:
    """(f_slide, f_hop) by lift-offs per floor period (claim T6b): f_hop the first frequency
    whose lift-offs per period reach ``threshold``, f_slide the frequency before it; None if
    none reaches it or the first frequency already does (the boundary lies outside)."""
    f, x = np.asarray(f, dtype=float), np.nan_to_num(np.asarray(per_period, dtype=float),
                                                     nan=-np.inf)
    hop = np.flatnonzero(x >= threshold)
    if hop.size == 0 or hop[0] == 0:
        return None
    i = int(hop[0])
    return float(f[i - 1]), float(f[i])


def judge_boundary(boundary: tuple[float, float] | None, f_v: float,
                   step: float = F_STEP) -> tuple[str, Quantity | None]:
    """The verdict of a boundary interval against Γ_v = 1 at ``f_v`` (Hz), claim T6's rule:
    the interval minus f_v (its midpoint the value, its ends the CI) judged against ± ``step``
    (pipeline.claims.claim.judge); 'disagrees' without a boundary."""
    if boundary is None:
        return "disagrees", None
    a, b = boundary
    q = Quantity(0.5 * (a + b) - f_v, a - f_v, b - f_v, "Hz", "the boundary's interval")
    return judge(q, Band(-step, step, "± one frequency step", "Hz")), q


def f_reversals(table: pd.DataFrame | None) -> tuple[list, np.ndarray, pd.DataFrame] | None:
    """(the sign changes of v along f as (f_a, f_b, sign after), the significant signs, the
    steady rows) of one line's diffusion table; None without transport columns."""
    t = steady_rows(table)
    if t is None:
        return None
    s = significant_signs(t["v"], t["v_lo"], t["v_hi"])
    return reversal_intervals(t["f"].to_numpy(float), s), s, t


def throw_cuts(lines: Mapping[str, tuple[Mapping, pd.DataFrame | None]]
               ) -> dict[tuple, pd.DataFrame]:
    """{(floor key, f): the cut along ψ} from lines {name: (grid values, diffusion table)}:
    lines that share every grid value but the throw (the floor: tilt, and contact model and
    μ where the map has them) and a frequency make one cut, rows (throw, v, v_lo, v_hi)
    sorted by ψ from 90° down (towards ever more uphill push), steady points only."""
    rows: dict[tuple, list] = {}
    for values, table in lines.values():
        t = steady_rows(table)
        if t is None:
            continue
        floor = tuple(sorted((k, v) for k, v in values.items() if k != "throw"))
        for r in t.itertuples(index=False):
            rows.setdefault((floor, float(r.f)), []).append(
                (float(values["throw"]), r.v, r.v_lo, r.v_hi))
    return {k: pd.DataFrame(v, columns=["throw", "v", "v_lo", "v_hi"])
            .sort_values("throw", ascending=False, ignore_index=True)
            for k, v in rows.items()}


def throw_reversals(cuts: Mapping[tuple, pd.DataFrame]) -> list[tuple[tuple, float, tuple]]:
    """(floor key, f, (ψ_a, ψ_b, sign after)) of every sign change along ψ of the cuts
    (Bonferroni over each cut's points)."""
    out = []
    for (floor, f), c in sorted(cuts.items()):
        if len(c) < 2:
            continue
        s = significant_signs(c["v"], c["v_lo"], c["v_hi"])
        out += [(floor, f, r) for r in reversal_intervals(c["throw"].to_numpy(float), s)]
    return out

