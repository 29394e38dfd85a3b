"""An independent trajectory checker: does a recorded run obey the model's equations?

Its own small numpy code (none of bbb's jitted helpers or bbb.surface): given one particle's
recorded events — post-collision states (t, x, y, vx, vy, floor phase) and the lift-offs that
start a flight from the floor (``simulate(record_liftoffs=True)``, column ``event`` = 1) — it
checks every pair of consecutive events against the model of Klages, Barna & Mátyás (2004):

* the clock: the time between two events from the recorded t agrees with the one from the
  recorded floor phases (phase = f·t_floor mod 1), to the rounding of t;
* a flight (from a collision or a lift-off to the next collision): in the floor's clock the
  particle flies the parabola x = x₀ + vₓτ, y = y₀ + v_yτ − gτ²/2 (Eqs. 1-4); the next
  collision point lies on that parabola and on the surface at its phase; between the two the
  gap G(τ) = y(τ) − y_s(x(τ), τ) stays ≥ 0 (dense samples and a rigorous lower bound on
  sub-intervals, below); the outgoing velocity follows Eqs. (5)-(6) from the incoming one;
* a carried stretch (a collision that ended stuck, then its lift-off): x does not move, the
  lift-off state is the floor's (on the surface, with the floor's velocity, vₓ = 0), and it
  happens at the first moment the floor accelerates downward faster than g, sin(2πft) < −1/Γ.

The floor (Sec. 2 and Fig. 1 of the paper): arc tops at y_f(t) = −A sin(2πft), arcs of radius
R centred at x = kS, so a point at offset d = x − kS lies c(d) = R − √(R² − d²) below the top.

The conveyor (bbb.Params ``tilt`` φ, ``throw`` ψ, in degrees), derived here on its own: in the
floor's coordinates (x along its plane, y normal to it) gravity is (−g sin φ, −g cos φ), so a
flight is x = x₀ + vₓτ − g sin φ τ²/2, y = y₀ + v_yτ − g cos φ τ²/2; the floor moves rigidly by
A (cos ψ, sin ψ)(−sin 2πft), so the arcs sit at x = kS − A cos ψ sin 2πft with tops at
−A sin ψ sin 2πft; Eqs. (5)-(6) act on the velocity relative to the floor's (both components);
a carried particle keeps its place relative to the floor and has the floor's velocity; it
lifts off when the normal contact force, n·(a_floor + g(sin φ, cos φ)), first turns negative.
Flights on the conveyor are certified by the range bounds (bounds 1-2 of _check_gap, with the
offset's range from the parabola and the floor's sideways sine), which need no split at
cusps, and, on sub-intervals whose offset range reaches at most two arcs, by the Taylor bounds
3-4 on each of their whole circles (the floor is the upper envelope of its circles, so G is the
smaller of the two circles' gaps, each smooth across the cusp) with
−G'' ≤ g cos φ + A sin ψ ω² max sin + |c'|max |d''|max (d'' = −g sin φ − A cos ψ ω² sin θ);
without these the range bounds alone leave near-grazing flights on arcs uncertified, and
flights that start on a cusp (a bounce there) too: their offset range always holds it.
Sliding on the conveyor (``slide``, ``coulomb``): the stretch is integrated in the floor's
frame under the effective gravity Gₓ = gₓ + Aₓω² sin θ, G_y = g_y + A_yω² sin θ (states and
offsets relative to the moving floor); a stretch from rest (a held collision, a stop, a start
at rest) has no row where it starts to slide, so the checker finds the slip itself: the first
phase where |F_t| > μN, F_t = G_y sin θ − Gₓ cos θ (in a cusp — within CUSP_REACH of it on the
conveyor, as for the lift-off — where a wall that presses, N > 0, is pulled up beyond μN; it
slides on that wall; a wall with N ≤ 0 does not touch the particle, and the floor lets go of it
only when both walls do), by its own sampling and bisection; and a held particle's lift-off
must not come after that slip.

Other floor shapes.  The floor's profile within a cell (depth, slope, curvature, normal,
their sensitivity to a rounding of the offset, and the bounds the level gap check takes over
an offset range: the least depth, the least curvature, the largest pull n_y² c'') is a small
class of tests/bbb/checker_profiles.py: ArcProfile, FlatProfile, SineProfile or SawtoothProfile
(the sine and the sawtooth of docs/physics.md, "Floors", written there on their own).
Common to all: cells of width S with any concave kink of the gap (an arc's cusp, a sawtooth's
valley) at their edges.  The sine and the sawtooth are checked on the level, vertically
vibrated floor under the stick model (the flights, the collision rule, sticking and lift-off),
which is where the kernel runs them; the conveyor's bounds (circles through the cusps, R as
the length scale) and the sliding stretches (an angle on a circle) remain written for arcs.

Tolerances are the checker's own, never read from the run under test (its bbb.Numerics): a run
made with a coarser root tolerance fails the checker.  Event times are asked to TOL_T = 1e-12 s,
the accuracy the model documents for a collision (docs/physics.md); that is attainable in
float64, whose resolution of the floor time within a period is ulp(1/f) < 1e-15 s for
f ≥ 1 Hz, and the recorded clock's own rounding (ulp(t), 1.8e-12 s at t = 1e4 s) is added
separately.  The sticking threshold V_STICK = 1e-3 mm/s is a parameter of the model (like α,
bbb.Numerics' default), passed in where a run used another.  A collision time is then known to
δτ = TOL_T + the clock's rounding, and the particle is put on the surface at that time, so a
collision point may lie off the exact intersection by |G'|·δτ, where G' is the
particle's vertical speed relative to the floor (plus the arc's slope times vₓ); on top of that
comes the rounding of the numbers involved (16 ε times their size) and the rounding of x
(spacing(x)), which moves the height by at most min(c'·δx, √(2Rδx)) — the square root near the
vertical cusps of R = S/2, where c' is infinite.  Velocities are compared to rounding plus
the normal's uncertainty from δx.  The lift-off phase may be off the window's edge by the
rounding of the phase (16 ε·2π rad).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from tests.bbb.checker_profiles import ArcProfile, FlatProfile, SawtoothProfile, SineProfile

EPS = float(np.finfo(np.float64).eps)
CHECKS = ("clock", "carried", "liftoff_state", "liftoff_time", "stuck_flight", "off_parabola",
          "off_surface", "velocity", "below", "uncertified", "contact_start", "contact_path",
          "contact_normal", "contact_event")
#: event codes (bbb.record.EVENT_CODES, restated): 4 contact start, 5 lift-off from sliding,
#: 6 Coulomb stop, 7 cusp reached while sliding
CONTACT, CONTACT_LIFT, STOP, CUSP = 4.0, 5.0, 6.0, 7.0
#: accuracy asked of the kernel's contact integration (RK4, ≤ T/256 per step) per stretch,
#: relative to the scales sqrt(g R) (speed) and 1 rad (angle), per period of the stretch (the
#: floor's or the arc's pendulum period, the shorter): the largest discrepancy measured on
#: the calibration runs times the margin stated there (benchmarks/calibrations/checker_calibration.py,
#: stored beside this module in data/checker_calibration.json)
CALIBRATION = json.loads((Path(__file__).parent / "data" / "checker_calibration.json").read_text())
CONTACT_RTOL = CALIBRATION["contact_rtol_needed"] * CALIBRATION["margin"]
#: the model's cusp (docs/physics.md, "Transport"): a particle carried within this fraction
#: of S of a cusp rests in it, held by both arcs
CUSP_REACH = 1e-9
#: the accuracy (s) the checker asks of an event time, its own (module doc)
TOL_T = 1e-12
#: the model's sticking threshold (mm/s): a collision whose outgoing relative normal speed is
#: below it ends in contact (docs/physics.md, "Creeping, sticking and lift-off")
V_STICK = 1e-3


@dataclass
class Report:
    """Per check, how many event pairs failed it; the first few failures in words."""

    flights: int = 0
    carried: int = 0
    contacts: int = 0
    failures: dict[str, int] = field(default_factory=lambda: dict.fromkeys(CHECKS, 0))
    messages: list[str] = field(default_factory=list)
    worst_gap: float = math.inf  # mm, the lowest sampled gap of any flight
    #: the least CONTACT_RTOL at which every sliding stretch's path (θ, v) would pass (< 0:
    #: the derived terms alone cover it): what CONTACT_RTOL is calibrated on
    contact_need: float = -math.inf

    @property
    def ok(self) -> bool:
        return not any(self.failures.values())

    def flag(self, check: str, mask: np.ndarray, index: np.ndarray, what: np.ndarray,
             limit: np.ndarray) -> None:
        mask = np.asarray(mask, bool)
        self.failures[check] += int(np.count_nonzero(mask))
        what, limit = np.broadcast_to(what, mask.shape), np.broadcast_to(limit, mask.shape)
        for i in np.nonzero(mask)[0][: max(0, 5 - len(self.messages))]:
            self.messages.append(f"{check} at event {int(index[i])}: {what[i]:.3e} > {limit[i]:.3e}")

    def add(self, other: Report) -> None:
        self.flights += other.flights
        self.carried += other.carried
        self.contacts += other.contacts
        for k, v in other.failures.items():
            self.failures[k] += v
        self.messages += other.messages[: max(0, 10 - len(self.messages))]
        self.worst_gap = min(self.worst_gap, other.worst_gap)
        self.contact_need = max(self.contact_need, other.contact_need)


class Floor:
    """The moving corrugated floor of the paper, in its own numpy code."""

    def __init__(self, p) -> None:
        self.g, self.A, self.f, self.R, self.S = p.g, p.A, p.f, p.R, p.S
        self.alpha, self.beta = p.alpha, p.beta
        self.mu = getattr(p, "mu", 0.0)
        self.w = 2.0 * math.pi * p.f
        self.shape = getattr(p, "floor", "arc")
        self.flat = self.shape == "flat" or (self.shape == "arc" and math.isinf(p.R))
        # what depends on the floor's shape (its height profile within a cell) lives there
        if self.shape == "sine":
            self.profile = SineProfile(p.depth, p.S)
        elif self.shape == "sawtooth":
            self.profile = SawtoothProfile(p.depth, p.peak, p.S)
        else:
            self.profile = FlatProfile() if self.flat else ArcProfile(p.R)
        phi, psi = math.radians(getattr(p, "tilt", 0.0)), math.radians(getattr(p, "throw", 90.0))
        self.conveyor = phi != 0.0 or psi != math.pi / 2
        sliding = getattr(p, "contact", "stick") != "stick"
        if self.shape in ("sine", "sawtooth") and (self.conveyor or sliding):
            # the conveyor's bounds and the sliding checks here are written for arcs (module doc)
            raise ValueError(f"the trajectory checker checks a {self.shape} floor level, vertically "
                             "vibrated and under contact = 'stick' only")
        # gravity's magnitudes along −x and −y, the floor's amplitudes along x and y
        self.gx, self.gy = (p.g * math.sin(phi), p.g * math.cos(phi)) if self.conveyor else (0.0, p.g)
        self.Ax, self.Ay = (p.A * math.cos(psi), p.A * math.sin(psi)) if self.conveyor else (0.0, p.A)
        # the rounding of a floor velocity (mm/s), ~16 ε Aω: 32 spacings of Aω, so that a
        # subnormal amplitude (absolute spacing 5e-324, not relative) keeps a bound that
        # does not underflow to 0 (A = 2.2e-311 mm: the kernel's floor velocity and this one
        # differ by a few spacings at a sticking collision)
        self.vf_tol = 32.0 * float(np.spacing(self.A * self.w))

    def cell(self, x):
        return np.floor(x / self.S + 0.5)

    def xf(self, th):
        """The floor's sideways displacement −A cos ψ sin θ (mm)."""
        return -self.Ax * np.sin(th)

    def vxf(self, th):
        return -self.Ax * self.w * np.cos(th)

    def offset(self, x, th):
        """Offset (mm) of lab position x from the nearest arc centre of the floor at phase θ."""
        r = x - self.xf(th)
        return r - self.cell(r) * self.S

    def q(self, d):
        """√(R² − d²) (mm; arcs only)."""
        return self.profile.q(d)

    def depth(self, d):
        """How far below the floor's top the floor lies at offset d from a cell's centre (mm)."""
        return self.profile.depth(d)

    def slope(self, d):
        """depth'(d); ±inf at a vertical cusp."""
        return self.profile.slope(d)

    def curvature(self, d):
        """depth''(d)."""
        return self.profile.curvature(d)

    def normal(self, d):
        """Outward unit normal (nₓ, n_y) of the floor at offset d."""
        return self.profile.normal(d)

    def height_error(self, d, dx):
        """Largest change of the depth when d moves by dx (mm)."""
        return self.profile.height_error(d, dx)

    def normal_error(self, dx, d=None):
        """Largest change of the normal (either component) when d (if given) moves by dx."""
        return self.profile.normal_error(dx, d)

    def y(self, th):
        return -self.Ay * np.sin(th)

    def v(self, th):
        return -self.Ay * self.w * np.cos(th)

    def surface(self, x, th):
        return self.y(th) - self.depth(self.offset(x, th))


