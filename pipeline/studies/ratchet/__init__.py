"""Ratchet transport without tilt: the drift v over (sawtooth peak position p, restitution α,
f) on a level, vertically vibrated sawtooth floor, from the map scene ``scenes/ratchet.toml``:
the claims as data (``claims``, their synthetic cases in ``cases``) and the study record
(:data:`STUDY`).

Built only through the study interface (:mod:`pipeline.studies.interface`): a folder, and its
name in :data:`pipeline.studies.registry.STUDIES`.
"""

from ...claims.section import Section
from ..interface import Study
from .claims import CLAIMS, SCENE, TABLE, context

WORDS = ("Drift v with its bootstrap CI (bbb.analysis.transport) over the sawtooth's peak "
         "position p and α along f, particles from rest, independent (no mirror pairs); "
         "pipeline/studies/ratchet/claims.py states the rules.")

STUDY = Study(
    name="ratchet",
    scenes=(SCENE,),
    section=Section("Ratchet transport on a level sawtooth floor (scene ratchet)", WORDS,
                    prefix="R"),
    claims=tuple(CLAIMS),
    context=context,
    reads=(TABLE,),
)

__all__ = ["STUDY"]
