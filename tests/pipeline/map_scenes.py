"""The shipped map scenes (every scene with a ``[grid]``) and their tiny versions: the same
``[params]``, ``[grid]`` (and ``[grid.refine]``), families and observables, at two or three
frequencies with a few particles for a few seconds, so a test runs the real pipeline on
every map layout the project ships."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

#: every shipped scene with a [grid], relative to the repository (a test checks the list)
MAP_SCENES = (
    "pipeline/studies/contact/scenes/contact.toml",
    "pipeline/studies/contact/scenes/contact_proj.toml",
    "pipeline/studies/dissipation/scenes/dissipation.toml",
    "pipeline/studies/dissipation/scenes/dissipation_locking.toml",
    "pipeline/studies/dissipation/scenes/dissipation_r25.toml",
    "pipeline/studies/onset/scenes/onset_map.toml",
    "pipeline/studies/onset/scenes/onset_sine.toml",
    "pipeline/studies/ratchet/scenes/ratchet.toml",
    "pipeline/studies/ratchet/scenes/ratchet_states.toml",
    "pipeline/studies/transport/scenes/transport.toml",
    "pipeline/studies/transport/scenes/transport_reversal.toml",
    "pipeline/studies/transport/scenes/transport_sliding.toml",
    "workflows/sawtooth.toml",
    "workflows/sine.toml",
)

TINY_ACCURACY = {"preset": "draft", "n_particles": 4, "chunk_size": 4, "t_max": 8.0,
                 "sample_dt": 0.1, "n_resamples": 50}


def shipped_maps() -> list[str]:
    """The scenes with a [grid] found in the repository now."""
    found = [*ROOT.glob("pipeline/studies/*/scenes/*.toml"), *ROOT.glob("workflows/*.toml")]
    return sorted(str(p.relative_to(ROOT)) for p in found
                  if "grid" in tomllib.loads(p.read_text()))


def tiny_scene(scene: str, frequencies=(54.0, 60.0), refine_f: float = 3.0) -> str:
    """The TOML of ``scene``'s tiny version: its [grid] at ``frequencies`` (Hz), a chunk of 4
    particles per (point, family) for 8 s; a [grid.refine] refines along f only, to
    ``refine_f`` Hz."""
    doc = tomllib.loads((ROOT / scene).read_text())
    doc["study"] = {"name": f"tiny_{doc['study']['name']}", "seed": doc["study"]["seed"]}
    doc["frequencies"] = {"values": list(frequencies)}
    doc["accuracy"] = dict(TINY_ACCURACY)
    if "collisions" in doc.get("observables", {}):
        doc["observables"]["collisions"] = {"record": 20, "record_from": 2.0}
    refine = doc.get("grid", {}).get("refine")
    if refine is not None:
        kept = {k: v for k, v in refine.items() if k in ("extrema", "jumps", "quantity")}
        doc["grid"]["refine"] = {**kept, "f": refine_f}
    return _toml(doc)


def _toml(doc: dict, prefix: str = "") -> str:
    """A small TOML writer for a workflow: tables of strings, numbers, booleans and lists."""
    plain = {k: v for k, v in doc.items() if not isinstance(v, dict)}
    nested = any(isinstance(v, dict) for v in doc.values())
    lines = [f"[{prefix}]"] if prefix and (plain or not nested) else []
    lines += [f"{k} = {_value(v)}" for k, v in plain.items()]
    out = "\n".join(lines) + "\n" if lines else ""
    for k, v in doc.items():
        if isinstance(v, dict):
            out += "\n" + _toml(v, f"{prefix}.{k}" if prefix else k)
    return out


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, str):
        return json.dumps(v)
    return repr(v)
