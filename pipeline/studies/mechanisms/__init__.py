"""Why D(f) is irregular: the Taylor–Green–Kubo expansion of D (memory) and which part of it
makes each extremum, and the largest Lyapunov exponent (chaos) of the particles that move,
along f, with the creeping fraction, from the scene ``workflows/mechanisms.toml``: its figure
(``figures``) and its claims as data (``claims``).

The interface make_figures uses: :data:`SCENES`, :func:`draw`, :data:`CAPTIONS`,
:func:`report_lines`.
"""

from .claims import CLAIMS, report_lines
from .figures import CAPTIONS, draw

#: the scenes this study runs
SCENES = ("mechanisms",)

__all__ = ["SCENES", "CLAIMS", "CAPTIONS", "draw", "report_lines"]
