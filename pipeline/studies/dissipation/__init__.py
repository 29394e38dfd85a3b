"""D(f, α): the diffusion coefficient over vibration frequency and normal restitution, from rest
at the paper's arcs (``scenes/dissipation.toml``, a map refined along f and α), with the
spiral's locking lines k_max = integer from post-collision states on the same grid
(``scenes/dissipation_locking.toml``), and a small map on Mátyás & Klages' arcs (R = 25 mm,
``scenes/dissipation_r25.toml``) whose α = 0.5 line is compared with their Fig. 2, and the
map's α = 0.7 line run with a seed of its own (``scenes/dissipation_own_seeds.toml``), compared
with the paper's Fig. 2.  The
figures (``figures``), the claims as data (``claims``: the onset against the flat-floor
thresholds Γ₁, Γ', the first maximum and the loops against α, where ergodicity breaks, the
cuts against the committed Fig. 2 curves), read off the map's judged lines (``lines``).

The study record: :data:`STUDY`.
"""

from ...claims.section import Section
from ..interface import Study
from .claims import CLAIMS
from .figures import CAPTIONS
from .report import SCENES, WORDS, context, draw, facts

STUDY = Study(
    name="dissipation",
    scenes=SCENES,
    section=Section("D(f, α): dissipation (scenes dissipation, dissipation_locking, "
                    "dissipation_r25)", WORDS, prefix="A"),
    claims=tuple(CLAIMS),
    context=context,
    draw=draw,
    reads=("dissipation_diffusion", "dissipation_locking_locking", "dissipation_cuts",
           "dissipation_r25_diffusion"),
    captions=CAPTIONS,
    facts=facts,
)

__all__ = ["STUDY"]
