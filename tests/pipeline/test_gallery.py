"""The gallery (pipeline/gallery.py): docs/gallery.md shows one figure of each kind, written
from real stores; its scenes are shipped ones run small."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from pipeline.gallery import ENTRIES, GALLERY_SIZE, Entry, gallery_study, write_gallery

from .figure_store import assert_png_drawn, tiny_floor, tiny_map

ROOT = Path(__file__).resolve().parents[2]


def test_every_entry_is_a_shipped_scene_run_at_gallery_size_and_a_kind_of_its_own():
    assert len({e.kind for e in ENTRIES}) == len(ENTRIES)
    for e in ENTRIES:
        acc = gallery_study(e.scene).accuracy
        assert (acc.n_particles, acc.chunk_size, acc.t_max) == tuple(GALLERY_SIZE.values()), e
        assert acc.target_ci is None, e


def test_the_committed_page_shows_every_entry_and_its_image_is_committed():
    page = (ROOT / "docs" / "gallery.md").read_text(encoding="utf-8")
    shown = re.findall(r"!\[[^]]*\]\(gallery/([^)]+)\.png\)", page)
    assert shown == [e.kind for e in ENTRIES]
    for kind in shown:
        assert_png_drawn(ROOT / "docs" / "gallery" / f"{kind}.png")


@pytest.fixture(scope="module")
def stores(tmp_path_factory):
    return {"map": tiny_map(tmp_path_factory), "saw": tiny_floor(tmp_path_factory, "sawtooth")}


def test_write_gallery_copies_each_entrys_figure_and_names_the_scene_and_size(stores, tmp_path):
    entries = (Entry("comparison", "map", "curve_D_vs_frequency_by_contact", "Models", "text"),
               Entry("signed_map", "saw", "map_v_frequency-peak", "Ratchet", "text"))
    page = write_gallery(stores, tmp_path, entries).read_text(encoding="utf-8")
    for e in entries:
        assert_png_drawn(tmp_path / "gallery" / f"{e.kind}.png")
        assert f"](gallery/{e.kind}.png)" in page and f"Scene `{e.scene}`" in page
    assert "6 points × 8 particles (all families) × 10 s" in page  # the sawtooth: 3 f x 2 peaks


def test_an_entry_whose_figure_bbb_plot_did_not_draw_is_named(stores, tmp_path):
    with pytest.raises(FileNotFoundError, match="saw: bbb plot draws no map_v_frequency-depth"):
        write_gallery({"saw": stores["saw"]}, tmp_path,
                      (Entry("x", "saw", "map_v_frequency-depth", "X", "text"),))
