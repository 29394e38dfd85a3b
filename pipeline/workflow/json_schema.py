"""The scene format as a JSON Schema (draft 2020-12), for editors that check TOML against one
(``python -m pipeline.workflow --schema > bbb-scene.schema.json``; e.g. Even Better TOML's
``#:schema`` directive or taplo's ``[schema]``).

Generated from the one source of the scene format: every key's declaration in
:mod:`pipeline.workflow.keys` (type, choices, pattern, bounds, default, doc and units) and,
for the ``[params]`` keys that bbb.Params checks itself, its ranges
(:data:`bbb.params.PARAM_RANGES`).  What a schema cannot say -- a bound that is another key
(``record_from < t_max``), rules over several keys (``chunk_size`` divides ``n_particles``,
``R >= S/2``, a key valid only for one ``initial``) -- is in each key's ``description`` and
checked by the loader, whose one-line errors stay the authority: a scene the schema accepts
may still be refused, never the other way round for what the schema does state.
"""

from __future__ import annotations

from typing import Any

from bbb.params import PARAM_RANGES

from .keys import (
    GRID_AXES,
    TABLES,
    Accuracy,
    Analysis,
    Family,
    FrequenciesTable,
    GridRefineTable,
    GridTable,
    ParamsTable,
    StudyTable,
    observables_table,
)
from .schema import REQUIRED, Key, declared

__all__ = ["scene_schema", "key_schema", "table_schema"]

_FAMILY_NAME = "^[A-Za-z][A-Za-z0-9_-]*$"


def key_schema(k: Key) -> dict[str, Any]:
    """The JSON Schema of one declared key: its type, choices, pattern and numeric bounds,
    its default and a description (doc, units and what is allowed, in the loader's words)."""
    kind = k.kind
    if kind == "table":
        s: dict[str, Any] = {"anyOf": [table_schema(k.base), {"type": "boolean"}]}
    elif kind == "pair":
        s = {"type": "array", "items": {"type": "number", **_bounds(k)},
             "minItems": 2, "maxItems": 2}
    elif kind == "list":
        s = {"type": "array", "items": {"type": "number", **_bounds(k)}, "minItems": 1}
    elif kind in ("int", "float"):
        s = {"type": "integer" if kind == "int" else "number", **_bounds(k)}
    elif kind == "str":
        s = {"type": "string"}
        if k.choices is not None:
            s["enum"] = list(k.choices)
        if k.pattern is not None:
            s["pattern"] = f"^(?:{k.pattern})$"
    else:
        s = {"type": "boolean"}
    words = [k.doc]
    if k.units:
        words.append(f"units: {k.units}")
    if kind != "table":
        words.append(f"allowed: {k.allowed_text()}")
    words.append(f"default: {k.default_text()}")
    s["description"] = "; ".join(w for w in words if w)
    if k.default is not REQUIRED and k.default is not None and kind != "table":
        s["default"] = list(k.default) if isinstance(k.default, tuple) else k.default
    return s


def _bounds(k: Key) -> dict[str, float]:
    """The numeric bounds of ``k`` (a bound that names another key is left to the loader);
    a [params] key's from bbb.Params' own ranges."""
    out: dict[str, float] = {}
    for name, word in (("gt", "exclusiveMinimum"), ("ge", "minimum"),
                       ("lt", "exclusiveMaximum"), ("le", "maximum")):
        v = getattr(k, name)
        if isinstance(v, int | float) and not isinstance(v, bool):
            out[word] = v
    rng = PARAM_RANGES.get(k.name) if k.name in _PARAM_KEYS else None
    if rng is not None and not out:
        out["exclusiveMinimum" if rng.lo_open else "minimum"] = rng.lo
        if k.finite or rng.hi != float("inf"):
            out["exclusiveMaximum" if rng.hi_open else "maximum"] = rng.hi
    if k.name == "R" and k.name in _PARAM_KEYS:
        out.pop("maximum", None)  # R may be inf (a flat floor): TOML's inf has no JSON form
    return out


_PARAM_KEYS = {k.name for k in declared(ParamsTable)}


def table_schema(cls: type, extra: dict[str, Any] | None = None,
                 closed: bool = True) -> dict[str, Any]:
    """The JSON Schema of a TOML table declared by dataclass ``cls``: its keys as
    properties, the REQUIRED ones required, no other key (unless ``closed`` is False)."""
    keys = declared(cls)
    s: dict[str, Any] = {"type": "object",
                         "properties": {k.name: key_schema(k) for k in keys}}
    doc = (cls.__doc__ or "").strip()
    if doc and not doc.startswith(f"{cls.__name__}("):
        s["description"] = " ".join(doc.split())
    required = [k.name for k in keys if k.default is REQUIRED and k.when is None]
    if required:
        s["required"] = required
    if extra:
        s["properties"].update(extra)
    if closed:
        s["additionalProperties"] = False
    return s


def _axis_schema(k: Key) -> dict[str, Any]:
    """A [grid] axis: a non-empty list of distinct values of the [params] key ``k``."""
    one = key_schema(k)
    item = {n: v for n, v in one.items() if n not in ("description", "default")}
    return {"type": "array", "items": item, "minItems": 1, "uniqueItems": True,
            "description": f"grid axis over {k.name} ({k.doc}): its values"}


def scene_schema() -> dict[str, Any]:
    """The whole scene format (the tables of :data:`pipeline.workflow.keys.TABLES`)."""
    params = {k.name: k for k in declared(ParamsTable)}
    grid = table_schema(GridTable, closed=False)
    grid["properties"].update({a: _axis_schema(params[a]) for a in GRID_AXES})
    grid["properties"]["refine"] = table_schema(
        GridRefineTable, closed=False,
        extra={"f": {"type": "number", "minimum": 0.002,
                     "description": "resolution along f (Hz)"}})
    grid["properties"]["refine"]["additionalProperties"] = {
        "type": "number", "exclusiveMinimum": 0,
        "description": "a resolution along a numeric grid axis, in its unit"}
    grid["additionalProperties"] = False
    frequencies = table_schema(FrequenciesTable)
    accuracy = table_schema(Accuracy)
    preset = accuracy["properties"]["preset"]
    tables = {
        "study": table_schema(StudyTable),
        "params": table_schema(ParamsTable),
        "frequencies": {"anyOf": [frequencies, key_schema(_values_key())],
                        "description": "values = [...] (Hz), or start, stop, step (Hz); "
                                       "or frequencies = [...]"},
        "grid": grid,
        "families": {"type": "object", "minProperties": 1,
                     "propertyNames": {"pattern": _FAMILY_NAME},
                     "additionalProperties": _family_schema(),
                     "description": "[families.NAME]: one table per initial-condition family"},
        "accuracy": {"anyOf": [accuracy, {k: v for k, v in preset.items() if k != "default"}]},
        "observables": {**table_schema(observables_table()), "minProperties": 1},
        "analysis": table_schema(Analysis),
    }
    assert list(tables) == list(TABLES)
    return {"$schema": "https://json-schema.org/draft/2020-12/schema", "title": "bbb scene",
            "description": "A scene of the bbb study pipeline (python -m pipeline.workflow "
                           "--reference: the same keys as a table)",
            "type": "object", "properties": tables, "required": ["frequencies", "observables"],
            "additionalProperties": False}


def _values_key() -> Key:
    return next(k for k in declared(FrequenciesTable) if k.name == "values")


def _family_schema() -> dict[str, Any]:
    """[families.NAME]: ``initial`` may be left out when NAME is one of its choices."""
    s = table_schema(Family)
    s.pop("required", None)
    return s
