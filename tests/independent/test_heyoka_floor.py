"""The heyoka event detector on its own: against the closed form on a still flat floor, against
the brute-force gap scan on every shape (level and conveyor), and at grazing flights, cusps and
kinks, where the answer is known in closed form."""

import math

import numpy as np
import pytest

from tests.independent.floors import Arc, Drive, Flat, Sawtooth, Sine
from tests.independent.gap_scan import first_contact, gap
from tests.independent.heyoka_floor import SLOTS, next_contact

EPS = float(np.finfo(np.float64).eps)
G = 9800.0
#: the agreement asked of two root finders of the same gap function, s: each resolves the root
#: to the float grain of the gap (ε·mm over |G'| ≳ 1 mm/s, ~1e-16 s), far below the 1e-12 s
#: a model collision time is documented to (docs/physics.md)
TOL_TAU = 1e-13
SHAPES = {
    "arc": Arc(15.0, 2.0),
    "arc_vertical_cusps": Arc(1.0, 2.0),
    "flat": Flat(),
    "sine": Sine(0.3, 2.0),
    "sawtooth": Sawtooth(2.0, 0.3, 0.5),
}
DRIVES = {"level": Drive(G, 0.1, 60.0), "conveyor": Drive(G, 0.1, 60.0, tilt=5.0, throw=60.0)}


def random_flights(shape, drive: Drive, n: int, seed: int):
    """Flights starting 1 µm to 1 mm above the floor, any direction, any floor phase."""
    rng = np.random.default_rng(seed)
    ax, ay = drive.amplitude
    for _ in range(n):
        x0, th = rng.uniform(-5.0, 5.0), rng.uniform(0.0, 2.0 * math.pi)
        y0 = float(shape.height(np.array(x0 + ax * math.sin(th)))) - ay * math.sin(th) \
            + rng.uniform(1e-3, 1.0)
        yield x0, y0, rng.uniform(-300.0, 300.0), rng.uniform(-50.0, 300.0), th


def test_a_still_flat_floor_is_hit_at_the_closed_form_time():
    drive = Drive(G, 0.0, 60.0)
    rng = np.random.default_rng(0)
    for _ in range(50):
        y0, vy = rng.uniform(1e-3, 5.0), rng.uniform(-300.0, 300.0)
        tau = (vy + math.sqrt(vy * vy + 2.0 * G * y0)) / G
        c = next_contact(Flat(), drive, 0.0, y0, 10.0, vy, rng.uniform(0.0, 6.0))
        assert abs(c.tau - tau) <= 8.0 * EPS * tau
        assert abs(c.y) <= 8.0 * EPS * (y0 + abs(vy) * tau)


@pytest.mark.parametrize("drive", DRIVES, ids=list(DRIVES))
@pytest.mark.parametrize("shape", SHAPES, ids=list(SHAPES))
def test_the_detector_finds_the_brute_force_contact_on_every_shape(shape, drive):
    sh, dr = SHAPES[shape], DRIVES[drive]
    seed = 2 * list(SHAPES).index(shape) + list(DRIVES).index(drive)
    for k, flight in enumerate(random_flights(sh, dr, 8, seed=seed)):
        c = next_contact(sh, dr, *flight)
        assert abs(c.tau - first_contact(sh, dr, *flight, n=100_000)) <= TOL_TAU, (k, flight)
        assert abs(gap(sh, dr, *flight, np.array(c.tau))) <= 1e-12


def test_a_flight_over_more_cells_than_one_integrator_holds_is_cut_into_windows():
    sh, dr = SHAPES["arc"], DRIVES["conveyor"]
    flight = (0.3, 2.0, 3000.0, 200.0, 1.0)  # ~ 70 mm: ~ 35 arcs, more than SLOTS
    c = next_contact(sh, dr, *flight)
    assert abs(c.x - flight[0]) > 2.0 * SLOTS * sh.S
    assert abs(c.tau - first_contact(sh, dr, *flight, n=400_000)) <= TOL_TAU


# ---- grazing: a flight whose apex passes δ above a still sine's crest (the parabola, curvature
#      g/vₓ², is flatter than the crest, a(2π/λ)²: it touches at the apex alone for δ = 0)
SINE = Sine(0.3, 2.0)
STILL = Drive(G, 0.0, 60.0)
VX = 100.0
K = SINE.amplitude * (2.0 * math.pi / SINE.wavelength) ** 2 - G / VX**2  # (gap)''/vₓ², 1/mm, > 0
APEX_TAU = 0.01


def apex_flight(delta: float):
    """Launched so that the apex (τ = APEX_TAU) is δ above the crest at u = 0."""
    vy = G * APEX_TAU
    return -VX * APEX_TAU, SINE.top + delta - 0.5 * G * APEX_TAU**2, VX, vy, 0.0


def test_a_flight_grazing_one_nanometre_above_a_crest_is_not_a_contact():
    c = next_contact(SINE, STILL, *apex_flight(1e-6))
    assert c.tau > APEX_TAU + 1e-3  # it lands beyond the crest, not at it
    assert abs(c.tau - first_contact(SINE, STILL, *apex_flight(1e-6))) <= TOL_TAU


def test_a_flight_dipping_one_nanometre_into_a_crest_hits_it_before_the_apex():
    delta = -1e-6
    c = next_contact(SINE, STILL, *apex_flight(delta))
    # gap ≈ δ + K vₓ² (τ − τₐ)²/2 near the apex: the root sits √(2|δ|/(K vₓ²)) before it
    early = math.sqrt(2.0 * -delta / (K * VX**2))
    assert c.tau == pytest.approx(APEX_TAU - early, abs=1e-3 * early)


