"""Contact models (issue 13): D(f) and the time held and sliding near onset (46–62 Hz) under
``stick``, ``slide``, ``coulomb`` μ = 0.05 and μ = 0.3, D(f) at 58–99 Hz under stick, slide
and μ = 0.3, and the 54 Hz (y, v_y⁺) projection per model, from the scenes ``scenes/*.toml``:
the figures (``figures``) and the paper's claims 1–4 and 16 per model as data (``claims``).

The interface make_figures uses: :data:`SCENES`, :func:`draw`, :func:`report_lines`.
"""

from .claims import CLAIMS, SCENES, report_lines
from .figures import draw

__all__ = ["SCENES", "CLAIMS", "draw", "report_lines"]
