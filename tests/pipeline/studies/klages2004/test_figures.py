"""Each figure function draws from a real (tiny) store and its tables a non-blank PNG and a
PDF, returns its Figure, and draws no text over other text."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest
from matplotlib.figure import Figure

from pipeline.studies.klages2004 import figures as fg

from ...figure_store import assert_png_drawn, tiny_store
from ...text_overlap import overlaps

ROOT = Path(__file__).resolve().parents[4]


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    return tiny_store(tmp_path_factory)


def _check(fig, out_dir, min_size=(400, 300)):
    assert isinstance(fig, Figure)
    paths = fg.figure_files(out_dir, fig.get_label())
    assert {p.suffix for p in paths} == {".png", ".pdf"}
    for p in paths:
        assert p.exists() and p.stat().st_size > 1000, p
    assert_png_drawn(next(p for p in paths if p.suffix == ".png"), min_size)


def test_fig1_draws_the_arcs_and_a_real_trajectory_from_the_store_parameters(made, tmp_path):
    store, _ = made
    _check(fg.figure1(store, None, tmp_path), tmp_path, min_size=(1500, 500))


def test_fig2_draws_d_of_f_with_error_bars_letters_and_other_families(made, tmp_path):
    store, t = made
    # the tiny store has two families: its own table serves as the ergodicity table too
    _check(fg.figure2(store, {"diffusion": t["diffusion"], "ergodicity": t["diffusion"]},
                      tmp_path), tmp_path, min_size=(900, 600))


def test_fig2_with_a_locking_table_adds_the_k_panel(made, tmp_path):
    store, t = made
    fig = fg.figure2(store, {"diffusion": t["diffusion"], "locking": t["locking"]}, tmp_path,
                     name="fig2_k", letters=None, inset=None)
    _check(fig, tmp_path, min_size=(900, 900))


def test_fig3_draws_the_phase_space_panels_with_the_spiral(made, tmp_path):
    store, _ = made
    _check(fg.figure3(store, None, tmp_path), tmp_path, min_size=(600, 800))


def test_fig3_accepts_several_stores(made, tmp_path):
    store, _ = made
    _check(fg.figure3([store, store], None, tmp_path, name="fig3_two"), tmp_path,
           min_size=(600, 800))


def test_locking_plot_draws_k_against_f(made, tmp_path):
    store, t = made
    _check(fg.figure_locking(store, {"locking": t["locking"]}, tmp_path), tmp_path,
           min_size=(900, 600))


def test_the_locking_table_has_one_row_per_frequency_and_family(made):
    store, t = made
    lock = t["locking"]
    assert len(lock) == 4 * 2 and set(lock["family"]) == {"rest", "launched"}
    assert (lock["n_states"] > 0).all()


def test_without_out_dir_a_figure_is_returned_and_nothing_written(made, tmp_path, monkeypatch):
    store, t = made
    monkeypatch.chdir(tmp_path)
    fig = fg.figure_locking(store, {"locking": t["locking"]})
    assert isinstance(fig, Figure) and fig.get_label() == "fig_locking"
    assert list(tmp_path.iterdir()) == []


def test_importing_the_figures_selects_no_matplotlib_backend():
    # a notebook's inline backend must survive `import pipeline.studies.klages2004.figures`
    code = ("import matplotlib; matplotlib.use('svg'); "
            "import pipeline.studies.klages2004.figures, pipeline.api; "
            "print(matplotlib.get_backend())")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "svg"


# -- no text over text ---------------------------------------------------------------------
def _tiny_figures(store, t):
    """Every figure the figure functions make, drawn from the tiny store."""
    both = {"diffusion": t["diffusion"], "ergodicity": t["diffusion"]}
    return [fg.figure1(store, None), fg.figure2(store, both),
            fg.figure2(store, {"diffusion": t["diffusion"], "locking": t["locking"]},
                       name="fig2_k", letters=None, inset=None, legend_loc="upper left"),
            fg.figure3(store, None), fg.figure_locking(store, {"locking": t["locking"]})]


def test_no_figure_of_the_tiny_store_draws_text_over_text(made):
    store, t = made
    found = {fig.get_label(): overlaps(fig) for fig in _tiny_figures(store, t)}
    assert not any(found.values()), found


def _committed(name):
    return pd.read_csv(ROOT / "figures" / name)


def test_fig2_drawn_from_the_committed_tables_has_no_text_over_text():
    # the committed paper-quality tables: Fig. 2 with its inset, letters and legend, and the
    # R = 25 mm variant with its k panel (the stores are not committed: no title)
    fig2 = fg.figure2(None, {"diffusion": _committed("diffusion_figure2.csv"),
                             "ergodicity": _committed("diffusion_ergodicity.csv")})
    matyas = fg.figure2(None, {"diffusion": _committed("diffusion_figure2_matyas2004.csv"),
                               "locking": _committed("locking_matyas2004.csv")},
                        name="fig2_matyas2004", letters=None, inset=None,
                        legend_loc="upper left")
    lock = fg.figure_locking(None, {"locking": _committed("locking.csv")})
    assert [overlaps(f) for f in (fig2, matyas, lock)] == [[], [], []]


def test_the_overlap_check_finds_text_drawn_over_text_and_across_an_axis():
    fig = Figure(figsize=(3, 2))
    ax = fig.subplots()
    ax.text(0.5, 0.5, "first label")
    ax.text(0.52, 0.52, "second label")
    ix = ax.inset_axes([0.08, 0.6, 0.3, 0.3])  # its tick labels lie across ax's left spine
    ix.plot([0, 1], [0, 100])
    found = overlaps(fig)
    assert ("first label", "second label") in [f[:2] for f in found]
    assert any(b.startswith("spine left") for _, b, *_ in found)
    ax.texts[1].set_position((0.5, 0.1))
    ix.set_visible(False)
    assert overlaps(fig) == []
