"""Each figure function draws from a real (tiny) store and its tables a non-blank PNG and a PDF."""

from __future__ import annotations

from pathlib import Path

import pytest

from pipeline import figures as fg

from .figure_store import assert_png_drawn, tiny_store


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    return tiny_store(tmp_path_factory)


def _check(paths, min_size=(400, 300)):
    paths = [Path(p) for p in paths]
    assert {p.suffix for p in paths} == {".png", ".pdf"}
    for p in paths:
        assert p.exists() and p.stat().st_size > 1000, p
    assert_png_drawn(next(p for p in paths if p.suffix == ".png"), min_size)


def test_fig1_draws_the_arcs_and_a_real_trajectory_from_the_store_parameters(made, tmp_path):
    store, _ = made
    _check(fg.figure1(store, None, tmp_path), min_size=(1500, 500))


def test_fig2_draws_d_of_f_with_error_bars_letters_and_other_families(made, tmp_path):
    store, t = made
    # the tiny store has two families: its own table serves as the ergodicity table too
    _check(fg.figure2(store, {"diffusion": t["diffusion"], "ergodicity": t["diffusion"]},
                      tmp_path), min_size=(900, 600))


def test_fig2_with_a_locking_table_adds_the_k_panel(made, tmp_path):
    store, t = made
    paths = fg.figure2(store, {"diffusion": t["diffusion"], "locking": t["locking"]}, tmp_path,
                       name="fig2_k", letters=None, inset=None)
    _check(paths, min_size=(900, 900))


def test_fig3_draws_the_phase_space_panels_with_the_spiral(made, tmp_path):
    store, _ = made
    _check(fg.figure3(store, None, tmp_path), min_size=(600, 800))


def test_fig3_accepts_several_stores(made, tmp_path):
    store, _ = made
    _check(fg.figure3([store, store], None, tmp_path, name="fig3_two"), min_size=(600, 800))


def test_locking_plot_draws_k_against_f(made, tmp_path):
    store, t = made
    _check(fg.figure_locking(store, {"locking": t["locking"]}, tmp_path), min_size=(900, 600))


def test_the_locking_table_has_one_row_per_frequency_and_family(made):
    store, t = made
    lock = t["locking"]
    assert len(lock) == 4 * 2 and set(lock["family"]) == {"rest", "launched"}
    assert (lock["n_states"] > 0).all()
