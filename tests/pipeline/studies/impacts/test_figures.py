"""The impact-phase study from a small real store (the draft scene cut to two frequencies and
eight particles, run by real Dask into real Zarr): its tables, its figures as PNG + PDF files
that draw what the table holds, and its section judged from the tables read back."""

from __future__ import annotations

import numpy as np
import pytest

from pipeline.execute.run import run_study
from pipeline.studies.registry import study
from pipeline.workflow.load import parse_workflow
from pipeline.workflow.observables.impacts import BINS
from pipeline.workflow.scenes import ROOT

DRAFT = ROOT / "pipeline/studies/impacts/scenes/draft/impacts.toml"


def _small(text: str) -> str:
    """The draft scene at 50 and 80 Hz (below and inside the claims' frequencies), 8 particles."""
    text = text.replace("values = [45.0, 60.0, 80.0, 95.0]", "values = [50.0, 80.0]")
    text = text.replace("n_particles = 16\nchunk_size = 16", "n_particles = 8\nchunk_size = 8")
    assert "[50.0, 80.0]" in text and "n_particles = 8" in text
    return text


def _store(root: str, scheduler: str) -> str:
    path = f"{root}/impacts.zarr"
    run_study(parse_workflow(_small(DRAFT.read_text(encoding="utf-8")), str(DRAFT)), path,
              scheduler=scheduler, progress=False, dashboard=False, echo=lambda m: None)
    return path


@pytest.fixture
def made(tmp_path, dask_cluster):
    s = study("impacts")
    stores = {"impacts": _store(str(tmp_path), dask_cluster)}
    tables = s.tables(stores, echo=lambda m: None)
    return s, stores, tables, tmp_path / "out"


def test_figures_render_from_a_real_store_and_draw_the_tables_phase_shares_and_upward_share(made):
    s, stores, tables, out = made
    out.mkdir()
    paths = s.draw(tables, stores, out)
    assert sorted(p.name for p in paths) == ["fig_impacts_phase.pdf", "fig_impacts_phase.png",
                                             "fig_impacts_vx.pdf", "fig_impacts_vx.png"]
    assert all(p.stat().st_size > 1000 for p in paths)
    from pipeline.studies.impacts.figures import figure_phase

    t = tables["impacts"]
    fig = figure_phase(t, None)
    rest = t[t["family"] == "rest"].sort_values("f")
    dens = fig.axes[0].collections[0].get_array()  # the rest family's map, bins x f
    dens = np.ma.filled(dens.reshape(BINS, len(rest)).astype(float), np.nan)
    for j, (_, r) in enumerate(rest.iterrows()):
        if r["n_impacts"] > 0:  # each column is the table's phase shares, times 24: sums to 24
            assert dens[:, j] == pytest.approx([BINS * r[f"phase_{b}"] for b in range(BINS)])
            assert np.nansum(dens[:, j]) == pytest.approx(BINS)
        else:  # no impacts: blank, never drawn as zero
            assert np.isnan(dens[:, j]).all()
    up = fig.axes[2].get_lines()[0]
    shown = rest[rest["up_share"].notna()]
    assert np.array_equal(up.get_xdata(), shown["f"]) and np.array_equal(up.get_ydata(),
                                                                         shown["up_share"])


def test_the_section_is_made_from_the_tables_read_back_with_a_verdict_for_each_claim(made):
    s, stores, tables, out = made
    out.mkdir()
    s.write_tables(out, tables)
    back = s.read_tables(out)
    assert set(back) == set(tables)
    text = "\n".join(s.report(back))
    for c in s.claims:
        row = next(r for r in s.judge(back)[None] if r.id == c.id)
        assert f"| {c.id} |" in text and f"**{row.verdict}**" in text
        assert "80 Hz rest" in row.measured and "50 Hz" not in row.measured  # only f ≥ 60 Hz
