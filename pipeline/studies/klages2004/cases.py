"""Synthetic inputs with known answers for the paper's claims 1–19, and each claim's cases
(:class:`~pipeline.claims.claim.Case`: the verdict its frozen rule must give, and a
perturbation that must flip it), named by the claim records of :mod:`.claims`.

The inputs: a Fig. 2 D(f) curve with the paper's landmarks (onset at 50 Hz, maxima at 54,
60 and 80 Hz, minima at 58 and 62 Hz, a tenfold rise from 66 Hz), a locking table whose
k_max reaches n = 2, 3, 4, 5 at 66, 76, 86, 96 Hz, an ergodicity table of two families, the
Mátyás–Klages curve with its locking table, a fine-scale window, and a store of
post-collision states on (or off) the spiral of Eqs. (8)–(9).  f in Hz, D in mm²/s, v in
mm/s, k dimensionless.
"""

from __future__ import annotations

import functools
import tempfile
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd

from bbb.analysis.approx import spiral
from bbb.record import COLLISION_FIELDS

from ...claims.claim import Case
from ...store.layout import STOP_LEGEND, TARGET, ZERO
from .measures import MAIN, context

__all__ = ["F", "K_SCALE", "figure2", "locking", "ergodicity", "matyas", "finescale",
           "spiral_store", "CASES"]

#: the Fig. 2 grid: 0.4 Hz from 46 Hz (below the onset) to 99.2 Hz
F = np.round(46.0 + 0.4 * np.arange(134), 1)
#: the paper's landmarks as knots of a piecewise-linear D(f) (Hz, mm²/s); D = 0 below 50 Hz
KNOTS = ((50.0, 100.0), (54.0, 250.0), (58.0, 80.0), (60.0, 300.0), (62.0, 150.0),
         (66.0, 350.0), (72.0, 1500.0), (80.0, 3000.0), (84.0, 2400.0), (90.0, 2600.0),
         (99.2, 2800.0))
#: the factor of a perturbed locking table (every k and v_peak): 1.5 times the paper's
K_SCALE = 1.5


def _table(f, D, rel: float) -> pd.DataFrame:
    """A D(f) table: D with a ± rel CI, a still ensemble (D = 0) resolved to ±d_resolved."""
    D = np.asarray(D, float)
    zero = D <= 0
    D = np.where(zero, 1e-7, D)
    return pd.DataFrame({"f": f, "D": D, "D_lo": np.where(zero, 0.0, D * (1 - rel)),
                         "D_hi": np.where(zero, 2e-7, D * (1 + rel)),
                         "stop": np.where(zero, STOP_LEGEND[ZERO], STOP_LEGEND[TARGET])})


def figure2(shift: float = 0.0, flat_from: float | None = None, rel: float = 0.01) -> pd.DataFrame:
    """Fig. 2's D(f) on :data:`F` with every landmark ``shift`` Hz later; with ``flat_from``,
    D constant from that frequency on (no growth)."""
    kf, kd = (np.array(x) for x in zip(*KNOTS, strict=True))
    D = np.where(F < 50.0 + shift, 0.0, np.interp(F, kf + shift, kd))
    if flat_from is not None:
        D = np.where(F >= flat_from, np.interp(flat_from, kf + shift, kd), D)
    return _table(F, D, rel)


def locking(scale: float = 1.0) -> pd.DataFrame:
    """A locking table (family rest): k_max = (f − 46)/10 (1.4 at 60, 2.6 at 72, 3.4 at 80,
    4.4 at 90 Hz; reaching n = 2..5 at 66, 76, 86, 96 Hz), k_peak = f/54 (1 at 54 Hz),
    v_peak = 70 f/60 mm/s (70 at 60 Hz), each ± 0.02 (k) or ± 2 mm/s; all times ``scale``."""
    k = scale * (F - 46.0) / 10.0
    kp = scale * F / 54.0
    vp = scale * 70.0 * F / 60.0
    return pd.DataFrame({"f": F, "family": MAIN, "k_max": k, "k_max_lo": k - 0.02,
                         "k_max_hi": k + 0.02, "v_max": k * 9800.0 / (2 * F), "k_peak": kp,
                         "k_peak_lo": kp - 0.02, "k_peak_hi": kp + 0.02, "v_peak": vp,
                         "v_peak_lo": vp - 2.0, "v_peak_hi": vp + 2.0, "frac_creep": 0.1})


