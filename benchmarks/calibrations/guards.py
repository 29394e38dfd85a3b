"""The kernel's guards against endless loops, measured: how close real inputs come to them.

    .venv/bin/python -m benchmarks.calibrations.guards [--particles 8] [--t-max 10] [--random 300]

bbb.contact.slide stops a contact stretch whose step debt (tried RK4 steps beyond PAYBACK per
nominal step of the time covered) exceeds STRETCH_BUDGET, bbb.kernel stops a particle with
more than EVENT_BUDGET events within EVENT_WINDOW floor periods or whose collision searches
draw more than SEARCH_BURST steps beyond SEARCH_RATE per floor period (bbb.dynamics.events);
bbb.simulate then raises.
This runs the inputs the project uses — the paper's floor under every contact model (the
contact scenes, 46-99 Hz, from rest and launched), the transport scenes (tilt, throw, stick
and Coulomb 0.3; the sliding scene at its own length where its debts peak), the conveyor
contact rows of the soak, the extremes table — and random
inputs of the hypothesis domain (tests/bbb/dynamics/test_contact_step_conveyor.py, every contact model on
tilted and thrown floors), and prints the largest step debt, events per window and draw on the
search budget each met.
Writes the maxima to benchmarks/results/guards-<date>.json (--json), which
tests/bbb/dynamics/test_guards.py reads: each budget must exceed its measured maximum by MARGIN.
Commit the printed table under benchmarks/results/ with the date and machine.
"""

from __future__ import annotations

import argparse
import datetime
import json
import math
import platform
import time
from pathlib import Path

import numba
import numpy as np

from bbb import Params, simulate
from bbb.dynamics.events import EVENT_BUDGET, EVENT_WINDOW, SEARCH_BURST, SEARCH_RATE
from bbb.dynamics.slide import PAYBACK, STRETCH_BUDGET
from bbb.ensemble import initial_state, speed_cap
from benchmarks.common import cpu_name

PAPER_F = (46.0, 48.0, 50.0, 51.0, 52.0, 53.0, 54.0, 56.0, 58.0, 60.0, 65.0, 70.0, 80.0, 90.0, 99.0)
MODELS = (("stick", 0.0), ("slide", 0.0), ("coulomb", 0.05), ("coulomb", 0.3))
TRANSPORT = (dict(tilt=2.0), dict(tilt=5.0), dict(throw=30.0), dict(throw=60.0),
             dict(throw=30.0, contact="coulomb", mu=0.3))
SOAK_ROWS = (dict(contact="coulomb", mu=0.3, throw=30.0, f=50.0),
             dict(contact="slide", tilt=3.0, throw=60.0, f=55.0),
             dict(contact="coulomb", mu=0.3, tilt=3.0, throw=60.0, f=55.0),
             dict(contact="coulomb", mu=0.3, tilt=10.0, f=40.0),
             dict(contact="coulomb", mu=0.05, tilt=5.0, throw=60.0, f=45.0, R=math.inf),
             dict(contact="slide", tilt=-3.0, throw=120.0, f=70.0))


def measure(p: Params, n: int, t_max: float, seed: int, family: str = "rest",
            **kw) -> tuple[float, float, float, int, float]:
    """(peak step debt, most events in one window, deepest search-budget draw, collisions,
    CPU s) of one ensemble."""
    guards = np.zeros((n, 5))
    st = initial_state(p, n, np.random.SeedSequence(seed), family, **kw)
    t0 = time.process_time()
    run = simulate(p, n, t_max, seed=seed, initial=st, _guards=guards, _force_conveyor=p.transport)
    return (float(guards[:, 1].max()), float(guards[:, 2].max()), float(guards[:, 4].max()),
            int(run.counters["collisions"].sum()), time.process_time() - t0)