def sin_range(a, b):
    """Exact (min, max) of sin over [a, b] (radians, arrays)."""
    two_pi = 2.0 * math.pi
    lo = np.minimum(np.sin(a), np.sin(b))
    hi = np.maximum(np.sin(a), np.sin(b))
    has_min = np.floor((b - 1.5 * math.pi) / two_pi) >= np.ceil((a - 1.5 * math.pi) / two_pi)
    has_max = np.floor((b - 0.5 * math.pi) / two_pi) >= np.ceil((a - 0.5 * math.pi) / two_pi)
    return np.where(has_min, -1.0, lo), np.where(has_max, 1.0, hi)


START, START_STUCK = 2.0, 3.0  # event codes of an initial state put before the record


def start_event(p, cell: int, d: float, y: float, vx: float, vy: float, s: float, stuck: bool) -> np.ndarray:
    """A particle's initial state (bbb.ensemble.InitialState fields, floor time s in s) as an
    event row at t = 0, so that the flight from it (or the carried stretch) is checked too."""
    x = cell * p.S + d + Floor(p).xf(2.0 * math.pi * p.f * s)  # d is relative to the floor
    return np.array([0.0, x, y, vx, vy, s * p.f, START_STUCK if stuck else START])


def check_particle(p, events: np.ndarray, samples: int = 64, per_period: int = 50,
                   v_stick: float = V_STICK) -> Report:
    """Check one particle's recorded events (rows of EVENT_FIELDS: t, x, y, vx, vy, phase,
    event; the first row may be a ``start_event``) against the model; ``p`` a bbb.Params,
    ``v_stick`` the model's sticking threshold (mm/s), a parameter of the model like α, not a
    tolerance: the kernel's default.  Every tolerance is the checker's own (module doc)."""
    fl = Floor(p)
    rep = Report()
    ev = events[np.all(np.isfinite(events), axis=1)]
    if ev.shape[0] < 2:
        return rep
    a, b = ev[:-1], ev[1:]
    idx = np.arange(1, ev.shape[0])
    t_a, x_a, y_a, vx_a, vy_a, ph_a, kind_a = a.T
    t_b, x_b, y_b, vx_b, vy_b, ph_b, kind_b = b.T
    th_a, th_b = 2.0 * math.pi * ph_a, 2.0 * math.pi * ph_b
    # clock: τ from the phases (floor time, exact to the phase's rounding) against t
    dph = ph_b - ph_a
    tau = (dph + np.round((t_b - t_a) * fl.f - dph)) / fl.f
    clock_tol = 8.0 * (np.spacing(np.abs(t_a)) + np.spacing(np.abs(t_b))) + 16.0 * EPS / fl.f
    rep.flag("clock", (np.abs(tau - (t_b - t_a)) > clock_tol) | (tau < -clock_tol), idx,
             np.abs(tau - (t_b - t_a)), clock_tol)
    dtau_clock = 16.0 * EPS * (1.0 + tau * fl.f) / fl.f
    vf_tol = fl.vf_tol
    at_rest = (np.abs(vx_a - fl.vxf(th_a)) <= vf_tol) & (np.abs(vy_a - fl.v(th_a)) <= vf_tol)
    if not fl.conveyor:
        at_rest &= vx_a == 0.0
    stuck_a = ((kind_a == 0) & at_rest) | (kind_a == START_STUCK) | ((kind_a == STOP) & at_rest)
    # the rounding of an offset read off x: of x, of the cell's centre, and (conveyor) of the
    # floor's sideways displacement −A cos ψ sin θ in the lab x (16 ε |Aₓ|)
    dx_b = 2.0 * np.spacing(np.abs(x_b)) + np.spacing(fl.S * np.abs(fl.cell(x_b)) + fl.S) \
        + 16.0 * EPS * abs(fl.Ax)

    # ---- carried stretches: a collision that ended stuck, then its lift-off
    lift = kind_b == 1
    rep.carried = int(np.count_nonzero(lift))
    if rep.carried:
        # carried with the floor: the place relative to it does not change
        moved = np.abs((x_b - fl.xf(th_b)) - (x_a - fl.xf(th_a)))
        dx_c = dx_b + 2.0 * np.spacing(np.abs(x_a)) + 16.0 * EPS * abs(fl.Ax)
        rep.flag("carried", lift & (~stuck_a | (moved > dx_c)), idx, moved, dx_c)
        d_b = fl.offset(x_b, th_b)
        y_tol = 16.0 * EPS * (np.abs(y_b) + fl.A + fl.depth(d_b)) + fl.height_error(d_b, dx_c)
        off = np.abs(y_b - fl.surface(x_b, th_b))
        bad = (np.abs(vx_b - fl.vxf(th_b)) > vf_tol) | (np.abs(vy_b - fl.v(th_b)) > vf_tol) \
            | (off > y_tol)
        if not fl.conveyor:
            bad |= vx_b != 0.0
        rep.flag("liftoff_state", lift & bad, idx, off, y_tol)
        # lift-off: where the normal force per mass, gₙ + Aₙω² sin θ, first reaches 0 (gₙ, Aₙ:
        # gravity and floor amplitude along the arc's normal; on the paper's floor gₙ/Aₙ = g/A,
        # never for Γ ≤ 1).  Written as −gₙ − Aₙω² sin θ ≥ 0 over a positive aw2 = |Aₙ|ω²
        # with the phase shifted by π where Aₙ < 0.
        nx, ny = fl.normal(d_b)
        a_n = nx * fl.Ax + ny * fl.Ay
        g_n = nx * fl.gx + ny * fl.gy
        shift = np.where(a_n < 0, math.pi, 0.0)
        aw2 = np.abs(a_n) * fl.w**2
        g2 = -g_n - aw2 * np.sin(th_b + shift)
        g2_tol = 16.0 * EPS * (fl.g + aw2) + aw2 * 16.0 * EPS * 2.0 * math.pi
        if fl.conveyor and not fl.flat:
            # the normal is known to δn ≤ δd/R + √(2R δd)/R from d's rounding (as in
            # _check_velocity); on the paper's floor it cancels (Aₙ/gₙ = A/g), here it does not
            g2_tol = g2_tol + (fl.g + fl.A * fl.w**2) * fl.normal_error(dx_c)
        late = np.zeros_like(lift)
        window = (aw2 > g_n) & (g_n > 0)
        if np.any(window):
            with np.errstate(divide="ignore", invalid="ignore"):
                ratio = np.where(window, g_n / aw2, 0.0)
                th_l = math.pi + np.arcsin(ratio)  # the window sin θ' < −gₙ/(|Aₙ|ω²) opens here
                th_a2 = th_a + shift
                inside_a = np.sin(th_a2) < -ratio - g2_tol / np.where(window, aw2, 1.0)
                end = th_a2 + fl.w * tau - 1e-9  # a window opening in (θ_a, θ_b − 1e-9) was skipped
                opens = np.floor((end - th_l) / (2 * math.pi)) >= np.ceil((th_a2 - th_l) / (2 * math.pi))
            late = window & ((inside_a & (tau > dtau_clock)) | opens)
        # in a cusp both arcs carry the particle (the model's rule, docs/physics.md "Transport"):
        # checked on its own below, with both arcs' normals
        cusp = lift & (0.5 * fl.S - np.abs(d_b) <= CUSP_REACH * fl.S) if fl.conveyor and not fl.flat \
            else np.zeros_like(lift)
        rep.flag("liftoff_time", lift & ~cusp & ((g2 < -g2_tol) | late), idx, -g2, g2_tol)
        if np.any(cusp):
            _check_cusp_liftoff(fl, rep, idx[cusp], th_a[cusp], tau[cusp], d_b[cusp],
                                np.broadcast_to(g2_tol, lift.shape)[cusp])
        if fl.conveyor and getattr(p, "contact", "stick") != "stick":
            # under slide and coulomb a held particle slides where static friction lets go
            # (on a conveyor that depends on the phase): not before the floor let go of it
            slip_tol = 64.0 * EPS * (fl.g + fl.A * fl.w**2) * (1.0 + fl.mu)
            slipped = np.zeros_like(lift)
            for i in np.nonzero(lift & stuck_a)[0]:
                d_i = float(fl.offset(x_a[i], th_a[i]))
                in_cusp = not fl.flat and 0.5 * fl.S - abs(d_i) <= CUSP_REACH * fl.S
                th_s = _slip(fl, fl.mu, d_i, th_a[i], th_a[i] + fl.w * tau[i], in_cusp, -slip_tol)[0]
                slipped[i] = th_s < th_a[i] + fl.w * (tau[i] - TOL_T)  # nan: never
            rep.flag("liftoff_time", slipped, idx, tau, np.zeros_like(tau))

    # ---- sliding stretches (contact models): from a contact start, a stop or a start at rest
    #      to a lift-off from sliding, a stop or a cusp
    slid = (kind_b == CONTACT_LIFT) | (kind_b == STOP) | (kind_b == CUSP)
    rep.contacts = int(np.count_nonzero(slid))
    if rep.contacts:
        _check_contact(fl, v_stick, rep, idx, slid, tau, a, b)

    # ---- flights: from a collision that did not stick, or from a lift-off, to a collision
    fly = ~lift & ~slid
    sliding_a = (kind_a == CONTACT) | ((kind_a == STOP) & ~at_rest)
    rep.flag("stuck_flight", fly & (stuck_a | sliding_a), idx, np.zeros_like(tau), np.zeros_like(tau))
    fly &= ~stuck_a & ~sliding_a
    rep.flights = int(np.count_nonzero(fly))
    if not rep.flights:
        return rep
    k = np.nonzero(fly)[0]
    tau_f = tau[k]
    x0, y0, vx, vy0, th0 = x_a[k], y_a[k], vx_a[k], vy_a[k], th_a[k]
    xb, yb, vxb, vyb, thb = x_b[k], y_b[k], vx_b[k], vy_b[k], th_b[k]
    dxb = dx_b[k]
    xp = x0 + vx * tau_f - 0.5 * fl.gx * tau_f**2
    yp = y0 + vy0 * tau_f - 0.5 * fl.gy * tau_f**2
    vx_end = vx - fl.gx * tau_f
    # rounding of each term, of the clock, of x, and of the floor's sideways displacement in
    # both ends' lab x (the kernel's and the start row's −A cos ψ sin θ: 16 ε |Aₓ|, and the
    # rounding of sin's argument ω(s + τ), which a flight of many periods makes large)
    x_tol = 4.0 * (np.spacing(np.abs(xb)) + np.spacing(np.abs(vx * tau_f)) + np.spacing(np.abs(x0))
                   + np.spacing(0.5 * fl.gx * tau_f**2)) + np.abs(vx_end) * dtau_clock[k] + dxb \
        + abs(fl.Ax) * (16.0 * EPS + 4.0 * np.spacing(2 * math.pi + th0 + fl.w * tau_f))
    rep.flag("off_parabola", np.abs(xb - xp) > x_tol, idx[k], np.abs(xb - xp), x_tol)
    # on the surface at its phase, to |G'| δτ (δτ = tol_t + clock) + rounding of y and x
    d_p = fl.offset(xp, thb)
    vf_b = fl.v(thb)
    dtau = TOL_T + dtau_clock[k]
    g1 = np.abs(vy0 - fl.gy * tau_f - vf_b)
    scale = np.abs(y0) + np.abs(vy0 * tau_f) + 0.5 * fl.g * tau_f**2 + fl.A + fl.depth(d_p) \
        + (np.abs(x0) + np.abs(vx * tau_f) if fl.conveyor else 0.0)
    rnd = 16.0 * EPS * scale
    u_end = np.abs(vx_end - fl.vxf(thb))  # sideways speed relative to the floor
    on_tol = (g1 * dtau + fl.height_error(d_p, u_end * dtau + x_tol + 16.0 * EPS * abs(fl.Ax)) + rnd
              + (fl.g + fl.A * fl.w**2) * dtau**2)
    gap_end = yp - fl.surface(xp, thb)
    rep.flag("off_surface", (np.abs(gap_end) > on_tol) | (np.abs(yb - yp) > on_tol + rnd), idx[k],
             np.abs(gap_end), on_tol)
    # a collision is declared where G ≤ 0 in floating point: within √(2 rnd/K) of the true one
    # when G' is small there, so the incoming normal speed may have either sign up to K·that
    K = fl.g + fl.A * fl.w**2
    graze = K * np.minimum(tau_f, np.sqrt(2.0 * rnd / K))
    _check_velocity(fl, v_stick, rep, idx[k], vx_end, vy0 - fl.gy * tau_f, xb, dxb, thb, vxb, vyb,
                    kind_a[k], dtau_clock[k], graze, kind_b[k])
    _check_gap(fl, rep, idx[k], x0, y0, vx, vy0, th0, tau_f, dxb, samples, per_period,
               dtau, on_tol)
    return rep


