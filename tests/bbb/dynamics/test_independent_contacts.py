"""bbb's collision sequences against an independent event detector: every flight a run records
(from a collision or a lift-off to the next collision) is flown again from its recorded start
by heyoka's Taylor integrator with event detection (tests/independent/heyoka_floor.py, which
knows nothing of bbb's kernel), and the next contact it finds must be bbb's next recorded
collision: the same time and the same point.

Tolerances.  bbb documents each collision time to its root tolerance tol_t = 1e-12 s
(docs/physics.md, "Never missing a collision"; bbb.Numerics); the detector agrees with a
brute-force scan of the gap to ~1e-16 s (tests/independent/test_heyoka_floor.py).  The time
between two recorded rows carries the rounding of the recorded clock t (a few ulp), and a
point moves by the particle's speed times the time's error, plus rounding of the numbers
(16 ε of their size).
"""

import math

import numpy as np
import pytest

from bbb import Params, simulate
from bbb.ensemble import InitialState, initial_state
from tests.independent.floors import Arc, Drive, Flat, Sawtooth, Sine
from tests.independent.heyoka_floor import next_contact

EPS = float(np.finfo(np.float64).eps)
#: bbb's documented collision-time accuracy, s (bbb.Numerics.tol_t's default)
TOL_T = 1e-12
#: the floors of bbb compared with the detector: Params overrides of the klages2004 preset and
#: the detector's shape for those Params.  A floor shape the kernel gains is one entry here:
#: its scene keys, and the detector's class of the same name (tests/independent/floors.py).
BBB_FLOORS = {
    "arc": (dict(R=15.0), lambda p: Arc(p.R, p.S)),
    "arc_steep": (dict(R=1.2), lambda p: Arc(p.R, p.S)),
    "flat": (dict(R=math.inf), lambda p: Flat()),
    # a sine of top-to-valley depth d has amplitude d/2; a sawtooth's period is S
    "sine": (dict(floor="sine", depth=0.3), lambda p: Sine(0.5 * p.depth, p.S)),
    "sine_steep": (dict(floor="sine", depth=1.0, A=0.1), lambda p: Sine(0.5 * p.depth, p.S)),
    "sawtooth": (dict(floor="sawtooth", depth=0.3, peak=0.3), lambda p: Sawtooth(p.S, p.peak, p.depth)),
    "sawtooth_steep": (dict(floor="sawtooth", depth=1.0, peak=0.1, A=0.1),
                       lambda p: Sawtooth(p.S, p.peak, p.depth)),
}
#: the shapes the kernel runs on the level, vertically vibrated floor only (Params refuses a
#: tilt or a throw with them)
LEVEL_ONLY = {"sine", "sine_steep", "sawtooth", "sawtooth_steep"}
#: the level floor (the paper's kernel) and a conveyor (tilted, thrown: the conveyor's kernel)
FRAMES = {"level": {}, "conveyor": dict(tilt=5.0, throw=60.0)}


def flights(p: Params, start: InitialState, run):
    """(start row, end row) of every recorded flight: from the launch, a collision that did not
    stick or a lift-off, to a collision (rows of EVENT_FIELDS: t, x, y, vx, vy, phase, event).
    The launch is the row at t = 0 of the particle's initial state (x = cell·S + d + X_f, the
    floor's phase f·s)."""
    _, _, ax, _ = p.floor_frame()
    for i in range(run.n_particles):
        th = 2.0 * math.pi * p.f * start.s[i]
        x = start.cell[i] * p.S + start.d[i] - ax * math.sin(th)
        launch = [0.0, x, start.y[i], start.vx[i], start.vy[i], p.f * start.s[i], 0.0]
        ev = np.vstack([launch, run.collisions_dense[i, : run.n_recorded[i]]])
        for a, b in zip(ev[:-1], ev[1:], strict=True):
            if b[6] == 0.0 and a[6] in (0.0, 1.0):  # a stuck collision is followed by its lift-off
                yield a, b


def disagreements(p: Params, shape, start: InitialState, run) -> tuple[int, list[str]]:
    """The number of flights compared and, for those where bbb and the detector disagree
    beyond the tolerances (module doc), a line each."""
    drive = Drive(p.g, p.A, p.f, p.tilt, p.throw)
    n, bad = 0, []
    for a, b in flights(p, start, run):
        c = next_contact(shape, drive, a[1], a[2], a[3], a[4], 2.0 * math.pi * a[5])
        tol_t = TOL_T + 8.0 * (np.spacing(a[0]) + np.spacing(b[0]))
        speed = math.hypot(c.vx, c.vy) + p.A * p.omega
        tol_x = speed * tol_t + 16.0 * EPS * (abs(b[1]) + abs(b[2]) + 1.0)
        dt, dx, dy = c.tau - (b[0] - a[0]), c.x - b[1], c.y - b[2]
        if abs(dt) > tol_t or abs(dx) > tol_x or abs(dy) > tol_x:
            bad.append(f"flight from t = {a[0]!r} s: Δτ = {dt:.2e} s, Δx = {dx:.2e}, Δy = {dy:.2e} mm "
                       f"(tolerances {tol_t:.1e} s, {tol_x:.1e} mm)")
        n += 1
    return n, bad


def run_and_compare(floor: str, frame: str, f: float, seed: int, n_particles: int, t_max: float):
    overrides, shape_of = BBB_FLOORS[floor]
    p = Params.preset("klages2004", f=f, **overrides, **FRAMES[frame])
    start = initial_state(p, n_particles, np.random.SeedSequence(seed), "launched")
    run = simulate(p, n_particles, t_max, seed=seed, initial=start, record_collisions=60,
                   record_liftoffs=True)
    return disagreements(p, shape_of(p), start, run)


CASES = [(floor, frame) for floor in BBB_FLOORS for frame in FRAMES
         if frame == "level" or floor not in LEVEL_ONLY]


@pytest.mark.parametrize("floor,frame", CASES)
def test_bbb_and_the_independent_detector_find_the_same_collisions(floor, frame):
    n, bad = run_and_compare(floor, frame, f=60.0, seed=7, n_particles=12, t_max=0.5)
    assert n >= 300  # the flights compared: bouncing, creeping and lift-offs of 12 particles
    assert not bad, f"{len(bad)} of {n} flights disagree; " + "; ".join(bad[:5])


@pytest.mark.slow
@pytest.mark.parametrize("f", [45.0, 52.0, 70.0, 90.0])
@pytest.mark.parametrize("floor,frame", CASES)
def test_bbb_and_the_detector_agree_over_frequencies(floor, frame, f):
    n, bad = run_and_compare(floor, frame, f=f, seed=11, n_particles=40, t_max=2.0)
    assert n >= 1000
    assert not bad, f"{len(bad)} of {n} flights disagree; " + "; ".join(bad[:5])
