"""Calibration of the state classifier (bbb.analysis.states) on runs with known answers.

    .venv/bin/python -m benchmarks.calibrations.states_calibration [--particles 16] \
        [--json bbb/analysis/states_rule.json]

Prints a table (committed as benchmarks/results/states-calibration-<date>.txt) and writes the
rule's thresholds to the JSON the classifier reads.  The cases, each a run of the kernel
(paper's preset, α = 0.7, A = 0.1 mm) whose answer is known before it runs:

flat 1/1       flat floor at 45 Hz (Γ₁ < Γ < 1: bbb.analysis.period1), started on the stable
               1/1 orbit (flight 1/f, floor velocity g (1 − α) / (2 f (1 + α)) at the impact)
               with vy perturbed by 0 … 0.3 mm/s: locked 1/1 over the run's second half;
flat rest      flat floor at 45 Hz from rest (Γ < 1: the floor never lets go,
               bbb.analysis.liftoff_onset): stuck in every window;
flat creeping  flat floor at 50.5 Hz from rest (just above Γ = 1: the particle lifts off a
               little each period and its cascade ends at rest, one stick per period; Luck &
               Mehta's complete chattering): stuck/creeping in every window;
flat period-2  flat floor at 56 Hz (Γ′ < Γ: the 1/1 orbit is unstable, its period-doubled
               orbit stable), started on either 1/1 orbit with vy perturbed by 0.001 … 0.05
               mm/s: locked with a cycle of 2 floor periods over the run's second half --
               except the particles that fall into the chattering motion that coexists there
               (the kernel counts their sticks: ``sticks`` > 0), stuck/creeping over it;
arc diffusing  the paper's floor at 62 and 70 Hz, launched (the paper: ergodic diffusion from
               58 Hz): chaotic or diffusing in every window, every particle crossing arcs.

The thresholds, each set in the gap between the cases that must fall on either side of it
(the run fails, writing nothing, if a gap is missing):

lock_tol     the geometric mean of the largest pair mismatch of the locked cases' settled
             windows and the smallest best-k mismatch of the diffusing cases' windows;
stick_speed  the geometric mean of the largest relative speed among the rows the kernel
             counted as sticks (each particle's ``sticks`` smallest) and the smallest among
             the other rows, over every case;
creep_share  the midpoint of the smallest stick share per floor period of the creeping
             windows and the largest of the locked and diffusing windows;
k_max, min_pairs   fixed by design (a cycle of up to 8 collisions; 4 pairs to call one).

Window 0.5 s, runs 10 s, 25 000 recorded rows per particle (a creeping particle collides about
25 times a period).
"""

from __future__ import annotations

import argparse
import datetime
import json
import math
import platform
import sys
from pathlib import Path

import numpy as np

from bbb import Params
from bbb.analysis import states as st
from bbb.analysis.period1 import gamma_1, gamma_prime
from bbb.ensemble import InitialState
from bbb.simulate import simulate
from benchmarks.common import ROOT, cpu_name

WINDOW, T_MAX, ROWS = 0.5, 10.0, 25000
K_MAX, MIN_PAIRS = 8, 4
#: the smallest ratio between the two sides of a gap for its threshold to be set
MIN_GAP = 100.0


def orbit_1_1(p: Params, branch: int) -> tuple[float, float, float]:
    """The flat floor's 1/1 orbit (Luck & Mehta): (floor time s of the impact, s; surface
    height there, mm; vy after it, mm/s).  branch 0: floor phase ω s = arccos(−V/Aω), 1: the
    other root (the stable one below Γ′)."""
    V = p.g * (1 - p.alpha) / (2 * p.f * (1 + p.alpha))
    c = -V / (p.A * p.omega)
    th = math.acos(c) if branch == 0 else 2 * math.pi - math.acos(c)
    return th / p.omega, -p.A * math.sin(th), p.g / (2 * p.f)


def near_orbit(p: Params, n: int, kicks: np.ndarray, branches) -> InitialState:
    """``n`` particles leaving the floor on the 1/1 orbit's impact, vy raised by ``kicks``
    (mm/s), alternating between ``branches``."""
    rows = [orbit_1_1(p, branches[i % len(branches)]) for i in range(n)]
    s = np.array([r[0] for r in rows])
    y = np.array([r[1] for r in rows])
    v = np.array([r[2] for r in rows]) + kicks
    return InitialState(np.zeros(n, np.int64), np.full(n, 0.3), y, np.zeros(n), v, s,
                        np.zeros(n, bool), np.ones(n, bool))


