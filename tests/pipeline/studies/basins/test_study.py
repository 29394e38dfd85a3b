"""The basins study from a small real store (the draft scene cut to two frequencies, a 4 x 4
lattice, 2 s, run by real Dask into real Zarr): the lattice reaches the store and survives it,
the tables hold what the labels say (shares, D_mix from its own parts), the figures are files,
and a bad lattice is refused in one line."""

from __future__ import annotations

import math
import shutil

import numpy as np
import pandas as pd
import pytest
import zarr

from bbb.analysis import states as st
from pipeline.execute.run import run_study
from pipeline.store.study_store import StudyStore
from pipeline.studies.basins.tables import NOT_COMPUTED, dmix_boot, grids
from pipeline.studies.registry import study
from pipeline.workflow.load import WorkflowError, parse_workflow
from pipeline.workflow.scenes import ROOT, load_scene

DRAFT = ROOT / "pipeline/studies/basins/scenes/draft/basins.toml"


def _small(text: str) -> str:
    text = text.replace("values = [46.0, 52.0, 54.0, 60.0]", "values = [46.0, 60.0]")
    text = text.replace("lattice = [8, 8]", "lattice = [4, 4]")
    text = text.replace("n_particles = 64\nchunk_size = 64", "n_particles = 16\nchunk_size = 8")
    text = text.replace("t_max = 4.0", "t_max = 2.0")
    assert "[46.0, 60.0]" in text and "n_particles = 16" in text and "t_max = 2.0" in text
    return text


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    root = tmp_path_factory.mktemp("basins")
    path = f"{root}/basins.zarr"
    run_study(parse_workflow(_small(DRAFT.read_text(encoding="utf-8")), str(DRAFT)), path,
              workers=1, progress=False, dashboard=False, echo=lambda m: None)
    s = study("basins")
    stores = {"basins": path}
    return s, stores, s.tables(stores, echo=lambda m: None), root / "out"


def test_the_lattice_survives_the_store_and_fills_every_cell(made):
    _s, stores, _t, _o = made
    store = StudyStore.open(stores["basins"])
    assert all(f.lattice == (4.0, 4.0) and f.offset == 0.5 for f in store.study.families)
    g = grids(store)
    assert set(g) == {(46.0, "dropped"), (46.0, "launched"), (60.0, "dropped"), (60.0, "launched")}
    assert all(v.shape == (4, 4) and (v != st.UNKNOWN).all() for v in g.values())


def test_cells_of_a_chunk_not_done_are_not_computed_never_a_state(made, tmp_path):
    s, stores, _t, _o = made
    copy = tmp_path / "partial.zarr"
    shutil.copytree(stores["basins"], copy)
    zarr.open_group(str(copy), mode="r+")["done"][0, 0, 1] = False
    g = grids(StudyStore.open(str(copy)))[(46.0, "dropped")].ravel()
    # chunk 1 of 8 particles: cells 8-15 of the 4 x 4 lattice, flattened as the particles
    assert (g[8:] == NOT_COMPUTED).all() and (g[:8] != NOT_COMPUTED).all()
    assert (g != st.UNKNOWN).all()
    fig = s.draw(s.tables({"basins": str(copy)}, echo=lambda m: None), {"basins": str(copy)},
                 tmp_path / "out")
    assert any(p.name == "fig_basins_grids.png" for p in fig)


def test_final_shares_are_those_of_the_grid(made):
    _s, stores, tables, _o = made
    g = grids(StudyStore.open(stores["basins"]))
    t = tables["states"].set_index(["f", "family"])
    for (f, fam), grid in g.items():
        for code, name in enumerate(st.LABELS):
            if code != st.UNKNOWN:
                assert t.loc[(f, fam), f"final_{name}"] == pytest.approx(np.mean(grid == code))


def test_dmix_is_the_shares_times_the_classes_d():
    # two particles: one irregular throughout (dx = 2 mm over the second half), one stuck
    lab = np.array([[st.DIFFUSING] * 4, [st.CHAOTIC, st.STUCK, st.STUCK, st.STUCK]], np.int8)
    x = np.array([[0.0, 0.0, 1.0, 2.0, 3.0], [0, 0, 0, 0, 0]])
    est, boot, why = dmix_boot(lab, x, 0.5, np.random.default_rng(1), 50)
    d_irr = (3.0 - 1.0) ** 2 / (2 * 1.0)
    assert est[0] == pytest.approx(d_irr) and est[-1] == pytest.approx(0.5 * d_irr + 0.5 * 0.0)
    assert why == [""] * 4 and boot.shape == (50, 4)


def test_dmix_without_a_class_d_is_not_measured_and_says_why():
    # the locked particle leaves its class in the second half: no D of locked_1
    lab = np.array([[st.LOCKED_1, st.LOCKED_1, st.DIFFUSING, st.DIFFUSING]], np.int8)
    est, _b, why = dmix_boot(lab, np.zeros((1, 5)), 0.5, np.random.default_rng(1), 10)
    assert math.isnan(est[0]) and "locked_1" in why[0] and est[-1] == 0.0


def test_figures_are_png_and_pdf_files(made):
    s, stores, tables, out = made
    out.mkdir(exist_ok=True)
    paths = s.draw(tables, stores, out)
    names = {p.name for p in paths}
    assert {"fig_basins_grids.png", "fig_basins_shares.pdf", "fig_basins_dmix.png"} <= names
    assert all(p.stat().st_size > 1000 for p in paths)


def test_a_lattice_that_is_not_one_particle_per_cell_is_refused_in_one_line():
    text = _small(DRAFT.read_text(encoding="utf-8")).replace("lattice = [4, 4]", "lattice = [4, 5]", 1)
    with pytest.raises(WorkflowError) as e:
        parse_workflow(text, "basins.toml")
    msg = str(e.value)
    assert "\n" not in msg and "families.dropped.lattice" in msg and "n_particles" in msg


@pytest.mark.parametrize("fast", [False, True], ids=["scene", "draft"])
def test_the_scene_and_its_draft_are_lattices_of_the_papers_floor_across_46_to_62_hz(fast):
    s = load_scene("basins", fast)
    f = sorted(p.f for p in s.points)
    assert s.preset == "klages2004" and not s.overrides and f[0] == 46.0 and f[-1] <= 62.0
    assert all(fam.lattice is not None for fam in s.families)
    if not fast:  # the grid: at least 256 x 256 per frequency, >= 17 frequencies
        assert len(f) >= 17 and all(fam.lattice[0] * fam.lattice[1] >= 256 * 256
                                    for fam in s.families)


def test_the_report_says_the_log2_test_is_blind_where_only_two_basins_meet():
    from pipeline.studies.basins.report import facts

    t = pd.DataFrame({"f": [54.0], "family": ["dropped"], "n_particles": [16]})
    blind = pd.DataFrame({"f": [54.0], "family": ["dropped"], "fractal": [False]})
    assert "cannot find a fractal boundary" in facts({"states": t, "entropy": blind})["fractal"]
    found = blind.assign(fractal=[True])
    assert facts({"states": t, "entropy": found})["fractal"] == "dropped: 54 Hz"
