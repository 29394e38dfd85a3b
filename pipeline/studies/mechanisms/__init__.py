"""Why D(f) is irregular: the Taylor–Green–Kubo expansion of D (memory) and which part of it
makes each extremum, and the largest Lyapunov exponent (chaos) of the particles that move,
along f, with the creeping fraction, from the scene ``workflows/mechanisms.toml``: its figure
(``figures``), its claims as data (``claims``) and the study record (:data:`STUDY`).
"""

from ...claims.section import Section
from ..interface import Study
from .claims import CLAIMS, WORDS, context
from .figures import CAPTIONS, draw
from .lyapunov_table import lyapunov_lines

STUDY = Study(
    name="mechanisms",
    scenes=("mechanisms",),
    section=Section("Mechanisms: which part of D makes the extrema, and chaos where particles "
                    "move (scene mechanisms)", WORDS, prefix="M"),
    claims=tuple(CLAIMS),
    context=context,
    draw=draw,
    reads=("mechanisms", "mechanisms_diffusion"),
    captions=CAPTIONS,
    further=lambda tables, verdicts: lyapunov_lines(tables.get("mechanisms")),
)

__all__ = ["STUDY"]