def cases(n: int) -> list[dict]:
    """The calibration cases: name, params, initial, expected labels, which windows count."""
    flat = {f: Params.preset("klages2004", f=f, floor="flat") for f in (45.0, 50.5, 56.0)}
    kicks = np.linspace(0.0, 0.3, n)
    kicks2 = np.linspace(0.001, 0.05, n)
    return [
        dict(name="flat 1/1 (45 Hz, on the orbit)", p=flat[45.0],
             initial=near_orbit(flat[45.0], n, kicks, (1,)), expect=(st.LOCKED_1,), period=1,
             settled="second half", side="locked"),
        dict(name="flat rest (45 Hz)", p=flat[45.0], initial="rest", expect=(st.STUCK,),
             settled="all", side="none"),
        dict(name="flat creeping (50.5 Hz, rest)", p=flat[50.5], initial="rest",
             expect=(st.STUCK,), settled="all", side="creeping"),
        dict(name="flat period-2 (56 Hz, near 1/1)", p=flat[56.0],
             initial=near_orbit(flat[56.0], n, kicks2, (0, 1)), expect=(st.LOCKED_K,), period=2,
             settled="second half", side="locked", chatter=True),
        dict(name="arc diffusing (62 Hz, launched)", p=Params.preset("klages2004", f=62.0),
             initial="launched", expect=(st.CHAOTIC, st.DIFFUSING), settled="all",
             side="chaotic"),
        dict(name="arc diffusing (70 Hz, launched)", p=Params.preset("klages2004", f=70.0),
             initial="launched", expect=(st.CHAOTIC, st.DIFFUSING), settled="all",
             side="chaotic"),
    ]


def chattering(case: dict, run) -> np.ndarray:
    """The particles of a case that may fall into the chattering motion (``chatter``) and did:
    the kernel counted a stick (bool, particle)."""
    if not case.get("chatter"):
        return np.zeros(run.n_particles, bool)
    return run.counters["sticks"] > 0


def run_case(case: dict, n: int, seed: int):
    p = case["p"]
    run = simulate(p, n, T_MAX, seed, case["initial"], record_collisions=ROWS)
    return p, run


