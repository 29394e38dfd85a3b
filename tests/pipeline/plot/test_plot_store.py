"""pipeline.api.plot_store: the talk figures of a real (tiny) store, through
``open_study(path, reduced=True)`` (the plot layer takes a Dataset; the API opens the store)."""

from __future__ import annotations

import pytest

from pipeline.api import plot_store

from ..figure_store import assert_png_drawn, tiny_store


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    return tiny_store(tmp_path_factory)


def test_a_store_without_a_grid_gets_its_d_of_f_curve_as_png_and_pdf(made, tmp_path):
    store, _ = made
    files = plot_store(store, tmp_path)
    assert [p.name for p in files] == ["curve_D_vs_frequency.png", "curve_D_vs_frequency.pdf",
                                       "curve_D_family_vs_frequency.png",
                                       "curve_D_family_vs_frequency.pdf"]
    assert all(p.stat().st_size > 1000 for p in files)
    assert_png_drawn(files[0])