def ergodicity(apart=(55.0,), eb_fail=()) -> pd.DataFrame:
    """Two families (rest, launched) at 50–70 Hz, 1 Hz apart: their D's CIs apart at the
    frequencies ``apart`` and overlapping elsewhere; the EB rule failing at ``eb_fail``."""
    f = np.arange(50.0, 70.5, 1.0)
    D = 100.0 + 20.0 * (f - 50.0)
    other = np.where(np.isin(f, apart), 1.5 * D, 1.01 * D)
    rows = {"f": f}
    for fam, d in (("rest", D), ("launched", other)):
        rows |= {f"D_{fam}": d, f"D_{fam}_lo": 0.97 * d, f"D_{fam}_hi": 1.03 * d}
    ok = ~np.isin(f, eb_fail)
    return pd.DataFrame({**rows, "eb_ok": ok, "ergodic": ok & ~np.isin(f, apart)})


def matyas(k_offset: float = 0.0) -> dict[str, pd.DataFrame]:
    """Mátyás & Klages' curve: three maxima (52, 64, 76 Hz) on a rising D, at k_peak = 1, 2, 3
    (+ ``k_offset``) ± 0.02; the tables the claim reads."""
    f = np.round(np.arange(40.0, 90.01, 0.5), 1)
    peaks = ((52.0, 1.0), (64.0, 2.0), (76.0, 3.0))
    D = 200.0 + 5.0 * (f - 40.0) + sum(400.0 * np.exp(-0.5 * ((f - p) / 1.0) ** 2)
                                        for p, _ in peaks)
    k = np.interp(f, [p for p, _ in peaks], [n for _, n in peaks]) + k_offset
    lock = pd.DataFrame({"f": f, "family": MAIN, "k_peak": k, "k_peak_lo": k - 0.02,
                         "k_peak_hi": k + 0.02, "k_max": k + 0.3})
    return {"figure2_matyas2004": _table(f, D, 0.01), "locking_matyas2004": lock}


def finescale(amplitude: float = 100.0) -> pd.DataFrame:
    """The refined window 58–64 Hz at 0.05 Hz: D = 1000 + amplitude sin(2π (f − 58)/0.2), ±
    0.5 %: zero on the 0.4 Hz grid (smooth there), an extremum every 0.1 Hz at 0.05 Hz."""
    f = np.round(58.0 + 0.05 * np.arange(121), 2)
    return _table(f, 1000.0 + amplitude * np.sin(2 * np.pi * (f - 58.0) / 0.2), 0.005)


_SPIRAL_SCENE = """\
[study]
name = "spiral_cases"
seed = 1

[params]
preset = "klages2004"

[frequencies]
values = [66.0, 72.0, 78.0]

[families.rest]
initial = "rest"

[accuracy]
preset = "draft"
n_particles = {n}
chunk_size = {n}
t_max = 10.0

[observables.collisions]
record = 2
"""


#: the folder of the case stores: one per process, removed at its exit
_KEEP: list[tempfile.TemporaryDirectory] = []


def _stores_dir() -> Path:
    if not _KEEP:
        _KEEP.append(tempfile.TemporaryDirectory(prefix="bbb-claim-cases-"))
    return Path(_KEEP[0].name)


@functools.cache
def spiral_store(on_curve: bool, n: int = 256) -> str:
    """A real store (written by the store's own write_chunk) of post-collision states at 66,
    72, 78 Hz, family rest: each particle creeps at the floor (state 1, v = 0) and lands after
    a flight t_c ∈ [0.03, 0.12] s (state 2) on the spiral of Eqs. (8)–(9) at that t_c
    (``on_curve``), or at a point drawn uniformly over the same box; the creeping state sits
    where the flight from it lands exactly there (the flights are consistent).  Its path."""
    from pipeline.store.study_store import StudyStore
    from pipeline.workflow.load import parse_workflow
    from pipeline.workflow.observables.contract import Chunk
    from pipeline.workflow.observables.counters import COUNTERS
    from pipeline.workflow.observables.registry import selected

    study = parse_workflow(_SPIRAL_SCENE.format(n=n), source="spiral_cases.toml")
    path = _stores_dir() / f"spiral_{'on' if on_curve else 'off'}.zarr"
    store = StudyStore.create_or_open(path, study)
    rng = np.random.default_rng(15)
    ix = {name: COLLISION_FIELDS.index(name) for name in ("t", "y", "vy")}
    for fi, f in enumerate(study.frequencies):
        p = study.params(f)
        tc = rng.uniform(0.03, 0.12, n)
        y1, v1 = spiral(p.A, f, p.g, p.alpha, tc)
        if not on_curve:
            y1, v1 = rng.uniform(y1.min(), y1.max(), n), rng.uniform(v1.min(), v1.max(), n)
        rec = np.zeros((n, 2, len(COLLISION_FIELDS)))
        t0 = rng.uniform(1.0, 5.0, n)
        rec[:, 0, ix["t"]], rec[:, 1, ix["t"]] = t0, t0 + tc
        rec[:, 0, ix["y"]] = y1 + 0.5 * p.g * tc ** 2  # from v = 0, the flight lands at y1
        rec[:, 1, ix["y"]], rec[:, 1, ix["vy"]] = y1, v1
        run = SimpleNamespace(positions=None, collisions_dense=rec,
                              n_recorded=np.full(n, 2, np.int64),
                              counters={c: np.zeros(n, np.int64) for c in COUNTERS})
        chunk = Chunk(study=study, point=study.points[fi], family=study.families[0], index=0,
                      run=run)
        values = {name: v for o in selected(study) for name, v in o.compute(chunk).items()}
        store.write_chunk(fi, 0, 0, values, seconds=0.0)
    return store.path


