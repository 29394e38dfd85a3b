"""Contact models: D(f) and the time held and sliding near onset (46–62 Hz) under ``stick``,
``slide``, ``coulomb`` μ = 0.05 and μ = 0.3, D(f) from rest at 46–99 Hz under each, and the
54 Hz (y, v_y⁺) projection per model, from the map scenes ``scenes/contact.toml`` and
``scenes/contact_proj.toml`` (contact × μ, one grid line per model): the figures
(``figures``) and the paper's claims 1–4 and 16 per model as data (``claims``), which read
each model's line (``claims.line_tables``).

The interface make_figures uses: :data:`SCENES`, :func:`draw`, :func:`report_lines` and
:data:`CAPTIONS`.
"""

from .claims import CLAIMS, SCENES, report_lines
from .figures import CAPTIONS, draw

__all__ = ["SCENES", "CLAIMS", "CAPTIONS", "draw", "report_lines"]
