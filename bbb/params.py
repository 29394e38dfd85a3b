"""Physical parameters of the bouncing ball billiard, validated on construction.

Units are the paper's reduced units: lengths in mm, times in s, so g = 9800 mm/s².
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields, replace

import numpy as np

__all__ = ["CONTACT_MODELS", "FLOORS", "GAMMA_MAX", "PARAM_RANGES", "Params", "PRESETS", "Range", "real"]

#: what a particle does in sustained contact with an arc (docs/physics.md, "Contact models"):
#: carried with the floor at fixed x (the default, today's model), frictionless sliding, or
#: sliding with Coulomb friction μ
CONTACT_MODELS = ("stick", "slide", "coulomb")
#: slide/coulomb need R ≥ S/2 · this (cusp walls ≥ 17.8° from vertical): at R = S/2 the walls
#: are vertical, where sliding contact ping-pongs between the walls without end, and just
#: above it (1 + 1e-9) the checker still flags the contact starts; 1.05 is the smallest ratio
#: the hypothesis no-miss test has covered (docs/physics.md, "Contact models")
VERTICAL_CUSP_R = 1.05
#: the floor shapes (docs/physics.md, "Floors"): the paper's circular arcs of radius R, a flat
#: floor (R = inf), a sine of top-to-valley ``depth`` and wavelength S, a sawtooth of ``depth``
#: and period S with its peak a fraction ``peak`` of S from the left valley
FLOORS = ("arc", "flat", "sine", "sawtooth")



@dataclass(frozen=True)
class Range:
    """An allowed interval of a number: ``lo`` to ``hi`` (each bound inclusive unless its
    ``*_open`` says so), in ``unit``.  Its :meth:`text` is what an error and the workflow
    reference (pipeline/README.md) say is allowed, so the bound is stated in one place."""

    lo: float
    hi: float
    unit: str = ""
    lo_open: bool = False
    hi_open: bool = False

    def __contains__(self, value: float) -> bool:
        above = value > self.lo if self.lo_open else value >= self.lo
        below = value < self.hi if self.hi_open else value <= self.hi
        return above and below

    def text(self, name: str) -> str:
        unit = f" ({self.unit})" if self.unit else ""
        if self.lo == -self.hi and not (self.lo_open or self.hi_open):
            return f"|{name}| ≤ {self.hi:g}{unit}"
        lo = f"{self.lo:g} {'<' if self.lo_open else '≤'} "
        hi = f" {'<' if self.hi_open else '≤'} {self.hi:g}"
        return f"{lo}{name}{hi}{unit}"


#: the allowed range of every numeric Params field (docs/physics.md, "Parameter ranges"):
#: wide enough for any floor the project studies (Earth's g = 9800 mm/s², the paper's
#: A = 0.1 mm, S = 2 mm, R = 15 mm, f = 40-100 Hz sit deep inside), bounded so that the
#: floor's period 1/f, ω = 2πf, its peak speed Aω and Γ = Aω²/g stay finite and far from
#: overflow and underflow.  R is also ≥ S/2 (and may be inf: a flat floor); mu > 0 only with
#: contact = "coulomb".
PARAM_RANGES: dict[str, Range] = {
    "g": Range(1.0, 1e8, "mm/s²"),
    "A": Range(0.0, 1e6, "mm"),
    "f": Range(1e-3, 1e5, "Hz"),
    "R": Range(0.0, 1e15, "mm"),
    "S": Range(1e-6, 1e6, "mm"),
    "alpha": Range(0.0, 1.0, lo_open=True),
    "beta": Range(0.0, 1.0),
    "tilt": Range(-30.0, 30.0, "degrees"),
    "throw": Range(10.0, 170.0, "degrees"),
    "mu": Range(0.0, 1e12),
    "depth": Range(0.0, 1e6, "mm"),
    "peak": Range(0.0, 1.0, lo_open=True, hi_open=True),
}
#: the largest peak floor acceleration Γ = A(2πf)²/g (in g): a particle thrown by such a
#: floor flies ~Γ/π periods, each searched in steps of at most Numerics.max_step; the paper's
#: scenes have Γ < 5, the extreme tests Γ = 29
GAMMA_MAX = 1e3


def real(owner: str, name: str, value: object) -> float:
    """``value`` as a float if it is a real number (int, float, or a numpy integer or float
    scalar; never a bool), else a ValueError naming ``owner.name`` (e.g. ``Params.f``)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer,
                                                                      np.floating)):
        raise ValueError(f"{owner}.{name} must be a real number (int or float), got "
                         f"{type(value).__name__} {value!r}")
    return float(value)


