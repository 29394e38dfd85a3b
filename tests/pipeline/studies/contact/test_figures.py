"""The contact figures are drawn as real PNG + PDF files, with no text drawn over text."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pipeline.studies.contact.claims import MODELS
from pipeline.studies.contact.figures import draw, figure_contact, figure_contact_high

from ...text_overlap import overlaps
from .test_claims import F, _paper_like, _table


def _contact(f: np.ndarray, held: float, slide: float) -> pd.DataFrame:
    rows = []
    for fam in ("rest", "launched"):
        for x in f:
            h, s = held * (x < 58), slide * (x < 58)
            rows.append({"f": x, "family": fam, "held_frac": h, "held_frac_lo": 0.9 * h,
                         "held_frac_hi": 1.1 * h, "slide_frac": s, "slide_frac_lo": 0.9 * s,
                         "slide_frac_hi": 1.1 * s})
    return pd.DataFrame(rows)


def _inputs():
    rng = np.random.default_rng(0)
    f = np.concatenate([F, np.arange(63.0, 100.0)])
    D = _paper_like(f)
    tables = {m: (_table(D * (1 + 0.1 * i), D, f=f), _contact(f, 0.4 - 0.1 * i, 0.1 * i))
              for i, m in enumerate(MODELS)}
    proj = {m: {"y": rng.normal(0, 0.05, (4, 200)), "vy": rng.uniform(0, 120, (4, 200))}
            for m in MODELS}
    proj["coulomb03"] = None  # a model without its projection store
    return tables, proj


def test_the_contact_figure_draws_all_panels_without_overlapping_text(tmp_path):
    tables, proj = _inputs()
    fig = figure_contact(tables, proj, tmp_path)
    assert overlaps(fig) == []
    assert len(fig.axes) == 2 + len(MODELS)
    assert all((tmp_path / f"fig_contact.{ext}").stat().st_size > 1000 for ext in ("png", "pdf"))


def test_the_full_range_figure_draws_without_overlapping_text(tmp_path):
    tables, _ = _inputs()
    fig = figure_contact_high({m: d for m, (d, _c) in tables.items()}, tmp_path)
    assert overlaps(fig) == []
    assert len(fig.axes[0].lines) > 0


def test_draw_writes_both_figures_from_the_maps_reduce_tables_without_stores(tmp_path):
    from pipeline.studies.contact.claims import LINES

    tables, _ = _inputs()
    t = {"contact_diffusion": pd.concat([d.assign(**LINES[m]) for m, (d, _c) in tables.items()]),
         "contact": pd.concat([c.assign(**LINES[m]) for m, (_d, c) in tables.items()])}
    paths = draw(t, {}, tmp_path)
    assert sorted(p.name for p in paths) == ["fig_contact.pdf", "fig_contact.png",
                                             "fig_contact_high.pdf", "fig_contact_high.png"]
    assert all(p.stat().st_size > 1000 for p in paths)
