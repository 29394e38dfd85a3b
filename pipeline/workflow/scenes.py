"""Where the shipped scenes live and how to read one: ``workflows/*.toml`` (installed as the
package ``pipeline.workflows``) and every study's ``pipeline/studies/<study>/scenes/*.toml``,
found through importlib.resources so that an installed bbb finds them from any directory (a
name in both: ``workflows/`` wins).  Also the TOML writer for workflow-shaped documents and
the draft version of a scene (``make figures FAST=1``): the study's own
``scenes/draft/<name>.toml`` if it ships one, else the scene at the draft preset.

The studies are discovered as folders, not imported: the engine knows no study.
"""

from __future__ import annotations

import json
import math
import os
import tomllib
from importlib import resources
from importlib.resources.abc import Traversable
from pathlib import Path

__all__ = ["ROOT", "scene_names", "scene_path", "scene_label", "scene_study", "scene_description",
           "workflow_file", "load_named", "toml_dump", "draft_text", "load_scene", "shipped_draft",
           "DRAFT_COLLISIONS", "DRAFT_RECORD", "DRAFT_TARGET"]

#: the source tree (the repository): labels and run logs are relative to it
ROOT = Path(__file__).resolve().parents[2]  # pipeline/workflow/scenes.py -> the repository
#: draft accuracy of collision scenes (positions scenes use the plain "draft" preset)
DRAFT_COLLISIONS = {"n_particles": 4, "chunk_size": 4, "t_max": 60.0}
DRAFT_RECORD = {"record": 1000, "record_from": 20.0}
#: draft accuracy of target-driven scenes: a loose target, small chunks, a low cap
DRAFT_TARGET = {"target_ci": 0.15, "chunk_size": 64, "max_particles": 256}


def _scene_folders() -> list[tuple[str, Traversable]]:
    """(source-tree label, folder) of every scene folder, in order of precedence: the
    top-level workflows/, then each study's scenes/ (sorted by study name)."""
    try:
        folders = [("workflows", resources.files("pipeline.workflows"))]
    except ModuleNotFoundError:  # a source tree put on sys.path without `pip install`
        folders = [("workflows", ROOT / "workflows")]
    studies = resources.files("pipeline.studies")
    for study in sorted((s for s in studies.iterdir() if s.is_dir()), key=lambda s: s.name):
        scenes = study / "scenes"
        if scenes.is_dir():
            folders.append((f"pipeline/studies/{study.name}/scenes", scenes))
    return folders


def _find_scene(name: str) -> tuple[str, Traversable]:
    for label, folder in _scene_folders():
        p = folder / f"{name}.toml"
        if p.is_file():
            return f"{label}/{name}.toml", p
    raise FileNotFoundError(f"no scene {name!r} in {' or '.join(lab for lab, _ in _scene_folders())}; "
                            f"allowed: {', '.join(scene_names())}")


def _unknown(workflow: str):
    """The WorkflowError of a workflow argument that is neither a file nor a scene's name."""
    from .study import WorkflowError
    from .suggest import did_you_mean

    near = did_you_mean(Path(workflow).name.removesuffix(".toml"), scene_names(), n=3)
    return WorkflowError(workflow, "", f"no such workflow file or shipped scene{near}",
                         "a TOML file, or a scene name that `bbb scenes` lists")


def workflow_file(workflow: str | os.PathLike) -> Path:
    """The file of a workflow argument: a path that exists (it wins over a scene of the same
    name), else the shipped scene of that name (:func:`scene_path`, a file of the installed
    package); WorkflowError naming the closest scene names if it is neither."""
    if Path(workflow).exists():
        return Path(workflow)
    if str(workflow) in scene_names():
        return Path(str(scene_path(str(workflow))))
    raise _unknown(os.fspath(workflow))


def load_named(workflow: str | os.PathLike):
    """The Study of a workflow argument (:func:`workflow_file`): a scene read by its name is
    labelled by its place in the source tree (``workflows/smoke.toml``), as in make_figures."""
    from .load import load_workflow, parse_workflow

    if Path(workflow).exists():
        return load_workflow(workflow)
    if str(workflow) in scene_names():
        return parse_workflow(scene_path(str(workflow)).read_text(encoding="utf-8"),
                              source=scene_label(str(workflow)))
    raise _unknown(os.fspath(workflow))


def scene_study(name: str) -> str:
    """The study a shipped scene belongs to: its folder pipeline/studies/<study>/, or
    "workflows" for the top-level workflows/ (the paper's and the pipeline's own scenes)."""
    label = scene_label(name)
    return label.split("/")[2] if label.startswith("pipeline/studies/") else "workflows"


