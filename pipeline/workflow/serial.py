"""A Study as a store keeps it: :func:`study_to_dict` (everything resolved, JSON-able; a key
only when used, so that the stored workflow of every older scene stays as it was) and back,
:func:`study_from_dict`."""

from __future__ import annotations

from typing import Any

from .keys import Accuracy, Analysis, Family, GridRefine, Observables, RefineTable
from .schema import as_dict

__all__ = ["study_to_dict", "study_from_dict", "grid_list", "drop_none"]


def study_to_dict(self) -> dict[str, Any]:
    """The Study ``self`` with everything resolved (preset numbers written out), JSON-able."""
    d = {
        "name": self.name,
        "source": self.source,
        "seed": self.seed,
        "params": {"preset": self.preset, **self.overrides},
        "resolved_params": self.base_params,
        "frequencies": list(self.frequencies),
        "families": [drop_none(as_dict(fam)) for fam in self.families],
        "accuracy": as_dict(self.accuracy),
        "observables": as_dict(self.observables),
        "analysis": as_dict(self.analysis),
    }
    # only when used, so that the stored workflow of every older scene stays as it was
    if self.refine is not None:
        d["refine"] = as_dict(self.refine)
    if self.refined:
        d["refined"] = list(self.refined)
    if self.grid:
        d["grid"] = grid_list(self.grid)
        d["invalid"] = self.invalid
        if self.grid_refine is not None:
            d["grid_refine"] = as_dict(self.grid_refine)
        if self.stored_points:  # else the grid's own order
            d["points"] = [[p.f, [list(av) for av in p.grid]] for p in self.points]
    return d


def study_from_dict(cls: type, d: dict[str, Any], text: str = ""):
    """The Study (of class ``cls``) of a stored :func:`study_to_dict`; ``text``: its TOML."""
    params = dict(d["params"])
    preset = params.pop("preset")
    fams = tuple(
        Family(
            name=fd["name"],
            initial=fd["initial"],
            drop_height=_tuple_or_none(fd.get("drop_height")),
            launch_speed=_tuple_or_none(fd.get("launch_speed")),
            mirror=fd.get("mirror"),
            lattice=_tuple_or_none(fd.get("lattice")),
            offset=None if fd.get("offset") is None else float(fd["offset"]),
            description=fd.get("description", ""),
        )
        for fd in d["families"]
    )
    return cls(
        name=d["name"],
        source=d["source"],
        seed=int(d["seed"]),
        preset=preset,
        overrides={k: v if k in ("contact", "floor") else float(v) for k, v in params.items()},
        frequencies=tuple(float(f) for f in d["frequencies"]),
        families=fams,
        accuracy=Accuracy(**d["accuracy"]),
        observables=Observables(**d["observables"]),
        analysis=Analysis(**d["analysis"]),
        refine=RefineTable(**d["refine"]) if d.get("refine") is not None else None,
        refined=tuple(float(f) for f in d.get("refined", ())),
        grid=tuple((a, tuple(v if isinstance(v, str) else float(v) for v in values))
                   for a, values in d.get("grid", ())),
        invalid=d.get("invalid", "refuse"),
        grid_refine=(GridRefine(**{**d["grid_refine"], "to": tuple(
            (a, float(v)) for a, v in d["grid_refine"]["to"])})
            if d.get("grid_refine") else None),
        stored_points=tuple((float(f), tuple((a, v if isinstance(v, str) else float(v))
                                             for a, v in grid))
                            for f, grid in d.get("points", ())),
        text=text,
    )


def grid_list(grid) -> list:
    """A grid as JSON: [[axis, [values]], ...]."""
    return [[a, list(values)] for a, values in grid]


def drop_none(d: dict) -> dict:
    """``d`` without its None values, tuples as lists."""
    return {k: (list(v) if isinstance(v, tuple) else v) for k, v in d.items() if v is not None}


def _tuple_or_none(v):
    return None if v is None else tuple(float(x) for x in v)
