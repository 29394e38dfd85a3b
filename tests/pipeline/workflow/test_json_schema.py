"""The scene format's JSON Schema (``python -m pipeline.workflow --schema``): every shipped
scene passes it, and a scene the loader refuses for a reason the schema states (an unknown
key, a value out of range, a wrong type, an unknown choice) fails it too."""

from __future__ import annotations

import json
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from pipeline.workflow.json_schema import scene_schema
from pipeline.workflow.keys import SECTIONS, TABLES
from pipeline.workflow.load import WorkflowError, parse_workflow
from pipeline.workflow.schema import declared

jsonschema = pytest.importorskip("jsonschema", reason="the JSON Schema validator (test extra)")

ROOT = Path(__file__).resolve().parents[3]
SCENES = sorted([*ROOT.glob("workflows/*.toml"), *ROOT.glob("pipeline/studies/*/scenes/*.toml"),
                 *ROOT.glob("pipeline/studies/*/scenes/draft/*.toml")])


def _errors(doc: dict) -> list[str]:
    validator = jsonschema.Draft202012Validator(scene_schema())
    return [e.message for e in validator.iter_errors(doc)]


def test_the_schema_is_a_valid_draft_2020_12_schema_printed_by_the_module():
    out = subprocess.run([sys.executable, "-m", "pipeline.workflow", "--schema"], check=True,
                         capture_output=True, text=True, timeout=120).stdout
    printed = json.loads(out)
    jsonschema.Draft202012Validator.check_schema(printed)
    assert printed == json.loads(json.dumps(scene_schema()))


def test_every_table_of_the_schema_holds_exactly_the_declared_keys():
    props = scene_schema()["properties"]
    assert list(props) == list(TABLES)
    for header, cls, _ in SECTIONS:
        path = header.strip("[]").split(".")
        if path[0] in ("families", "observables") or path == ["frequencies", "refine"]:
            continue  # families: one table per NAME; observables: its own and the plug-ins'
        node = props[path[0]]
        node = next((s for s in node.get("anyOf", [node]) if s.get("type") == "object"), node)
        for part in path[1:]:
            node = node["properties"][part]
        assert {k.name for k in declared(cls)} <= set(node["properties"]), header


@pytest.mark.parametrize("scene", SCENES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_shipped_scene_passes_the_schema(scene):
    assert _errors(tomllib.loads(scene.read_text(encoding="utf-8"))) == []


SMOKE = (ROOT / "workflows" / "smoke.toml").read_text(encoding="utf-8")

# id: an edit of the smoke scene that the loader refuses, and that the schema states
REFUSED = {
    "unknown key": lambda t: t.replace("t_max = 100.0", "t_max = 100.0\ntmax = 5"),
    "unknown table": lambda t: t + "\n[extras]\nx = 1\n",
    "alpha out of range": lambda t: t.replace('preset = "klages2004"',
                                              'preset = "klages2004"\nalpha = 1.5'),
    "throw out of range": lambda t: t.replace('preset = "klages2004"',
                                              'preset = "klages2004"\nthrow = 5.0'),
    "unknown contact model": lambda t: t.replace('preset = "klages2004"',
                                                 'preset = "klages2004"\ncontact = "glue"'),
    "string for an integer": lambda t: t.replace("n_particles = 64", 'n_particles = "64"'),
    "unknown accuracy preset": lambda t: t.replace('preset = "draft"', 'preset = "quick"'),
    "unknown grid axis": lambda t: t + "\n[grid]\nomega = [1.0, 2.0]\n",
    "bad family name": lambda t: t.replace("[families.launched]", "[families.1launched]"),
    "negative frequency": lambda t: t.replace("[54.0, 58.0", "[-54.0, 58.0"),
    "unknown initial condition": lambda t: t.replace('initial = "launched"', 'initial = "thrown"'),
}


def test_the_smoke_scene_passes_the_schema_and_loads():
    assert _errors(tomllib.loads(SMOKE)) == [] and parse_workflow(SMOKE).name == "smoke"


@pytest.mark.parametrize("case", sorted(REFUSED))
def test_a_scene_the_loader_refuses_fails_the_schema_too(case):
    text = REFUSED[case](SMOKE)
    assert text != SMOKE
    with pytest.raises(WorkflowError):
        parse_workflow(text, source="bad.toml")
    assert _errors(tomllib.loads(text)), case
