"""Contact models: D(f) and the time held and sliding near onset (46–62 Hz) under ``stick``,
``slide``, ``coulomb`` μ = 0.05 and μ = 0.3, D(f) from rest at 46–99 Hz under each, and the
54 Hz (y, v_y⁺) projection per model, from the map scenes ``scenes/contact.toml`` and
``scenes/contact_proj.toml`` (contact × μ, one grid line per model): the figures
(``figures``) and the paper's claims 1–4 and 16 per model (records of the claims registry,
``claims``), which read each model's line (``claims.line_tables``).

The study record: :data:`STUDY`.
"""

from ...claims.section import Section
from ..interface import Study
from .claims import CLAIMS, LEAD, SCENES, WORDS, paragraph, verdicts
from .figures import CAPTIONS, draw

STUDY = Study(
    name="contact",
    scenes=SCENES,
    section=Section("Contact models: the onset claims under stick, slide and Coulomb friction",
                    WORDS, layout="by claim", lead=LEAD),
    claims=tuple(CLAIMS),
    draw=draw,
    reads=("contact_diffusion", "contact_contact", "contact_proj_locking",
           "contact_proj_contact"),
    captions=CAPTIONS,
    verdicts=verdicts,
    further=paragraph,
    labels=tuple(c.text for c in CLAIMS),
)

__all__ = ["STUDY"]
