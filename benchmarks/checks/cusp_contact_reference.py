"""What should a cascade that ends in a cusp lead to?  An independent reference for the
level kernel's Coulomb contact start at steep cusps, against the kernel and the checker.

    nice .venv/bin/python -m benchmarks.checks.cusp_contact_reference [--baseline 717f991]

Runs the examples the focused property run found (Coulomb, R 1.05-1.2 mm, f 111-154 Hz,
plus the strict xfail's) in this checkout's bbb and in the bbb of revision REF (``git
archive``, fresh processes, own numba caches), and at every cascade that ends in a cusp —
a collision at the cusp point d = ±S/2 whose outgoing relative normal speed is below v_stick
— computes on its own (numpy + scipy, none of bbb's code):

* the collision: Eqs. (5)-(6) of the paper on the wall the incoming velocity (the previous
  row's, flown τ) approaches, relative to the floor's velocity -Aω cos ωt, giving the
  outgoing normal and tangential speeds u⊥, u∥;
* the model's verdict (docs/physics.md, "Contact models"): at rest in the cusp — a
  tangential speed below v_stick there, as after a cusp event — or sent straight back into
  it, the particle is held by both walls; else it slides up the wall;
* the path the kernel of REF took instead (it slid up the wall at |u∥| < v_stick): the exact
  excursion up the wall and back under R θ̈ = g_eff sin θ − μN sgn θ̇,
  N = g_eff cos θ − R θ̇², integrated (scipy DOP853, rtol 1e-12) in the angle u = θ_c − |θ|
  from the cusp, so that a 1e-14 mm excursion keeps its digits, with its own events (v = 0,
  N = 0, back at u = 0) — its length δ (mm along x), its stop and return times, its speed
  back at the cusp — beside the kernel's rows and the checker's resolution of the cusp at
  that x (4 spacing(|x| + S): a particle at rest within it is in the cusp);
* the lift-off after the hold: the first phase where sin ωt < −g/(Aω²) (g_eff < 0).

Prints one line per such cascade and the checker's flags per record; commit the output
under benchmarks/results/.
"""

from __future__ import annotations

import argparse
import datetime
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
from types import SimpleNamespace

import numpy as np
from scipy.integrate import solve_ivp

from benchmarks.common import ROOT, baseline_tree, cpu_name
from tests.bbb.trajectory_check import check_particle, start_event

HERE = str(ROOT)

G = 9800.0
S = 2.0
V_STICK = 1e-3  # the model's sticking threshold (mm/s), the kernel's default
#: the four examples of the focused property run (Coulomb near steep cusps) and the strict
#: xfail's, as the no-miss test takes them (tests/bbb/dynamics/test_contact_step_level.py)
EXAMPLES = [
    dict(f=128.0, A=0.9219666711070154, radius=1.2025988186809293, alpha=0.08455653926320933,
         beta=0.46157377184696957, mu=0.06366547442083818, family="dropped", seed=3931057938),
    dict(f=154.4200126835485, A=0.7673357731776671, radius=1.05, alpha=0.5972407915321887,
         beta=0.0625, mu=0.2099822901585309, family="dropped", seed=1248847216),
    dict(f=128.0, A=0.23322376756075258, radius=1.05, alpha=0.5, beta=0.01382658081265642,
         mu=0.46404252803079116, family="rest", seed=2063327549),
    dict(f=111.4776297737117, A=0.45007617340052547, radius=1.05, alpha=0.39840021076526877,
         beta=0.8011422441468397, mu=0.1449586375921342, family="rest", seed=1116787676),
    dict(f=128.0, A=0.453125, radius=1.05, alpha=0.5, beta=0.0625, mu=0.05, family="dropped",
         seed=1),
]

