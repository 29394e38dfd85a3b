"""The store's layout (pipeline.store.layout): named dimensions xarray reads, one chunk per
(frequency, family, ensemble chunk), a unit on every collision field."""

from __future__ import annotations

import xarray as xr

from bbb.record import COLLISION_FIELDS
from pipeline.workflow.observables.collisions import collision_field_units


def test_xarray_opens_the_store_with_named_dims_and_coords(store, study):
    store.consolidate()
    ds = xr.open_zarr(store.path)
    assert ds["positions"].dims == ("frequency", "family", "particle", "time")
    assert ds["collisions"].dims == ("frequency", "family", "particle", "collision", "field")
    assert list(ds["frequency"].values) == [54.0, 60.0]
    assert list(ds["family"].values) == ["rest", "launched"]
    assert list(ds["field"].values) == ["t", "x", "y", "vx", "vy", "phase"]
    assert "initial" in ds.coords
    assert ds["time"].values[-1] == study.accuracy.t_max


def test_one_chunk_per_frequency_family_and_ensemble_chunk(store, study):
    g = store.group()
    cs, T = study.accuracy.chunk_size, len(study.sample_times())
    assert g["positions"].chunks == (1, 1, cs, T)
    assert g["collisions"].chunks == (1, 1, cs, study.observables.collisions_record, 6)
    assert g["n_collisions"].chunks == (1, 1, cs)
    assert g["done"].shape == (2, 2, study.accuracy.n_chunks) and g["done"].chunks == (1, 1, 1)


def test_every_collision_field_has_a_unit_in_the_store(store):
    # bbb.record.COLLISION_FIELDS is the record's dtype; a new field needs its unit in
    # pipeline.store.layout.FIELD_UNITS, else the store's metadata would describe it as '?'
    units = collision_field_units()
    assert "?" not in units, dict(zip(COLLISION_FIELDS, units, strict=True))
    g = store.group()
    for name in ("field", "collisions"):
        assert g[name].attrs["units"].split(", ") == list(units), name
    assert all(f in g["collisions"].attrs["long_name"] for f in COLLISION_FIELDS)


def test_the_stop_at_d_resolved_is_named_by_its_resolution_not_as_zero():
    """The rule stops D = 300 ± 8.6 mm²/s at d_resolved = 9 (a 2 % target not met): its stop
    names the resolution it tested, and says nothing of zero."""
    from pipeline.execute.adaptive import StoppingRule, decide
    from pipeline.store.layout import STOP_LEGEND, ZERO

    reason, _ = decide(StoppingRule(0.02, 9.0, 32), 4, (300.0, 291.4, 308.6))
    assert reason == ZERO
    assert "d_resolved" in STOP_LEGEND[reason] and "zero" not in STOP_LEGEND[reason]
