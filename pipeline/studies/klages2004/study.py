"""The paper's study as the registry sees it (:data:`STUDY`): its scenes, the tables its claims
read (its own file names, :data:`~.committed.TABLE_FILES`), its figures and captions, its claims
and its REPORT.md section (the claims table under the words :data:`~.committed.CLAIMS_INTRO`,
then the extrema, stationarity, ergodicity, locking and definitions of :mod:`.report`)."""

from __future__ import annotations

import functools
from collections.abc import Callable, Mapping
from pathlib import Path

import pandas as pd

from ...claims.section import Section
from ..interface import Study
from .claims import CLAIMS, context
from .committed import CLAIMS_HEADING, CLAIMS_INTRO, NEEDS_STORES, TABLE_FILES, figure2_params
from .report import CAPTIONS, further_lines
from .scene_list import SCENES

__all__ = ["STUDY", "make_tables", "draw", "judged_in"]

#: the scenes whose diffusion table its claims read, and those whose locking table
DIFFUSION = ("figure2", "ergodicity", "figure2_matyas2004", "finescale")
LOCKING = ("locking", "locking_matyas2004")


def make_tables(stores: Mapping[str, str], echo: Callable[[str], None] = print
                ) -> dict[str, pd.DataFrame]:
    """The diffusion tables of :data:`DIFFUSION` (bbb reduce's) and the locking tables of
    :data:`LOCKING`, keyed by scene."""
    from ...tables.collisions import locking_table
    from ...tables.reduce import reduce_store

    out = {name: reduce_store(stores[name], echo=echo)["diffusion"] for name in DIFFUSION}
    out.update((name, locking_table(stores[name])) for name in LOCKING)
    return out


def draw(tables: dict[str, pd.DataFrame], stores: Mapping[str, str], out_dir) -> list[Path]:
    """Figs. 1-3, k(f), the R = 25 Fig. 2 and the fine scales into ``out_dir``; adds the fine
    scales' extrema table (``finescale_extrema``, written beside the others)."""
    from .figures import figure1, figure2, figure3, figure_files, figure_locking
    from .finescale import figure_finescale
    from .finescale import write_table as write_finescale

    out = Path(out_dir)
    figs = [
        figure1(stores["locking"], None, out),
        figure2(stores["figure2"], {"diffusion": tables["figure2"],
                                       "ergodicity": tables["ergodicity"]}, out),
        figure3([stores["figure3"], stores["locking"]], None, out),
        figure_locking(stores["locking"], {"locking": tables["locking"]}, out),
        figure2(stores["figure2_matyas2004"],
                   {"diffusion": tables["figure2_matyas2004"],
                    "locking": tables["locking_matyas2004"]},
                   out, name="fig2_matyas2004", letters=None, inset=None,
                   legend_loc="upper left"),
        figure_finescale(tables["finescale"], out),
    ]
    write_finescale(tables["finescale"], out)
    return [p for fig in figs for p in figure_files(out, fig.get_label())]


@functools.cache
def _scene_params() -> tuple[float | None, dict | None]:
    return figure2_params(None)


def judged_in(tables: Mapping[str, pd.DataFrame], stores: Mapping[str, str]) -> dict:
    """The context of the paper's claims, with the Fig. 2 scene's parameters for the notes
    (from its store when there is one, else from its scene file, read once)."""
    f_gamma1, params = figure2_params(stores) if stores.get("figure2") else _scene_params()
    return context(tables, stores, f_gamma1, None if params is None else dict(params))


STUDY = Study(
    name="klages2004",
    scenes=SCENES,
    section=Section(CLAIMS_HEADING, CLAIMS_INTRO, claim_header="the paper says", summary=True),
    claims=tuple(CLAIMS),
    context=judged_in,
    draw=draw,
    reads=tuple(TABLE_FILES),
    captions=CAPTIONS,
    make_tables=make_tables,
    files=TABLE_FILES,
    further=further_lines,
    needs_stores=NEEDS_STORES,
)
