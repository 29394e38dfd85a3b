"""Calibration of the trajectory checker's one measured tolerance: CONTACT_RTOL, how far a
sliding stretch's path (θ, v) may part from the checker's own integration, per period.

    .venv/bin/python -m benchmarks.calibrations.checker_calibration [--random 400] [--write]

Every sliding stretch of these runs goes through tests/bbb/trajectory_check.py, which reports
the least CONTACT_RTOL at which each stretch's path passes (Report.contact_need: |Δθ| in rad
and |Δv| in units of sqrt(g R) beyond the derived terms — event location, reading θ off x,
rounding —, over 1 + the stretch's length in periods: the kernel's RK4 against the checker's
finer one; < 0 where the derived terms alone cover it): the paper's floor under slide and
Coulomb (0.05, 0.3) at 46-99 Hz from rest and launched, the soak's six conveyor contact rows,
and random inputs of the conveyor contact hypothesis test's domain.  ``--write`` stores the
largest rtol needed and the margin in tests/bbb/data/checker_calibration.json; the checker sets
CONTACT_RTOL = largest × MARGIN from it, and tests/bbb/test_trajectory_check.py holds it to
that.  Rules
before data: MARGIN is fixed here, before the measurement, not fitted to it.
"""

from __future__ import annotations

import argparse
import datetime
import json
import math
import platform
import subprocess
from pathlib import Path

import numba
import numpy as np

from bbb import Params, simulate
from bbb.ensemble import initial_state
from benchmarks.calibrations.guards import SOAK_ROWS, random_params
from benchmarks.common import ROOT, cpu_name
from tests.bbb.trajectory_check import check_particle, start_event

#: CONTACT_RTOL = MARGIN × the largest rtol needed (chosen before measuring: the
#: random inputs' tail beyond the calibration sample, with an order of magnitude to spare)
MARGIN = 10.0
STORE = ROOT / "tests" / "bbb" / "data" / "checker_calibration.json"
PAPER_F = (46.0, 48.0, 50.0, 51.0, 52.0, 53.0, 54.0, 55.0, 56.0, 57.0, 58.0, 60.0, 65.0, 70.0,
           80.0, 90.0, 99.0)


def discrepancy(p: Params, n: int, t_max: float, seed: int, family: str,
                **kw) -> tuple[float, int]:
    """(the least CONTACT_RTOL every sliding stretch of one ensemble passes at, stretches)."""
    st = initial_state(p, n, np.random.SeedSequence(seed), family, **kw)
    run = simulate(p, n, t_max, seed=seed, initial=st, record_collisions=4000,
                   record_liftoffs=True, _force_conveyor=p.transport)
    need, stretches = -math.inf, 0
    for i in range(n):
        start = start_event(p, st.cell[i], st.d[i], st.y[i], st.vx[i], st.vy[i], st.s[i], st.stuck[i])
        rep = check_particle(p, np.vstack([start, run.collisions_dense[i, : run.n_recorded[i]]]))
        need, stretches = max(need, rep.contact_need), stretches + rep.contacts
    return need, stretches


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--random", type=int, default=400)
    ap.add_argument("--write", action="store_true", help=f"store the result in {STORE.name}")
    ap.add_argument("--json", type=Path, help="write the calibration JSON here (make calibrate)")
    args = ap.parse_args()
    now = datetime.datetime.now().isoformat(timespec="seconds")
    print(f"# bbb checker calibration (CONTACT_RTOL)  {now}")
    print(f"# CPU: {cpu_name()}  python {platform.python_version()}  numba {numba.__version__}  "
          f"numpy {np.__version__}")
    rows: list[tuple[str, str, float, int]] = []

    def row(group: str, label: str, need: float, k: int) -> None:
        rows.append((group, label, need, k))
        if k:
            print(f"  {group:<8} {label:<60} stretches {k:6d}  rtol needed {need:10.3e}", flush=True)

    for contact, mu in (("slide", 0.0), ("coulomb", 0.05), ("coulomb", 0.3)):
        for f in PAPER_F:
            for family in ("rest", "launched"):
                p = Params.preset("klages2004", f=f, contact=contact, mu=mu)
                row("paper", f"{contact} {mu:g} {f:g} Hz {family}",
                    *discrepancy(p, 4, 2.0, int(f * 10), family))
    for kw in SOAK_ROWS:
        row("soak", f"{kw}", *discrepancy(Params.preset("klages2004", **kw), 4, 2.0, 1, "launched"))
    rng = np.random.default_rng(20261126)
    k = 0
    while k < args.random:
        p, family, t_max = random_params(rng)
        if p.contact == "stick":
            continue
        row("random", f"#{k} {p.contact} {p.mu:.2f} f={p.f:.1f} R={p.R:.3g} tilt={p.tilt:.1f} "
            f"throw={p.throw:.1f}", *discrepancy(p, 3, t_max, k, family, drop_height=(0.0, 1.0),
                                                  launch_speed=(0.0, 150.0)))
        k += 1
    print()
    worst = max(rows, key=lambda r: r[2])
    for group in ("paper", "soak", "random"):
        g = [r for r in rows if r[0] == group and r[3]]
        print(f"{group:<8} runs {len(g):4d}  stretches {sum(r[3] for r in g):7d}  "
              f"largest rtol needed {max(r[2] for r in g):10.3e}")
    print(f"\nlargest {worst[2]:.3e} ({worst[0]} {worst[1]}); CONTACT_RTOL = {MARGIN:g} x that "
          f"= {MARGIN * worst[2]:.3e}")
    path = STORE if args.write else args.json
    if path:
        rev = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                             cwd=ROOT).stdout.strip()
        Path(path).write_text(json.dumps(dict(
            contact_rtol_needed=worst[2], where=f"{worst[0]} {worst[1]}", margin=MARGIN,
            runs=sum(1 for r in rows if r[3]), stretches=sum(r[3] for r in rows),
            date=datetime.date.today().isoformat(), kernel=rev), indent=1) + "\n")


if __name__ == "__main__":
    main()
