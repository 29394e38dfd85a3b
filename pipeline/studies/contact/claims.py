"""The paper's claims 1–4 and 16 judged under each contact model, and where D(f) depends on
the model beyond its CIs.

Per model the klages2004 claim records and rules are reused unchanged (not re-tuned): the
model's line of the near-onset map ``contact`` (contact × μ, one grid line per model) plays
both the Fig. 2 scene (its ``rest`` family is the main curve) and the ergodicity scene
(families rest and launched); its line of the 54 Hz projection map ``contact_proj`` gives the
locking table of claim 3.  :func:`line_tables` slices the maps' long tables into one table
per model, keyed as ``contact_<model>_<table>`` and ``contact_proj_<model>_<table>``.

Model dependence (:func:`model_differences`), a rule fixed before any contact scene ran and
calibrated on synthetic tables (tests/pipeline/studies/contact/test_claims.py): at a frequency
and family, two models differ when z = |D_a − D_b| / √(s_a² + s_b²) exceeds the Bonferroni
critical value Φ⁻¹(1 − 0.05 / (2m)) over all m comparisons made, where s = (D_hi − D_lo) /
(2 · 1.96) is the standard error read off the 95 % bootstrap CI.  Its false-alarm rate on
synthetic tables of equal models (4 models × 27 f × 2 families, normal errors, CIs ± 15 %; the
intended rate is FWER) and its power on a 60 % difference at 3 frequencies are measured by
that test module, which bounds them (false alarms within three binomial SDs of FWER over 400
tables, power ≥ 90 % over 200).  Real bootstrap CIs of a D near 0 are skewed; the rule reads
them as symmetric.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from itertools import combinations
from statistics import NormalDist

import pandas as pd

from bbb.params import Params

from ...claims.claim import POSITIVE, Row, evaluate
from ..map_lines import split_lines
from ..registry import claim, study

__all__ = ["MODELS", "LABELS", "LINES", "SCENES", "CLAIM_IDS", "CLAIMS", "FWER",
           "Difference", "line_tables", "model_tables", "model_rows", "model_differences",
           "WORDS", "LEAD", "verdicts", "paragraph"]

#: contact models of the study, in order: scene suffix -> label
LABELS = {"stick": "stick", "slide": "slide", "coulomb005": "Coulomb μ = 0.05",
          "coulomb03": "Coulomb μ = 0.3"}
MODELS = tuple(LABELS)
#: each model's grid values in the maps
LINES = {"stick": {"contact": "stick", "mu": 0.0}, "slide": {"contact": "slide", "mu": 0.0},
         "coulomb005": {"contact": "coulomb", "mu": 0.05},
         "coulomb03": {"contact": "coulomb", "mu": 0.3}}
#: the map scenes: near onset (46–99 Hz) and the 54 Hz projection, each contact × μ
SCENES = ("contact", "contact_proj")
ONSET_RANGE = (46.0, 62.0)  # Hz: the onset claims' range; above it, Fig. 2's (from rest)
FAMILIES = ("rest", "launched")
PROJ_F = 54.0  # Hz, the projection scenes' frequency
#: the paper's claims judged per model: records 1–4 and 16 of the claims registry
CLAIM_IDS = ("1", "2", "3", "4", "16")
CLAIMS = [claim("klages2004", i) for i in CLAIM_IDS]
#: their short names in the generated paragraph
SHORT = ("the onset near 50 Hz", "the maximum near 54 Hz", "the 1/1 spot at 54 Hz",
         "the minimum near 58 Hz", "non-ergodicity only near 55 Hz")
FWER = 0.05  # family-wise error rate of the model-dependence rule
_Z95 = NormalDist().inv_cdf(0.975)


def line_tables(tables: Mapping[str, pd.DataFrame]) -> dict[str, pd.DataFrame]:
    """The maps' tables (``contact_diffusion``, ``contact`` (the contact table),
    ``contact_proj_locking``, ...) as one table per model, keyed ``contact_<model>_<table>``
    and ``contact_proj_<model>_<table>``: that model's rows without the axis columns, exactly
    what the scene with its contact and μ in [params] gives."""
    return {**split_lines(tables, "contact", {f"contact_{m}": LINES[m] for m in MODELS},
                          ("diffusion", "contact", "counters")),
            **split_lines(tables, "contact_proj", {f"contact_proj_{m}": LINES[m] for m in MODELS},
                          ("locking", "contact", "counters"))}


def model_tables(tables: Mapping[str, pd.DataFrame], model: str) -> dict[str, pd.DataFrame]:
    """The klages2004 claim context of one model: figure2 (rest only, as D), ergodicity (the
    near-onset diffusion table) and locking (of the projection scene), those present."""
    out: dict[str, pd.DataFrame] = {}
    onset = tables.get(f"contact_{model}_diffusion")
    if onset is not None and "D_rest" in onset:
        rest = onset.copy()
        rest["D"], rest["D_lo"], rest["D_hi"] = rest["D_rest"], rest["D_rest_lo"], rest["D_rest_hi"]
        keep = [c for c in rest.columns if not (c.startswith("D_") and c[2:].split("_")[0]
                                                 in FAMILIES)]
        out["figure2"] = rest[keep]
        out["ergodicity"] = onset
    lock = tables.get(f"contact_proj_{model}_locking")
    if lock is not None:
        out["locking"] = lock
    return out


def model_rows(tables: Mapping[str, pd.DataFrame]) -> dict[str, list[Row]]:
    """{model: the claim rows of CLAIMS judged on that model's tables} (the per-model tables of
    :func:`line_tables`), in the paper's context (its study's, from the registry)."""
    p = Params.preset("klages2004", f=60.0)
    f_gamma1 = math.sqrt(p.g / p.A) / (2 * math.pi)
    paper = study("klages2004")
    return {m: evaluate(CLAIMS, {**paper.context(model_tables(tables, m), {}),
                                 "f_gamma1": f_gamma1, "params": p.as_dict()})
            for m in MODELS}


@dataclass(frozen=True)
class Difference:
    """Models a and b differ at frequency f (Hz) for family ``family``: D (mm²/s) and z."""

    f: float
    family: str
    a: str
    b: str
    D_a: float
    D_b: float
    z: float


def _z(da: float, la: float, ha: float, db: float, lb: float, hb: float) -> float:
    sa, sb = (ha - la) / (2 * _Z95), (hb - lb) / (2 * _Z95)
    s = math.hypot(sa, sb)
    if s > 0:
        return abs(da - db) / s
    return math.inf if abs(da - db) > 1e-6 else 0.0  # two still ensembles: D = 0 ± 0


def model_differences(curves: Mapping[str, pd.DataFrame], families: Sequence[str] = ("rest",),
                      fwer: float = FWER) -> tuple[list[Difference], int]:
    """Where D(f) depends on the model (rule in the module docstring).

    curves -- {model: diffusion table with f, D_<fam>, D_<fam>_lo, D_<fam>_hi (or D, D_lo, D_hi
              for a family named "")}.  Returns (the differences found, m comparisons made).
    """
    rows = []
    for fam in families:
        c = (f"D_{fam}", f"D_{fam}_lo", f"D_{fam}_hi") if fam else ("D", "D_lo", "D_hi")
        by_f: dict[float, dict[str, tuple[float, float, float]]] = {}
        for m, t in curves.items():
            if t is None or c[0] not in t:
                continue
            for _, r in t.iterrows():
                v = tuple(float(r[x]) for x in c)
                if all(math.isfinite(x) for x in v):
                    by_f.setdefault(round(float(r["f"]), 3), {})[m] = v
        for f, ms in sorted(by_f.items()):
            for a, b in combinations(sorted(ms, key=list(curves).index), 2):
                rows.append((f, fam, a, b, ms[a], ms[b], _z(*ms[a], *ms[b])))
    m = len(rows)
    if m == 0:
        return [], 0
    zc = NormalDist().inv_cdf(1 - fwer / (2 * m))
    return [Difference(f, fam, a, b, va[0], vb[0], z) for f, fam, a, b, va, vb, z in rows
            if z > zc], m


def _freqs(fs: Sequence[float], grid: Sequence[float]) -> str:
    """Frequencies as runs of consecutive points of ``grid`` (Hz): 'a–b' for a run."""
    index = {round(f, 3): i for i, f in enumerate(sorted(set(grid)))}
    runs: list[list[float]] = []
    for f in sorted(set(fs)):
        if runs and index[round(f, 3)] == index[round(runs[-1][-1], 3)] + 1:
            runs[-1].append(f)
        else:
            runs.append([f])
    return ", ".join(f"{r[0]:g}" if len(r) == 1 else f"{r[0]:g}–{r[-1]:g}" for r in runs)


def _differences_text(diffs: list[Difference], m: int, what: str,
                      grid: Sequence[float]) -> str:
    if m == 0:
        return f"{what}: not measured."
    if not diffs:
        return (f"{what}: D(f) does not depend on the contact model beyond its CIs at any of "
                f"the {m} comparisons (family-wise 5 %).")
    parts = []
    for fam in dict.fromkeys(d.family for d in diffs):
        pairs: dict[tuple[str, str], list[float]] = {}
        for d in diffs:
            if d.family == fam:
                pairs.setdefault((d.a, d.b), []).append(d.f)
        parts.append(f"from {fam or 'rest'}: " + "; ".join(
            f"{LABELS[a]} vs {LABELS[b]} at f = {_freqs(fs, grid)} Hz" for (a, b), fs in pairs.items()))
    return (f"{what}: D(f) depends on the contact model beyond its CIs (family-wise 5 % over "
            f"{m} comparisons) " + "; ".join(parts) + ".")


def _fractions_text(tables: Mapping[str, pd.DataFrame]) -> str:
    out = []
    for m in MODELS:
        t = tables.get(f"contact_{m}_contact")
        if t is None:
            continue
        r = t[(t["family"] == "rest") & ((t["f"] - PROJ_F).abs() < 1e-6)]
        if len(r):
            r = r.iloc[0]
            out.append(f"{LABELS[m]} held {100 * r.held_frac:.1f} % "
                       f"[{100 * r.held_frac_lo:.1f}, {100 * r.held_frac_hi:.1f}], sliding "
                       f"{100 * r.slide_frac:.1f} % [{100 * r.slide_frac_lo:.1f}, "
                       f"{100 * r.slide_frac_hi:.1f}]")
    return (f"Time in contact at {PROJ_F:g} Hz from rest (share of the run, 95 % CI): "
            + "; ".join(out) + ".") if out else ""


def _measured(text: str) -> str:
    """A klages2004 row's measured text in this study's terms: the scene's rest family once,
    not as both 'Fig. 2 scene' and 'ergodicity scene' curves."""
    parts = [p for p in text.split("; ") if not p.startswith("rest (ergodicity scene)")]
    return "; ".join(parts).replace(" (Fig. 2 scene)", "").replace(" (ergodicity scene)", "")


#: the section's own words, and the line before what was measured
WORDS = ("Scenes `pipeline/studies/contact/scenes/` (docs/contact.md), maps with one line per "
         "contact model: D(f) at 46–99 Hz from rest and launched, and post-collision states at "
         "54 Hz from rest, under each contact model; verdicts by the rules of the claims above, "
         "evaluated on each model's tables (the rest family is the main curve).")
LEAD = "Measured (the rest curve is the main one; launched from the same scene):"


def verdicts(tables: Mapping[str, pd.DataFrame]) -> dict[str, list[Row]]:
    """{model label: the rows of CLAIMS judged on its line}, what was measured said in this
    study's terms (:func:`_measured`)."""
    rows = model_rows(line_tables(tables))
    return {LABELS[m]: [replace(r, measured=_measured(r.measured)) for r in rows[m]]
            for m in MODELS}