SNIPPET = """
import json, sys
import numpy as np
from bbb import Params, simulate
from bbb.ensemble import initial_state
out = []
for kw in json.loads(sys.argv[1]):
    p = Params(g=9800.0, A=kw["A"], f=kw["f"], R=kw["radius"], S=2.0, alpha=kw["alpha"],
               beta=kw["beta"], contact="coulomb", mu=kw["mu"])
    st = initial_state(p, 3, np.random.SeedSequence(kw["seed"]), kw["family"],
                       drop_height=(0.0, 1.0), launch_speed=(0.0, 150.0))
    r = simulate(p, 3, 60.0 / kw["f"], seed=kw["seed"], initial=st, record_collisions=300,
                 record_liftoffs=True)
    out.append(dict(start=[[int(st.cell[i]), float(st.d[i]), float(st.y[i]), float(st.vx[i]),
                            float(st.vy[i]), float(st.s[i]), bool(st.stuck[i])] for i in range(3)],
                    rows=[r.collisions_dense[i, :r.n_recorded[i]].tolist() for i in range(3)]))
print(json.dumps(out))
"""


def records(tree: str, cache: str) -> list[dict]:
    env = dict(os.environ, PYTHONPATH=tree, NUMBA_CACHE_DIR=cache, PYTHONDONTWRITEBYTECODE="1")
    res = subprocess.run([sys.executable, "-c", SNIPPET, json.dumps(EXAMPLES)], env=env,
                         check=True, capture_output=True, text=True, cwd=tree)
    return json.loads(res.stdout)


class Scene:
    """The floor of one example, in this script's own formulae (paper, Sec. 2)."""

    def __init__(self, kw: dict) -> None:
        self.A, self.f, self.R, self.mu = kw["A"], kw["f"], kw["radius"], kw["mu"]
        self.alpha, self.beta = kw["alpha"], kw["beta"]
        self.w = 2.0 * math.pi * self.f
        self.sc = 0.5 * S / self.R  # sin θ_c
        self.cc = math.sqrt((self.R - 0.5 * S) * (self.R + 0.5 * S)) / self.R  # cos θ_c

    def vf(self, ph):
        return -self.A * self.w * math.cos(2.0 * math.pi * ph)

    def geff(self, ph0, t):
        return G + self.A * self.w**2 * math.sin(2.0 * math.pi * ph0 + self.w * t)

    def walls(self):
        # the two walls at a cusp: (name, outward normal, the x direction up that wall)
        return (("left arc", (self.sc, self.cc), -1.0), ("right arc", (-self.sc, self.cc), 1.0))

    def excursion(self, ph0, w0):
        """From the cusp up a wall at speed w0 > 0 (mm/s, relative): the exact stretch up,
        the stop, and (static friction cannot hold it) back down into the cusp.  State (u, w):
        u = θ_c − |θ| (rad), w = R u̇ (mm/s, + up the wall); returns (stop time, u at the stop,
        time back at the cusp, speed there) or the lift-off (N = 0) where it comes first."""
        R, sc, cc, mu = self.R, self.sc, self.cc, self.mu

        def rhs(sgn):
            def f(t, z):
                u, w = z
                ge = self.geff(ph0, t)
                n = ge * (cc * math.cos(u) + sc * math.sin(u)) - w * w / R
                return [w / R, -ge * (sc * math.cos(u) - cc * math.sin(u)) - mu * n * sgn]
            return f

        def normal(t, z):
            return self.geff(ph0, t) * (cc * math.cos(z[0]) + sc * math.sin(z[0])) - z[1] ** 2 / R

        def stop(t, z):
            return z[1]

        def back(t, z):
            return z[0]

        for e in (normal, stop, back):
            e.terminal = True
        stop.direction = -1.0
        back.direction = -1.0
        a = G + self.A * self.w**2
        span = 50.0 * w0 / (a * (sc + mu * cc))  # ≫ the stop time
        opts = dict(method="DOP853", rtol=1e-12, atol=[1e-40, 1e-22], dense_output=False)
        up = solve_ivp(rhs(1.0), (0.0, span), [0.0, w0], events=(normal, stop), **opts)
        if up.t_events[0].size:
            return dict(lift=float(up.t_events[0][0]))
        t_s, u_s = float(up.t_events[1][0]), float(up.y_events[1][0][0])
        if math.tan(math.asin(sc) - u_s) <= mu:
            return dict(t_stop=t_s, u_stop=u_s, held_at_stop=True)
        down = solve_ivp(lambda t, z: rhs(-1.0)(t + t_s, z), (0.0, 4.0 * span + t_s), [u_s, 0.0],
                         events=(lambda t, z: normal(t + t_s, z), back), **opts)
        if down.t_events[0].size:
            return dict(t_stop=t_s, u_stop=u_s, lift=t_s + float(down.t_events[0][0]))
        return dict(t_stop=t_s, u_stop=u_s, t_back=t_s + float(down.t_events[1][0]),
                    v_back=float(-down.y_events[1][0][1]))

    def liftoff_phase(self, ph):
        """The first phase ≥ ph (in periods) where g_eff < 0: sin 2πφ < −g/(Aω²)."""
        r = G / (self.A * self.w**2)
        if r >= 1.0:
            return math.inf
        start = (math.pi + math.asin(r)) / (2.0 * math.pi)  # the window (start, end) per period
        end = (2.0 * math.pi - math.asin(r)) / (2.0 * math.pi)
        k = math.floor(ph)
        frac = ph - k
        if start <= frac <= end:
            return ph
        return k + start if frac < start else k + 1 + start