# ---- cusps and kinks: a vertical drop onto a still floor lands at the closed-form time
def drop_time(height: float, y0: float = 1.0, vy: float = 0.0) -> float:
    return (vy + math.sqrt(vy * vy + 2.0 * G * (y0 - height))) / G


@pytest.mark.parametrize("shape,u", [
    (Arc(15.0, 2.0), 1.0),  # a cusp between two arcs
    (Arc(1.0, 2.0), 3.0),  # a vertical cusp (R = S/2)
    (Sawtooth(2.0, 0.3, 0.5), 3.0),  # a valley (the cell edges (k + ½)P)
    (Sawtooth(2.0, 0.3, 0.5), 3.6),  # a peak ((k − ½ + ξ)P)
], ids=["arc_cusp", "vertical_cusp", "sawtooth_valley", "sawtooth_peak"])
def test_a_drop_onto_a_cusp_or_kink_lands_at_the_closed_form_time(shape, u):
    c = next_contact(shape, STILL, u, 1.0, 0.0, 0.0, 0.0)
    tau = drop_time(float(shape.height(np.array(u))))
    assert abs(c.tau - tau) <= 8.0 * EPS * tau


def test_a_flight_skimming_a_sawtooth_peak_passes_over_the_faces_extension():
    # a level flight from 1 µm above the peak (u = 1.6, height 0): it crosses the rising
    # face's line beyond the peak (an event off the face, passed over) and lands further on
    saw = Sawtooth(2.0, 0.3, 0.5)
    flight = (1.595, saw.top + 1e-3, 200.0, 0.0, 0.0)
    c = next_contact(saw, STILL, *flight)
    assert c.x > 1.6
    assert abs(c.tau - first_contact(saw, STILL, *flight)) <= TOL_TAU


# ---- flights that start on the floor (after a collision, at a lift-off): the event function
#      starts at exactly 0
def test_a_hop_that_starts_on_an_arc_lands_in_the_same_cell():
    # a post-collision state as a kernel records it (the paper's floor, 60 Hz): its circle's
    # event function is exactly 0 at the start
    arc, drive = Arc(15.0, 2.0), DRIVES["level"]
    flight = (0.794427601939151, -0.11872769094585911, 2.197484215857952, 25.174291255962537,
              2.0 * math.pi * 0.28438126603948144)
    c = next_contact(arc, drive, *flight)
    assert c.cell == 0.0 and c.piece == 0
    assert abs(c.tau - first_contact(arc, drive, *flight)) <= TOL_TAU


def test_a_lift_off_from_a_flat_floor_lands_where_the_brute_force_scan_does():
    # at rest on the floor where its downward acceleration reaches g: sin θ = −g/(Aω²)
    drive = Drive(G, 0.1, 80.0)
    th = math.pi + math.asin(G / (drive.A * drive.omega**2))
    flight = (0.0, -drive.A * math.sin(th), 0.0, -drive.A * drive.omega * math.cos(th), th)
    c = next_contact(Flat(), drive, *flight)
    assert c.tau > 1e-3  # a real flight, not the start
    assert abs(c.tau - first_contact(Flat(), drive, *flight)) <= TOL_TAU


# ---- far from the origin: a periodic floor's flight is flown within one period of it
LD = np.longdouble


def sine_root_extended(sine: Sine, drive: Drive, flight, lo: float, hi: float) -> float:
    """The first root in (lo, hi] of the level sine's gap for ``flight``, bisected in extended
    precision (x87 long double: 64-bit mantissa) from a sign change on a grid."""
    x0, y0, vx, vy, th0 = (LD(v) for v in flight)
    pi = LD("3.141592653589793238462643383279502884")
    w, k, a = 2 * pi * LD(drive.f), 2 * pi / LD(sine.wavelength), LD(sine.amplitude)

    def gap_ld(t):
        return y0 + vy * t - LD(drive.g) * t * t / 2 + LD(drive.A) * np.sin(th0 + w * t) \
            - a * (np.cos(k * (x0 + vx * t)) - 1)

    ts = np.linspace(LD(lo), LD(hi), 4001)
    i = int(np.nonzero(np.array([gap_ld(t) for t in ts[1:]]) <= 0)[0][0]) + 1
    a_, b_ = ts[i - 1], ts[i]
    for _ in range(100):
        m = (a_ + b_) / 2
        a_, b_ = (m, b_) if gap_ld(m) > 0 else (a_, m)
    return float(b_)


@pytest.mark.skipif(np.finfo(np.longdouble).eps > 1e-18, reason="needs an extended long double")
def test_a_grazing_hop_far_from_the_origin_lands_at_the_extended_precision_root():
    # a hop of 1.3e-7 s recorded by bbb on a sine (depth 0.3 mm, 60 Hz) at x ≈ 24 mm that
    # meets the floor at a relative speed of 1.6e-3 mm/s: flown at x ≈ 24 mm, an ulp of x
    # (3.6e-15 mm) moves the floor's height by ~1e-15 mm and the contact by ~1.5e-12 s
    sine, drive = Sine(0.15, 2.0), Drive(9800.0, 0.1, 60.0)
    flight = (24.424306257624202, -0.212090998587658, -1.7644358878299167, 9.308704281965207,
              2.0 * math.pi * 0.2861916867276019)
    c = next_contact(sine, drive, *flight)
    assert abs(c.tau - sine_root_extended(sine, drive, flight, 1e-9, 1.338e-7)) <= TOL_TAU
    assert abs(c.x - (flight[0] + flight[2] * c.tau)) <= 4.0 * np.spacing(flight[0])
