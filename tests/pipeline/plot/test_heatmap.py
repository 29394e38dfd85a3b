"""plot_map: a variable over two dimensions, cells only where values were computed, flagged
cells marked, absent cells hatched as not computed (a real map's: never the grey of a failure
nor a colour of the scale), the CI as a second panel, contours (pipeline/plot/heatmap.py)."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.collections import QuadMesh
from matplotlib.contour import ContourSet
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from PIL import Image

from pipeline.api import reduced_dataset
from pipeline.plot import plot_map
from pipeline.plot.heatmap import cell_edges, cells

from ..figure_store import tiny_map
from ..text_overlap import overlaps
from .synthetic import failed, flag, reduced


@pytest.fixture(scope="module")
def real_map(tmp_path_factory):
    """The reduced Dataset of a real contact x mu map (figure_store.TINY_MAP)."""
    return reduced_dataset(tiny_map(tmp_path_factory))


def _by_gid(fig, kind):
    return {a.get_gid(): a for a in fig.findobj(kind) if a.get_gid()}


def _marked_cells(fig, name) -> set[tuple[float, float]]:
    """The (f, alpha) values of the cells marked for flag ``name`` (a marker inside the cell's
    x range, on its row)."""
    marks = _by_gid(fig, Line2D).get(f"flag:{name}")
    if marks is None:
        return set()
    ds = reduced()
    cf, ca = cells(ds["frequency"].values), cells(ds["alpha"].values)
    out = set()
    for x, y in zip(marks.get_xdata(), marks.get_ydata(), strict=True):
        i = int(np.flatnonzero((cf.lo <= x) & (x <= cf.hi))[0])
        j = int(np.flatnonzero(np.isclose(ca.centres, y))[0])
        out.add((float(ds["frequency"][i]), float(ds["alpha"][j])))
    return out


def test_cell_edges_lie_at_the_midpoints_of_a_non_uniform_grid():
    centres, edges = cell_edges([50.0, 52.0, 60.0])
    assert list(centres) == [50.0, 52.0, 60.0] and list(edges) == [49.0, 51.0, 56.0, 64.0]
    assert list(cell_edges(["stick", "slide"])[1]) == [-0.5, 0.5, 1.5]


def test_a_cell_reaches_the_midpoints_but_no_farther_than_the_median_spacing():
    c = cells([48.0, 50.0, 52.0, 54.0, 56.0, 60.0, 66.0, 80.0])  # the contact draft's kind
    assert c.to_scale  # median spacing 2 Hz
    assert list(c.lo) == [46.0, 49.0, 51.0, 53.0, 55.0, 58.0, 64.0, 78.0]
    assert list(c.hi) == [49.0, 51.0, 53.0, 55.0, 58.0, 62.0, 68.0, 82.0]
    # 62-64 and 68-78 Hz are gap columns of the mesh: nothing computed there
    assert list(c.edges) == [46.0, 49.0, 51.0, 53.0, 55.0, 58.0, 62.0, 64.0, 68.0, 78.0, 82.0]
    assert list(c.index) == [0, 1, 2, 3, 4, 5, 7, 9]


def test_two_values_are_two_cells_of_their_own_not_a_band_between_uncomputed_values():
    c = cells([0.6, 0.8])
    assert not c.to_scale and list(c.edges) == [-0.5, 0.5, 1.5]
    ds = reduced(alphas=(0.6, 0.8))
    ax = plot_map(ds).axes[0]
    assert [t.get_text() for t in ax.get_yticklabels()] == ["0.6", "0.8"]
    assert ax.get_ylim() == (-0.5, 1.5)  # no room for 0.5 or 0.9


def test_the_map_is_drawn_on_the_cells_and_a_gap_between_them_is_not_coloured():
    ds = reduced(freqs=(48.0, 50.0, 52.0, 60.0))
    mesh = _by_gid(plot_map(ds), QuadMesh)["map"]
    coords = mesh.get_coordinates()
    assert np.allclose(coords[0, :, 0], [46.0, 49.0, 51.0, 54.0, 58.0, 62.0])
    z = mesh.get_array().reshape(3, 5)
    assert np.ma.getmaskarray(z)[:, 3].all() and not np.ma.getmaskarray(z)[:, [0, 1, 2, 4]].any()


def test_marked_cells_are_exactly_the_flagged_ones_each_flag_its_own_marker():
    ds = reduced()
    ds = flag(ds, "ergodic", frequency=55.0, alpha=0.6)
    ds = flag(ds, "ergodic", frequency=80.0, alpha=0.5)
    ds = flag(ds, "stationary", frequency=80.0, alpha=0.5)  # two flags on one cell
    ds = flag(ds, "diffusive", frequency=62.0, alpha=0.8)
    fig = plot_map(ds)
    assert _marked_cells(fig, "ergodic") == {(55.0, 0.6), (80.0, 0.5)}
    assert _marked_cells(fig, "stationary") == {(80.0, 0.5)}
    assert _marked_cells(fig, "diffusive") == {(62.0, 0.8)}
    markers = {g: m.get_marker() for g, m in _by_gid(fig, Line2D).items()}
    assert len(set(markers.values())) == 3
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert legend == ["non-ergodic", "non-stationary", "not diffusive"]


def test_one_flag_sits_at_its_cells_centre_and_two_side_by_side_within_the_cell():
    ds = flag(reduced(), "ergodic", frequency=55.0, alpha=0.6)
    ds = flag(flag(ds, "ergodic", frequency=80.0, alpha=0.5), "stationary", frequency=80.0,
              alpha=0.5)
    marks = _by_gid(plot_map(ds), Line2D)
    cf = cells(ds["frequency"].values)
    lo55, hi55, lo80, hi80 = cf.lo[1], cf.hi[1], cf.lo[4], cf.hi[4]
    assert sorted(marks["flag:ergodic"].get_xdata()) == pytest.approx(
        [(lo55 + hi55) / 2, lo80 + (hi80 - lo80) / 3])
    assert list(marks["flag:stationary"].get_xdata()) == pytest.approx(
        [lo80 + 2 * (hi80 - lo80) / 3])


def test_a_flag_marker_is_black_edged_white_so_it_shows_on_the_darkest_and_lightest_colour():
    fig = plot_map(flag(reduced(), "ergodic", frequency=55.0, alpha=0.6))
    m = _by_gid(fig, Line2D)["flag:ergodic"]
    assert (m.get_markerfacecolor(), m.get_markeredgecolor()) == ("black", "white")


def test_no_cell_is_marked_and_no_legend_is_drawn_without_flags():
    fig = plot_map(reduced())
    assert not _by_gid(fig, Line2D) and fig.axes[0].get_legend() is None


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


def test_the_pixels_of_an_absent_cell_are_the_not_computed_hatch_not_a_colour(real_map, tmp_path):
    """The saved PNG itself: at mu = 0.3 only the Coulomb line exists; the stick and slide
    cells show only the white and light grey of the hatch, the Coulomb cells a colour of the
    map."""
    fig = plot_map(real_map.sel(mu=0.3), y="contact", ci=False)
    fig.savefig(tmp_path / "map.png", dpi=100)  # no tight box: the figure's own pixels
    with Image.open(tmp_path / "map.png") as im:
        rgb = np.asarray(im.convert("RGB"), dtype=int)
    ax = fig.axes[0]

    def patch(f, row):
        x, y = ax.transData.transform((f, row))
        r, c = int(round(rgb.shape[0] - y)), int(round(x))
        return rgb[r - 6:r + 6, c - 6:c + 6].reshape(-1, 3)

    for f in (0.0, 1.0):  # two frequencies: one cell each
        for row in (0, 1):  # stick, slide
            px = patch(f, row)
            grey = (px.max(axis=1) - px.min(axis=1)) <= 3  # no hue: white or the hatch grey
            assert grey.all() and (px.min() < 230) and (px.max() >= 250), (f, row)
        px = patch(f, 2)  # coulomb: drawn in a colour of the map
        assert (px.max(axis=1) - px.min(axis=1) > 20).mean() > 0.5, f  # flag markers aside
    assert "not computed" in [t.get_text() for t in ax.get_legend().get_texts()]


def test_the_colorbar_and_the_axes_are_labelled_with_units():
    fig = plot_map(reduced())
    ax, cbar = fig.axes[0], fig.axes[2]  # map, CI panel, then the colorbars
    assert (ax.get_xlabel(), ax.get_ylabel(), cbar.get_ylabel()) == ("f (Hz)", "α", "D (mm²/s)")


def test_the_ci_panel_shows_the_relative_half_width_in_percent():
    ds = reduced()
    ds["D_hi"] = ds["D_hi"] + ds["frequency"] / 10  # a width varying from cell to cell
    r = _by_gid(plot_map(ds), QuadMesh)["ci"].get_array()
    cf, ca = cells(ds["frequency"].values), cells(ds["alpha"].values)
    r = r.reshape(len(ca.edges) - 1, len(cf.edges) - 1)[np.ix_(ca.index, cf.index)]
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


def test_an_accelerating_cell_of_a_v_map_is_marked_with_its_own_marker():
    ds = reduced(velocity=True)
    ds["steady"] = (("frequency", "alpha"), np.ones(ds["v"].shape, dtype=bool),
                    {"units": "", "long_name": "steady"})
    ds = flag(flag(ds, "steady", frequency=70.0, alpha=0.8), "diffusive", frequency=62.0, alpha=0.8)
    fig = plot_map(ds, var="v")
    assert _marked_cells(fig, "steady") == {(70.0, 0.8)}
    markers = {g: m.get_marker() for g, m in _by_gid(fig, Line2D).items()}
    assert markers["flag:steady"] == "^" and len(set(markers.values())) == 2
    assert "accelerating" in [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
