"""plot_curve: a variable against one dimension with its CI, flags marked, failed points not
drawn as values, labels with units (pipeline/plot/curve.py)."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from pipeline.api import reduced_dataset
from pipeline.plot import plot_curve
from pipeline.plot.style import FAMILY_COLORS

from ..figure_store import tiny_map
from ..text_overlap import overlaps
from .synthetic import failed, flag, reduced


@pytest.fixture(scope="module")
def real_map(tmp_path_factory):
    """The reduced Dataset of a real contact x mu map (figure_store.TINY_MAP)."""
    return reduced_dataset(tiny_map(tmp_path_factory))


def _artists(fig, kind, gid_prefix):
    return {a.get_gid(): a for a in fig.axes[0].findobj(kind)
            if (a.get_gid() or "").startswith(gid_prefix)}


def _has_point(line: Line2D, x: float, y: float) -> bool:
    return any(np.isclose(a, x) and np.isclose(b, y)
               for a, b in zip(line.get_xdata(), line.get_ydata(), strict=True))


def _legend(fig) -> list[str]:
    return [t.get_text() for t in fig.axes[0].get_legend().get_texts()]


def test_axis_labels_carry_the_units_of_the_units_map():
    fig = plot_curve(reduced())
    assert isinstance(fig, Figure)
    assert (fig.axes[0].get_xlabel(), fig.axes[0].get_ylabel()) == ("f (Hz)", "D (mm²/s)")


def test_one_line_per_value_of_the_remaining_grid_axis_labelled_with_it():
    fig = plot_curve(reduced())
    assert sorted(_artists(fig, Line2D, "line:")) == ["line:0.5", "line:0.6", "line:0.8"]
    assert _legend(fig)[:3] == ["α = 0.5", "α = 0.6", "α = 0.8"]


def test_d_family_gets_one_line_per_family_in_the_family_colours():
    fig = plot_curve(reduced().sel(alpha=0.6), var="D_family")
    lines = _artists(fig, Line2D, "line:")
    assert {g: lines[g].get_color() for g in lines} == {
        "line:rest": FAMILY_COLORS["rest"], "line:launched": FAMILY_COLORS["launched"]}
    assert fig.get_suptitle() == "α = 0.6"  # the selection


@pytest.mark.parametrize("name,meaning", [("ergodic", "non-ergodic"),
                                          ("stationary", "non-stationary"),
                                          ("diffusive", "not diffusive")])
def test_a_flagged_point_is_drawn_with_its_flag_marker_and_an_unflagged_one_is_not(name, meaning):
    ds = flag(reduced(), name, frequency=62.0, alpha=0.6)
    fig = plot_curve(ds)
    marks = _artists(fig, Line2D, "flag:")
    assert list(marks) == [f"flag:{name}:0.6"]
    d = ds["D"].sel(alpha=0.6)
    assert _has_point(marks[f"flag:{name}:0.6"], 62.0, float(d.sel(frequency=62.0)))
    assert not _has_point(marks[f"flag:{name}:0.6"], 55.0, float(d.sel(frequency=55.0)))
    assert meaning in _legend(fig)


def test_without_flags_no_flag_marker_and_no_flag_legend_entry():
    fig = plot_curve(reduced())
    assert _artists(fig, Line2D, "flag:") == {}
    assert not {"non-ergodic", "non-stationary", "not diffusive"} & set(_legend(fig))


def test_an_unknown_flag_nan_is_not_a_flag():
    ds = reduced()
    ds["ergodic"] = ds["ergodic"].astype(float)
    ds["ergodic"].loc[{"frequency": 62.0, "alpha": 0.6}] = np.nan
    assert _artists(plot_curve(ds), Line2D, "flag:") == {}


def test_the_ci_band_spans_lo_to_hi_at_every_point():
    ds = reduced()
    band = _artists(plot_curve(ds), PolyCollection, "band:")["band:0.6"]
    verts = band.get_paths()[0].vertices
    for f in ds["frequency"].values:
        ys = verts[np.isclose(verts[:, 0], f), 1]
        pick = {"frequency": f, "alpha": 0.6}
        assert np.isclose(ys.min(), float(ds["D_lo"].sel(pick)))
        assert np.isclose(ys.max(), float(ds["D_hi"].sel(pick)))


def test_error_bars_span_lo_to_hi_at_every_point():
    ds = reduced()
    bars = _artists(plot_curve(ds, ci="bars"), LineCollection, "bars:")["bars:0.5"]
    got = sorted((s[0, 0], s[:, 1].min(), s[:, 1].max()) for s in bars.get_segments())
    want = [(f, float(ds["D_lo"].sel(frequency=f, alpha=0.5)),
             float(ds["D_hi"].sel(frequency=f, alpha=0.5))) for f in ds["frequency"].values]
    assert np.allclose(got, want)


def test_a_point_whose_estimator_failed_is_not_drawn_as_a_value_but_marked_failed():
    ds = flag(failed(reduced(), frequency=70.0, alpha=0.5), "ergodic", frequency=70.0, alpha=0.5)
    fig = plot_curve(ds)
    line = _artists(fig, Line2D, "line:")["line:0.5"]
    assert np.isnan(line.get_ydata()[list(line.get_xdata()).index(70.0)])
    assert _artists(fig, Line2D, "flag:") == {}  # a flag on a value not drawn: nothing
    assert list(_artists(fig, Line2D, "failed")["failed"].get_xdata()) == [70.0]
    assert "estimator failed" in _legend(fig)


def test_nothing_is_marked_failed_when_every_estimate_exists():
    assert _artists(plot_curve(reduced()), Line2D, "failed") == {}


def test_a_line_a_real_map_does_not_have_is_neither_drawn_nor_marked_failed(real_map):
    """At mu = 0.3 the map has the Coulomb line only (mu applies under Coulomb)."""
    fig = plot_curve(real_map.sel(mu=0.3), hue="contact")
    assert sorted(_artists(fig, Line2D, "line:")) == ["line:coulomb"]
    assert _artists(fig, Line2D, "failed") == {}
    assert not {"estimator failed", "stick", "slide"} & set(_legend(fig))


def test_a_variable_varying_along_a_dimension_neither_along_nor_hue_is_refused():
    with pytest.raises(ValueError, match="select one value"):
        plot_curve(reduced(), var="D_family")


def test_no_text_overlaps_another_in_a_curve_with_flags_and_failed_points():
    ds = flag(failed(reduced(), frequency=70.0, alpha=0.5), "stationary", frequency=55.0,
              alpha=0.8)
    assert overlaps(plot_curve(ds)) == []
    assert overlaps(plot_curve(ds.sel(alpha=0.8), var="D_family", ci="bars")) == []


def test_drawing_into_a_given_axes_returns_its_figure():
    fig = Figure()
    ax = fig.add_subplot()
    assert plot_curve(reduced(), ax=ax) is fig and fig.axes[0] is ax


def test_an_accelerating_conveyor_point_is_marked_on_the_v_curve(tmp_path):
    """A real conveyor (tests/pipeline/conveyor.py) opened with its tables: the 80 Hz point,
    whose drift accelerates, carries the triangle; the still 50 Hz one does not."""
    import warnings

    from pipeline.api import open_study

    from ..conveyor import conveyor_store

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # zarr: no consolidated metadata
        ds = open_study(conveyor_store(tmp_path / "conveyor.zarr"), reduced=True)
    fig = plot_curve(ds, var="v")
    (marks,) = _artists(fig, Line2D, "flag:steady").values()
    assert marks.get_marker() == "^" and list(marks.get_xdata()) == [80.0]
    assert _has_point(marks, 80.0, float(ds["v"].sel(frequency=80.0)))
    assert "accelerating" in _legend(fig)
