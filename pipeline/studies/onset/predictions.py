"""The two onset predictions, computed once from the theory (:mod:`bbb.analysis.onset_theory`)
before any map that tests them ran, and the vertical motion a particle started at rest
reaches on the flat floor (measured with the kernel), written to ``predictions.json`` beside
this module; the claims read their numbers from there::

    python -m pipeline.studies.onset.predictions --write     # remake predictions.json

(a) horizontal: at the arcs' cusp (a wedge) every vertical motion with a flight is
    horizontally unstable, so the prediction is the first lift-off, f(Γ = 1); at the sine's
    valley the chattering cycle's horizontal multiplier λ over [f(Γ = 1), f_c) and the 1/1
    orbit's flip frequency are recorded.
(b) vertical: f_c(α), where the chattering cycle from rest stops ending within its period.

Units: Hz, mm.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

from bbb import Params, simulate
from bbb.analysis.liftoff_onset import liftoff_frequency
from bbb.analysis.onset_theory import (
    chatter_cycle,
    chatter_lambda,
    chatter_limit,
    period1,
    sine_curvature,
)

__all__ = ["PATH", "ALPHAS", "DEPTHS", "load", "compute", "reached", "main"]

PATH = Path(__file__).resolve().parent / "predictions.json"
#: the restitutions and sine depths (mm) of the study's scenes (their [grid] lines)
ALPHAS = (0.5, 0.7, 0.9)
DEPTHS = (0.1, 0.3, 0.6)
#: Hz: the bisection's tolerance on f_c, far below the scenes' grid step
TOL = 0.01
#: Hz: the λ scan's step over [f(Γ = 1), f_c)
SCAN = 0.25


def load() -> dict:
    """The committed predictions (predictions.json)."""
    return json.loads(PATH.read_text(encoding="utf-8"))


def flip_frequency(alpha: float, beta: float, kappa: float, g: float) -> float:
    """The f (Hz) below which the 1/1 bounce at a smooth minimum of curvature κ (1/mm) is
    horizontally unstable (flip): (α + β) κ g / ((1 + α) f²) = 2 (1 + β)."""
    return math.sqrt((alpha + beta) * kappa * g / (2.0 * (1.0 + alpha) * (1.0 + beta)))


def compute(alphas=ALPHAS, depths=DEPTHS, tol: float = TOL) -> dict:
    """Every number the claims read: f(Γ = 1), f_c(α), and at each sine depth the chattering
    cycle's largest |λ| below f_c and the 1/1 orbit's flip frequency."""
    p = Params.preset("klages2004", f=50.0)
    f1 = liftoff_frequency(p)
    out = {"preset": "klages2004", "A": p.A, "g": p.g, "S": p.S, "beta": p.beta,
           "v_stick": 1e-3, "f_liftoff": f1, "tol_Hz": tol, "alpha": {}}
    for a in alphas:
        fc = chatter_limit(a, A=p.A, g=p.g, tol=tol)
        sine = {}
        for dep in depths:
            k = sine_curvature(dep, p.S)
            lams = []
            for f in np.arange(math.ceil(f1 / SCAN) * SCAN, fc, SCAN):
                gam = p.A * (2 * math.pi * f) ** 2 / p.g
                lams.append(abs(chatter_lambda(k, chatter_cycle(gam, f, a, p.g), a, p.beta)))
            sine[f"{dep:g}"] = {"kappa": k, "max_abs_lambda": max(lams) if lams else math.nan,
                                "flip_f": flip_frequency(a, p.beta, k, p.g),
                                "U_tau_1_1_at_fc": float(np.prod(period1(fc, a, p.g)))}
        out["alpha"][f"{a:g}"] = {"f_c": fc, "sine": sine}
    return out


def reached(alphas=ALPHAS, freqs=tuple(range(50, 71)), n: int = 4) -> dict:
    """The vertical motion a particle started at rest reaches on the flat floor (the kernel):
    per α and f (Hz), sticks and collisions per period over 2–4 s (the first 2 s a
    transient): 1 stick per period is the chattering cycle."""
    out = {}
    for a in alphas:
        rows = {}
        for f in freqs:
            p = Params.preset("klages2004", f=float(f), alpha=a, R=math.inf)
            r1, r2 = simulate(p, n, 2.0, 1, "rest"), simulate(p, n, 4.0, 1, "rest")
            per = 2.0 * f
            rows[f"{f:g}"] = {
                "sticks": float(np.mean(r2.counters["sticks"] - r1.counters["sticks"]) / per),
                "collisions": float(np.mean(r2.counters["collisions"]
                                            - r1.counters["collisions"]) / per)}
        out[f"{a:g}"] = rows
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m pipeline.studies.onset.predictions",
                                 description=__doc__.split("\n")[0])
    ap.add_argument("--write", action="store_true", help="write predictions.json")
    a = ap.parse_args(argv)
    data = compute()
    data["reached_flat"] = reached()
    data["maker"] = {"script": "pipeline/studies/onset/predictions.py",
                     "reached": "4 particles, seed 1, 2 s and 4 s from rest"}
    text = json.dumps(data, indent=1) + "\n"
    if a.write:
        PATH.write_text(text, encoding="utf-8")
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
