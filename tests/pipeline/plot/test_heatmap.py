"""plot_map: a variable over two dimensions, flagged cells hatched, absent cells blank (a real
map's: never the grey of a failure), the CI as a second panel, contours
(pipeline/plot/heatmap.py)."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.collections import PatchCollection, QuadMesh
from matplotlib.contour import ContourSet
from matplotlib.figure import Figure
from PIL import Image

from pipeline.api import reduced_dataset
from pipeline.plot import plot_map
from pipeline.plot.heatmap import cell_edges

from ..figure_store import tiny_map
from ..text_overlap import overlaps
from .synthetic import failed, flag, reduced


@pytest.fixture(scope="module")
def real_map(tmp_path_factory):
    """The reduced Dataset of a real contact x mu map (figure_store.TINY_MAP)."""
    return reduced_dataset(tiny_map(tmp_path_factory))


def _by_gid(fig, kind):
    return {a.get_gid(): a for a in fig.findobj(kind) if a.get_gid()}


def _hatched_cells(fig, name) -> set[tuple[float, float]]:
    """The (f, alpha) centres of the cells hatched for flag ``name``."""
    coll = _by_gid(fig, PatchCollection).get(f"hatch:{name}")
    if coll is None:
        return set()
    return {tuple(np.round(p.vertices[:4].mean(axis=0), 6)) for p in coll.get_paths()}


def _centre(ds, f, a):
    (cf, ef), (ca, ea) = cell_edges(ds["frequency"].values), cell_edges(ds["alpha"].values)
    i, j = list(cf).index(f), list(ca).index(a)
    return (round((ef[i] + ef[i + 1]) / 2, 6), round((ea[j] + ea[j + 1]) / 2, 6))


def test_cell_edges_lie_at_the_midpoints_of_a_non_uniform_grid():
    centres, edges = cell_edges([50.0, 52.0, 60.0])
    assert list(centres) == [50.0, 52.0, 60.0] and list(edges) == [49.0, 51.0, 56.0, 64.0]
    assert list(cell_edges(["stick", "slide"])[1]) == [-0.5, 0.5, 1.5]


def test_the_map_is_drawn_on_the_cell_edges():
    ds = reduced(freqs=(50.0, 52.0, 60.0))
    mesh = _by_gid(plot_map(ds), QuadMesh)["map"]
    coords = mesh.get_coordinates()
    assert np.allclose(coords[0, :, 0], [49.0, 51.0, 56.0, 64.0])
    assert np.allclose(coords[:, 0, 1], cell_edges(ds["alpha"].values)[1])


def test_hatched_cells_are_exactly_the_flagged_ones_each_flag_its_own_hatch():
    ds = reduced()
    ds = flag(ds, "ergodic", frequency=55.0, alpha=0.6)
    ds = flag(ds, "ergodic", frequency=80.0, alpha=0.5)
    ds = flag(ds, "stationary", frequency=80.0, alpha=0.5)  # two flags on one cell
    ds = flag(ds, "diffusive", frequency=62.0, alpha=0.8)
    fig = plot_map(ds)
    assert _hatched_cells(fig, "ergodic") == {_centre(ds, 55.0, 0.6), _centre(ds, 80.0, 0.5)}
    assert _hatched_cells(fig, "stationary") == {_centre(ds, 80.0, 0.5)}
    assert _hatched_cells(fig, "diffusive") == {_centre(ds, 62.0, 0.8)}
    hatches = {c.get_gid(): c.get_hatch() for c in fig.findobj(PatchCollection)}
    assert len(set(hatches.values())) == 3
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert legend == ["non-ergodic", "non-stationary", "not diffusive"]


def test_no_cell_is_hatched_and_no_legend_is_drawn_without_flags():
    fig = plot_map(reduced())
    assert not _by_gid(fig, PatchCollection) and fig.axes[0].get_legend() is None


def test_absent_cells_of_a_real_map_are_masked_and_only_they(real_map):
    cut = real_map.sel(mu=0.0)  # coulomb is absent there (mu = 0.3 only), stick and slide not
    z = _by_gid(plot_map(cut, y="contact"), QuadMesh)["map"].get_array()
    gone = ~cut["present"].any("family").transpose("contact", "frequency").values
    assert gone[2].all() and not gone[:2].any()
    want = gone | np.isnan(cut["D"].transpose("contact", "frequency").values)
    assert np.array_equal(np.ma.getmaskarray(z).reshape(3, 2), want)


def test_a_failed_cell_is_drawn_grey_but_an_absent_one_of_a_real_map_is_not(real_map):
    cut = failed(real_map.sel(mu=0.0), frequency=54.0, contact="slide")
    fig = plot_map(cut, y="contact")
    grey = ~np.ma.getmaskarray(_by_gid(fig, QuadMesh)["failed"].get_array()).reshape(3, 2)
    want = np.zeros((3, 2), bool)  # rows stick, slide, coulomb; columns 54, 60 Hz
    want[1, 0] = True
    assert np.array_equal(grey, want)
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert legend[:2] == ["estimator failed", "not computed"]


def test_the_pixels_of_an_absent_cell_are_the_background_not_the_failed_grey(real_map,
                                                                             tmp_path):
    """The saved PNG itself: at mu = 0.3 only the Coulomb line exists; the stick and slide
    cells show the axes' white, the Coulomb cells a colour of the map."""
    fig = plot_map(real_map.sel(mu=0.3), y="contact", ci=False)
    fig.savefig(tmp_path / "map.png", dpi=100)  # no tight box: the figure's own pixels
    with Image.open(tmp_path / "map.png") as im:
        rgb = np.asarray(im.convert("RGB"), dtype=int)
    ax = fig.axes[0]

    def pixel(f, row):
        x, y = ax.transData.transform((f, row))
        return rgb[int(round(rgb.shape[0] - y)), int(round(x))]

    for f in (54.0, 60.0):
        assert (pixel(f, 0) >= 250).all() and (pixel(f, 1) >= 250).all(), f  # stick, slide
        assert not (pixel(f, 2) >= 250).all(), f  # coulomb: drawn
    assert "not computed" in [t.get_text() for t in ax.get_legend().get_texts()]


