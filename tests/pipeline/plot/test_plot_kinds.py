"""Every kind of figure ``bbb plot`` draws, from real (tiny) stores -- D(f) without a grid, a
contact x mu map on a tilted floor (v, D_drift), a sawtooth and a sine floor -- read back from
the matplotlib Figures: the title names the scene and what it fixes, the axes carry one label
per quantity with its unit, the value axis is log exactly where the values span more than two
decades, and a signed quantity is mapped in a diverging colour map centred at 0
(pipeline/plot/figures.py, scales.py, titles.py)."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.collections import QuadMesh
from matplotlib.colors import LogNorm
from matplotlib.lines import Line2D

from pipeline.api import reduced_dataset
from pipeline.plot import plot_dataset
from pipeline.plot.figures import talk_figures

from ..figure_store import assert_png_drawn, tiny_floor, tiny_map, tiny_store

#: each real store: its scene's name and what its TOML fixes, as the title must say them
#: (figure_store's TOMLs: tilt = 2.0 deg; floor and depth = 0.3 mm; N = particles per point,
#: all families; t_max in s)
SCENES = {
    "tiny_figures": ["tiny_figures (klages2004)", "N = 16", "= 12 s"],
    "tiny_map": ["tiny_map (klages2004)", "tilt = 2°", "N = 16", "= 10 s"],
    "tiny_sawtooth": ["tiny_sawtooth (klages2004)", "floor = sawtooth", "depth = 0.3 mm",
                      "N = 8", "= 10 s"],
    "tiny_sine": ["tiny_sine (klages2004)", "floor = sine", "depth = 0.3 mm", "N = 8", "= 10 s"],
}
#: the one label of each quantity drawn (units: mm, s, Hz)
LABELS = {"D": "D (mm²/s)", "D_family": "D (mm²/s)", "v": "v (mm/s)",
          "D_drift": r"$D_\mathrm{drift}$ (mm²/s)", "frequency": "f (Hz)"}


@pytest.fixture(scope="module")
def stores(tmp_path_factory):
    return {"tiny_figures": tiny_store(tmp_path_factory)[0], "tiny_map": tiny_map(tmp_path_factory),
            "tiny_sawtooth": tiny_floor(tmp_path_factory, "sawtooth"),
            "tiny_sine": tiny_floor(tmp_path_factory, "sine")}


@pytest.fixture(scope="module")
def figures(stores):
    """{(scene, figure name): Figure} of every figure of every store."""
    return {(scene, name): fig for scene, path in stores.items()
            for name, fig in talk_figures(reduced_dataset(path))}


def _var(name: str) -> str:
    return name.removeprefix("curve_").split("_vs_")[0] if name.startswith("curve_") \
        else name.removeprefix("map_").split("_frequency-")[0]


def _mesh(fig) -> QuadMesh:
    return next(m for m in fig.findobj(QuadMesh) if m.get_gid() == "map")


def _curves(fig) -> np.ndarray:
    """Every value the curves draw (NaN left out)."""
    y = np.concatenate([np.asarray(ln.get_ydata(), float) for ln in fig.axes[0].get_lines()
                        if (ln.get_gid() or "").startswith("line:")])
    return y[np.isfinite(y)]


def _decades(v) -> float:
    v = np.asarray(v, float)
    v = v[np.isfinite(v) & (v > 0)]
    return float(np.log10(v.max() / v.min())) if v.size > 1 else 0.0


def test_every_kind_of_figure_is_drawn_from_the_real_stores(figures):
    kinds = {(s, n.split("_")[0], _var(n)) for s, n in figures}
    assert {("tiny_figures", "curve", "D"), ("tiny_figures", "curve", "D_family"),
            ("tiny_map", "curve", "v"), ("tiny_map", "map", "v"), ("tiny_map", "map", "D"),
            ("tiny_map", "curve", "D_drift"), ("tiny_sawtooth", "map", "v"),
            ("tiny_sawtooth", "curve", "v"), ("tiny_sine", "curve", "D")} <= kinds


def test_every_figure_is_titled_with_its_scene_and_what_the_scene_fixes(figures):
    for (scene, name), fig in figures.items():
        title = fig.get_suptitle()
        missing = [w for w in SCENES[scene] if w not in title.replace("$t_\\mathrm{max}$", "")]
        assert not missing, f"{scene} {name}: {missing} not in {title!r}"
        assert "max}$ =" in title, f"{scene} {name}: no t_max in {title!r}"


def test_every_quantity_has_one_label_with_its_unit_on_every_figure(figures):
    seen: dict[str, set[str]] = {}
    for (_, name), fig in figures.items():
        var, ax = _var(name), fig.axes[0]
        seen.setdefault("frequency", set()).add(ax.get_xlabel())
        label = _mesh(fig).colorbar.ax.get_ylabel() if name.startswith("map_") else ax.get_ylabel()
        seen.setdefault(var, set()).add(label)
    assert seen == {k: {LABELS[k]} for k in seen}


def test_the_value_axis_is_log_exactly_where_the_values_span_more_than_two_decades(figures):
    kinds = set()
    for (scene, name), fig in figures.items():
        if not name.startswith("curve_"):
            continue
        y, scale = _curves(fig), fig.axes[0].get_yscale()
        if _var(name) == "v":
            assert scale == "linear", (scene, name)
        elif _decades(y) > 2:
            assert scale == ("symlog" if (y == 0).any() else "log"), (scene, name, _decades(y))
        else:
            assert scale == "linear", (scene, name, _decades(y))
        kinds.add(scale)
    assert "log" in kinds or "symlog" in kinds  # the tilted map's D spans five decades


def test_a_signed_quantity_is_mapped_diverging_centred_at_zero_and_d_sequentially(figures):
    for (scene, name), fig in figures.items():
        if not name.startswith("map_"):
            continue
        mesh = _mesh(fig)
        cmap, norm = mesh.get_cmap().name, mesh.norm
        if _var(name) == "v":
            assert cmap == "RdBu_r" and norm.vmin == -norm.vmax and norm(0.0) == 0.5, (scene, name)
        else:
            values = np.ma.compressed(mesh.get_array())
            assert cmap == "viridis", (scene, name)
            assert isinstance(norm, LogNorm) == (_decades(values) > 2 and (values > 0).all()), (
                scene, name)


def test_the_contact_models_are_one_comparison_figure_with_a_curve_per_model(figures):
    fig = figures[("tiny_map", "curve_D_vs_frequency_by_contact")]
    lines = {ln.get_gid() for ln in fig.axes[0].findobj(Line2D)
             if (ln.get_gid() or "").startswith("line:")}
    assert lines == {"line:stick", "line:slide", "line:coulomb, μ = 0.3"}
    assert not [n for s, n in figures if s == "tiny_map" and "mu=" in n and "family" not in n]


def test_bbb_plot_writes_a_drawn_png_for_every_figure(stores, tmp_path):
    for scene, path in stores.items():
        files = plot_dataset(reduced_dataset(path), tmp_path / scene, formats=("png",))
        assert files and all(p.exists() for p in files), scene
        for p in files:
            assert_png_drawn(p)
