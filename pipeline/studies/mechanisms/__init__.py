"""Why D(f) is irregular (issue 15): the Taylor–Green–Kubo expansion of D (memory) and the
largest Lyapunov exponent (chaos) along f, with the creeping fraction, from the scene
``workflows/mechanisms.toml``: its figure (``figures``) and its claims as data (``claims``).

The interface make_figures uses: :data:`SCENES`, :func:`draw` and :data:`CLAIMS`.
"""

from .claims import CLAIMS, report_lines
from .figures import draw

#: the scenes this study runs
SCENES = ("mechanisms",)

__all__ = ["SCENES", "CLAIMS", "draw", "report_lines"]
