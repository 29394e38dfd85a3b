"""The observables' registry: one list the engine reads (layout, task, tables), each
observable's arrays declared with units, and a task that names none of them."""

from __future__ import annotations

import ast
from pathlib import Path

import zarr

from pipeline.store.study_store import StudyStore
from pipeline.tables.units import UNKNOWN, unit
from pipeline.workflow.load import parse_workflow
from pipeline.workflow.observables.registry import OBSERVABLES, selected

from ...execute.store_bits import SCENES

ROOT = Path(__file__).resolve().parents[4]


def _every():
    return parse_workflow(SCENES["every_observable"], "every_observable.toml")


def test_a_store_holds_exactly_its_observables_arrays_in_registry_order(tmp_path):
    study = _every()
    store = StudyStore.create_or_open(tmp_path / "s.zarr", study)
    declared = [a.name for o in selected(study) for a in o.arrays(study)]
    assert list(store.checked) == declared  # the digest's array order: the registry's
    g = zarr.open_group(str(store.path), mode="r")
    for o in selected(study):
        for a in o.arrays(study):
            assert g[a.name].attrs["units"] == a.units
            assert tuple(g[a.name].metadata.dimension_names[3:]) == tuple(d for d, _ in a.trailing)


def test_every_array_and_coordinate_of_an_observable_names_a_known_unit():
    study = _every()
    for o in selected(study):
        for item in (*o.coords(study), *o.arrays(study)):
            for u in item.units.split(", "):
                assert u in {"", "1", "s", "mm", "mm/s", "1/s", "mm^2/s^2"}, (o.name, item.name, u)


def test_the_observables_own_table_columns_have_units_in_the_one_map():
    for o in OBSERVABLES:
        for name, _, u, _ in o.columns:
            probe = name.replace("<n>", "3").replace("<state>", "stuck").replace("<class>", "stuck")
            assert unit(probe) == u != UNKNOWN, (o.name, name)


def test_array_names_are_unique_across_observables():
    study = _every()
    names = [a.name for o in OBSERVABLES if o.on(study.observables) for a in o.arrays(study)]
    assert len(names) == len(set(names))


def test_the_dask_task_names_no_particular_observable():
    # no scene's observables read (Study.observables, where every setting is), no observable
    # module imported: it asks the registry
    tree = ast.parse((ROOT / "pipeline" / "execute" / "task.py").read_text(encoding="utf-8"))
    reads = [n.attr for n in ast.walk(tree) if isinstance(n, ast.Attribute)
             and n.attr == "observables"]
    assert reads == []
    imported = {n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)
                and n.module and "observables" in n.module}
    assert imported == {"workflow.observables.contract", "workflow.observables.registry"}


def test_a_plug_in_with_its_own_table_is_on_exactly_when_the_scene_gives_that_table():
    from dataclasses import dataclass

    from pipeline.workflow.keys import Observables
    from pipeline.workflow.observables.contract import Observable

    @dataclass(frozen=True)
    class Keys:
        pass

    class Mine(Observable):
        name, scene = "mine", Keys

    assert not Mine().on(Observables(positions=True))
    assert Mine().on(Observables(positions=True, more=(("mine", ()),)))
    assert Mine().settings(Observables(positions=True, more=(("mine", (("k", 2),)),))) == {"k": 2}