def _cusp_loads(fl: Floor, d, th):
    """The normal forces per unit mass (mm/s²) that carry a particle in the cusp at offset d
    with the floor at phase θ, one per arc: n·(a_floor + (gₓ, g_y)), rows (own, other).  In a
    vertical cusp (R = S/2, horizontal normals) only a vertical load lets go: the load along
    (0, 1) for both when the floor has no sideways load, else +inf (held at every phase)."""
    side = np.sign(d)
    other = d - side * fl.S
    ax, ay = fl.Ax * fl.w**2 * np.sin(th) + fl.gx, fl.Ay * fl.w**2 * np.sin(th) + fl.gy
    loads = np.array([nx * ax + ny * ay for nx, ny in (fl.normal(d), fl.normal(other))])
    vertical = (fl.q(d) == 0.0) | (fl.q(other) == 0.0)
    if np.any(vertical):
        up = fl.Ay * fl.w**2 * np.sin(th) + fl.gy
        if fl.Ax != 0.0 or fl.gx != 0.0:
            up = np.full_like(up, np.inf)
        loads[:, vertical] = up[vertical]
    return loads


def _check_cusp_liftoff(fl: Floor, rep: Report, index, th_a, tau, d_b, tol) -> None:
    """A lift-off from a cusp: both arcs' loads ≤ 0 at it, and no phase of the carried
    stretch (sampled at ≤ T/512, up to 1e-9 rad before the end) where both were below 0."""
    at_b = _cusp_loads(fl, d_b, th_a + fl.w * tau)
    worst = at_b.max(axis=0)
    late = np.zeros(index.shape, bool)
    for i in range(index.size):
        n = int(math.ceil(tau[i] * fl.f * 512)) + 2
        th = np.linspace(th_a[i], th_a[i] + fl.w * tau[i] - 1e-9, n)
        both = _cusp_loads(fl, np.full(n, d_b[i]), th).max(axis=0)
        late[i] = np.any(both < -tol[i]) and tau[i] > 0.0
    rep.flag("liftoff_time", (worst > tol) | late, index, worst, tol)


