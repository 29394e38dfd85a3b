"""contact x mu as one axis of models (pipeline/plot/models.py)."""

from __future__ import annotations

import numpy as np
import xarray as xr

from pipeline.plot.models import merge_conditional


def _grid() -> xr.Dataset:
    """A contact x mu map as a store holds it: stick and slide at mu = 0, Coulomb at 0.05 and
    0.3; D = 10 * (contact index + 1) + mu; absent cells NaN with ``present`` False."""
    contact, mu, f = ["stick", "slide", "coulomb"], [0.0, 0.05, 0.3], [50.0, 60.0]
    here = np.array([[1, 0, 0], [1, 0, 0], [0, 1, 1]], bool)
    d = (10 * (np.arange(3)[:, None] + 1) + np.array(mu)[None, :])[:, :, None] + 0 * np.array(f)
    d = np.where(here[:, :, None], d, np.nan)
    return xr.Dataset({"D": (("contact", "mu", "frequency"), d),
                       "present": (("contact", "mu", "frequency"),
                                   np.broadcast_to(here[:, :, None], d.shape).copy())},
                      coords={"contact": contact, "mu": mu, "frequency": f})


def test_the_lines_the_store_has_become_one_axis_named_with_mu_where_it_applies():
    m = merge_conditional(_grid())
    assert list(m["contact"].values) == ["stick", "slide", "coulomb, μ = 0.05",
                                         "coulomb, μ = 0.3"]
    assert list(m["mu"].values) == [0.0, 0.0, 0.05, 0.3] and "mu" not in m.dims
    assert m["D"].sel(contact="coulomb, μ = 0.3").values.tolist() == [30.3, 30.3]
    assert bool(m["present"].all())


def test_a_dataset_without_both_axes_is_left_as_it_is():
    ds = _grid().sel(mu=0.0)
    assert merge_conditional(ds) is ds


def test_a_cut_at_one_model_is_titled_by_the_model_alone():
    from pipeline.plot.titles import cut_line

    m = merge_conditional(_grid())
    assert cut_line(m["D"].sel(contact="stick"), skip=("frequency",)) == "contact = stick"
    assert cut_line(m["D"].sel(contact="coulomb, μ = 0.3")) == "contact = coulomb, μ = 0.3"
