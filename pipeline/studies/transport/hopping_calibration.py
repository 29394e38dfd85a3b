"""The hopping rule's calibration on floors with a known answer, written to ``hopping.json``
(read by :mod:`.reversal`): ``python -m pipeline.studies.transport.hopping_calibration``.

On a flat floor (R = ∞) a particle at rest lifts off exactly when the throw number
Γ_v = A ω² sin ψ / (g cos φ) exceeds 1, whatever its restitution and friction; so the rule
"the boundary lies between the last frequency whose airborne share is significantly below H
and the first one significantly above it" (:func:`.reversal.hopping_boundary`) must find
Γ_v = 1 there.  Each candidate H is run on the flat versions of the map's floors (φ = 2°,
every throw of the scene, stick and Coulomb μ = 0.3, the scene's frequencies) and judged as
claim T6 judges the map: the boundary interval minus the f of Γ_v = 1 must lie within ± one
frequency step (``agrees``).  The threshold the rule uses, H = 0.1 (a tenth of the run in
flight: rare hops of a few particles do not make a regime), was chosen before the map was
run and is written here only if it passes on every flat floor; the candidates around it show
how far the check can move (a threshold of one half fails: on a flat floor the share is only
~0.3 one step above Γ_v = 1).
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np

from bbb import Params, simulate

from ...workflow.scenes import load_scene
from .reversal import REVERSAL_MAP, hopping_boundary, judge_boundary, throw_number_frequency

__all__ = ["THRESHOLD", "CANDIDATES", "PARTICLES", "T_MAX", "flat_share", "calibrate", "main"]

THRESHOLD = 0.1
CANDIDATES = (0.01, 0.03, 0.1, 0.3, 0.5)
PARTICLES, T_MAX, SEED = 4, 10.0, 2004
#: frequencies simulated per floor: those of the scene within this distance of Γ_v = 1 (Hz);
#: farther ones are at rest (below) or airborne beyond every candidate (above)
WINDOW = 12.0


def flat_share(tilt: float, throw: float, contact: str, mu: float, f: float
               ) -> tuple[float, float, float]:
    """(share, lo, hi) of the run in flight from rest on the flat floor (R = ∞) at f; the
    particles of a flat floor from rest move alike, so lo = min and hi = max over them."""
    p = Params.preset("klages2004", f=float(f), tilt=tilt, throw=throw, R=math.inf,
                      contact=contact, mu=mu)
    r = simulate(p, PARTICLES, T_MAX, SEED, "rest")
    air = 1.0 - (r.contact_time["held"] + r.contact_time["sliding"]) / T_MAX
    return float(air.mean()), float(air.min()), float(air.max())


def calibrate() -> dict:
    """Every candidate H on every flat floor of the map (module docstring)."""
    study = load_scene(REVERSAL_MAP)
    lines = list(dict.fromkeys(p.grid for p in study.points))
    floors = []
    for line in lines:
        g = dict(line)
        f_v = throw_number_frequency(g["tilt"], g["throw"])
        fs = [f for f in study.line(g).frequencies if abs(f - f_v) <= WINDOW]
        shares = np.array([flat_share(g["tilt"], g["throw"], g["contact"], g["mu"], f)
                           for f in fs])
        row = {**g, "f_v": f_v, "f": fs, "share": shares[:, 0].tolist(), "verdicts": {}}
        for h in CANDIDATES:
            b = hopping_boundary(fs, shares[:, 1], shares[:, 2], h)
            row["verdicts"][f"{h:g}"] = {"boundary": b, "verdict": judge_boundary(b, f_v)[0]}
        floors.append(row)
    passes = {f"{h:g}": all(r["verdicts"][f"{h:g}"]["verdict"] == "agrees" for r in floors)
              for h in CANDIDATES}
    if not passes[f"{THRESHOLD:g}"]:
        raise SystemExit(f"H = {THRESHOLD:g} misses Γ_v = 1 on a flat floor: {floors}")
    return {"source": "pipeline/studies/transport/hopping_calibration.py",
            "threshold": THRESHOLD, "passes": passes, "particles": PARTICLES, "t_max": T_MAX,
            "seed": SEED, "floors": floors}


def main(argv: list[str] | None = None) -> int:
    """Writes hopping.json beside this module, or where ``--json PATH`` says (make calibrate)."""
    args = sys.argv[1:] if argv is None else argv
    if args and (len(args) != 2 or args[0] != "--json"):
        print(f"hopping_calibration: {' '.join(args)}: the only argument is --json PATH", file=sys.stderr)
        return 2
    out = Path(args[1]) if args else Path(__file__).with_name("hopping.json")
    out.write_text(json.dumps(calibrate(), indent=1, ensure_ascii=False) + "\n",
                   encoding="utf-8")
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