def _check_velocity(fl: Floor, v_stick, rep: Report, index, vx_in, vy_in, xb, dxb, thb, vxb, vyb,
                    kind_a, dtau, graze, kind_b) -> None:
    """Eqs. (5)-(6) relative to the moving floor: u⊥⁺ = −α u⊥⁻, u∥⁺ = β u∥⁻, and the
    kernel's sticking rule (α|u⊥⁻| < v_stick: carried with the floor, or, once, a fly-off
    with u⊥⁺ = v_stick where the arc falls away faster than g + a_floor pull it down)."""
    vf = fl.v(thb)
    vfx = fl.vxf(thb)
    ux, uy = vx_in - vfx, vy_in - vf
    ox, oy = vxb - vfx, vyb - vf
    speed = np.hypot(ux, uy)
    d = fl.offset(xb, thb)
    # the normal from d is known to δn ≤ δd/R + √(2R δd)/R (the √ at a vertical cusp)
    dn = fl.normal_error(dxb, d)
    tol = 32.0 * EPS * (speed + np.abs(vf) + np.hypot(ox, oy)) + 2.0 * speed * dn \
        + (fl.g + fl.A * fl.w**2) * dtau
    vs = v_stick
    ok = np.zeros(d.shape, bool)
    kick = np.zeros(d.shape, bool)
    # at a cusp (d = ±S/2) either arc's normal is the contact normal
    for dd in (d, d - np.sign(d) * fl.S):
        near = np.abs(dd) <= 0.5 * fl.S + dxb
        nx, ny = fl.normal(dd)
        un, ut = ux * nx + uy * ny, ux * ny - uy * nx
        on, ot = ox * nx + oy * ny, ox * ny - oy * nx
        out = fl.alpha * np.abs(un)
        approach = un <= tol + graze
        bounce = (np.abs(on - out) <= tol) & (np.abs(ot - fl.beta * ut) <= tol) & (out >= vs - tol)
        still = (vxb == 0.0) if not fl.conveyor else (np.abs(ox) <= fl.vf_tol)
        stuck = still & (np.abs(oy) <= fl.vf_tol) & (out <= vs + tol)
        # a contact model: the cascade ends in sliding, relative normal speed 0, β u∥ kept
        slides = (kind_b == CONTACT) & (np.abs(on) <= tol) & (np.abs(ot - fl.beta * ut) <= tol) \
            & (out <= vs + tol)
        # the floor's pull (β u∥ n_y)² c'' (on an arc (β u∥)²/√(R² − d²)), at its largest
        # within δd of d
        pull_c = fl.profile.pull(dd, dxb)
        with np.errstate(divide="ignore", invalid="ignore"):
            pull = np.where(fl.beta * ut != 0.0, (fl.beta * ut) ** 2 * pull_c, 0.0)
        g2 = -fl.gy - fl.Ay * fl.w**2 * np.sin(thb) + pull
        slope_term = np.zeros_like(g2)
        sw = np.zeros_like(g2)
        if fl.conveyor and not fl.flat:
            # and the arc's slope against the sideways pull: c'(d)(−gₓ − ẍ_floor)
            sw = -fl.gx - fl.Ax * fl.w**2 * np.sin(thb)
            with np.errstate(invalid="ignore"):
                slope_term = np.where(sw != 0.0, fl.slope(dd) * sw, 0.0)
            g2 = g2 + slope_term
        g2_tol = _kick_tolerance(fl, dd, dxb, dtau, ut, tol, pull_c, pull, slope_term, sw)
        flies = (np.abs(on - vs) <= tol) & (np.abs(ot - fl.beta * ut) <= tol) & (out <= vs + tol) \
            & (np.abs(fl.beta * ut) >= vs - tol) & (g2 > -g2_tol)
        ok |= near & approach & ((bounce | stuck | flies) & (kind_b != CONTACT) | slides)
        kick |= near & approach & flies & ~bounce & ~stuck
    # a fly-off never follows a fly-off (kick after kick would be an endless Zeno sequence)
    twice = kick & np.concatenate([[False], kick[:-1]]) & (kind_a == 0)
    rep.flag("velocity", ~ok | twice, index, np.zeros_like(tol), tol)


