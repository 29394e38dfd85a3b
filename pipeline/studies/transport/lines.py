"""The transport maps' lines: the floors (tilt φ, throw ψ) of the map ``transport``, the contact
models of ``transport_sliding``, and the lines each claim reads (:mod:`.claims`); the lines of
``transport_reversal`` are :mod:`.reversal`'s.  Angles in degrees."""

from __future__ import annotations

from .reversal import REVERSAL_LINES, REVERSAL_MAP

__all__ = ["MAP", "SLIDING_MAP", "SCENES", "GEOMETRY", "COMBINED_GEOMETRY", "HOPPING", "COMBINED",
           "CONVEYORS", "LABELS", "SLIDING_GEOMETRY", "SLIDING", "SLIDING_LABELS", "LINES",
           "GEOMETRIES"]

#: the map scenes: tilt x throw (hopping), and the sliding floor's contact x mu
MAP, SLIDING_MAP = "transport", "transport_sliding"
SCENES = (MAP, SLIDING_MAP, REVERSAL_MAP)
#: (line, tilt φ °, throw ψ °) of the map judged by the claims; the first one is the paper's
#: symmetric floor.  A line's name keys its tables (``<line>_diffusion``, :func:`line_tables`)
GEOMETRY = (("transport_t0", 0.0, 90.0), ("transport_t2", 2.0, 90.0),
            ("transport_t5", 5.0, 90.0), ("transport_p60", 0.0, 60.0),
            ("transport_p30", 0.0, 30.0))
#: the map's other lines, floors both tilted and thrown: judged by T3b only (the registered T3,
#: T1, T2 and T4 read the five floors above)
COMBINED_GEOMETRY = (("transport_t2_p60", 2.0, 60.0), ("transport_t2_p30", 2.0, 30.0),
                     ("transport_t5_p60", 5.0, 60.0), ("transport_t5_p30", 5.0, 30.0))
HOPPING = tuple(s for s, _, _ in GEOMETRY)
COMBINED = tuple(s for s, _, _ in COMBINED_GEOMETRY)
CONVEYORS = HOPPING[1:]
LABELS = {s: f"φ = {t:g}°, ψ = {p:g}°" for s, t, p in GEOMETRY + COMBINED_GEOMETRY}
#: the sliding regime: one floor (level, thrown at ψ = 30°, the paper's arcs) from low Γ to
#: above lift-off, under (line, contact model, μ)
SLIDING_GEOMETRY = {"tilt": 0.0, "throw": 30.0}
SLIDING = (("transport_sliding_stick", "stick", 0.0),
           ("transport_sliding_coulomb", "coulomb", 0.3))
SLIDING_LABELS = {"transport_sliding_stick": "stick",
                  "transport_sliding_coulomb": "Coulomb, μ = 0.3"}
#: {line: its grid values} of the maps transport and transport_sliding (transport_reversal's:
#: reversal.REVERSAL_LINES)
LINES = {**{s: {"tilt": t, "throw": p} for s, t, p in GEOMETRY + COMBINED_GEOMETRY},
         **{s: {"contact": c, "mu": mu} for s, c, mu in SLIDING}}
#: {line: its floor and driving (tilt, throw; contact, mu where the map has them)}: the
#: conveyor lines claim T3 judges (every line of the maps transport and transport_reversal but
#: the mirror-symmetric φ = 0°, ψ = 90°)
GEOMETRIES = {**{s: {"tilt": t, "throw": p} for s, t, p in GEOMETRY[1:] + COMBINED_GEOMETRY},
              **REVERSAL_LINES}
