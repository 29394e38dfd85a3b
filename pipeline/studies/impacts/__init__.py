"""The impact phase: where in the floor's period the particles hit the paper's floor and how
long their horizontal velocity remembers a collision, along f, from the scene
``scenes/impacts.toml`` (the ``impacts`` observable): its figures (``figures``), its claims as
data (``claims``, their synthetic cases in ``cases``) and the study record (:data:`STUDY`).

Built only through the study interface (:mod:`pipeline.studies.interface`): a folder, and its
name in :data:`pipeline.studies.registry.STUDIES`.
"""

from ...claims.section import Section
from ..interface import Study
from .claims import CLAIMS, SCENE, context
from .figures import CAPTIONS, draw
from .report import WORDS, facts

STUDY = Study(
    name="impacts",
    scenes=(SCENE,),
    section=Section("The impact phase: floor phase at the collisions and vx memory across them "
                    "(scene impacts)", WORDS, prefix="I"),
    claims=tuple(CLAIMS),
    context=context,
    draw=draw,
    reads=(SCENE,),
    captions=CAPTIONS,
    facts=facts,
)

__all__ = ["STUDY"]
