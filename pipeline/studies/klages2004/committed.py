"""The paper's tables beside ``REPORT.md`` (the CSV file each is written to), the words of its
claims section, and the claims whose measure reads a store.

The report is written from the tables read back from these files
(:mod:`pipeline.tables.files`), so that every claims section is a function of committed files
(``python -m pipeline.studies.report`` regenerates them).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

__all__ = ["TABLE_FILES", "CLAIMS_HEADING", "CLAIMS_INTRO", "NEEDS_STORES", "figure2_params"]

#: this study's tables (as write_report reads them) -> the CSV beside REPORT.md
TABLE_FILES = {"figure2": "diffusion_figure2.csv", "ergodicity": "diffusion_ergodicity.csv",
               "figure2_matyas2004": "diffusion_figure2_matyas2004.csv",
               "finescale": "diffusion_finescale.csv", "locking": "locking.csv",
               "locking_matyas2004": "locking_matyas2004.csv",
               # the protocol study's verdicts (pipeline.studies.protocol), read by claim 2's note
               "protocol_verdicts": "protocol_verdicts.csv"}
#: the heading of this study's claims section in REPORT.md, and the paragraph under it
CLAIMS_HEADING = "Claims"
CLAIMS_INTRO = (
    "Each measured number carries its 95 % CI; each claim is judged against the tolerance "
    "band in the 'judged by' column, with the reason for its width. Verdicts: **agrees** "
    "(the whole CI inside the band), **agrees within the CI** (the value inside, the CI "
    "reaching beyond an edge: the verdict flips inside the CI), **inconclusive** (the "
    "value outside, the CI reaching in), **disagrees** (the whole CI outside, or the "
    "feature not found), **partly** (some parts agree, or only a curve other than the "
    "claim's main one), **not measured** (a table missing; for a rule stated over all its "
    "parts, a part missing). Two kinds of row are never agrees or disagrees: **consistent** / "
    "**inconsistent** (a result compared with itself, e.g. runs sharing seeds and chunks: a "
    "check of the pipeline, not a test of the paper) and **by construction** (true by the "
    "design of the ensemble). A quantity shown with '(no CI)' is judged by its value alone. "
    "⚠ marks a D that depends on the run length (stationarity below). Every claim is "
    "registered with its id, rule, scope and commit (pipeline/studies/registry.py); once "
    "judged its rule and scope are frozen, and a changed rule or widened scope is a new id "
    "(T3 → T3b) judged beside the old one.")
#: claims whose measure reads a store, not a committed table, and why: regenerated from the
#: committed tables alone their rows are kept from the report the stores wrote
NEEDS_STORES = {
    "klages2004.spiral_approx": (
        "claim 15 reads the post-collision states of the figure3 and locking stores (distances "
        "of every state to the curve of Eqs. (8)-(9)), which are not committed; its measure "
        "(pipeline/studies/klages2004/measures.py) would have to read a table of those "
        "distances instead"),
}


def figure2_params(stores: Mapping[str, str] | None = None, fast: bool = False
                   ) -> tuple[float | None, dict | None]:
    """(f at Γ = 1 in Hz, the parameters as a dict) of the Fig. 2 scene: from its store when
    one is given, else from the scene file (the same parameters); (None, None) if A = 0."""
    if stores and stores.get("figure2"):
        from ...tables.collisions import as_store

        p = as_store(stores["figure2"]).study.params(60.0)
    else:
        from ...workflow.scenes import load_scene

        p = load_scene("figure2", fast).params(60.0)
    if not p.A > 0:
        return None, None
    return math.sqrt(p.g / p.A) / (2 * math.pi), p.as_dict()


