"""Synthetic onset maps with known answers, and each onset claim's synthetic cases
(:class:`~pipeline.claims.claim.Case`), named by the claim records of :mod:`.claims`.

A synthetic line is D(f) on 48–70 Hz in steps of 1 Hz: 0 (interval ± 0.5) below its onset,
100 ± 10 mm²/s from it on, so the onset rule locates it exactly at that grid point with the
CI ± half a step.  The predictions are the committed ones (predictions.json), so each case
places its onsets relative to what the claim predicts."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ...claims.claim import Case
from .predictions import load

__all__ = ["onset_table", "horizontal_cases", "sine_floor_cases", "vertical_cases",
           "vertical_sine_cases"]

_F = np.arange(48.0, 70.5, 1.0)
_STEP = 1.0
_LINES = {"onset_map": ("R", [(0.7, 1.05), (0.7, 15.0), (0.9, 15.0)]),
          "onset_sine": ("depth", [(0.7, 0.1), (0.9, 0.3)])}


def onset_table(axis: str, onsets: dict) -> pd.DataFrame:
    """A long table of lines {(α, axis value): onset f (Hz), or NaN: D 0 everywhere}."""
    rows = []
    for (a, v), on in onsets.items():
        for f in _F:
            up = math.isfinite(on) and f >= on
            D = 100.0 if up else 0.0
            rows.append({"f": f, "alpha": a, axis: v, "family": "rest", "D": D,
                         "D_lo": D - (10.0 if up else 0.5), "D_hi": D + (10.0 if up else 0.5)})
    return pd.DataFrame(rows)


def _prediction(which: str, a: float, preds: dict) -> float:
    return float(preds["f_liftoff"] if which == "liftoff" else preds["alpha"][f"{a:g}"]["f_c"])


def _ctx(scene: str, table: pd.DataFrame | None, preds: dict) -> dict:
    return {"tables": {f"{scene}_diffusion": table}, "predictions": preds,
            "step": {scene: _STEP}, "listed": {scene: _LINES[scene][1]}}


def _cases(scene: str, which: str, side: str = "both") -> list[Case]:
    preds = load()
    axis, lines = _LINES[scene]
    at = {ln: float(round(_prediction(which, ln[0], preds))) for ln in lines}
    if side == "above":  # holding: well above the prediction; failing: at the first lift-off
        hold = {ln: f + 3.0 for ln, f in at.items()}
        fail = {ln: 50.0 for ln in lines}
    else:
        hold = dict(at)
        fail = {ln: f + 5.0 if f < 64 else f - 6.0 for ln, f in at.items()}
    first = lines[0]
    base = "onset where predicted on every line"
    return [
        Case(base, _ctx(scene, onset_table(axis, hold), preds), "agrees"),
        Case("onset elsewhere on every line", _ctx(scene, onset_table(axis, fail), preds),
             "disagrees", perturbs=base),
        Case("one line elsewhere", _ctx(scene, onset_table(axis, hold | {first: fail[first]}),
                                        preds), "partly", perturbs=base),
        Case("one line without onset", _ctx(scene, onset_table(axis, hold | {first: math.nan}),
                                            preds), "partly", perturbs=base),
        Case("one listed line missing", _ctx(scene, onset_table(
            axis, {k: v for k, v in hold.items() if k != first}), preds), "not measured",
            perturbs=base),
        Case("no table", _ctx(scene, None, preds), "not measured", perturbs=base),
        # the theory moved by 6 Hz (a wrong prediction): every line leaves the band
        Case("prediction shifted by 6 Hz", _ctx(scene, onset_table(axis, hold), preds),
             "disagrees", perturbs=base, options={"shift": 6.0 if side == "above" else -6.0}),
    ]


def horizontal_cases() -> list[Case]:
    """O1's rule: the onset at f(Γ = 1) ± step on every (α, R) line."""
    return _cases("onset_map", "liftoff")


def sine_floor_cases() -> list[Case]:
    """O1s's rule: the onset at or above f_c(α) − step on every (α, depth) line."""
    return _cases("onset_sine", "chatter", side="above")


def vertical_cases() -> list[Case]:
    """O2's rule: the onset at f_c(α) ± step on every (α, R) line."""
    return _cases("onset_map", "chatter")


def vertical_sine_cases() -> list[Case]:
    """O2s's rule: the onset at f_c(α) ± step on every (α, depth) line."""
    return _cases("onset_sine", "chatter")
