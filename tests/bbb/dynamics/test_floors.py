"""The invariants every floor shape must keep (bbb.dynamics.floors), one suite over all of
them: elastic bounces on a motionless floor conserve energy, no flight passes below the
floor (brute force against profiles written here, independently of the kernel's), mirror
pairs on a mirror-symmetric floor give zero mean displacement exactly, and a sawtooth's broken
symmetry drives a drift.  The flat floor's period-1 window and the arcs' bits are
tests/bbb/dynamics/test_evolve_level.py's and test_paper_floor_bits.py's (R = inf is the
floor "flat")."""

import math

import numpy as np
import pytest

from bbb import Params, simulate
from bbb.ensemble import mirror_pairs
from bbb.surface import cell_of

#: one scene per shape: (floor, its keys); depths and the sawtooth's asymmetry as a user would
FLOORS = {
    "arc": {"R": 15.0},
    "flat": {"floor": "flat"},
    "sine": {"floor": "sine", "depth": 0.3},
    "sawtooth": {"floor": "sawtooth", "depth": 0.3, "peak": 0.3},
}
#: the mirror-symmetric shapes that move particles sideways (every arc, every sine, a sawtooth
#: with its peak centred; on the flat floor nothing moves sideways from vx = 0)
SYMMETRIC = {"arc": FLOORS["arc"], "sine": FLOORS["sine"],
             "sawtooth": {"floor": "sawtooth", "depth": 0.3, "peak": 0.5}}
ON_SURFACE_MM = 1e-9


def profile(p: Params, d: np.ndarray) -> np.ndarray:
    """Depth (mm) below the tops at offset d, written from each shape's definition (not the
    kernel's code)."""
    if p.floor == "flat":
        return np.zeros_like(d)
    if p.floor == "arc":
        return p.R - np.sqrt(p.R**2 - d**2)
    if p.floor == "sine":
        return 0.5 * p.depth * (1.0 - np.cos(2 * np.pi * d / p.S))
    top = (p.peak - 0.5) * p.S
    return np.where(d < top, p.depth * (top - d) / (top + p.S / 2),
                    p.depth * (d - top) / (p.S / 2 - top))


def lowest_gap(p: Params, rows: np.ndarray, n_grid: int = 300) -> tuple[float, float, int]:
    """(smallest gap (mm) on a grid inside every flight, largest |gap| at a recorded
    collision, flights checked): a flight runs from a collision or lift-off to the next
    collision (7-column rows; event 0 collision, 1 lift-off)."""
    worst, off, n = math.inf, 0.0, 0
    for k in range(rows.shape[0] - 1):
        if rows[k + 1, 6] != 0.0:
            continue
        t0, x0, y0, vx, vy, ph = rows[k, :6]
        tau = np.linspace(0.0, rows[k + 1, 0] - t0, n_grid + 2)[1:-1]
        _, d = cell_of(x0 + vx * tau, p.S)
        gap = y0 + vy * tau - 0.5 * p.g * tau**2 + p.A * np.sin(2 * np.pi * ph + p.omega * tau) \
            + profile(p, d)
        if gap.size:
            worst = min(worst, float(gap.min()))
        _, d1 = cell_of(rows[k + 1, 1], p.S)
        surface = -p.A * math.sin(2 * math.pi * rows[k + 1, 5]) - float(profile(p, np.array([d1]))[0])
        off = max(off, abs(rows[k + 1, 2] - surface))
        n += 1
    return worst, off, n


@pytest.fixture(scope="module", params=sorted(FLOORS))
def bouncing(request):
    """Eight particles launched on each floor at 60 Hz, 2 s, collisions and lift-offs kept."""
    p = Params.preset("klages2004", f=60.0, **FLOORS[request.param])
    return p, simulate(p, 8, 2.0, seed=11, initial="launched", record_collisions=4000,
                       record_liftoffs=True)


def test_no_flight_passes_below_the_floor(bouncing):
    p, run = bouncing
    for i in range(run.n_particles):
        worst, _, n = lowest_gap(p, run.collisions_dense[i, : run.n_recorded[i]])
        assert n > 20 and worst > -ON_SURFACE_MM


