"""Figure titles: the scene, what it fixes, N and t_max, then the cut
(pipeline/plot/titles.py)."""

from __future__ import annotations

import numpy as np
import xarray as xr

from pipeline.plot.titles import figure_title, scene_attrs, scene_line
from pipeline.workflow.load import parse_workflow

SCENE = """\
[study]
name = "belt"

[params]
preset = "klages2004"
tilt = 3.0
throw = 45.0

[grid]
alpha = [0.6, 0.8]
contact = ["stick", "coulomb"]
mu = [0.3]

[frequencies]
values = [50.0, 70.0]

[families.rest]
initial = "rest"

[observables.positions]
"""


def test_the_scene_attributes_name_it_and_what_it_fixes_but_no_grid_axis():
    attrs = scene_attrs(parse_workflow(SCENE))
    assert attrs == {"scene": "belt", "scene_preset": "klages2004", "fixed_tilt": 3.0,
                     "fixed_throw": 45.0}  # mu = [0.3] is Coulomb's: the models say it


def test_a_grid_axis_of_one_value_is_fixed():
    attrs = scene_attrs(parse_workflow(SCENE.replace("alpha = [0.6, 0.8]", "alpha = [0.6]")))
    assert attrs["fixed_alpha"] == 0.6


def _ds(n, t) -> xr.Dataset:
    ds = xr.Dataset({"n_particles": ("frequency", n), "t_max": ("frequency", t)},
                    coords={"frequency": [50.0, 60.0, 70.0]})
    ds.attrs.update(scene_attrs(parse_workflow(SCENE)))
    return ds


def test_the_scene_line_says_tilt_throw_n_and_t_max_with_their_units():
    line = scene_line(_ds([64.0, 64.0, np.nan], [100.0, 100.0, np.nan]))
    assert line == "belt (klages2004): tilt = 3°, throw = 45°, N = 64, $t_\\mathrm{max}$ = 100 s"


def test_n_differing_between_points_is_given_as_its_range():
    assert "N = 32–128," in scene_line(_ds([32.0, 128.0, 64.0], [50.0] * 3))


def test_the_cut_follows_on_its_own_line_without_what_the_scene_line_says():
    ds = _ds([8.0] * 3, [10.0] * 3).assign_coords(alpha=0.8, tilt=3.0)
    title = figure_title(ds, ds["n_particles"], note="a note")
    assert title.split("\n")[1:] == ["α = 0.8", "a note"]