# The paper prints A = 0.01; with g = 9800 that gives Γ < 0.41 for f ≤ 100 Hz and
# nothing ever lifts off.  A = 0.1 puts Γ = 1 at f ≈ 49.8 Hz, where the paper sees
# the onset of diffusion (see docs/design.md, "Units and the amplitude").
PRESETS: dict[str, dict[str, float]] = {
    "klages2004": dict(g=9800.0, A=0.1, R=15.0, S=2.0, alpha=0.7, beta=0.99),
    "matyas2004": dict(g=9800.0, A=0.1, R=25.0, S=2.0, alpha=0.5, beta=0.99),
}


@dataclass(frozen=True)
class Params:
    """One bouncing-ball-billiard configuration.

    g     -- gravitational acceleration, mm/s² (1 ≤ g ≤ 1e8)
    A     -- floor amplitude, mm (0 ≤ A ≤ 1e6); floor height y_f(t) = -A sin(2π f t)
    f     -- floor frequency, Hz (1e-3 ≤ f ≤ 1e5)
    R     -- scatterer (arc) radius, mm (S/2 ≤ R ≤ 1e15; ``inf`` is a flat floor)
    S     -- distance between scatterer centres, mm (1e-6 ≤ S ≤ 1e6)
    alpha -- normal restitution coefficient, Eq. (5) (0 < alpha ≤ 1)
    beta  -- tangential restitution coefficient, Eq. (6) (0 ≤ beta ≤ 1)
    tilt  -- inclination φ of the floor's plane, degrees (|tilt| ≤ 30; default 0): in floor
             coordinates gravity is (−g sin φ, −g cos φ)
    throw -- angle ψ of the vibration to the floor's plane, degrees (10 ≤ throw ≤ 170;
             default 90, the paper's vertical vibration): the floor moves by
             A·(cos ψ, sin ψ)·(−sin 2πft)
    contact -- sustained-contact model: "stick" (default), "slide" or "coulomb" (also on a
             tilted or thrown floor: bbb.dynamics.contact_step); only "stick" with vertical cusp
             walls, R < S/2 · (1 + 1e-9) (sliding there never ends: Zeno)
    mu    -- Coulomb friction coefficient (0 ≤ mu ≤ 1e12; only with contact = "coulomb", else 0)
    floor -- the floor's shape (FLOORS): "arc" (default, the paper's arcs of radius R), "flat"
             (R = inf; an arc with R = inf is read as "flat"), "sine" or "sawtooth" (R does not
             apply and is held at inf; level floor and stick model only)
    depth -- top-to-valley depth of a sine or sawtooth, mm (0 < depth ≤ 1e6; else 0)
    peak  -- where a sawtooth's peak sits, as a fraction of S from its left valley
             (0 < peak < 1; 0.5 symmetric teeth; default 0.5, the only value elsewhere)

    Also Γ = A(2πf)²/g ≤ GAMMA_MAX = 1e3.  The ranges are :data:`PARAM_RANGES` (numbers may be
    Python or numpy ints and floats, never bools); a value outside raises a one-line
    ValueError naming the field, its value and the allowed range.

    ``tilt``, ``throw``, ``contact``, ``mu``, ``floor``, ``depth`` and ``peak`` are left out of
    :meth:`as_dict` at their defaults (``floor`` also when "flat": R = inf says it), so every
    store and fingerprint of a scene without them is what it was before they existed.
    """

    g: float
    A: float
    f: float
    R: float
    S: float
    alpha: float
    beta: float
    tilt: float = 0.0
    throw: float = 90.0
    contact: str = "stick"
    mu: float = 0.0
    floor: str = "arc"
    depth: float = 0.0
    peak: float = 0.5

    def __post_init__(self) -> None:
        if not isinstance(self.contact, str) or self.contact not in CONTACT_MODELS:
            raise ValueError(f"Params.contact = {self.contact!r} is not a contact model; "
                             f"allowed: {', '.join(CONTACT_MODELS)}")
        if not isinstance(self.floor, str) or self.floor not in FLOORS:
            raise ValueError(f"Params.floor = {self.floor!r} is not a floor shape; "
                             f"allowed: {', '.join(FLOORS)}")
        if self.floor != "arc":
            # flat, sine and sawtooth have no arcs: R = inf (the flat floor's own definition)
            object.__setattr__(self, "R", math.inf)
        elif isinstance(self.R, (int, float, np.integer, np.floating)) and math.isinf(self.R):
            object.__setattr__(self, "floor", "flat")
        for fl in fields(self):
            if fl.name in ("contact", "floor"):
                continue
            value = real("Params", fl.name, getattr(self, fl.name))
            object.__setattr__(self, fl.name, value)
            if math.isnan(value) or (math.isinf(value) and fl.name != "R"):
                raise ValueError(f"Params.{fl.name} = {value!r} must be finite; allowed: "
                                 f"{PARAM_RANGES[fl.name].text(fl.name)}")
        for name, rng in PARAM_RANGES.items():
            if name != "R":
                _check(name, getattr(self, name), getattr(self, name) in rng, rng.text(name))
        _check("R", self.R,
               self.S / 2 <= self.R and (self.R <= PARAM_RANGES["R"].hi or math.isinf(self.R)),
               f"S/2 = {self.S / 2:g} ≤ R ≤ {PARAM_RANGES['R'].hi:g} (mm; arcs must close the "
               "floor), or inf")
        _check("mu", self.mu, self.mu == 0 or self.contact == "coulomb",
               "mu = 0 unless contact = 'coulomb'")
        self._check_floor()
        _check("A", self.A, self.gamma <= GAMMA_MAX,
               f"Γ = A(2πf)²/g = {self.gamma:.6g} ≤ {GAMMA_MAX:g}, i.e. A ≤ "
               f"{GAMMA_MAX * self.g / self.omega**2:.6g} mm at f = {self.f:g} Hz, g = {self.g:g}")
        if self.contact != "stick" and self.R < VERTICAL_CUSP_R * self.S / 2:
            # a particle sliding down a (near-)vertical cusp wall lifts off at once (N = g cos θ
            # − v²/R ≤ 0 at θ → 90°), hits the other wall and slides again: an endless
            # ping-pong of ever shorter events (Zeno) that never settles in the cusp
            raise ValueError(f"Params.contact = {self.contact!r} with R = {self.R!r}, S = {self.S:g}: "
                             "R near S/2 makes (near-)vertical cusp walls, where sliding contact is a "
                             "Zeno ping-pong between the walls; allowed: contact = 'stick' there, "
                             f"or slide/coulomb with R ≥ S/2 · {VERTICAL_CUSP_R:g} (or inf)")

        if self.transport and self.R < VERTICAL_CUSP_R * self.S / 2:
            # a particle bouncing down between (near-)vertical walls on a tilted or thrown floor:
            # the 1e9 soak found flights below the surface there (1e-5 mm) that no fix has
            # removed yet; refused rather than computed wrong
            raise ValueError(f"Params.tilt = {self.tilt!r}, throw = {self.throw!r} with R = {self.R!r}, "
                             f"S = {self.S:g}: R near S/2 makes (near-)vertical cusp walls, which the "
                             "conveyor kernel does not handle yet; allowed: R ≥ S/2 · "
                             f"{VERTICAL_CUSP_R:g} (or inf) with tilt/throw, or tilt = 0 and throw = 90")

    def _check_floor(self) -> None:
        profiled = self.floor in ("sine", "sawtooth")
        _check("depth", self.depth, self.depth > 0 if profiled else self.depth == 0,
               "0 < depth ≤ 1e6 (mm) on a sine or sawtooth floor" if profiled
               else f"depth = 0 unless floor = 'sine' or 'sawtooth' (floor = {self.floor!r})")
        _check("peak", self.peak, self.floor == "sawtooth" or self.peak == 0.5,
               f"peak = 0.5 unless floor = 'sawtooth' (floor = {self.floor!r})")
        if profiled and (self.contact != "stick" or self.transport):
            raise ValueError(f"Params.floor = {self.floor!r} with contact = {self.contact!r}, tilt = "
                             f"{self.tilt:g}, throw = {self.throw:g}: the kernel runs a {self.floor} floor "
                             "level and vertically vibrated under the stick model only; allowed: "
                             "contact = 'stick', tilt = 0, throw = 90 there, or floor = 'arc' or 'flat'")

    @classmethod
    def preset(cls, name: str, **overrides: float | str) -> Params:
        """A named parameter set (``klages2004``, ``matyas2004``) with ``f`` and any overrides."""
        if name not in PRESETS:
            raise ValueError(f"unknown preset {name!r}; allowed: {', '.join(sorted(PRESETS))}")
        values = dict(PRESETS[name])
        unknown = set(overrides) - {fl.name for fl in fields(cls)}
        if unknown:
            raise ValueError(
                f"unknown Params field(s) {sorted(unknown)}; allowed: "
                "g, A, f, R, S, alpha, beta, tilt, throw, contact, mu, floor, depth, peak"
            )
        values.update(overrides)
        if "f" not in values:
            raise ValueError("Params.f (floor frequency, Hz) must be given, e.g. preset(name, f=60.0)")
        return cls(**values)

    def with_(self, **changes: float | str) -> Params:
        """A copy with some fields changed (validated again)."""
        return replace(self, **changes)

    @property
    def omega(self) -> float:
        """Angular frequency 2πf, 1/s."""
        return 2.0 * math.pi * self.f

    @property
    def gamma(self) -> float:
        """Dimensionless peak floor acceleration Γ = A(2πf)²/g."""
        return self.A * self.omega**2 / self.g

    @property
    def flat(self) -> bool:
        """Whether the floor is flat (floor = "flat", R = inf)."""
        return self.floor == "flat"

    @property
    def mirror_symmetric(self) -> bool:
        """Whether the floor is its own mirror image x → −x (level, vibrated vertically, and
        not a sawtooth with its peak off centre): a particle's image then moves as its
        reflection, so the mean drift is 0 by symmetry."""
        return not self.transport and (self.floor != "sawtooth" or self.peak == 0.5)

    @property
    def transport(self) -> bool:
        """Whether the floor is tilted or thrown off the vertical (the conveyor kernel runs)."""
        return self.tilt != 0.0 or self.throw != 90.0

    def floor_frame(self) -> tuple[float, float, float, float]:
        """(gx, gy, Ax, Ay): gravity's components (mm/s², pointing to −x, −y) and the floor's
        amplitudes (mm) along and normal to its plane, as bbb.dynamics.options.conveyor_frame
        computes them."""
        dev = math.radians(self.throw - 90.0)
        return (self.g * math.sin(math.radians(self.tilt)),
                self.g * math.cos(math.radians(self.tilt)),
                -self.A * math.sin(dev), self.A * math.cos(dev))

    def as_dict(self) -> dict[str, float | str]:
        """The fields; ``tilt``, ``throw``, ``contact``, ``mu``, ``depth``, ``peak`` only when they
        differ from 0, 90, stick, 0, 0, 0.5; ``floor`` only when sine or sawtooth."""
        d = asdict(self)
        if d["tilt"] == 0.0:
            del d["tilt"]
        if d["throw"] == 90.0:
            del d["throw"]
        if self.contact == "stick":
            del d["contact"]
        if self.mu == 0.0:
            del d["mu"]
        if self.floor in ("arc", "flat"):
            del d["floor"]
        if self.depth == 0.0:
            del d["depth"]
        if self.peak == 0.5:
            del d["peak"]
        return d


def _check(name: str, value: float, ok: bool, allowed: str) -> None:
    if not ok:
        raise ValueError(f"Params.{name} = {value!r} is out of range; allowed: {allowed}")