def test_every_collision_lies_on_the_floor(bouncing):
    p, run = bouncing
    for i in range(run.n_particles):
        _, off, _ = lowest_gap(p, run.collisions_dense[i, : run.n_recorded[i]], n_grid=0)
        assert off < ON_SURFACE_MM


def test_no_anomaly_is_counted(bouncing):
    _, run = bouncing
    assert run.counters["anomalies"].sum() == 0 and run.counters["collisions"].min() > 20


#: steep shapes, strong vibration: flanks near 60° and 80°, c'' of the sine to ±5 /mm, Γ ≈ 3.3
STEEP = {
    "sine": {"floor": "sine", "depth": 1.0, "A": 0.1},
    "sawtooth": {"floor": "sawtooth", "depth": 1.0, "peak": 0.1, "A": 0.1},
}


@pytest.mark.parametrize("floor", sorted(STEEP))
def test_no_flight_passes_below_a_steep_floor_at_high_frequency(floor):
    p = Params.preset("klages2004", f=90.0, alpha=0.9, **STEEP[floor])
    run = simulate(p, 8, 3.0, seed=4, initial="launched", launch_speed=(0.0, 400.0),
                   record_collisions=4000, record_liftoffs=True)
    for i in range(run.n_particles):
        worst, off, n = lowest_gap(p, run.collisions_dense[i, : run.n_recorded[i]])
        assert n > 20 and worst > -ON_SURFACE_MM and off < ON_SURFACE_MM


@pytest.mark.parametrize("floor", sorted(FLOORS))
def test_elastic_bounces_on_a_motionless_floor_conserve_energy(floor):
    p = Params(g=9800.0, A=0.0, f=50.0, R=15.0, S=2.0, alpha=1.0, beta=1.0, **{
        k: v for k, v in FLOORS[floor].items() if k != "R"})
    run = simulate(p, 1, 2000.0, seed=3, initial="dropped", drop_height=(1.0, 3.0),
                   record_collisions=20_000)
    rows = run.collisions_dense[0, : run.n_recorded[0]]
    assert rows.shape[0] == 20_000
    energy = 0.5 * (rows[:, 3] ** 2 + rows[:, 4] ** 2) + p.g * rows[:, 2]
    assert np.max(np.abs(energy / energy[0] - 1.0)) <= 1e-9


@pytest.mark.parametrize("floor", sorted(SYMMETRIC))
def test_mirror_pairs_on_a_symmetric_floor_move_zero_exactly(floor):
    p = Params.preset("klages2004", f=70.0, **SYMMETRIC[floor])
    st = mirror_pairs(p, 16, np.random.SeedSequence(5), "launched")
    run = simulate(p, 16, 5.0, seed=5, initial=st, sample_times=np.array([0.0, 5.0]))
    dx = run.positions[:, -1] - run.positions[:, 0]
    assert np.all(dx[:8] == -dx[8:]) and np.any(dx != 0.0)
    assert dx.sum() == 0.0


def drift_interval(p: Params, n: int = 64, t_max: float = 10.0) -> tuple[float, float]:
    """The 95 % interval (mm/s) of the mean drift velocity x(t_max)/t_max over n particles
    from rest (t quantile, the particles independent)."""
    run = simulate(p, n, t_max, seed=7, initial="rest", sample_times=np.array([0.0, t_max]))
    v = (run.positions[:, -1] - run.positions[:, 0]) / t_max
    half = 2.0 * v.std(ddof=1) / math.sqrt(n)  # t_{0.975, 63} = 2.00
    return v.mean() - half, v.mean() + half


def test_a_level_sawtooth_drives_a_drift_whose_interval_excludes_zero():
    lo, hi = drift_interval(Params.preset("klages2004", f=60.0, **FLOORS["sawtooth"]))
    assert lo > 0.0 or hi < 0.0


def test_a_symmetric_sawtooth_drives_no_drift_its_interval_holds_zero():
    lo, hi = drift_interval(Params.preset("klages2004", f=60.0, **SYMMETRIC["sawtooth"]))
    assert lo < 0.0 < hi
