"""What an observable is: the contract every plug-in of :mod:`pipeline.workflow.observables`
fulfils, so that the engine (the store's layout and writes, the Dask task, the tables) names
no particular observable.

An observable declares

- whether a scene selects it (:meth:`Observable.on`, read off the scene's
  :class:`pipeline.workflow.keys.Observables`), and the keys of its own ``[observables.NAME]``
  table when it brings one (:attr:`Observable.scene`, a declared dataclass);
- what it asks of the run: sample times (:meth:`Observable.sample_times`, s) and recorded
  collisions per particle (:meth:`Observable.rows`, from :meth:`Observable.rows_from` on);
- its store arrays with their units (:meth:`Observable.coords`, :meth:`Observable.arrays`;
  every data array is (point, family, particle, ...), chunked by the ensemble's chunks);
- how one chunk computes them from its run (:meth:`Observable.compute`, given a
  :class:`Chunk`);
- how it reduces: the engine's tables it feeds (:attr:`Observable.tables`), or a table of its
  own (:meth:`Observable.table`, with its columns' units and meanings in
  :attr:`Observable.columns`, which the one units map :mod:`pipeline.tables.units` reads).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

__all__ = ["Coord", "Array", "Chunk", "Observable"]


@dataclass(frozen=True)
class Coord:
    """A coordinate array of the store: ``values`` along dimension ``dim`` (its own name when
    None), with its units (UDUNITS; "" not a quantity) and long name."""

    name: str
    values: Any
    dtype: Any
    units: str
    long_name: str
    dim: str | None = None


@dataclass(frozen=True)
class Array:
    """A data array: dims (point, family, particle, *trailing), one chunk per ensemble chunk
    and the whole of each trailing axis; ``fill`` where a chunk has no value; ``extra``: more
    attributes of the array."""

    name: str
    trailing: tuple[tuple[str, int], ...]  # (dim, size) after particle
    dtype: str
    fill: Any
    units: str
    long_name: str
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True)
class Chunk:
    """One chunk's run and where it comes from, as an observable computes from it.

    study, point, family: the chunk's Study, Point and Family; index: the chunk's index;
    run: what :func:`bbb.simulate.simulate` recorded; times: the sample times it was asked
    for (s, sorted; None: none); initial: the initial-condition keywords it was run with."""

    study: Any
    point: Any
    family: Any
    index: int
    run: Any
    times: np.ndarray | None = None
    initial: dict = field(default_factory=dict)

    def positions_at(self, times: np.ndarray) -> np.ndarray:
        """x (mm) of the chunk's particles at ``times`` (s, some of :attr:`times`):
        (particle, len(times))."""
        if self.times is not None and self.times.shape == times.shape and np.array_equal(
                self.times, times):
            return self.run.positions
        return self.run.positions[:, np.searchsorted(self.times, times)]


class Observable:
    """An observable's declarations; a plug-in subclasses it and overrides what it records.

    name: its name (the ``[observables.NAME]`` table of a scene when :attr:`scene` is given);
    doc: one line for the workflow reference; scene: the declared dataclass of its table's
    keys (None: an engine table of :class:`pipeline.workflow.keys.ObservablesTable`);
    tables: the engine tables it feeds (:mod:`pipeline.tables.catalog`); growing_dims:
    trailing dims that lengthen when a map grows by points (the digest of a chunk leaves out
    their trailing fill); columns: its own table's columns after (f, grid axes, family,
    initial), each (name, whether ``_lo``/``_hi`` follow, unit, meaning), the rows that the
    one units map (:mod:`pipeline.tables.units`) and docs/tables.md read; when: which stores
    have its table, in words."""

    name: ClassVar[str] = ""
    doc: ClassVar[str] = ""
    scene: ClassVar[type | None] = None
    tables: ClassVar[tuple[str, ...]] = ()
    growing_dims: ClassVar[tuple[str, ...]] = ()
    index: ClassVar[tuple[str, ...]] = ("f", "family")
    columns: ClassVar[tuple[tuple[str, bool, str, str], ...]] = ()
    when: ClassVar[str] = ""

    def on(self, obs) -> bool:
        """Whether a scene's :class:`~pipeline.workflow.keys.Observables` select it."""
        return self.settings(obs) is not None

    def settings(self, obs) -> dict | None:
        """Its ``[observables.NAME]`` keys as the scene gave them (None: not selected); only
        for a plug-in with :attr:`scene`."""
        given = obs.more_of(self.name) if self.scene is not None else None
        return dict(given) if given is not None else None

    def sample_times(self, study, f: float) -> np.ndarray | None:
        """The times (s) at which a chunk at ``f`` must know the positions (None: none)."""
        return None

    def rows(self, study) -> int:
        """Collisions (post-collision states) per particle it needs recorded."""
        return 0

    def rows_from(self, study) -> float:
        """From which time on (s) the collisions are recorded: one recording serves every
        observable, so each that records says the same, ``[observables.collisions]
        record_from`` (0 without that table)."""
        return float(study.observables.collisions_from)

    def coords(self, study) -> tuple[Coord, ...]:
        return ()

    def arrays(self, study) -> tuple[Array, ...]:
        return ()

    def compute(self, chunk: Chunk) -> dict[str, np.ndarray]:
        """{array name: values of the chunk's particles (leading axis; a shorter one fills
        the first particles, the rest stays fill)}."""
        return {}

    def table(self, store, done: np.ndarray):
        """Its own table (a DataFrame, one row per :attr:`index`) from the done chunks of
        ``store`` (a :class:`pipeline.store.study_store.StudyStore`); None: it has none."""
        return None

    def has_table(self) -> bool:
        return type(self).table is not Observable.table
