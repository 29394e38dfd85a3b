"""Physical parameters of the bouncing ball billiard, validated on construction.

Units are the paper's reduced units: lengths in mm, times in s, so g = 9800 mm/s².
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields, replace

__all__ = ["CONTACT_MODELS", "Params", "PRESETS"]

#: what a particle does in sustained contact with an arc (docs/physics.md, "Contact models"):
#: carried with the floor at fixed x (the default, today's model), frictionless sliding, or
#: sliding with Coulomb friction μ
CONTACT_MODELS = ("stick", "slide", "coulomb")
#: slide/coulomb need R ≥ S/2 · this (cusp walls ≥ 17.8° from vertical): at R = S/2 the walls
#: are vertical, where sliding contact ping-pongs between the walls without end, and just
#: above it (1 + 1e-9) the checker still flags the contact starts; 1.05 is the smallest ratio
#: the hypothesis no-miss test has covered (docs/physics.md, "Contact models")
VERTICAL_CUSP_R = 1.05

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

    g     -- gravitational acceleration, mm/s² (> 0)
    A     -- floor amplitude, mm (≥ 0); floor height y_f(t) = -A sin(2π f t)
    f     -- floor frequency, Hz (> 0)
    R     -- scatterer (arc) radius, mm (≥ S/2; ``inf`` is a flat floor)
    S     -- distance between scatterer centres, mm (> 0)
    alpha -- normal restitution coefficient, Eq. (5) (0 < alpha ≤ 1)
    beta  -- tangential restitution coefficient, Eq. (6) (0 ≤ beta ≤ 1)
    tilt  -- inclination φ of the floor's plane, degrees (|tilt| ≤ 30; default 0): in floor
             coordinates gravity is (−g sin φ, −g cos φ)
    throw -- angle ψ of the vibration to the floor's plane, degrees (10 ≤ throw ≤ 170;
             default 90, the paper's vertical vibration): the floor moves by
             A·(cos ψ, sin ψ)·(−sin 2πft)
    contact -- sustained-contact model: "stick" (default), "slide" or "coulomb" (also on a
             tilted or thrown floor: bbb.dynamics.contact_conveyor); only "stick" with vertical cusp
             walls, R < S/2 · (1 + 1e-9) (sliding there never ends: Zeno)
    mu    -- Coulomb friction coefficient (≥ 0; only with contact = "coulomb", else 0)

    ``tilt``, ``throw``, ``contact`` and ``mu`` are left out of :meth:`as_dict` at their
    defaults, so every store and fingerprint of a scene without them is what it was before they existed.
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

    def __post_init__(self) -> None:
        if self.contact not in CONTACT_MODELS:
            raise ValueError(f"Params.contact = {self.contact!r} is not a contact model; "
                             f"allowed: {', '.join(CONTACT_MODELS)}")
        for fl in fields(self):
            if fl.name == "contact":
                continue
            value = getattr(self, fl.name)
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise ValueError(f"Params.{fl.name} must be a real number, got {value!r}")
            object.__setattr__(self, fl.name, float(value))
            if math.isnan(value) or (math.isinf(value) and fl.name != "R"):
                raise ValueError(f"Params.{fl.name} = {value!r} must be finite")
        _check("g", self.g, self.g > 0, "g > 0")
        _check("A", self.A, self.A >= 0, "A ≥ 0")
        _check("f", self.f, self.f > 0, "f > 0")
        _check("S", self.S, self.S > 0, "S > 0")
        _check("R", self.R, self.R >= self.S / 2,
               f"R ≥ S/2 = {self.S / 2:g} (arcs must close the floor), or inf")
        _check("alpha", self.alpha, 0 < self.alpha <= 1, "0 < alpha ≤ 1")
        _check("beta", self.beta, 0 <= self.beta <= 1, "0 ≤ beta ≤ 1")
        _check("tilt", self.tilt, abs(self.tilt) <= 30, "|tilt| ≤ 30 (degrees)")
        _check("throw", self.throw, 10 <= self.throw <= 170, "10 ≤ throw ≤ 170 (degrees)")
        _check("mu", self.mu, self.mu >= 0 and (self.mu == 0 or self.contact == "coulomb"),
               "mu ≥ 0, and mu = 0 unless contact = 'coulomb'")
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
            # removed yet (issue 14); refused rather than computed wrong
            raise ValueError(f"Params.tilt = {self.tilt!r}, throw = {self.throw!r} with R = {self.R!r}, "
                             f"S = {self.S:g}: R near S/2 makes (near-)vertical cusp walls, which the "
                             "conveyor kernel does not handle yet; allowed: R ≥ S/2 · "
                             f"{VERTICAL_CUSP_R:g} (or inf) with tilt/throw, or tilt = 0 and throw = 90")

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
                "g, A, f, R, S, alpha, beta, tilt, throw, contact, mu"
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
        return math.isinf(self.R)

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
        """The fields; ``tilt``, ``throw``, ``contact``, ``mu`` only when they differ from 0, 90,
        stick, 0."""
        d = asdict(self)
        if d["tilt"] == 0.0:
            del d["tilt"]
        if d["throw"] == 90.0:
            del d["throw"]
        if self.contact == "stick":
            del d["contact"]
        if self.mu == 0.0:
            del d["mu"]
        return d


def _check(name: str, value: float, ok: bool, allowed: str) -> None:
    if not ok:
        raise ValueError(f"Params.{name} = {value!r} is out of range; allowed: {allowed}")
