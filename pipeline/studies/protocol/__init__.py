"""The measuring protocol behind the paper's D(f) near onset: D at 46–62 Hz per initial
ensemble (rest; dropped from two height ranges; launched at two speed ranges; their mixture)
× analysis run length T (the first 5, 10, 20, 50 s of each run) × averaging (all particles;
the moving ones under the two definitions of :mod:`bbb.analysis.moving`), from the scene
``scenes/protocol.toml``: the table (``tables``), the paper's claims 1, 2, 4, 5 and 16
re-judged per protocol (``claims``), the figures (``figures``) and the report section with
its generated paragraph (``report``).

The study record: :data:`STUDY`.
"""

from ..interface import Study
from .claims import CURVE_CLAIMS, ERGODIC_CLAIM, SCENES
from .figures import CAPTIONS, draw
from .report import LABELS, SECTION, further, verdicts

STUDY = Study(
    name="protocol",
    scenes=SCENES,
    section=SECTION,
    claims=(*CURVE_CLAIMS.values(), ERGODIC_CLAIM),
    draw=draw,
    reads=("protocol_verdicts", "protocol_curves"),
    captions=CAPTIONS,
    verdicts=verdicts,
    further=further,
    labels=LABELS,
)

__all__ = ["STUDY"]
