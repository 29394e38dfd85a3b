"""The lift-off rule of claim T6b checked on floors with a known answer, before the map's
counters are judged by it.

    .venv/bin/python -m benchmarks.calibrations.hopping_liftoffs [--write]

Rule (fixed before this script ran and before the map's lift-off counts were read): a
frequency *hops* when its lift-offs per floor period (lift-offs that start a flight from
contact, bbb's counter ``liftoffs``, per particle, divided by f t_max) reach L = 0.5; the
sliding/hopping boundary of a line lies between the last frequency below the first hopping
one and that frequency.  A bouncing particle that never comes to rest on the floor (chatter)
lifts off from no contact and counts none: chatter is not hopping.

Known answer: on a flat floor (R = ∞) a particle at rest lifts off exactly where the throw
number Γ_v = A ω² sin ψ / (g cos φ) exceeds 1, whatever its restitution and friction.  Each
candidate L is run on the flat versions of the transport_reversal map's floors (φ = 2°, every
throw, stick and Coulomb μ = 0.3, the scene's frequencies within 12 Hz of Γ_v = 1, 4
particles from rest, 10 s, seed 2004: as pipeline/studies/transport/hopping_calibration.py)
and judged as T6 judges a boundary: the interval minus the f of Γ_v = 1 within ± one
frequency step.  L is written (``--write``: pipeline/studies/transport/liftoffs.json, which
the claim reads) only if it passes on every flat floor; the result is committed as
benchmarks/results/hopping-liftoffs-<date>.json.
"""

from __future__ import annotations

import argparse
import datetime as dt
import json
import math
import os
import platform
import sys
from pathlib import Path

import numpy as np

from bbb import Params, simulate
from benchmarks.common import ROOT
from pipeline.studies.transport.reversal import (
    REVERSAL_MAP,
    judge_boundary,
    liftoff_boundary,
    throw_number_frequency,
)
from pipeline.workflow.scenes import load_scene

THRESHOLD = 0.5
CANDIDATES = (0.1, 0.25, 0.5, 0.75, 0.9)
PARTICLES, T_MAX, SEED, WINDOW = 4, 10.0, 2004, 12.0


def flat_liftoffs(tilt: float, throw: float, contact: str, mu: float, f: float) -> float:
    """Lift-offs per floor period, mean over the particles, on the flat floor at f (Hz)."""
    p = Params.preset("klages2004", f=float(f), tilt=tilt, throw=throw, R=math.inf,
                      contact=contact, mu=mu)
    r = simulate(p, PARTICLES, T_MAX, SEED, "rest")
    return float(np.mean(r.counters["liftoffs"])) / (f * T_MAX)


def calibrate() -> dict:
    study = load_scene(REVERSAL_MAP)
    floors = []
    for line in dict.fromkeys(p.grid for p in study.points):
        g = dict(line)
        f_v = throw_number_frequency(g["tilt"], g["throw"])
        fs = [f for f in study.line(g).frequencies if abs(f - f_v) <= WINDOW]
        per = [flat_liftoffs(g["tilt"], g["throw"], g["contact"], g["mu"], f) for f in fs]
        row = {**g, "f_v": f_v, "f": fs, "liftoffs_per_period": per, "verdicts": {}}
        for h in CANDIDATES:
            b = liftoff_boundary(fs, per, h)
            row["verdicts"][f"{h:g}"] = {"boundary": b, "verdict": judge_boundary(b, f_v)[0]}
        floors.append(row)
        print(f"{g}: Γ_v = 1 at {f_v:.1f} Hz; per period "
              + ", ".join(f"{f:g}: {x:.2f}" for f, x in zip(fs, per, strict=True)), flush=True)
    passes = {f"{h:g}": all(r["verdicts"][f"{h:g}"]["verdict"] == "agrees" for r in floors)
              for h in CANDIDATES}
    return {"source": "benchmarks/calibrations/hopping_liftoffs.py", "threshold": THRESHOLD,
            "passes": passes, "particles": PARTICLES, "t_max": T_MAX, "seed": SEED,
            "date": dt.date.today().isoformat(), "cpu": platform.processor() or platform.machine(),
            "cpus": os.cpu_count(), "floors": floors}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--write", action="store_true", help="write the package's liftoffs.json")
    ap.add_argument("--json", type=Path, help="write the rule (as liftoffs.json) here, and no results "
                    "file (make calibrate)")
    a = ap.parse_args(argv)
    res = calibrate()
    print("passes on every flat floor:", res["passes"])
    out = ROOT / "benchmarks" / "results" / f"hopping-liftoffs-{res['date']}.json"
    if not a.json:
        out.write_text(json.dumps(res, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
        print(f"wrote {out.relative_to(ROOT)}")
    if not res["passes"][f"{THRESHOLD:g}"]:
        print(f"L = {THRESHOLD:g} misses Γ_v = 1 on a flat floor: not written", file=sys.stderr)
        return 2
    pkg = ROOT / "pipeline" / "studies" / "transport" / "liftoffs.json" if a.write else a.json
    if pkg:
        pkg = Path(pkg)
        pkg.write_text(json.dumps({"source": str(out.relative_to(ROOT)),
                                   "threshold": THRESHOLD, "passes": res["passes"]},
                                  indent=1) + "\n", encoding="utf-8")
        print(f"wrote {pkg}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
