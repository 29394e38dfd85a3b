"""Basins and transients near the onset of diffusion: the state each particle of a grid of
initial conditions reaches on the paper's floor (the ``states`` observable and its calibrated
classifier, bbb.analysis.states), from the scene ``scenes/basins.toml``: its tables
(``tables``: shares, lifetimes, escape rates, basin entropy, D_mix), its figures
(``figures``), claim B1 as data (``claims``) and the study record (:data:`STUDY`).

Built only through the study interface (:mod:`pipeline.studies.interface`): a folder, and its
name in :data:`pipeline.studies.registry.STUDIES`.
"""

from ...claims.section import Section
from ..interface import Study
from .claims import CLAIMS, context
from .figures import CAPTIONS, draw
from .report import WORDS, facts, further
from .tables import SCENE, make_tables

FILES = {k: f"basins_{k}.csv" for k in ("states", "shares", "dmix", "peak", "entropy")}

STUDY = Study(
    name="basins",
    scenes=(SCENE,),
    section=Section("Basins and transients near onset: what each initial condition ends in, "
                    "and D as a mixture of the states (scene basins)", WORDS, prefix="B"),
    claims=tuple(CLAIMS),
    context=context,
    draw=draw,
    reads=("peak", "states", "entropy"),
    captions=CAPTIONS,
    make_tables=make_tables,
    files=FILES,
    facts=facts,
    further=further,
)

__all__ = ["STUDY"]
