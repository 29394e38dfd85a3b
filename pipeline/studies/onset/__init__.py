"""Why motion starts: two no-fit predictions of the onset of motion from rest -- (a) the
horizontal instability of the vertical motion at the rest point, (b) the end of the
chattering cycle -- tested on a D(f, R) map of the arcs (``scenes/onset_map.toml``) and on the
sine floor (``scenes/onset_sine.toml``): the predictions (``predictions``, from
:mod:`bbb.analysis.onset_theory`), the maps read line by line (``lines``), the claims as
data (``claims``, their synthetic cases in ``cases``) and the study record (:data:`STUDY`).

Built only through the study interface (:mod:`pipeline.studies.interface`): a folder, and its
name in :data:`pipeline.studies.registry.STUDIES`.
"""

from ...claims.section import Section
from ..interface import Study
from .claims import CLAIMS, MAP, SINE, context
from .figures import CAPTIONS, draw
from .report import WORDS, facts, further

STUDY = Study(
    name="onset",
    scenes=(MAP, SINE),
    section=Section("Why motion starts: the onset from rest against two no-fit predictions "
                    "(scenes onset_map, onset_sine)", WORDS, prefix="O"),
    claims=tuple(CLAIMS),
    context=context,
    draw=draw,
    captions=CAPTIONS,
    reads=(f"{MAP}_diffusion", f"{SINE}_diffusion"),
    facts=facts,
    further=further,
)

__all__ = ["STUDY"]
