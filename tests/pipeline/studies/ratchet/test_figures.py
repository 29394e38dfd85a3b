"""The ratchet study from small real stores (the draft scene cut to two frequencies and eight
particles, and the draft states scene, run by real Dask into real Zarr): its figures as PNG +
PDF files that draw what the table holds, the states table, and its section judged from the
tables read back."""

from __future__ import annotations

import numpy as np
import pytest

from pipeline.execute.run import run_study
from pipeline.studies.registry import study
from pipeline.workflow.load import parse_workflow
from pipeline.workflow.scenes import ROOT

DRAFT = ROOT / "pipeline/studies/ratchet/scenes/draft/ratchet.toml"
STATES = ROOT / "pipeline/studies/ratchet/scenes/draft/ratchet_states.toml"


def _small(text: str) -> str:
    """The draft scene at 56 and 84 Hz, 8 particles."""
    text = text.replace("values = [56.0, 70.0, 84.0]", "values = [56.0, 84.0]")
    text = text.replace("n_particles = 16\nchunk_size = 16", "n_particles = 8\nchunk_size = 8")
    assert "[56.0, 84.0]" in text and "n_particles = 8" in text
    return text


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    from dask.distributed import Client, LocalCluster

    root = tmp_path_factory.mktemp("ratchet")
    stores = {"ratchet": str(root / "ratchet.zarr"), "ratchet_states": str(root / "states.zarr")}
    texts = {"ratchet": (_small(DRAFT.read_text(encoding="utf-8")), DRAFT),
             "ratchet_states": (STATES.read_text(encoding="utf-8"), STATES)}
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                      dashboard_address=None) as cluster, Client(cluster):
        for name, (text, src) in texts.items():
            run_study(parse_workflow(text, str(src)), stores[name],
                      scheduler=cluster.scheduler_address, progress=False, dashboard=False,
                      echo=lambda m: None)
    s = study("ratchet")
    return s, stores, s.tables(stores, echo=lambda m: None), root / "out"


def test_the_map_draws_the_tables_signed_drift_on_a_colour_map_centred_at_zero(made):
    s, stores, tables, out = made
    from pipeline.studies.ratchet.figures import figure_map

    t = tables["ratchet_diffusion"]
    fig = figure_map(t, None)
    mesh = fig.axes[0].collections[0]
    z = np.ma.filled(mesh.get_array().astype(float), np.nan).reshape(3, 2)  # peaks x f
    peaks, fs = sorted(t["peak"].unique()), sorted(t["f"].unique())
    for r in t.itertuples(index=False):
        want = r.v
        got = z[peaks.index(r.peak), fs.index(r.f)]
        assert (np.isnan(got) and np.isnan(want)) or got == pytest.approx(want)
    norm = mesh.norm  # diverging: centred at 0, symmetric ends
    assert norm.vmin == -norm.vmax and mesh.get_cmap().name == "RdBu_r"


def test_the_figures_render_and_the_section_is_judged_from_the_tables_read_back(made):
    s, stores, tables, out = made
    out.mkdir(exist_ok=True)
    paths = s.draw(tables, stores, out)
    assert sorted(p.name for p in paths) == sorted(
        f"fig_ratchet_{n}.{e}" for n in ("map", "lines", "mechanism") for e in ("pdf", "png"))
    assert all(p.stat().st_size > 1000 for p in paths)
    s.write_tables(out, tables)
    back = s.read_tables(out)
    assert {"ratchet_diffusion", "ratchet_impacts", "ratchet_counters",
            "ratchet_reversals"} <= set(back)
    text = "\n".join(s.report(back))
    rows = s.judge(back)[None]
    assert [r.id for r in rows] == ["R1", "R2", "R3", "R4"]
    for r in rows:
        assert f"| {r.id} |" in text and f"**{r.verdict}**" in text


def test_the_states_table_gives_each_point_shares_summing_to_one_with_wilson_intervals(made):
    from bbb.analysis.states import LABELS
    from pipeline.studies.ratchet.reversal_states import states_table

    t = states_table(made[1]["ratchet_states"])
    assert list(t["f"]) == [56.0, 84.0] and (t["n_particles"] == 8).all()
    shares = t[list(LABELS)].to_numpy(float)
    assert np.allclose(shares.sum(axis=1), 1.0)
    for lab in LABELS:  # each interval holds its share and is never of zero width
        assert (t[f"{lab}_lo"] <= t[lab]).all() and (t[lab] <= t[f"{lab}_hi"]).all()
        assert (t[f"{lab}_hi"] - t[f"{lab}_lo"] > 0).all()


def test_a_blank_drift_is_left_blank_in_the_map_never_drawn_as_zero():
    from pipeline.studies.ratchet.cases import F, map_table
    from pipeline.studies.ratchet.figures import figure_map

    t = map_table()
    t.loc[(t["peak"] == 0.3) & (t["f"] == 70.0), ["v", "v_lo", "v_hi"]] = np.nan
    z = figure_map(t, None).axes[0].collections[0].get_array()
    z = z.reshape(3, F.size)
    assert z.mask[0, list(F).index(70.0)] and z.mask.sum() == 1
