"""plot_dataset: the talk figures of a reduced Dataset written as non-empty PNG and PDF files
with deterministic names (pipeline/plot/figures.py)."""

from __future__ import annotations

import numpy as np
import pytest

from pipeline.api import reduced_dataset
from pipeline.plot import plot_dataset

from ..figure_store import assert_png_drawn, tiny_map
from .synthetic import failed, reduced

MAGIC = {".png": b"\x89PNG\r\n\x1a\n", ".pdf": b"%PDF-"}


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    out = tmp_path_factory.mktemp("talk")
    return out, plot_dataset(reduced(velocity=True), out)


def test_every_file_returned_exists_is_a_non_empty_png_or_pdf_and_nothing_else_is_written(written):
    out, files = written
    assert sorted(files) == sorted(out.iterdir())
    for p in files:
        assert p.read_bytes().startswith(MAGIC[p.suffix]) and p.stat().st_size > 1000, p
        if p.suffix == ".png":
            assert_png_drawn(p)


def test_one_grid_axis_gives_curves_by_it_per_family_curves_and_maps_of_d_v_and_d_drift(written):
    _, files = written
    assert sorted({p.stem for p in files}) == sorted([
        "curve_D_vs_frequency_by_alpha", "curve_v_vs_frequency_by_alpha",
        "curve_D_drift_vs_frequency_by_alpha",
        "curve_D_family_vs_frequency_alpha=0.5", "curve_D_family_vs_frequency_alpha=0.6",
        "curve_D_family_vs_frequency_alpha=0.8",
        "map_D_frequency-alpha", "map_v_frequency-alpha", "map_D_drift_frequency-alpha"])
    assert all({p.with_suffix(s) for s in (".png", ".pdf")} <= set(files) for p in files)


def test_without_a_grid_axis_only_curves_are_drawn(tmp_path):
    ds = reduced().sel(alpha=0.5, drop=True)
    names = {p.stem for p in plot_dataset(ds, tmp_path, formats=("png",))}
    assert names == {"curve_D_vs_frequency", "curve_D_family_vs_frequency"}


def test_two_grid_axes_give_a_cut_per_value_of_the_other_axis(tmp_path):
    ds = reduced(alphas=(0.5, 0.8), families=("rest",)).expand_dims(mu=[0.1, 0.3])
    ds = ds.assign(D=ds["D"] * (1 + ds["mu"]))
    names = {p.stem for p in plot_dataset(ds, tmp_path, formats=("png",))
             if p.stem.startswith("map_")}
    assert names == {"map_D_frequency-alpha_mu=0.1", "map_D_frequency-alpha_mu=0.3",
                     "map_D_frequency-mu_alpha=0.5", "map_D_frequency-mu_alpha=0.8"}


def test_a_real_contact_map_is_one_axis_of_models_without_its_absent_lines(tmp_path_factory,
                                                                           tmp_path):
    ds = reduced_dataset(tiny_map(tmp_path_factory))
    names = {p.stem for p in plot_dataset(ds, tmp_path, formats=("png",))}
    assert not ds["present"].sel(contact="stick", mu=0.3).any()  # mu is Coulomb's
    assert {n for n in names if n.startswith("curve_D_family")} == {
        "curve_D_family_vs_frequency_contact=stick", "curve_D_family_vs_frequency_contact=slide",
        "curve_D_family_vs_frequency_contact=coulomb_mu=0.3"}
    assert "curve_D_vs_frequency_by_contact" in names and not any("by_mu" in n for n in names)


def test_a_cut_whose_points_all_failed_is_drawn(tmp_path):
    ds = reduced(families=("rest",))
    for f in ds["frequency"].values:
        ds = failed(ds, "D_family", frequency=f, alpha=0.8)
    names = {p.stem for p in plot_dataset(ds, tmp_path, formats=("png",))}
    assert np.isnan(ds["D_family"].sel(alpha=0.8)).all()
    assert "curve_D_family_vs_frequency_alpha=0.8" in names


def test_formats_choose_the_files_written(tmp_path):
    files = plot_dataset(reduced().sel(alpha=0.5, drop=True), tmp_path, formats=("svg",))
    assert {p.suffix for p in files} == {".svg"} and all(p.exists() for p in files)