def _kick_tolerance(fl: Floor, dd, dxb, dtau, ut, tol, pull_c, pull, slope_term, sw):
    """How far (mm/s²) this checker's G'' of a fly-off (the kick of the sticking rule, which
    the kernel takes where its own G'' > 0) may lie from the kernel's: the rounding of its
    terms (16 ε each); the phase known to ω·dtau, in the floor's accelerations A_y ω² sin θ and
    A_x ω² sin θ (times the slope); u∥ known to ±tol (the velocity check's own bound), in the
    floor's pull (β u∥)² pull_c (pull_c = n_y² c'', 1/√(R² − d²) on an arc) — already taken at
    its largest within δd —; and d known to
    ±dxb, in the slope c'(d), by c''(|d| + dxb)·dxb."""
    w3 = fl.w**3
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        t = 16.0 * EPS * (fl.gy + abs(fl.Ay) * fl.w**2 + pull + np.abs(slope_term)) \
            + (abs(fl.Ay) + np.abs(slope_term / np.where(sw != 0.0, sw, 1.0)) * abs(fl.Ax)) * w3 * dtau \
            + fl.beta**2 * tol * (2.0 * np.abs(ut) + tol) * np.abs(pull_c)
        if fl.conveyor and not fl.flat:
            c2 = fl.curvature(np.minimum(np.abs(dd) + dxb, fl.R))
            t = t + np.where(sw != 0.0, c2 * dxb * np.abs(sw), 0.0)
    return np.where(np.isnan(t), np.inf, t)