def scene_description(name: str) -> str:
    """The scene's ``[study] description`` (one line), or "" if it has none."""
    doc = tomllib.loads(scene_path(name).read_text(encoding="utf-8"))
    study = doc.get("study")
    return " ".join(str(study.get("description", "")).split()) if isinstance(study, dict) else ""


def scene_path(name: str) -> Traversable:
    """The scene ``<name>.toml``: from ``workflows/`` (installed as ``pipeline.workflows``) if
    there, else from a study's ``scenes/``; found through importlib.resources (a
    ``pathlib.Path`` when the package is installed as files)."""
    return _find_scene(name)[1]


def scene_label(name: str) -> str:
    """Where the scene lives in the source tree, e.g. ``workflows/figure2.toml`` (never an
    absolute path of this machine)."""
    return _find_scene(name)[0]


def scene_names() -> list[str]:
    """Every scene name that :func:`scene_path` resolves, sorted."""
    return sorted({p.name.removesuffix(".toml") for _, folder in _scene_folders()
                   for p in folder.iterdir() if p.name.endswith(".toml")})


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int | float):
        if isinstance(v, float) and math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise TypeError(f"cannot write {type(v).__name__} to TOML")


def toml_dump(doc: dict, prefix: str = "") -> str:
    """TOML text of a document of tables, scalars and lists of scalars (workflow-shaped)."""
    lines, tables = [], []
    for k, v in doc.items():
        if isinstance(v, dict):
            tables.append((k, v))
        else:
            lines.append(f"{k} = {_toml_value(v)}")
    out = "\n".join(lines) + ("\n" if lines else "")
    for k, v in tables:
        name = f"{prefix}.{k}" if prefix else k
        out += f"\n[{name}]\n" + toml_dump(v, name)
    return out


def draft_text(text: str) -> str:
    """The same scene at draft accuracy: preset "draft"; for collision scenes also a few
    particles, a 60 s run and collisions recorded from 20 s; for target-driven scenes
    (``target_ci``) the loose target of DRAFT_TARGET, with d_resolved loosened by the same
    factor."""
    doc = tomllib.loads(text)
    obs = doc.get("observables", {})
    acc: dict = {"preset": "draft"}
    given = doc.get("accuracy", {})
    if isinstance(given, dict) and given.get("target_ci") is not None:
        acc.update(DRAFT_TARGET)
        if given.get("d_resolved") is not None:
            acc["d_resolved"] = float(given["d_resolved"]) * max(
                1.0, DRAFT_TARGET["target_ci"] / float(given["target_ci"]))
    if isinstance(obs.get("collisions"), dict) or obs.get("collisions") is True:
        acc.update(DRAFT_COLLISIONS)
        coll = obs["collisions"] if isinstance(obs["collisions"], dict) else {}
        coll = dict(coll)
        coll["record"] = min(int(coll.get("record", 1000)), DRAFT_RECORD["record"])
        coll["record_from"] = DRAFT_RECORD["record_from"]
        obs["collisions"] = coll
    if isinstance(obs.get("lyapunov"), dict):  # at most the draft's particles
        from .accuracy import ACCURACY_PRESETS

        n = acc.get("n_particles", ACCURACY_PRESETS["draft"]["n_particles"])
        obs["lyapunov"] = {**obs["lyapunov"], "particles": min(obs["lyapunov"]["particles"], n)}
    doc["accuracy"] = acc
    doc["observables"] = obs
    # the module's old path, kept: this line is part of the workflow text a draft store keeps
    # (its workflow_toml attribute), which stays as before the move to pipeline/workflow/
    return "# draft version written by pipeline.scenes.draft_text\n" + toml_dump(doc)


def shipped_draft(name: str) -> tuple[str, Traversable] | None:
    """(label, file) of the draft a study ships for scene ``name`` (``draft/<name>.toml`` beside
    the scene), or None: then the draft is :func:`draft_text` of the scene."""
    label, _ = _find_scene(name)
    for lab, folder in _scene_folders():
        if f"{lab}/{name}.toml" == label:
            p = folder / "draft" / f"{name}.toml"
            return (f"{lab}/draft/{name}.toml", p) if p.is_file() else None
    return None


def load_scene(name: str, fast: bool = False):
    """The Study of a scene, at draft accuracy if ``fast``: the study's own draft of it if it
    ships one (:func:`shipped_draft`, e.g. fewer frequencies), else :func:`draft_text`."""
    from .load import parse_workflow

    own = shipped_draft(name) if fast else None
    if own is not None:
        return parse_workflow(own[1].read_text(encoding="utf-8"), source=own[0])
    path = scene_path(name)
    text = path.read_text(encoding="utf-8")
    return parse_workflow(draft_text(text) if fast else text, source=scene_label(name))
