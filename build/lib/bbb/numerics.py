"""Numerical knobs of the collision map: what trades computing time for accuracy."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields, replace

__all__ = ["Numerics"]


@dataclass(frozen=True)
class Numerics:
    """Accuracy settings of the kernel.

    tol_t    -- root-finding tolerance on the collision time, s (Newton stops when its
                step is below it).  Default 1e-12 s.
    v_stick  -- sticking threshold, mm/s: a collision whose outgoing relative normal
                speed is below this ends a creeping cascade; the particle is then
                carried with the floor (x fixed) until the floor accelerates downward
                faster than g.  Default 1e-3 mm/s.
    max_step -- largest bracketing step of the certified collision search, in floor
                periods.  The search is exact for any step (every step is certified
                by a curvature bound); this only caps the first trial step.
                Default 0.25.
    """

    tol_t: float = 1e-12
    v_stick: float = 1e-3
    max_step: float = 0.25

    def __post_init__(self) -> None:
        for fl in fields(self):
            value = getattr(self, fl.name)
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise ValueError(f"Numerics.{fl.name} must be a real number, got {value!r}")
            object.__setattr__(self, fl.name, float(value))
            if not math.isfinite(value) or value <= 0:
                raise ValueError(f"Numerics.{fl.name} = {value!r} is out of range; allowed: finite and > 0")
        if self.tol_t > 1e-6:
            raise ValueError(f"Numerics.tol_t = {self.tol_t!r} is out of range; allowed: 0 < tol_t ≤ 1e-6 s")
        if self.max_step > 1.0:
            raise ValueError(
                f"Numerics.max_step = {self.max_step!r} is out of range; allowed: 0 < max_step ≤ 1 period"
            )

    def with_(self, **changes: float) -> Numerics:
        return replace(self, **changes)

    def as_dict(self) -> dict[str, float]:
        return asdict(self)
