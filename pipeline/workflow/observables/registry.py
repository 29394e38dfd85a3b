"""Every observable, listed once, in the order of their arrays in a store (the order of the
``array`` coordinate that a chunk's digests follow: a new observable goes last, so that every
store made before it keeps its layout).

The engine reads observables only through this list: the store's layout and writes
(:mod:`pipeline.store.layout`, :mod:`pipeline.store.study_store`), the Dask task
(:mod:`pipeline.execute.task`), the tables (:mod:`pipeline.tables.catalog`,
:mod:`pipeline.tables.units`) and the scene's ``[observables.NAME]`` tables of the plug-ins
that bring their own (:func:`scene_tables`).
"""

from __future__ import annotations

from .collision_jumps import CollisionJumps
from .collisions import Collisions
from .contact import Contact
from .contract import Observable
from .counters import Counters
from .impacts import Impacts
from .jumps import Jumps
from .lyapunov import Lyapunov
from .positions import Positions
from .states import States

__all__ = ["OBSERVABLES", "selected", "by_name", "scene_tables", "growing_dims", "feeds",
           "own_tables"]

OBSERVABLES: tuple[Observable, ...] = (
    Positions(), Collisions(), Counters(), Contact(), Jumps(), Lyapunov(), CollisionJumps(),
    Impacts(), States(),
)


def selected(study) -> tuple[Observable, ...]:
    """The observables a study's scene selects, in store order."""
    return tuple(o for o in OBSERVABLES if o.on(study.observables))


def by_name(name: str) -> Observable:
    return next(o for o in OBSERVABLES if o.name == name)


def scene_tables() -> tuple[Observable, ...]:
    """The plug-ins that bring their own ``[observables.NAME]`` table (:attr:`Observable.scene`)."""
    return tuple(o for o in OBSERVABLES if o.scene is not None)


def growing_dims() -> frozenset[str]:
    """Trailing dims that lengthen when a map grows by points."""
    return frozenset(d for o in OBSERVABLES for d in o.growing_dims)


def feeds(study, table: str) -> bool:
    """Whether an observable the study selects feeds the engine table ``table``."""
    return any(table in o.tables for o in selected(study))


def own_tables() -> tuple[Observable, ...]:
    """The observables with a table of their own (:meth:`Observable.table`), in store order."""
    return tuple(o for o in OBSERVABLES if o.has_table())