def cascades_into_cusp(sc: Scene, rows: np.ndarray):
    """Rows k ≥ 1 at a cusp point x = (m + ½)S whose collision (Eqs. 5-6 on the wall the
    incoming velocity approaches) leaves a normal speed below v_stick: the cascade ends there."""
    for k in range(1, rows.shape[0]):
        t, x, y, vx, vy, ph, code = rows[k]
        if code not in (0.0, 4.0) or x / S - 0.5 != math.floor(x / S - 0.5):
            continue
        t0, _, _, vx0, vy0, _, _ = rows[k - 1]
        tau = t - t0
        ux, uy = vx0, vy0 - G * tau - sc.vf(ph)
        met = [(ux * nx + uy * ny, name, nx, ny, up) for name, (nx, ny), up in sc.walls()]
        un, name, nx, ny, up = min(met)
        if un >= 0.0:
            continue
        ut = ux * ny - uy * nx  # towards +x along the wall
        un_out, ut_out = sc.alpha * abs(un), sc.beta * ut
        if un_out >= V_STICK:
            continue
        yield k, name, un, un_out, ut_out * up  # > 0: up the wall, away from the cusp


def report(label: str, recs: list[dict]) -> None:
    print(f"## {label}")
    print("ex p  row  wall       u_out_n    u_out_t(up)  model      kernel           "
          "exact excursion up and back (the kernel's path before the fix)")
    for j, (kw, rec) in enumerate(zip(EXAMPLES, recs, strict=True)):
        sc = Scene(kw)
        p = SimpleNamespace(g=G, A=kw["A"], f=kw["f"], R=kw["radius"], S=S, alpha=kw["alpha"],
                            beta=kw["beta"], mu=kw["mu"], contact="coulomb")
        for i in range(3):
            rows = np.array(rec["rows"][i]).reshape(-1, 7)
            start = start_event(p, *rec["start"][i])
            chk = check_particle(p, np.vstack([start, rows]))
            flags = {k: v for k, v in chk.failures.items() if v}
            for k, name, _un, un_out, ut_up in cascades_into_cusp(sc, rows):
                # the model: below v_stick in the cusp, rest there; sent into it, straight back
                verdict = "held" if abs(ut_up) < V_STICK or ut_up <= 0.0 else "slides up"
                nxt = rows[k + 1] if k + 1 < rows.shape[0] else None
                kern = f"code {rows[k, 6]:.0f}"
                if rows[k, 6] == 0.0 and rows[k, 3] == 0.0:
                    kern = "held"
                elif rows[k, 6] == 4.0 and nxt is not None and nxt[6] == 6.0:
                    kern = "slides up"
                elif rows[k, 6] == 4.0 and nxt is not None and nxt[6] == 7.0 and nxt[0] == rows[k, 0]:
                    kern = "into it, held" if k + 2 < rows.shape[0] and rows[k + 2, 3] == 0.0 \
                        and rows[k + 2, 6] == 0.0 else "into it"
                line = f"{j}  {i} {k:4d}  {name:9s}  {un_out:.3e}  {ut_up:+.3e}  {verdict:9s}  {kern:15s}"
                if kern == "slides up" and ut_up > 0.0:
                    ex = sc.excursion(rows[k, 5], ut_up)
                    if "t_back" in ex:
                        delta = sc.R * (sc.sc - math.sin(math.asin(sc.sc) - ex["u_stop"]))
                        x_c = rows[k, 1]
                        stop_row, back_row = rows[k + 1], rows[k + 2]
                        reach = 4.0 * float(np.spacing(abs(stop_row[1]) + S))
                        line += (f"  δ = {delta:.2e} mm (recorded {abs(stop_row[1] - x_c):.2e}; "
                                 f"the cusp's reach {reach:.2e}); stop {ex['t_stop']:.4e} s "
                                 f"(kernel {stop_row[0] - rows[k, 0]:.4e}), back {ex['t_back']:.4e} s "
                                 f"(kernel {back_row[0] - rows[k, 0]:.4e}) at "
                                 f"{ex['v_back']:.4e} mm/s (kernel "
                                 f"{math.hypot(back_row[3], back_row[4] - sc.vf(back_row[5])):.4e})")
                    else:
                        line += f"  {ex}"
                lifts = np.nonzero(rows[k:, 6] == 1.0)[0]
                if lifts.size:
                    lr = rows[k + lifts[0]]
                    ph_l = sc.liftoff_phase(rows[k, 5])
                    t_l = rows[k, 0] + (ph_l - rows[k, 5]) / sc.f
                    line += f"  | lift-off {lr[0]:.12f} s (g_eff < 0 from {t_l:.12f} s)"
                print(line)
            if flags:
                print(f"   example {j} particle {i}: the checker flags {flags} {chk.messages[:2]}")
    print()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", metavar="REF", default="717f991")
    args = ap.parse_args()
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=HERE, check=True,
                          capture_output=True, text=True).stdout.strip()
    print(f"# bbb cusp contact reference  {datetime.datetime.now().isoformat(timespec='seconds')}")
    print(f"# CPU: {cpu_name()}  python {platform.python_version()}  (numpy + scipy, none of bbb's "
          f"code; the checker: tests/bbb/trajectory_check.py)")
    print(f"# v_stick = {V_STICK} mm/s; u_out_n, u_out_t: the outgoing relative normal and "
          f"tangential speeds (mm/s, t > 0 up the wall); row: in the particle's record (the "
          f"checker's event k is row k - 1: its event 0 is the initial state); model: this "
          f"script's verdict; kernel: what the record shows; δ: the exact excursion's length in x "
          f"beside the recorded stop's distance from the cusp and the checker's resolution of the "
          f"cusp there; times from the contact start")
    with tempfile.TemporaryDirectory() as tmp, tempfile.TemporaryDirectory() as c1, \
            tempfile.TemporaryDirectory() as c2:
        ref_tree, ref_label = baseline_tree(args.baseline, tmp)
        report(f"bbb of {ref_label}", records(ref_tree, c1))
        report(f"bbb of this checkout (HEAD {head})", records(HERE, c2))


if __name__ == "__main__":
    main()