def test_the_colorbar_and_the_axes_are_labelled_with_units():
    fig = plot_map(reduced())
    ax, cbar = fig.axes[0], fig.axes[2]  # map, CI panel, then the colorbars
    assert (ax.get_xlabel(), ax.get_ylabel(), cbar.get_ylabel()) == ("f (Hz)", "α", "D (mm²/s)")
    ds = reduced()
    ds["D"].attrs["units"] = "m^2/s"
    assert plot_map(ds).axes[2].get_ylabel() == "D (m²/s)"


def test_the_ci_panel_shows_the_relative_half_width_in_percent():
    ds = reduced()
    ds["D_hi"] = ds["D_hi"] + ds["frequency"] / 10  # a width varying from cell to cell
    r = _by_gid(plot_map(ds), QuadMesh)["ci"].get_array().reshape(3, 5)
    want = 100 * (ds["D_hi"] - ds["D_lo"]) / 2 / ds["D"]
    assert np.allclose(r, want.transpose("alpha", "frequency").values)


def test_without_ci_bounds_or_with_ci_false_there_is_one_panel():
    assert "ci" not in _by_gid(plot_map(reduced(), ci=False), QuadMesh)
    assert "ci" not in _by_gid(plot_map(reduced().drop_vars("D_hi")), QuadMesh)


def test_contours_of_a_callable_are_drawn_and_labelled():
    ds = reduced()
    fig = plot_map(ds, contours=lambda d: d["Gamma"] * d["alpha"], contour_levels=[0.5, 1.0])
    cs = next(c for c in fig.findobj(ContourSet))
    assert list(cs.levels) == [0.5, 1.0] and cs.labelTexts
    assert {t.get_text() for t in cs.labelTexts} <= {"0.5", "1"}


def test_a_named_axis_gets_one_cell_per_name():
    ds = reduced().rename({"alpha": "contact"}).assign_coords(
        contact=["stick", "slide", "coulomb"])
    ax = plot_map(ds, y="contact").axes[0]
    assert [t.get_text() for t in ax.get_yticklabels()] == ["stick", "slide", "coulomb"]


def test_a_variable_over_a_third_dimension_is_refused():
    with pytest.raises(ValueError, match="select one value"):
        plot_map(reduced(), var="D_family")


def test_no_text_overlaps_another_in_a_map_with_flags_contours_and_the_ci_panel():
    ds = flag(failed(reduced(), frequency=62.0, alpha=0.6), "ergodic", frequency=55.0, alpha=0.6)
    ds = flag(flag(ds, "stationary", frequency=50.0, alpha=0.8), "diffusive", frequency=80.0,
              alpha=0.5)
    assert overlaps(plot_map(ds, contours="Gamma")) == []


def test_drawing_into_given_axes_returns_their_figure():
    fig = Figure()
    ax, ci_ax = fig.subplots(1, 2)
    assert plot_map(reduced(), ax=ax, ci_ax=ci_ax) is fig
    assert "ci" in _by_gid(fig, QuadMesh)


def test_an_accelerating_cell_of_a_v_map_is_hatched_with_its_own_hatch():
    ds = reduced(velocity=True)
    ds["steady"] = (("frequency", "alpha"), np.ones(ds["v"].shape, dtype=bool),
                    {"units": "", "long_name": "steady"})
    ds = flag(flag(ds, "steady", frequency=70.0, alpha=0.8), "diffusive", frequency=62.0, alpha=0.8)
    fig = plot_map(ds, var="v")
    assert _hatched_cells(fig, "steady") == {_centre(ds, 70.0, 0.8)}
    hatches = {c.get_gid(): c.get_hatch() for c in fig.findobj(PatchCollection)}
    assert hatches["hatch:steady"] == "xx" and len(set(hatches.values())) == 2
    assert "accelerating" in [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
