"""Transport on a vibro-conveyor (issue 14): drift v(f) and D(f) about the drift at the
paper's parameters for a tilted floor (φ = 0°, 2°, 5°, vertical throw) and an oblique throw
(ψ = 60°, 30°, level floor), from the scenes ``scenes/transport_*.toml`` (one per (φ, ψ)),
and the sliding regime below lift-off on one floor under the stick and Coulomb contact models
(``scenes/transport_sliding_*.toml``, issue 13): the figures (``figures``) and the claims as
data (``claims``).

The interface make_figures uses: :data:`SCENES`, :func:`draw`, :func:`report_lines`.
"""

from .claims import CLAIMS, SCENES, report_lines
from .figures import CAPTIONS, draw

__all__ = ["SCENES", "CLAIMS", "CAPTIONS", "draw", "report_lines"]