def cap_rows() -> list[tuple[str, Params, str, dict]]:
    """Starts at the edges of what bbb accepts (bbb.params.GAMMA_MAX, bbb.ensemble.speed_cap):
    launched at the speed cap, dropped from the height cap, Γ = 1000 at 60 Hz and 1 kHz, the
    highest frequency; each run for at most 2000 floor periods."""
    out = []
    for f, gamma in ((60.0, 4.0), (60.0, 1000.0), (1000.0, 1000.0), (1e5, 3.0), (0.5, 1000.0)):
        p = Params.preset("klages2004", f=f, A=gamma * 9800.0 / (2 * math.pi * f) ** 2)
        cap = speed_cap(p)
        out.append((f"f={f:g} Gamma={gamma:g} launched at 0.9-1 x cap", p, "launched",
                    dict(launch_speed=(0.9 * (cap - p.A * p.omega), cap - p.A * p.omega))))
        out.append((f"f={f:g} Gamma={gamma:g} dropped from 0.9-1 x height cap", p, "dropped",
                    dict(drop_height=(0.9 * cap**2 / (2 * p.g), cap**2 / (2 * p.g)))))
        out.append((f"f={f:g} Gamma={gamma:g} rest", p, "rest", {}))
    return out


def random_params(rng: np.random.Generator) -> tuple[Params, str, float]:
    """One draw of the hypothesis domain of the conveyor contact test (its strategies'
    ranges, uniform; every fifth angle at an edge of its range)."""
    tilt = float(rng.choice([-30.0, 0.0, 30.0])) if rng.random() < 0.2 else float(rng.uniform(-30, 30))
    throw = float(rng.choice([10.0, 90.0, 170.0])) if rng.random() < 0.2 else float(rng.uniform(10, 170))
    contact = str(rng.choice(["stick", "slide", "coulomb"]))
    R = math.inf if rng.random() < 0.2 else float(rng.uniform(1.05, 60.0 if rng.random() < 0.7 else 2.0))
    p = Params(g=9800.0, A=float(rng.uniform(0.0, 1.0)), f=float(rng.uniform(5.0, 200.0)), R=R,
               S=2.0, alpha=float(rng.uniform(0.05, 1.0)), beta=float(rng.uniform(0.0, 1.0)),
               tilt=tilt, throw=throw, contact=contact,
               mu=float(rng.uniform(0.0, 3.0)) if contact == "coulomb" else 0.0)
    return p, str(rng.choice(["rest", "dropped", "launched"])), min(60.0 / p.f, 1.0)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--particles", type=int, default=8)
    ap.add_argument("--t-max", type=float, default=10.0)
    ap.add_argument("--random", type=int, default=300, help="random hypothesis-domain inputs")
    ap.add_argument("--json", type=Path, default=None, help="write the maxima here")
    args = ap.parse_args()
    n, t_max = args.particles, args.t_max
    print(f"# bbb kernel guards, measured  {datetime.datetime.now().isoformat(timespec='seconds')}")
    print(f"# CPU: {cpu_name()}  python {platform.python_version()}  numba {numba.__version__}  "
          f"numpy {np.__version__}")
    print(f"# budgets: step debt {STRETCH_BUDGET:g} (PAYBACK {PAYBACK:g}), events {EVENT_BUDGET} per "
          f"{EVENT_WINDOW:g} period, search steps {SEARCH_BURST} + {SEARCH_RATE} per period; "
          f"{n} particles x {t_max:g} s per row unless said")
    groups: dict[str, list[tuple[str, float, float, float, int, float]]] = {}

    def row(group: str, label: str, p: Params, n_: int, t_: float, seed: int, family: str,
            **kw) -> None:
        debt, events, search, coll, cpu = measure(p, n_, t_, seed, family, **kw)
        groups.setdefault(group, []).append((label, debt, events, search, coll, cpu))
        print(f"  {group:<10} {label:<58} debt {debt:10.1f}  events {events:6.0f}  "
              f"search {search:8.0f}  coll {coll:9d}  {cpu:6.2f} s", flush=True)

    for contact, mu in MODELS:
        for f in PAPER_F:
            for family in ("rest", "launched"):
                p = Params.preset("klages2004", f=f, contact=contact, mu=mu)
                row("paper", f"{contact} {mu:g} {f:g} Hz {family}", p, n, t_max, int(f * 10), family)
    for kw in TRANSPORT:
        for f in (20.0, 40.0, 50.0, 56.0, 60.0, 66.0, 70.0, 80.0, 90.0):
            p = Params.preset("klages2004", f=f, **kw)
            row("transport", f"{kw} {f:g} Hz", p, n, t_max, int(f * 10), "rest")
    for f in (62.0, 64.0, 66.0, 68.0, 70.0, 72.0, 74.0, 76.0):
        # the transport sliding scene where its debts peak (below and at lift-off, 66.7 Hz),
        # at the scene's own length: 64 of its 128 particles x 50 s
        p = Params.preset("klages2004", f=f, **TRANSPORT[-1])
        row("scene", f"transport_sliding_coulomb {f:g} Hz, 64 x 50 s", p, 64, 50.0, int(f), "rest")
    for kw in SOAK_ROWS:
        p = Params.preset("klages2004", **kw)
        row("soak", f"{kw}", p, n, t_max, 1, "launched")
    for label, p, family, kw in cap_rows():
        row("caps", label, p, 4, min(t_max, 2000.0 / p.f), 3, family, **kw)
    from tests.bbb.dynamics.test_extremes import CASES, start  # the table's own initial states
    for case in CASES:
        guards = np.zeros((case.n, 5))
        t0 = time.process_time()
        run = simulate(case.params, case.n, case.t_max, seed=20261122,
                       initial=start(case, case.n, 20261122), _guards=guards)
        groups.setdefault("extremes", []).append(
            (case.name, float(guards[:, 1].max()), float(guards[:, 2].max()),
             float(guards[:, 4].max()), int(run.counters["collisions"].sum()),
             time.process_time() - t0))
        print(f"  {'extremes':<10} {case.name[:58]:<58} debt {guards[:, 1].max():10.1f}  "
              f"events {guards[:, 2].max():6.0f}  search {guards[:, 4].max():8.0f}", flush=True)
    rng = np.random.default_rng(20261125)
    for k in range(args.random):
        p, family, t_ = random_params(rng)
        row("random", f"#{k} {p.contact} f={p.f:.1f} R={p.R:.3g} tilt={p.tilt:.1f} throw={p.throw:.1f}",
            p, 3, t_, k, family, drop_height=(0.0, 1.0), launch_speed=(0.0, 150.0))
    print()
    print(f"{'group':<10} {'rows':>5} {'max step debt':>14} {'max events/window':>18} "
          f"{'max search draw':>16} {'collisions':>12} {'CPU s':>8}")
    summary = {}
    for g, rows in groups.items():
        debt = max(r[1] for r in rows)
        events = max(r[2] for r in rows)
        search = max(r[3] for r in rows)
        summary[g] = dict(rows=len(rows), max_debt=debt, max_events=events, max_search=search,
                          worst_debt=max(rows, key=lambda r: r[1])[0],
                          worst_events=max(rows, key=lambda r: r[2])[0],
                          worst_search=max(rows, key=lambda r: r[3])[0])
        print(f"{g:<10} {len(rows):5d} {debt:14.1f} {events:18.0f} {search:16.0f} "
              f"{sum(r[4] for r in rows):12d} {sum(r[5] for r in rows):8.1f}")
    debt = max(s["max_debt"] for s in summary.values())
    events = max(s["max_events"] for s in summary.values())
    search = max(s["max_search"] for s in summary.values())
    print(f"\nlargest step debt {debt:.1f} (budget {STRETCH_BUDGET:g}: x{STRETCH_BUDGET / debt:.0f}); "
          f"most events in a window {events:.0f} (budget {EVENT_BUDGET}: x{EVENT_BUDGET / events:.0f}); "
          f"deepest search-budget draw {search:.0f} (burst {SEARCH_BURST}: x{SEARCH_BURST / search:.0f})")
    if args.json:
        args.json.write_text(json.dumps(dict(
            date=datetime.date.today().isoformat(), particles=n, t_max=t_max, random=args.random,
            max_debt=debt, max_events=events, max_search=search, groups=summary), indent=1) + "\n")


if __name__ == "__main__":
    main()
