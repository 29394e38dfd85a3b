"""Why D differs between two frequencies: the random walk or the memory.

The Taylor–Green–Kubo expansion (:mod:`bbb.analysis.greenkubo`) writes D_∞ = D_0 · (D_∞/D_0): the random
walk of uncorrelated jumps times the memory factor.  Between frequencies a and b the log
contrast splits exactly:

    ln D_∞(a)/D_∞(b)  =  ln D_0(a)/D_0(b)  +  ln [(D_∞/D_0)(a) / (D_∞/D_0)(b)]
         total        =        walk         +              memory

and the memory share s = memory / total says which part makes the contrast (s = 1: all memory,
s = 0: all random walk; s > 1 or s < 0 when the other part works against it).

CIs (:func:`contrast`): percentiles over paired bootstrap replicates.  Replicate r of one
frequency resamples its particles once and gives both its D_0 and its D_∞
(``GreenKubo.D0_boot``, ``GreenKubo.D_inf_boot``: the same resample), so the two parts of a
frequency are paired; the frequencies are resampled independently (their own seeds), and their
replicates r are combined.

Which part carries an extremum at a, against its neighbour b (:func:`carrier`; ``kind`` "max"
wants total > 0, "min" total < 0):

=============  ===============================================================================
not measured   a D_0 or D_∞ replicate of a or b is ≤ 0: nothing diffuses, no logarithm
wrong sign     the CI of total lies wholly on the other side of 0: no extremum of that kind
not resolved   the CI of total contains 0: the contrast itself is not resolved
memory         the CI of s lies at or above θ: the memory holds at least θ of the contrast
random walk    the CI of s lies at or below 1 − θ: the random walk holds at least θ
both           the CI of s lies within [1 − θ, θ]: neither part holds θ
undecided      the CI of s reaches across 1 − θ or θ
=============  ===============================================================================

θ and the CI level are arguments; :func:`calibrated_rule` reads the calibrated ones from
:data:`RULE_FILE`, written with the measured error rates by
``benchmarks/calibrations/contrast_calibration.py`` (AR(1) sequences with a known split).
Against both neighbours, :func:`combine_sides` gives one verdict.
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import numpy as np

from .greenkubo import GreenKubo

__all__ = ["CARRIERS", "RULE_FILE", "SPLITS", "Contrast", "calibrated_rule", "carrier",
           "combine_sides", "contrast"]

#: the calibrated rule: θ, the CI level and the rates measured on synthetic sequences
RULE_FILE = Path(__file__).resolve().parent / "gk_contrast_rule.json"

#: the verdicts that name a carrier (the split of a resolved contrast)
SPLITS = ("memory", "random walk", "both", "undecided")
#: every verdict of :func:`carrier`
CARRIERS = ("not measured", "wrong sign", "not resolved") + SPLITS


@dataclass(frozen=True)
class Contrast:
    """ln D_∞(a)/D_∞(b) and its two parts, each as (value, lo, hi) at level ``ci``.

    total  -- ln D_∞(a)/D_∞(b);  walk -- ln D_0(a)/D_0(b);  memory -- total − walk
    share  -- memory / total, the memory share of the log contrast (dimensionless)
    All NaN when a D_0 or D_∞ (estimate or replicate) of a or b is ≤ 0.
    """

    total: tuple[float, float, float]
    walk: tuple[float, float, float]
    memory: tuple[float, float, float]
    share: tuple[float, float, float]
    ci: float

    @property
    def measured(self) -> bool:
        return not math.isnan(self.total[0])


_NAN3 = (math.nan, math.nan, math.nan)


@cache
def calibrated_rule() -> dict:
    """The calibration's output (:data:`RULE_FILE`): "theta", "ci", "worst_wrong" (the largest
    wrong-verdict rate over the synthetic cases at that level), "right_rate", "source", ..."""
    return json.loads(RULE_FILE.read_text(encoding="utf-8"))


def contrast(a: GreenKubo, b: GreenKubo, ci: float = 0.95) -> Contrast:
    """The split of ln D_∞(a)/D_∞(b) with paired bootstrap CIs (module docstring)."""
    if not 0.0 < ci < 1.0:
        raise ValueError(f"ci = {ci!r} must be in (0, 1)")
    ra, rb = (np.column_stack([g.D0_boot, g.D_inf_boot]) for g in (a, b))
    if ra.shape != rb.shape or ra.shape[0] < 2:
        raise ValueError(f"the two expansions need the same number (≥ 2) of bootstrap "
                         f"replicates; got {ra.shape[0]} and {rb.shape[0]}")
    point = np.array([[a.D_n[0], a.D_inf], [b.D_n[0], b.D_inf]])
    if not (np.all(point > 0) and np.all(ra > 0) and np.all(rb > 0)):
        return Contrast(_NAN3, _NAN3, _NAN3, _NAN3, ci)
    q = (1.0 - ci) / 2.0

    def parts(d0a, dia, d0b, dib):
        total = np.log(dia / dib)
        walk = np.log(d0a / d0b)
        return total, walk, total - walk

    est = parts(*point[0], *point[1])
    reps = parts(ra[:, 0], ra[:, 1], rb[:, 0], rb[:, 1])
    out = []
    for e, r in zip((*est, est[2] / est[0]), (*reps, reps[2] / reps[0]), strict=True):
        lo, hi = np.quantile(r, [q, 1.0 - q])
        out.append((float(e), float(lo), float(hi)))
    return Contrast(*out, ci=ci)


def carrier(c: Contrast, kind: str, theta: float) -> str:
    """Which part carries the extremum of ``kind`` ("max" | "min") at a against b (table in
    the module docstring); ``theta`` in (0.5, 1)."""
    if kind not in ("max", "min"):
        raise ValueError(f"kind = {kind!r}; allowed: 'max', 'min'")
    if not 0.5 < theta < 1.0:
        raise ValueError(f"theta = {theta!r} must be in (0.5, 1)")
    if not c.measured:
        return "not measured"
    sign = 1.0 if kind == "max" else -1.0
    lo, hi = sorted((sign * c.total[1], sign * c.total[2]))
    if hi < 0.0:
        return "wrong sign"
    if lo <= 0.0:
        return "not resolved"
    _, s_lo, s_hi = c.share
    if s_lo >= theta:
        return "memory"
    if s_hi <= 1.0 - theta:
        return "random walk"
    if 1.0 - theta <= s_lo and s_hi <= theta:
        return "both"
    return "undecided"


def combine_sides(verdicts: Sequence[str]) -> str:
    """One verdict for an extremum from its sides' :func:`carrier` verdicts.

    Any side "wrong sign" -> "no extremum".  Otherwise, over the sides with a split
    (:data:`SPLITS`): none -> "not measured" if every side is, else "not resolved"; one
    verdict shared by all -> it; any "undecided" -> "undecided"; else (different carriers on
    the two sides, or "both" on one) -> "both".
    """
    bad = [v for v in verdicts if v not in CARRIERS]
    if bad:
        raise ValueError(f"unknown side verdict(s) {bad}; allowed: {', '.join(CARRIERS)}")
    if "wrong sign" in verdicts:
        return "no extremum"
    split = [v for v in verdicts if v in SPLITS]
    if not split:
        return "not measured" if all(v == "not measured" for v in verdicts) else "not resolved"
    if len(set(split)) == 1:
        return split[0]
    return "undecided" if "undecided" in split else "both"
