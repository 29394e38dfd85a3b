"""Transport on a vibro-conveyor: drift v(f) and D(f) about the drift at the paper's
parameters for a tilted floor (φ = 0°, 2°, 5°, vertical throw), an oblique throw (ψ = 60°,
30°, level floor) and both at once, from the map scene ``scenes/transport.toml`` (tilt ×
throw, one grid line per floor), and the sliding regime below lift-off on one floor under the
stick and Coulomb contact models (the map ``scenes/transport_sliding.toml``, one line per
model), and the transport map ``scenes/transport_reversal.toml``: v over (throw ψ, f) on a
floor tilted 2° against its throw, under stick and Coulomb friction, from below lift-off into
hopping, with the share of the run in flight (``reversal``: where v changes sign along f and
along ψ, each change located as an interval, and the sliding/hopping boundary against
conveyor theory's throw number Γ_v = Γ sin ψ / cos φ = 1, its threshold checked on flat
floors by ``hopping_calibration``).  The figures (``figures``) and the claims as data
(``claims``, the sign rules in :mod:`pipeline.claims.signs`) read each line's table
(``claims.line_tables``).

The study record: :data:`STUDY`.
"""

from ...claims.section import Section
from ..interface import Study
from .claims import CLAIMS, SCENES, WORDS, context, sliding_liftoff
from .figures import CAPTIONS, draw

STUDY = Study(
    name="transport",
    scenes=SCENES,
    section=Section("Transport on a vibro-conveyor (scenes transport, transport_sliding, "
                    "transport_reversal)", WORDS, prefix="T"),
    claims=tuple(CLAIMS),
    context=context,
    draw=draw,
    reads=tuple(f"{s}_{t}" for s in SCENES for t in ("diffusion", "contact", "counters")),
    captions=CAPTIONS,
    facts=lambda tables, verdicts: {"liftoff": sliding_liftoff()},
)

__all__ = ["STUDY"]