def paragraph(tables: Mapping[str, pd.DataFrame], verdicts: Mapping[str, list[Row]]
              ) -> list[str]:
    """The paragraph after the verdicts, generated from them and the tables: which models
    reproduce the onset and the maximum, where the verdict depends on the model, where D does
    (:func:`model_differences`), and the time in contact."""
    tables = line_tables(tables)
    rows = {m: verdicts[LABELS[m]] for m in MODELS}
    onset_ok = [m for m in MODELS if rows[m][0].verdict in POSITIVE]
    max_ok = [m for m in MODELS if rows[m][1].verdict in POSITIVE]
    both = [m for m in onset_ok if m in max_ok]

    def names(ms):
        return ", ".join(LABELS[m] for m in ms) if ms else "none"

    para = ("From rest, " + (f"{names(both)} reproduce{'s' if len(both) == 1 else ''} both the "
                             "onset near 50 Hz and the maximum near 54 Hz" if both else
                             "no contact model reproduces both the onset near 50 Hz and the "
                             "maximum near 54 Hz")
            + f" (onset: {names(onset_ok)}; maximum: {names(max_ok)}). ")
    same = [i for i in range(len(CLAIMS)) if len({rows[m][i].verdict for m in MODELS}) == 1]
    para += ("The verdict is the same under every contact model for "
             + (", ".join(SHORT[i] for i in same) or "none") + "; it depends on the model for "
             + (", ".join(SHORT[i] for i in range(len(CLAIMS)) if i not in same) or "none")
             + ". ")
    lo, hi = ONSET_RANGE
    near, high = {}, {}
    for m in MODELS:
        t = tables.get(f"contact_{m}_diffusion")
        if t is not None:
            near[m], high[m] = t[t["f"] <= hi], t[t["f"] > hi]
    d1, m1 = model_differences(near, FAMILIES)
    d2, m2 = model_differences(high, ("rest",))
    grid = [f for t in near.values() for f in t["f"]] + [f for t in high.values() for f in t["f"]]
    para += (_differences_text(d1, m1, f"{lo:g}–{hi:g} Hz (rest, launched)", grid) + " "
             + _differences_text(d2, m2, f"above {hi:g} Hz (rest)", grid))
    frac = _fractions_text(tables)
    return ["", para + (" " + frac if frac else ""), ""]