def _check_gap(fl: Floor, rep: Report, index, x0, y0, vx, vy0, th0, tau, dx, samples,
               per_period, dtau, end_tol) -> None:
    """G ≥ 0 along every flight: dense samples, and a rigorous lower bound of G on
    sub-intervals within one arc, bisected until it is ≥ −tolerance (or the interval is
    below 1e-15 s: then the flight is 'uncertified').  Within ``dtau`` of the end the
    collision's own tolerance ``end_tol`` applies (the root may lie up to dtau earlier)."""
    g, A, w, S = fl.gy, fl.Ay, fl.w, fl.S
    gx, Ax = fl.gx, fl.Ax
    n = tau.size
    # start offset (the start point's own rounding) is part of every flight's tolerance
    base = 16.0 * EPS * (np.abs(y0) + np.abs(vy0 * tau) + 0.5 * g * tau**2 + A + fl.profile.scale)
    g0 = y0 - fl.surface(x0, th0)
    base = base + np.maximum(-g0, 0.0) + (g + A * w * w) * TOL_T**2 / 8

    def rel(i, s):
        # the particle's place relative to the floor (unwrapped: arc k is at kS)
        return x0[i] + vx[i] * s - 0.5 * gx * s * s - fl.xf(th0[i] + w * s)

    def gap(i, s, k):
        d = rel(i, s) - k * S
        return y0[i] + vy0[i] * s - 0.5 * g * s * s + A * np.sin(th0[i] + w * s) + fl.depth(d), d

    def dgap(i, s, d):
        with np.errstate(invalid="ignore"):
            slope = np.where(vx[i] != 0.0, fl.slope(d) * vx[i], 0.0)
        return vy0[i] - g * s + A * w * np.cos(th0[i] + w * s) + slope

    # dense samples (nearest arc): at least `samples` per flight and `per_period` per period
    m = np.maximum(samples, np.ceil(per_period * tau * fl.f).astype(np.int64))
    fi = np.repeat(np.arange(n), m)
    frac = (np.arange(fi.size) - np.repeat(np.cumsum(m) - m, m) + 0.5) / np.repeat(m, m)
    s = frac * tau[fi]
    gs, ds = gap(fi, s, fl.cell(rel(fi, s)))
    tol_s = base[fi] + fl.height_error(ds, dx[fi]) + np.where(s >= tau[fi] - dtau[fi], end_tol[fi], 0.0)
    low = np.full(n, np.inf)
    np.minimum.at(low, fi, gs + tol_s)
    if gs.size:
        rep.worst_gap = min(rep.worst_gap, float(np.min(gs)))
    below = low < 0

    # sub-intervals within one arc: split each flight at the cusps x = (m + ½)S it crosses
    xe = x0 + vx * tau
    lo_c = np.ceil(np.minimum(x0, xe) / S - 0.5)
    hi_c = np.floor(np.maximum(x0, xe) / S - 0.5)
    ncusp = np.zeros(n, np.int64) if fl.flat else np.maximum(hi_c - lo_c + 1, 0).astype(np.int64)
    ncusp[vx == 0.0] = 0
    if fl.conveyor:
        ncusp[:] = 0  # bounds 1-2 below take the offset's whole range, cusps included
    fi = np.repeat(np.arange(n), ncusp + 1)
    j = np.arange(fi.size) - np.repeat(np.cumsum(ncusp + 1) - (ncusp + 1), ncusp + 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        first = np.where(vx[fi] > 0, lo_c[fi], hi_c[fi])
        step = np.where(vx[fi] > 0, 1.0, -1.0)
        cut = ((first + step * j + 0.5) * S - x0[fi]) / vx[fi]
    last = j == ncusp[fi]
    u = np.where(j == 0, 0.0, np.roll(cut, 1))
    v = np.where(last, tau[fi], cut)
    u, v = np.clip(u, 0.0, tau[fi]), np.clip(v, 0.0, tau[fi])
    uncert = np.zeros(n, bool)
    for _ in range(200):
        keep = (v > u) & ~below[fi]
        fi, u, v = fi[keep], u[keep], v[keep]
        if not fi.size:
            break
        h = v - u
        mid = 0.5 * (u + v)
        k = fl.cell(rel(fi, mid))
        gu, du = gap(fi, u, k)
        gv, dv = gap(fi, v, k)
        cu, cv = fl.depth(du), fl.depth(dv)
        cmin = fl.profile.depth_min(du, dv, cu, cv)
        smin, smax = sin_range(th0[fi] + w * u, th0[fi] + w * v)
        if fl.conveyor:
            # the nearest arc's depth, at least its minimum over the offset's range: the
            # parabola's exact range on [u, v] plus the floor's −xf = Ax sin θ ∈ Ax·[smin, smax]
            # (rounded outward); then the nearest offsets, depths at the ends as actual values
            su = np.stack([u, v, np.clip(np.where(gx != 0, vx[fi] / gx if gx else 0.0, u), u, v)])
            par = x0[fi] + vx[fi] * su - 0.5 * gx * su * su
            lo = par.min(axis=0) + np.minimum(Ax * smin, Ax * smax)
            hi = par.max(axis=0) + np.maximum(Ax * smin, Ax * smax)
            pad = 8.0 * EPS * (np.abs(lo) + np.abs(hi) + abs(fl.Ax)) + 1e-300
            lo, hi = lo - pad, hi + pad
            centre = np.ceil(lo / S) <= np.floor(hi / S)
            dl, dh = lo - fl.cell(lo) * S, hi - fl.cell(hi) * S
            cmin = np.where(centre, 0.0, fl.depth(np.minimum(np.abs(dl), np.abs(dh))))
            cu, cv = fl.depth(fl.offset(x0[fi] + vx[fi] * u - 0.5 * gx * u * u, th0[fi] + w * u)), \
                fl.depth(fl.offset(x0[fi] + vx[fi] * v - 0.5 * gx * v * v, th0[fi] + w * v))
            gu = gu - fl.depth(du) + cu  # the gap to the nearest arc, not to arc k
            gv = gv - fl.depth(dv) + cv
            k_lo, k_hi = fl.cell(lo), fl.cell(hi)  # the arcs the offset can reach
        # bound 1, term by term: the parabola is concave (min at an end), sin exact, c ≥ cmin
        pu, pv = gu - A * np.sin(th0[fi] + w * u) - cu, gv - A * np.sin(th0[fi] + w * v) - cv
        lb = np.minimum(pu, pv) + A * smin + cmin
        # bound 2, chord of H = G − c (H'' = −g − Aω² sin ≤ −g − Aω² smin) plus c ≥ cmin
        hmax = np.maximum(-g - A * w * w * smin, 0.0)
        lb = np.maximum(lb, np.minimum(gu - cu, gv - cv) - hmax * h * h / 8 + cmin)
        if fl.conveyor and not fl.flat:
            # bounds 3, 4 on whole circles: the floor is the upper envelope of its arcs' circles,
            # so G = min_k G_k over the arcs the offset can reach, and each G_k is smooth across
            # the cusps (the kernel's start step from a cusp bounds the same two circles).  On
            # circle k: G_k'' = −g − Aω² sin θ + c''(d) d'² + c'(d) d'' with d = offset − kS,
            # d'' = −gₓ − Aₓω² sin θ and c'' ≥ 0, so −G_k'' ≤ K_k = g + Aω² smax + |c'|max |d''|max.
            # A range that reaches more than two arcs (a cusp on either side) gets no Taylor bound.
            d2 = np.maximum(np.abs(gx + Ax * w * w * smin), np.abs(gx + Ax * w * w * smax))
            s_uv = np.stack([u, v])
            th_uv = th0[fi] + w * s_uv
            d1_uv = vx[fi] - gx * s_uv + Ax * w * np.cos(th_uv)  # the offset's rate d'
            taylor = np.full(fi.size, np.inf)
            with np.errstate(invalid="ignore"):
                for kk in (k_lo, k_hi):
                    amax = np.maximum(np.abs(lo - kk * S), np.abs(hi - kk * S))
                    K = np.maximum(g + A * w * w * smax + fl.slope(amax) * d2, 0.0)
                    (gk_u, dk_u), (gk_v, dk_v) = gap(fi, u, kk), gap(fi, v, kk)
                    # G_k' at either end: vy − g s + Aω cos θ + c'(d) d'
                    g1 = vy0[fi] - g * s_uv + A * w * np.cos(th_uv) + fl.slope(np.stack([dk_u, dk_v])) * d1_uv
                    t_u = np.minimum(gk_u, gk_u + g1[0] * h - 0.5 * K * h * h)
                    t_v = np.minimum(gk_v, gk_v - g1[1] * h - 0.5 * K * h * h)
                    # np.minimum keeps a nan (a circle the offset leaves, |d| ≥ R): no bound then
                    taylor = np.minimum(taylor, np.where(np.isfinite(K), np.fmax(t_u, t_v), -np.inf))
            lb = np.where(k_hi - k_lo <= 1, np.fmax(lb, taylor), lb)
        if not fl.conveyor:
            # bounds 3, 4: Taylor from either end with −G'' ≤ K = g + Aω² smax − vₓ² min c''
            # (an arc's c'' is least at the smallest |d|, a sine's at the largest; a sawtooth's
            # flanks have none and its peak is a convex kink, which only turns G' upward)
            with np.errstate(invalid="ignore"):
                arc = np.where(vx[fi] != 0.0, vx[fi] ** 2 * fl.profile.curvature_min(du, dv), 0.0) \
                    if not fl.flat else 0.0
            K = np.maximum(g + A * w * w * smax - arc, 0.0)
            with np.errstate(invalid="ignore"):
                t_u = np.minimum(gu, gu + dgap(fi, u, du) * h - 0.5 * K * h * h)
                t_v = np.minimum(gv, gv - dgap(fi, v, dv) * h - 0.5 * K * h * h)
            lb = np.fmax(lb, np.fmax(t_u, t_v))
        tol = base[fi] + fl.height_error(np.maximum(np.abs(du), np.abs(dv)), dx[fi]) \
            + np.where(v >= tau[fi] - dtau[fi], end_tol[fi], 0.0)
        bad = (np.minimum(gu, gv) < -tol)
        below[fi[bad]] = True
        done = lb >= -tol
        tiny = ~done & (h <= 1e-15 * (1.0 + v))
        uncert[fi[tiny]] = True
        split = ~done & ~tiny & ~bad
        if fl.conveyor and np.count_nonzero(split) > 200_000:
            # the range bounds converge only linearly: give up (uncertified) rather than let
            # the bisection's arrays grow without bound
            uncert[fi[split]] = True
            split[:] = False
        fi = np.concatenate([fi[split], fi[split]])
        u, v = np.concatenate([u[split], mid[split]]), np.concatenate([mid[split], v[split]])
    else:
        uncert[fi] = True
    rep.flag("below", below, index, -low, np.zeros(n))
    rep.flag("uncertified", uncert & ~below, index, np.zeros(n), np.zeros(n))


def _contact_state(fl: Floor, x, vx, vy, th, at_rest):
    """(q, v, d, uₙ): the angle θ of the contact point on its arc (on a flat floor: the offset
    relative to the floor), the tangential and normal speeds relative to the floor, and the
    offset d on that arc (all relative to the moving floor).  At a cusp the arc is the one the
    velocity is tangent to (the one it slides on)."""
    r = x - fl.xf(th)  # the place relative to the floor
    d = r - fl.cell(r) * fl.S
    ux, uy = vx - fl.vxf(th), vy - fl.v(th)
    nx, ny = fl.normal(d)
    un = ux * nx + uy * ny
    if not fl.flat:
        dx = 4.0 * np.spacing(np.abs(x) + fl.S) + 16.0 * EPS * abs(fl.Ax)
        alt = d - np.sign(d) * fl.S
        anx, any_ = fl.normal(alt)
        aun = ux * anx + uy * any_
        use = (np.abs(np.abs(d) - 0.5 * fl.S) <= dx) & (np.abs(aun) < np.abs(un)) & ~at_rest
        d, nx, ny, un = (np.where(use, alt, d), np.where(use, anx, nx), np.where(use, any_, ny),
                         np.where(use, aun, un))
    v = np.where(at_rest, 0.0, ux * ny - uy * nx)
    q = r if fl.flat else np.arcsin(np.clip(d / fl.R, -1.0, 1.0))
    return q, v, d, un


def _effective_gravity(fl: Floor, th):
    """(Gₓ, G_y) (mm/s²): gravity minus the floor's acceleration, in the floor's frame:
    Gₓ = gₓ + Aₓω² sin θ, G_y = g_y + A_yω² sin θ (on the paper's floor Gₓ = 0, G_y = g_eff)."""
    sw = fl.w**2 * np.sin(th)
    return fl.gx + fl.Ax * sw, fl.gy + fl.Ay * sw


def _contact_rates(fl: Floor, mu, q, v, th, sgn):
    # R θ̈ = G_y sin θ − Gₓ cos θ − μ N sgn(v), N = Gₓ sin θ + G_y cos θ − v²/R (docs/physics.md,
    # "Forces in contact"); flat: d̈ = −Gₓ − μ G_y sgn v, N = G_y.  Paper's floor: Gₓ = 0
    gxe, ge = _effective_gravity(fl, th)
    if fl.flat:
        return v, -gxe - mu * ge * sgn, ge
    sq, cq = np.sin(q), np.cos(q)
    n = gxe * sq + ge * cq - v * v / fl.R
    return v / fl.R, ge * sq - gxe * cq - mu * n * sgn, n


def _rest_loads(fl: Floor, mu, d, th):
    """At rest at offset d (floor phase θ): (F_t, N), the tangential pull (towards +x) and the
    normal load per unit mass (mm/s²) the arc must supply, friction aside."""
    gxe, ge = _effective_gravity(fl, th)
    nx, ny = fl.normal(d)
    return ge * nx - gxe * ny, gxe * nx + ge * ny


def _slip_parts(fl: Floor, mu, d, th, cusp):
    """The loads (mm/s², rows) whose signs decide a slip at rest at offset d: on one arc
    F_t − μN and −F_t − μN (it slips where either is > 0); in a cusp, per wall, its pull up
    the wall less μN, and N (it slips up a wall where both are > 0: a wall with N ≤ 0 does
    not touch the particle), own wall first.  Their roots bound every slip window."""
    ft, n = _rest_loads(fl, mu, d, th)
    if not cusp:
        return np.stack([ft - mu * n, -ft - mu * n])
    sg = 1.0 if d > 0 else -1.0
    ft2, n2 = _rest_loads(fl, mu, d - sg * fl.S, th)
    return np.stack([-sg * ft - mu * n, n, sg * ft2 - mu * n2, n2])


def _slip_excess(fl: Floor, mu, d, th, cusp):
    """How far (mm/s²) the pull at rest exceeds static friction (> 0: it slips), and the arc
    it slips on: |F_t| − μN on one arc.  In a cusp (within CUSP_REACH of d = ±S/2) the
    particle leaves up a wall only if that wall presses on it (N > 0: a wall with N ≤ 0 does
    not touch it) and its pull up the wall, F_t·(away from the cusp), beats μN: per wall
    min(pull − μN, N), the larger of the two walls, and that wall's offset."""
    parts = _slip_parts(fl, mu, d, th, cusp)
    if not cusp:
        return np.maximum(parts[0], parts[1]), d
    own = np.minimum(parts[0], parts[1])
    oth = np.minimum(parts[2], parts[3])
    other = d - (1.0 if d > 0 else -1.0) * fl.S
    return np.maximum(own, oth), np.where(oth > own, other, d)


def _slip(fl: Floor, mu, d, th_a, th_b, cusp, tol):
    """The first floor phase in [θ_a, θ_b] (rad) at which static friction lets go of a particle
    at rest at offset d (pull beyond μN by more than −tol), the arc's offset it then slides on,
    and the least normal load (_floor_load) until then.  Own search: samples at ≤ 2π/4096,
    plus samples 2π·2⁻¹² … 2π·2⁻⁴⁸ rad either side of every root of the loads that decide a
    slip (_slip_parts: a slip window is bounded by such roots, so a window narrower than the
    grid — a wall's pull beating friction just before its N reaches 0 — is found too), then
    bisection (nan: held to θ_b)."""
    n = int(np.ceil((th_b - th_a) / (2 * math.pi) * 4096)) + 2
    grid = np.linspace(th_a, th_b, n)
    extra = []
    offsets = 2 * math.pi * 2.0 ** -np.arange(12, 49, 2)
    for k, part in enumerate(_slip_parts(fl, mu, d, grid, cusp)):
        for j in np.nonzero(np.sign(part[:-1]) != np.sign(part[1:]))[0]:
            lo, hi, s_lo = grid[j], grid[j + 1], np.sign(part[j])
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                if mid <= lo or mid >= hi:
                    break
                if np.sign(_slip_parts(fl, mu, d, np.array(mid), cusp)[k]) == s_lo:
                    lo = mid
                else:
                    hi = mid
            extra += [lo - offsets, hi + offsets]
    th = np.unique(np.clip(np.concatenate([grid, *extra]), th_a, th_b)) if extra else grid
    ex, _ = _slip_excess(fl, mu, d, th, cusp)
    nn = _floor_load(fl, mu, d, th, cusp)
    hit = np.nonzero(ex > -tol)[0]
    if not hit.size:
        return math.nan, d, float(np.min(nn))
    j = int(hit[0])
    if j == 0:
        th_s = th_a
    else:
        lo, hi = th[j - 1], th[j]
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            if mid <= lo or mid >= hi:
                break
            if _slip_excess(fl, mu, d, np.array(mid), cusp)[0] > -tol:
                hi = mid
            else:
                lo = mid
        th_s = hi
    # the wall it slides up: the one whose slip condition holds just after the slip, 2π·2⁻²⁰
    # rad on, whatever the recorded stretch's length (at the slip itself, where the effective
    # gravity vanishes, both walls' loads are 0 and rounding would pick)
    arc = float(_slip_excess(fl, mu, d, np.array(th_s + 2 * math.pi * 2.0**-20), cusp)[1])
    # the least load up to the slip itself (the sample after it may lie past the floor's
    # letting go: a slip where N is about to reach 0, |F_t| ≤ μN failing just before)
    at_slip = float(_floor_load(fl, mu, d, np.array(th_s), cusp))
    return th_s, arc, min(float(np.min(nn[:j], initial=math.inf)), at_slip)


def _floor_load(fl: Floor, mu, d, th, cusp):
    # the normal load that keeps the floor in touch (mm/s²): the arc's at d; in a cusp the
    # larger of the two walls' (the floor lets go only when both do)
    n = _rest_loads(fl, mu, d, th)[1]
    if not cusp:
        return n
    return np.maximum(n, _rest_loads(fl, mu, d - (1.0 if d > 0 else -1.0) * fl.S, th)[1])


def _check_contact(fl: Floor, v_stick, rep: Report, idx, slid, tau, a, b) -> None:
    """Sliding stretches, by this checker's own RK4 (all stretches at once, ≥ 1024 steps per
    floor period or 1/8 of the pendulum period 2π√(R/g_max), whichever is shorter): the
    stretch starts on the surface with relative normal speed 0 (or at rest), N ≥ 0 at every
    step before the recorded end, no event (N = 0, a cusp, v = 0 under friction) before it,
    the recorded end state is the integrated one, and the end is the event it claims: N = 0
    (and leaving with normal speed v_stick), |d| = S/2, or v = 0."""
    mu = float(getattr(fl, "mu", 0.0))
    k = np.nonzero(slid)[0]
    t_a, x_a, y_a, vx_a, vy_a, ph_a, kind_a = a[k].T
    t_b, x_b, y_b, vx_b, vy_b, ph_b, kind_b = b[k].T
    th_a, th_b = 2 * math.pi * ph_a, 2 * math.pi * ph_b
    tf = tau[k]
    vf_tol = fl.vf_tol
    # at rest: a stop, a start at rest, or a collision that ended held (no contact start)
    rest_a = (kind_a == STOP) | (kind_a == START_STUCK) | (kind_a == 0)
    q, v, d_a, un = _contact_state(fl, x_a, vx_a, vy_a, th_a, rest_a)
    # the start: a contact start, a stop or a start at rest, on the surface
    ux, uy = vx_a - fl.vxf(th_a), vy_a - fl.v(th_a)
    scale_v = math.sqrt(fl.g * (1.0 if fl.flat else fl.R)) + np.abs(v)
    # rounding, and the normal's uncertainty from the rounding δd of d (√ at a vertical cusp)
    dd = 4.0 * np.spacing(np.abs(x_a) + fl.S) + 16.0 * EPS * abs(fl.Ax)
    dn = fl.normal_error(dd)
    # the floor velocity from the recorded phase: rounding of the phase moves it by up to
    # Aω·(a few eps), largest where v_f itself is near 0 (cos ωt ≈ 0), so scale with Aω
    start_tol = 64.0 * EPS * (np.hypot(ux, uy) + fl.A * fl.w) + 2.0 * np.hypot(ux, uy) * dn
    good_kind = (kind_a == CONTACT) | rest_a
    at_rest_a = (np.abs(ux) <= vf_tol if fl.conveyor else vx_a == 0.0) & (np.abs(uy) <= vf_tol)
    bad = ~good_kind | ((kind_a == CONTACT) & (np.abs(un) > start_tol)) | (rest_a & ~at_rest_a)
    off = np.abs(y_a - fl.surface(x_a, th_a))
    y_tol = 16.0 * EPS * (np.abs(y_a) + fl.A + (0 if fl.flat else fl.R)) \
        + fl.height_error(d_a, dd)
    bad |= off > y_tol
    # from rest the kernel writes no row where it starts to slide: find that phase here, the
    # first at which the pull exceeds static friction (in a cusp: one wall's push up it
    # exceeds μN), with the normal load ≥ 0 until then (else the floor lets go first)
    th0 = th_a.copy()
    gmax = fl.g + fl.A * fl.w**2
    slip_tol = 64.0 * EPS * gmax * (1.0 + mu)
    # in a cusp: on the conveyor within CUSP_REACH (the model's rule there, as for its
    # lift-off); on the paper's floor exactly at it (to d's rounding)
    reach = CUSP_REACH * fl.S if fl.conveyor else dd
    cusp_a = ~np.full(k.size, fl.flat) & (0.5 * fl.S - np.abs(d_a) <= reach)
    for i in np.nonzero(rest_a & at_rest_a)[0]:
        th_s, arc, n_least = _slip(fl, mu, float(d_a[i]), th_a[i], th_a[i] + fl.w * tf[i],
                                     bool(cusp_a[i]), slip_tol)
        if math.isnan(th_s) or n_least < -slip_tol:
            bad[i] = True  # it slid while static friction held it, or after the floor let go
            continue
        th0[i] = th_s
        if cusp_a[i] and fl.conveyor:
            # the model's cusp: a particle within CUSP_REACH rests at the cusp point and slides
            # from there, up the wall it slips on (its own arc's end or the neighbour's)
            arc = math.copysign(0.5 * fl.S, arc)
        if arc != d_a[i]:
            d_a[i] = arc
            q[i] = math.asin(max(-1.0, min(1.0, arc / fl.R)))
    rep.flag("contact_start", bad, idx[k], np.abs(un), start_tol)
    tf = tf - (th0 - th_a) / fl.w  # the sliding part: from the slip to the recorded end
    # friction's sign is fixed over a stretch (the kernel ends one at every stop); a start
    # speed within its rounding (start_tol) of 0 has no sign of its own: the particle moves
    # the way the tangential force pulls it (at rest: F_t, downhill on the paper's arcs)
    # On the conveyor the pull is read just after the slip (2π·2⁻²⁰ rad on: at it |F_t| = μN,
    # ~0 for a tiny μN, and rounding would pick), and from a cusp it slides up the wall it
    # slipped on, towards that arc's centre
    th_f = th0 + (2 * math.pi * 2.0**-20 if fl.conveyor else 0.0)
    ft0 = _rest_loads(fl, mu, d_a, th_f)[0] if not fl.flat else -_effective_gravity(fl, th_f)[0]
    ft0 = np.where(cusp_a & rest_a & fl.conveyor, -d_a, ft0)
    sgn = np.where(np.abs(v) <= start_tol, np.where(ft0 > 0, 1.0, -1.0), np.sign(v))
    # the faster of the floor's period and the arc's pendulum period 2π√(R/g_max)
    swing = math.inf if fl.flat else 2 * math.pi * math.sqrt(fl.R / (fl.g + fl.A * fl.w**2))
    fast = min(1.0 / fl.f, swing / 8)
    periods = tf / fast
    n = int(np.clip(np.ceil(1024 * np.max(periods, initial=0.0)), 256, 50_000))
    h = tf / n
    n_min = np.full(k.size, np.inf)
    q_max = np.zeros(k.size)
    v_min = np.full(k.size, np.inf)
    th = th0.copy()
    for i in range(n):
        k1q, k1v, n0 = _contact_rates(fl, mu, q, v, th, sgn)
        if i > 0:
            n_min = np.minimum(n_min, n0)
            q_max = np.maximum(q_max, np.abs(q))
            v_min = np.minimum(v_min, sgn * v)
        k2q, k2v, _ = _contact_rates(fl, mu, q + 0.5 * h * k1q, v + 0.5 * h * k1v, th + 0.5 * fl.w * h, sgn)
        k3q, k3v, _ = _contact_rates(fl, mu, q + 0.5 * h * k2q, v + 0.5 * h * k2v, th + 0.5 * fl.w * h, sgn)
        k4q, k4v, _ = _contact_rates(fl, mu, q + h * k3q, v + h * k3v, th + fl.w * h, sgn)
        q = q + h * (k1q + 2 * k2q + 2 * k3q + k4q) / 6
        v = v + h * (k1v + 2 * k2v + 2 * k3v + k4v) / 6
        th = th + fl.w * h
    # the recorded end, on the arc it ends on (a stop or a lift-off: where it is; a cusp: ±S/2)
    rest_b = kind_b == STOP
    q_b, v_b, d_b, _ = _contact_state(fl, x_b, vx_b, vy_b, th_b, rest_b)
    if not fl.flat:
        # a stretch stays on one arc: the end (a cusp row: d = ±S/2) is on the start's arc
        # (places relative to the floor: x − x_f)
        d_b = (x_b - fl.xf(th_b)) - (x_a - fl.xf(th_a) - d_a)
        q_b = np.arcsin(np.clip(d_b / fl.R, -1.0, 1.0))
        nxb, nyb = fl.normal(d_b)
        ub_x, ub_y = vx_b - fl.vxf(th_b), vy_b - fl.v(th_b)
        v_b = np.where(rest_b, 0.0, ub_x * nyb - ub_y * nxb)
        un_b = ub_x * nxb + ub_y * nyb
    else:
        ub_x, ub_y = vx_b - fl.vxf(th_b), vy_b - fl.v(th_b)
        un_b = ub_y
    # tolerances: the kernel's integration (CONTACT_RTOL per period) and event location
    # (tol_t at the event function's rates), plus the rounding of the numbers involved
    grow = CONTACT_RTOL * (1.0 + periods)
    dt = TOL_T + 16.0 * EPS * (1.0 + tf * fl.f) / fl.f
    v_tol = grow * scale_v + gmax * (1.0 + mu) * dt + 64 * EPS * scale_v
    dd_x = 4.0 * np.spacing(np.abs(x_b) + fl.S) + 4.0 * np.spacing(np.abs(x_a) + fl.S) \
        + 32.0 * EPS * abs(fl.Ax)
    # θ read off the recorded x: rounding, ill-conditioned at a steep cusp (δθ ≤ √(2δd/R))
    q_read = 16 * EPS * (np.abs(x_b) + fl.S) if fl.flat else np.sqrt(2.0 * dd_x / fl.R) + dd_x / fl.R
    q_tol = grow + (np.abs(v) + scale_v) * dt / (1.0 if fl.flat else fl.R) + q_read
    miss = np.abs(q - q_b) > q_tol
    rep.flag("contact_path", miss | (np.abs(v - v_b) > v_tol), idx[k], np.abs(v - v_b), v_tol)
    # the least CONTACT_RTOL at which this stretch's path passes: its discrepancy in θ (rad)
    # and v (in sqrt(g R)) beyond the derived terms (event location, reading θ off x,
    # rounding), per period — the integration error CONTACT_RTOL is calibrated on
    need = np.maximum(np.abs(q - q_b) - (q_tol - grow),
                      (np.abs(v - v_b) - (v_tol - grow * scale_v)) / scale_v) / (1.0 + periods)
    rep.contact_need = max(rep.contact_need, float(np.max(need, initial=-math.inf)))
    # no event before the recorded end: N > 0, inside the arc, still moving (friction)
    n_tol = gmax * grow + (fl.A * fl.w**3 + 4 * gmax * scale_v / (1.0 if fl.flat else fl.R)) * (dt + h)
    q_c = math.inf if fl.flat else math.asin(min(0.5 * fl.S / fl.R, 1.0))
    early = (n_min < -n_tol) | (q_max > q_c + q_tol)
    if mu > 0:
        early |= v_min < -v_tol
    # a stretch of zero length (the event at its start: e.g. a particle at rest where the floor
    # lets go at once) has no inside; its end check below covers it
    early &= tf > dt
    rep.flag("contact_normal", early, idx[k], -n_min, n_tol)
    # the end is the event it claims
    n_end = _contact_rates(fl, mu, q, v, th, sgn)[2]
    n_end_tol = gmax * grow + (fl.A * fl.w**3 + 4 * gmax * scale_v / (1.0 if fl.flat else fl.R)) * dt
    ev_bad = np.zeros(k.size, bool)
    lift = kind_b == CONTACT_LIFT
    dn_b = fl.normal_error(dd_x)
    un_tol = 64 * EPS * (scale_v + fl.A * fl.w) + 2.0 * np.hypot(ub_x, ub_y) * dn_b
    ev_bad |= lift & ((n_end > n_end_tol) | (np.abs(un_b - v_stick) > un_tol))
    ev_bad |= (kind_b == CUSP) & (np.abs(np.abs(q) - q_c) > q_tol)
    still_b = np.abs(ub_x) <= vf_tol if fl.conveyor else vx_b == 0.0
    ev_bad |= rest_b & ((mu == 0) | (np.abs(v) > v_tol) | ~still_b | (np.abs(ub_y) > vf_tol))
    rep.flag("contact_event", ev_bad, idx[k], n_end, n_end_tol)


def check_run(run, particles=None, last: int | None = None, v_stick: float = V_STICK) -> Report:
    """Check the recorded events of ``particles`` (all by default) of a bbb.SimRun made with
    ``record_liftoffs=True``; ``last``: only each particle's last that many events; ``v_stick``
    the model's threshold (check_particle)."""
    if not run.liftoffs:
        raise ValueError("the trajectory checker needs simulate(..., record_liftoffs=True)")
    rep = Report()
    for i in range(run.n_particles) if particles is None else particles:
        ev = run.collisions_dense[i, : run.n_recorded[i]]
        if last is not None:
            ev = ev[-last:]
        rep.add(check_particle(run.params, ev, v_stick=v_stick))
    return rep