def gap(lo_side: float, hi_side: float, what: str) -> float:
    """The geometric mean of the two sides of a gap; SystemExit naming it when there is none."""
    if not (hi_side > MIN_GAP * max(lo_side, 1e-300)):
        sys.exit(f"states calibration: no gap for {what}: {lo_side:.3g} (must stay below) vs "
                 f"{hi_side:.3g} (must stay above); allowed: a ratio ≥ {MIN_GAP:g}")
    return math.sqrt(max(lo_side, 1e-300) * hi_side) if lo_side > 0 else hi_side / MIN_GAP


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--particles", type=int, default=16)
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("--json", type=Path, default=None)
    a = ap.parse_args(argv)
    n = a.particles
    runs = [(c, *run_case(c, n, a.seed + i)) for i, c in enumerate(cases(n))]
    nw = st.n_windows(T_MAX, WINDOW)
    half = slice(nw // 2, nw)
    # the mismatches and stick shares, measured with a rule that locks nothing and counts
    # no sticks (the thresholds are what this measures)
    probe = dict(lock_tol=-1.0, stick_speed=-1.0, creep_share=math.inf, k_max=K_MAX,
                 min_pairs=MIN_PAIRS)
    locked_worst, chaotic_best = 0.0, math.inf
    stick_in, stick_out = 0.0, math.inf
    creep_min, other_max = math.inf, 0.0
    for c, p, run in runs:
        rec, nr = run.collisions_dense, run.n_recorded
        if np.any(nr >= ROWS):
            sys.exit(f"states calibration: {c['name']}: the recording ran out ({ROWS} rows)")
        _lab, _per, mism = st.classify(rec, nr, T_MAX, WINDOW, p.f, p.A, p.S, probe)
        # the exact k mismatch of the locked windows (best over k is ≤ it)
        if c["side"] == "locked":
            k = c["period"] if c["period"] == 1 else 2
            sel = range(nw) if c["settled"] == "all" else range(half.start, nw)
            for i in np.nonzero(chattering(c, run) == 0)[0]:
                mine = rec[i, :nr[i]]
                for q in sel:
                    rows = mine[(mine[:, 0] >= q * WINDOW) & (mine[:, 0] < (q + 1) * WINDOW)]
                    locked_worst = max(locked_worst, st.mismatch(rows, k, p.f, p.A, p.S))
        if c["side"] == "chaotic":
            chaotic_best = min(chaotic_best, float(np.nanmin(mism)))
        rel = st.relative_speed(rec, p.f, p.A)
        sticks = run.counters["sticks"]
        for i in range(n):
            r = np.sort(rel[i, :nr[i]])
            k = int(sticks[i])
            if k:
                stick_in = max(stick_in, float(r[k - 1]))
            if k < r.size:
                stick_out = min(stick_out, float(r[k]))
        c["rel"] = rel
    stick_speed = gap(stick_in, stick_out, "stick_speed")
    lock_tol = gap(locked_worst, chaotic_best, "lock_tol")
    for c, p, run in runs:
        rec, nr = run.collisions_dense, run.n_recorded
        for i in range(n):
            t = rec[i, :nr[i], 0]
            held = c["rel"][i, :nr[i]] <= stick_speed
            share = np.array([np.sum(held & (t >= q * WINDOW) & (t < (q + 1) * WINDOW))
                              for q in range(nw)]) / (WINDOW * p.f)
            if c["side"] == "creeping":
                creep_min = min(creep_min, float(share.min()))
            elif c["side"] == "chaotic" or (c["side"] == "locked" and not chattering(c, run)[i]):
                other_max = max(other_max, float(share.max()))
    if not creep_min > other_max:
        sys.exit(f"states calibration: no gap for creep_share: {other_max:.3g} vs {creep_min:.3g}")
    creep_share = 0.5 * (creep_min + other_max)
    rule = dict(lock_tol=lock_tol, stick_speed=stick_speed, creep_share=creep_share,
                k_max=K_MAX, min_pairs=MIN_PAIRS)
    # the known answers under the rule
    lines = [f"# states calibration, {datetime.date.today()}, {cpu_name()}, "
             f"{platform.machine()}, python {platform.python_version()}; {n} particles per "
             f"case, runs of {T_MAX:g} s, windows of {WINDOW:g} s, {ROWS} rows; loaded machine",
             "",
             f"flat floor, α = 0.7: Γ₁ = {gamma_1(0.7):.4f}, Γ′ = {gamma_prime(0.7):.4f}",
             "",
             "## the gaps the thresholds sit in", "",
             "| threshold | must stay below | must stay above | set to |", "| --- | --- | --- | --- |",
             f"| lock_tol (pair mismatch) | {locked_worst:.3g} (locked, settled) | "
             f"{chaotic_best:.3g} (diffusing, best k ≤ {K_MAX}) | {lock_tol:.3g} |",
             f"| stick_speed (mm/s) | {stick_in:.3g} (rows counted as sticks) | "
             f"{stick_out:.3g} (other rows) | {stick_speed:.3g} |",
             f"| creep_share (sticks per period) | {other_max:.3g} (locked, diffusing) | "
             f"{creep_min:.3g} (creeping) | {creep_share:.3g} |",
             "", "## the known answers under the rule", "",
             "| case | expected | windows judged | right | wrong labels seen |",
             "| --- | --- | --- | --- | --- |"]
    ok = True
    for c, p, run in runs:
        lab, per, _m = st.classify(run.collisions_dense, run.n_recorded, T_MAX, WINDOW, p.f,
                                   p.A, p.S, rule)
        sel = lab if c["settled"] == "all" else lab[:, half]
        right = np.isin(sel, c["expect"])
        if "period" in c:
            right &= (per if c["settled"] == "all" else per[:, half]) == c["period"]
        chat = chattering(c, run)
        right[chat] = sel[chat] == st.STUCK
        wrong = sorted({st.LABELS[v] for v in np.unique(sel[~right])})
        if c["side"] == "chaotic":
            cells = np.floor(run.collisions_dense[..., 1] / p.S + 0.5)
            crossed = np.nanmax(cells, axis=1) > np.nanmin(cells, axis=1)
            if not crossed.all():
                wrong.append(f"{int((~crossed).sum())} particles never crossed an arc")
        ok &= bool(right.all()) and not wrong
        exp = " or ".join(st.LABELS[e] for e in c["expect"])
        if "period" in c:
            exp += f" (cycle {c['period']})"
        if chat.any():
            exp += f"; stuck for the {int(chat.sum())} chattering (sticks > 0)"
        lines.append(f"| {c['name']} | {exp} | {c['settled']} | {right.mean():.3f} | "
                     f"{', '.join(wrong) or '-'} |")
    lines.append("")
    lines.append(f"rule: {json.dumps(rule)}")
    print("\n".join(lines))
    if not ok:
        print("states calibration: a known answer is not returned; no rule written")
        return 1
    if a.json is not None:
        out = dict(rule, source=f"benchmarks/results/states-calibration-{datetime.date.today()}.txt",
                   window=WINDOW, t_max=T_MAX, rows=ROWS, particles=n, seed=a.seed)
        path = a.json if a.json.is_absolute() else ROOT / a.json
        path.write_text(json.dumps(out, indent=1) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