# -- the cases, one list per claim ------------------------------------------------------------
def _fig2(**kw) -> dict:
    return context({"figure2": figure2(**kw)})


def _lock(scale: float = 1.0) -> dict:
    return context({"locking": locking(scale)})


def _pair(name: str, good: dict, bad: dict, bad_verdict: str = "disagrees",
          good_verdict: str = "agrees") -> list[Case]:
    return [Case(f"the paper's {name}", good, good_verdict),
            Case(f"{name} perturbed", bad, bad_verdict, perturbs=f"the paper's {name}")]


def _shifted(name: str) -> list[Case]:
    """A Fig. 2 landmark: the curve as the paper draws it, and every landmark 10 Hz later."""
    return _pair(name, _fig2(), _fig2(shift=10.0))


def _k(name: str) -> list[Case]:
    """A locking-table value: the paper's k (or v), and 1.5 times it."""
    return _pair(name, _lock(), _lock(K_SCALE))


def _spiral() -> list[Case]:
    def ctx(on):
        return {**context({}), "stores": {"figure3": spiral_store(on)}}
    return [Case("states on the spiral", ctx(True), "agrees"),
            Case("states scattered over the same box", ctx(False), "disagrees",
                 perturbs="states on the spiral"),
            Case("no store", context({}), "not measured", perturbs="states on the spiral")]


def _ergo(claim: int) -> list[Case]:
    if claim == 16:
        return [Case("families apart at 55 Hz only", context({"ergodicity": ergodicity()}),
                     "agrees"),
                Case("families apart at 55 and 70 Hz",
                     context({"ergodicity": ergodicity(apart=(55.0, 70.0))}), "partly",
                     perturbs="families apart at 55 Hz only"),
                Case("families together everywhere",
                     context({"ergodicity": ergodicity(apart=())}), "disagrees",
                     perturbs="families apart at 55 Hz only")]
    return [Case("families together and EB converging from 58 Hz",
                 context({"ergodicity": ergodicity()}), "agrees"),
            Case("EB failing at 64 Hz", context({"ergodicity": ergodicity(eb_fail=(64.0,))}),
                 "partly", perturbs="families together and EB converging from 58 Hz"),
            Case("families apart at 70 Hz",
                 context({"ergodicity": ergodicity(apart=(55.0, 70.0))}), "disagrees",
                 perturbs="families together and EB converging from 58 Hz")]


#: {claim id: its cases provider}
CASES = {
    "1": lambda: _shifted("onset"),
    "2": lambda: _shifted("maximum near 54 Hz"),
    "3": lambda: _k("k_peak at 54 Hz"),
    "4": lambda: _shifted("minimum near 58 Hz"),
    "5": lambda: _shifted("maximum at 60 Hz"),
    "6": lambda: _k("v_peak at 60 Hz"),
    "7": lambda: _shifted("minimum near 62 Hz"),
    "8": lambda: _k("loops"),
    "9": lambda: _pair("growth from 66 Hz", _fig2(), _fig2(flat_from=66.0)),
    "10": lambda: _shifted("washed-out maximum near 80 Hz"),
    "11": lambda: _k("k_max at 60 Hz"),
    "12": lambda: _k("k_max at 72 Hz"),
    "13": lambda: _k("k_max at 80 Hz"),
    "14": lambda: _k("k_max at 90 Hz"),
    "15": _spiral,
    "16": lambda: _ergo(16),
    "17": lambda: _ergo(17),
    "18": lambda: _pair("integer lockings", context(matyas()), context(matyas(0.5))),
    "19": lambda: _pair("fine-scale extrema", context({"finescale": finescale()}),
                        context({"finescale": finescale(0.0)})),
}
