"""Ratchet transport without tilt: the drift v over (sawtooth peak position p, restitution α,
f) on a level, vertically vibrated sawtooth floor, from the map scene ``scenes/ratchet.toml``:
the claims as data (``claims``, their synthetic cases in ``cases``), what the collisions do at
each current reversal and the tilted conveyor's reversals beside them (``mechanism``), the
states the particles reach there (``reversal_states``, scene ``scenes/ratchet_states.toml``), the
figures (``figures``), the section's words (``report``) and the study record (:data:`STUDY`).

Built only through the study interface (:mod:`pipeline.studies.interface`): a folder, and its
name in :data:`pipeline.studies.registry.STUDIES`.
"""

from ...claims.section import Section
from ..interface import Study
from .claims import CLAIMS, SCENE, TABLE, context
from .figures import CAPTIONS, draw
from .mechanism import STATES_TABLE
from .report import WORDS, facts, further
from .reversal_states import STATES_SCENE

STUDY = Study(
    name="ratchet",
    scenes=(SCENE, STATES_SCENE),
    section=Section("Ratchet transport on a level sawtooth floor (scenes ratchet, "
                    "ratchet_states)", WORDS,
                    prefix="R"),
    claims=tuple(CLAIMS),
    context=context,
    draw=draw,
    reads=(TABLE, f"{SCENE}_impacts", f"{SCENE}_counters", f"{SCENE}_reversals",
           f"{SCENE}_conveyor", STATES_TABLE),
    captions=CAPTIONS,
    facts=facts,
    further=further,
)

__all__ = ["STUDY"]
