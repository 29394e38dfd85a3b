"""Axis labels with units and value words (pipeline/plot/labels.py)."""

from __future__ import annotations

import xarray as xr

from pipeline.plot.labels import axis_label, file_token, pretty_unit, value_label


def test_units_are_written_with_superscripts_and_dimensionless_ones_not_at_all():
    assert [pretty_unit(u) for u in ("mm^2/s", "mm/s", "1/s", "degree", "1", "", None)] == [
        "mm²/s", "mm/s", "1/s", "°", "", "", ""]


def test_a_label_reads_the_units_map_and_an_attribute_only_for_a_name_the_map_lacks():
    ds = xr.Dataset({"D": ("frequency", [1.0], {"units": "cm^2/s"}), "knob": ((), 2.0),
                     "own": ((), 1.0, {"units": "mm/s^2"})},
                    coords={"frequency": [60.0], "R": ("R", [2.5], {"units": "mm"})})
    assert axis_label(ds, "D") == "D (mm²/s)"  # the map's, not a stray attribute's
    assert axis_label(ds, "frequency") == "f (Hz)"  # the tables' unit of f
    assert axis_label(ds, "R") == "R (mm)"
    assert axis_label(ds, "tilt") == "tilt (°)"
    assert axis_label(ds, "own") == "own (mm/s²)"  # not in the map: its attribute
    assert axis_label(ds, "knob") == "knob"  # unknown unit: the bare symbol


def test_a_value_is_written_with_its_symbol_and_unit_and_a_name_as_itself():
    ds = xr.Dataset(coords={"R": ("R", [2.5], {"units": "mm"}),
                            "alpha": ("alpha", [0.5], {"units": "1"})})
    assert value_label(ds, "R", 2.5) == "R = 2.5 mm"
    assert value_label(ds, "alpha", 0.5) == "α = 0.5"
    assert value_label(ds, "contact", "stick") == "stick"
    assert value_label(ds, "contact", "stick", named=True) == "contact = stick"
    assert value_label(ds, "tilt", 3.0) == "tilt = 3°"


def test_a_file_token_holds_only_safe_characters():
    assert file_token("alpha", 0.5) == "alpha=0.5"
    assert file_token("contact", "stick slide/x") == "contact=stick-slide-x"


def test_d_has_one_label_whether_or_not_the_dataset_drifts():
    ds = xr.Dataset({"D": ("frequency", [1.0], {"units": "mm^2/s"})}, coords={"frequency": [60.0]})
    level = axis_label(ds, "D")
    ds["D_drift"] = ("frequency", [0.5], {"units": "mm^2/s"})
    assert axis_label(ds, "D") == level == "D (mm²/s)"
    assert axis_label(ds, "D_family") == level  # per family: the same quantity
    assert axis_label(ds, "D_drift") == r"$D_\mathrm{drift}$ (mm²/s)"
