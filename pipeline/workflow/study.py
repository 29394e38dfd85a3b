"""The validated workflow, :class:`Study`: what a scene asks for, resolved, and what follows
from it -- the parameters at each frequency, the sample times, every chunk's seed, the
serialised form a store keeps, and the fingerprint of what determines the stored numbers.

A scene with a ``[grid]`` has points: every combination of its grid axes (in the order the
workflow gives them) with its frequencies, frequency innermost, so that each grid line -- one
value per axis -- is a contiguous D(f) curve, the unit along which frequency refinement works,
and a scene without a grid is the one-line case whose points are its frequencies, in order.
:attr:`Study.points` holds each point's Params; the per-frequency API (:meth:`Study.params`)
serves scenes without a grid only.

A Study is made by :func:`pipeline.workflow.load.parse_workflow` (which validates the TOML) or
read back from a store (:meth:`Study.from_dict`).  Frequencies in Hz (multiples of 1 mHz),
times in s, lengths in mm.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Any

import numpy as np

from bbb.params import Params

from .identity import chunk_seed, f_key, point_key
from .keys import Accuracy, Analysis, Family, GridRefine, Observables, RefineTable
from .point import Grid, Point, combinations, elsewhere, fmt_value, resolve_params
from .schema import InputError, as_dict, line_of
from .serial import drop_none

__all__ = ["Study", "Point", "resolve_params", "WorkflowError", "GridNotRunnable"]



class WorkflowError(InputError):
    """A malformed workflow: one line with file, line, key and what is allowed."""


class GridNotRunnable(WorkflowError):
    """A grid scene asked for something that knows one point per frequency only: refused in
    one line."""

    def __init__(self, study: Study, what: str):
        axes = ", ".join(a for a, _ in study.grid)
        super().__init__(study.source, "grid", f"{what} knows one point per frequency, and this "
                         f"scene also sweeps {axes}",
                         "a workflow without [grid], or one grid line of it (Study.line, e.g. "
                         "[params] alpha = 0.5)", line_of(study.text, ("grid",)))


@dataclass(frozen=True)
class Study:
    """A validated workflow.  Frequencies are in Hz, rounded to 1 mHz."""

    name: str
    source: str
    seed: int
    preset: str
    overrides: dict[str, float | str]
    frequencies: tuple[float, ...]
    families: tuple[Family, ...]
    accuracy: Accuracy
    observables: Observables
    analysis: Analysis
    #: adaptive frequency refinement ([frequencies] refine), or None
    refine: RefineTable | None = None
    #: frequencies added by refinement, Hz, in the order they joined the store; they follow
    #: the workflow's own grid in ``frequencies``
    refined: tuple[float, ...] = ()
    #: the [grid] axes, (axis, values) in the workflow's order; () without a grid
    grid: Grid = ()
    #: what a point bbb.Params refuses does: "refuse" (the workflow is refused) or "skip"
    invalid: str = "refuse"
    #: a grid store's points in store order, (f, grid values) each, as its store holds them
    #: (a store grows along points: a widened grid's new points follow the old ones); () for a
    #: workflow not yet stored, whose points are then in axis order
    stored_points: tuple[tuple[float, tuple[tuple[str, Any], ...]], ...] = ()
    #: a map's refinement rule ([grid.refine]), or None
    grid_refine: GridRefine | None = None
    text: str = field(default="", compare=False, repr=False)

    # -- derived quantities -------------------------------------------------------------------
    def params(self, f: float) -> Params:
        """The Params at frequency f (Hz) of a scene without a grid (a grid scene's points
        each have theirs: :attr:`points`)."""
        self.refuse_grid("Study.params(f)")
        return resolve_params(self.preset, f, self.overrides)

    def refuse_grid(self, what: str) -> None:
        """Refuse (GridNotRunnable, one line) ``what`` on a scene with a [grid]: ``what``
        knows one point per frequency only."""
        if self.grid:
            raise GridNotRunnable(self, what)

    @property
    def axes(self) -> tuple[tuple[str, tuple[Any, ...]], ...]:
        """Every axis of the points, outermost first: the [grid] axes in the workflow's order,
        then ("f", the frequencies in Hz) innermost."""
        return (*self.grid, ("f", self.frequencies))

    @cached_property
    def points(self) -> tuple[Point, ...]:
        """Every point, each with its Params, in store order: a grid store's points as it
        holds them (:attr:`stored_points`), then the grid's other points in axis order
        (:attr:`axes`; frequency innermost); with ``invalid = "skip"`` the points bbb.Params
        refuses are left out.  Without a grid: one point per frequency, in the order of
        ``frequencies``."""
        out, seen = [], set()
        for f, grid in self.stored_points:
            out.append(Point(f, grid, self._resolve(f, grid)))
            seen.add(point_key(f, grid))
        for grid in self._grid_values():
            for f in self.frequencies:
                if point_key(f, grid) in seen:
                    continue
                try:
                    p = self._resolve(f, grid)
                except ValueError:
                    if self.invalid == "skip":
                        continue
                    raise
                out.append(Point(f, grid, p))
        return tuple(out)

    def _resolve(self, f: float, grid: tuple[tuple[str, Any], ...]) -> Params:
        return resolve_params(self.preset, f, {**self.overrides, **dict(grid)})

    @property
    def point_dim(self) -> str:
        """The store's first dimension: "frequency" without a grid (one point per frequency,
        as every store before grids), "point" with one (coordinates: frequency and each
        axis along it)."""
        return "point" if self.grid else "frequency"

    def with_stored_points(self, points: tuple[tuple[float, tuple], ...]) -> Study:
        """This workflow on a grid store holding ``points`` ((f, grid values) in store order):
        the store's points first, then this workflow's points it lacks.  Points in the
        grid's own order are no news: the study is then this one (``stored_points`` ())."""
        stored = tuple((float(f), tuple(g)) for f, g in points)
        natural = replace(self, stored_points=())
        if [point_key(f, g) for f, g in stored] == [p.key for p in natural.points][:len(stored)]:
            return natural
        return replace(self, stored_points=stored)

    def line(self, values: Mapping[str, Any]) -> Study:
        """The scene without a grid at one value of every grid axis (``values``: axis ->
        value): its points are this grid line's, along f, and it is the Study of the same
        workflow with those values in [params] instead of [grid] -- same seeds, same
        fingerprint (a contact of "stick" is no override, as in [params])."""
        names = [a for a, _ in self.grid]
        if sorted(values) != sorted(names):
            raise ValueError(f"a grid line needs one value of each axis ({', '.join(names)}), "
                             f"got {', '.join(values) or 'none'}")
        overrides = dict(self.overrides)
        for a, axis in self.grid:
            v = values[a]
            if v not in axis and v != elsewhere(a, {**self.overrides, **values}):
                raise ValueError(f"{a} = {fmt_value(v)} is not on the grid; allowed: "
                                 + ", ".join(fmt_value(x) for x in axis))
            if (a, v) in (("contact", "stick"), ("floor", "arc")):
                overrides.pop(a, None)
            else:
                overrides[a] = v
        grid = tuple((a, values[a]) for a in names)
        freqs = tuple(sorted(p.f for p in self.points if p.grid == grid))
        label = ", ".join(f"{a} = {fmt_value(v)}" for a, v in grid)
        if not freqs:
            raise ValueError(f"every point of the line {label} is skipped as invalid")
        # the TOML a store keeps says which line of which grid it holds
        text = f"# the grid line {label} of this workflow\n{self.text}" if self.text else ""
        return replace(self, overrides=overrides, frequencies=freqs, grid=(), invalid="refuse",
                       refined=tuple(f for f in self.refined if f in freqs), stored_points=(),
                       text=text)

    def _grid_values(self):
        """Every combination of the grid axes' values as (axis, value) pairs, in axis order
        (:func:`pipeline.workflow.point.combinations`)."""
        return combinations(self.grid, self.overrides)

    @property
    def base_params(self) -> dict[str, float]:
        """The resolved parameters except f (which varies over the grid), the grid axes (so
        do they), and, with Gamma, A (Gamma instead)."""
        if not self.grid and "Gamma" not in self.overrides:
            d = Params.preset(self.preset, f=1.0, **self.overrides).as_dict()
            del d["f"]
            return d
        p = (self.points[0].params if self.grid and self.points
             else resolve_params(self.preset, 1.0, self.overrides))
        axes = {a for a, _ in self.grid}
        drop = {"f"} | axes | ({"A"} if "Gamma" in axes | set(self.overrides) else set())
        d = {k: v for k, v in p.as_dict().items() if k not in drop}
        if "Gamma" in self.overrides:
            d["Gamma"] = float(self.overrides["Gamma"])
        return d

    @property
    def f_mhz(self) -> tuple[int, ...]:
        return tuple(f_key(f) for f in self.frequencies)

    @property
    def base_frequencies(self) -> tuple[float, ...]:
        """The workflow's own frequencies, Hz (``frequencies`` without the refined ones)."""
        added = {f_key(f) for f in self.refined}
        return tuple(f for f in self.frequencies if f_key(f) not in added)

    @property
    def adaptive(self) -> bool:
        """Whether chunks are computed in waves (target_ci) or frequencies added (refine)."""
        return (self.accuracy.adaptive or self.refine is not None
                or self.grid_refine is not None)

    def with_refined(self, added: tuple[float, ...]) -> Study:
        """The study whose store also holds the refined frequencies ``added`` (Hz, in store
        order), appended after the workflow's own."""
        base = self.base_frequencies
        return replace(self, frequencies=base + tuple(added), refined=tuple(added))

    def sample_times(self) -> np.ndarray:
        """Position sample times, s: 0, dt, ..., t_max."""
        n = round(self.accuracy.t_max / self.accuracy.sample_dt)
        return np.arange(n + 1, dtype=np.float64) * self.accuracy.sample_dt

    def seed_sequence(self, f: float, family: Family, chunk: int) -> np.random.SeedSequence:
        """The seed of one chunk, keyed by values (f in mHz, family name hash, chunk index), so
        adding frequencies or families never changes the results of the others."""
        return chunk_seed(self, f, family, chunk)

    @property
    def mirror_symmetric(self) -> bool:
        """Whether the floor is mirror-symmetric (level, vibrated vertically: no tilt, throw
        90°) at every point, under any contact model: a particle's mirror image then moves as
        its reflection."""
        if self.grid:  # every point's floor (tilt, throw, the floor's shape may be axes)
            return all(p.params.mirror_symmetric for p in self.points)
        return resolve_params(self.preset, 1.0, self.overrides).mirror_symmetric

    def pairing(self, family: Family, point: Point | None = None) -> str:
        """How ``family``'s particles enter the estimates (bbb.analysis.transport.PAIRING) at
        ``point`` (None: at every point, as without a grid): "mirror symmetry" (images counted,
        not simulated), "pairs" (each chunk's second half are the mirror partners of its
        first half, bbb.ensemble.mirror_pairs) or "independent".  A grid line's points pair
        as the scene of that line does."""
        from bbb.analysis.transport import INDEPENDENT, PAIRS, SYMMETRY

        # the floor (tilt, throw) is the same along f: a point pairs as its grid line's scene
        symmetric = self.mirror_symmetric if point is None else point.params.mirror_symmetric
        mirror = symmetric if family.mirror is None else family.mirror
        return INDEPENDENT if not mirror else SYMMETRY if symmetric else PAIRS

    def with_frequencies(self, frequencies: tuple[float, ...]) -> Study:
        """The same study at some of its frequencies (Hz): every chunk keeps its seed, so it
        computes the same numbers as in the whole sweep."""
        mhz = {f_key(f) for f in frequencies}
        return replace(self, frequencies=tuple(f for f in self.base_frequencies
                                               if f_key(f) in mhz), refined=())

    # -- serialisation (pipeline.workflow.serial) ------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """Everything resolved (preset numbers written out), JSON-able."""
        from .serial import study_to_dict

        return study_to_dict(self)

    @classmethod
    def from_dict(cls, d: dict[str, Any], text: str = "") -> Study:
        """The Study of a stored :meth:`to_dict`, its TOML source ``text``."""
        from .serial import study_from_dict

        return study_from_dict(cls, d, text)

    def data_identity(self) -> dict[str, Any]:
        """The parts that determine the stored numbers (not the name, not reduce settings)."""
        acc = as_dict(self.accuracy, identity=True)
        del acc["preset"], acc["n_resamples"]
        d = {
            "seed": self.seed,
            "params": self.base_params,
            # a grid store's points are its coordinates, not its identity: it grows along
            # them (a widened grid, refinement) without rewriting what is done
            **({} if self.grid else {"f_mhz": [f_key(f) for f in self.base_frequencies]}),
            "families": [self._family_identity(fam) for fam in self.families],
            "accuracy": acc,
            "observables": as_dict(self.observables, identity=True),
        }
        if self.adaptive:
            # Which chunks and frequencies get computed depends on the CI of D, so on the
            # settings of that CI too (absent for fixed-N scenes: their fingerprints stay).
            an = self.analysis
            d["stopping"] = {"n_resamples": self.accuracy.n_resamples, "ci": an.ci,
                             "ci_method": an.ci_method, "discard": an.discard,
                             "fit_from": an.fit_from, "fit_to": an.fit_to}
        if self.refine is not None:
            d["refine"] = as_dict(self.refine)
        if self.grid:  # absent without a grid: every older store keeps its fingerprint
            d["axes"] = [a for a, _ in self.grid]
        return d

    def _family_identity(self, fam: Family) -> dict[str, Any]:
        # mirror changes the stored numbers only where the partners are simulated ("pairs");
        # images counted by symmetry, or none, leave the store (and its fingerprint) as before
        d = drop_none(as_dict(fam, identity=True))
        d.pop("mirror", None)
        if self.grid:  # the points (so where partners are simulated) are not the identity
            if fam.mirror is not None:
                d["mirror"] = fam.mirror
        elif self.pairing(fam) == "pairs":
            d["mirror"] = True
        return d

    def fingerprint(self) -> str:
        blob = json.dumps(self.data_identity(), sort_keys=True, default=_json_default)
        return hashlib.sha256(blob.encode()).hexdigest()


def _json_default(o):
    if isinstance(o, tuple):
        return list(o)
    raise TypeError(type(o))

