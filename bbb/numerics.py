"""Numerical knobs of the collision map: what trades computing time for accuracy."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields, replace

from .params import Range, real

__all__ = ["NUMERICS_RANGES", "Numerics"]

#: the allowed range of every knob (docs/physics.md, "Parameter ranges"): a tolerance finer
#: than 1e-18 s is below the rounding of any floor time; a sticking speed above 10 mm/s ends
#: real bounces as "creeping" (the paper's impact speeds are 10-400 mm/s); a first step
#: below 1e-3 period makes every flight cost over 1000 search steps per period it lasts
NUMERICS_RANGES: dict[str, Range] = {
    "tol_t": Range(1e-18, 1e-6, "s"),
    "v_stick": Range(1e-12, 10.0, "mm/s"),
    "max_step": Range(1e-3, 1.0, "floor periods"),
}


@dataclass(frozen=True)
class Numerics:
    """Accuracy settings of the kernel.

    tol_t    -- root-finding tolerance on the collision time, s (Newton stops when its
                step is below it).  Default 1e-12 s; 1e-18 ≤ tol_t ≤ 1e-6.
    v_stick  -- sticking threshold, mm/s: a collision whose outgoing relative normal
                speed is below this ends a creeping cascade; the particle is then
                carried with the floor (x fixed) until the floor accelerates downward
                faster than g.  Default 1e-3 mm/s; 1e-12 ≤ v_stick ≤ 10.
    max_step -- largest bracketing step of the certified collision search, in floor
                periods.  The search is exact for any step (every step is certified
                by a curvature bound); this only caps the first trial step.
                Default 0.25; 1e-3 ≤ max_step ≤ 1.

    Numbers may be Python or numpy ints and floats, never bools; a value outside its range
    (:data:`NUMERICS_RANGES`) raises a one-line ValueError naming the knob, its value and the
    range.
    """

    tol_t: float = 1e-12
    v_stick: float = 1e-3
    max_step: float = 0.25

    def __post_init__(self) -> None:
        for fl in fields(self):
            value = real("Numerics", fl.name, getattr(self, fl.name))
            object.__setattr__(self, fl.name, value)
            rng = NUMERICS_RANGES[fl.name]
            if not math.isfinite(value) or value not in rng:
                raise ValueError(f"Numerics.{fl.name} = {value!r} is out of range; allowed: "
                                 f"{rng.text(fl.name)}")

    def with_(self, **changes: float) -> Numerics:
        return replace(self, **changes)

    def as_dict(self) -> dict[str, float]:
        return asdict(self)
