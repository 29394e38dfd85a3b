"""Every table a store has, in one place: which tables a study's store gives
(:func:`table_names`) and the tables themselves (:func:`tables`), for ``bbb reduce``
(:func:`pipeline.tables.reduce.reduce_store`, which writes them as Parquet and CSV) and for
the API (:func:`pipeline.api.reduced`, ``open_study(reduced=True)``), so the two cannot list
different tables.

=============  ==============  ==================================================================
table          one row per     the store has it with                    columns in
=============  ==============  ==================================================================
counters       (f, family)     always                                   pipeline.tables.counters
diffusion      f               [observables.positions] (transport       pipeline.tables.diffusion
                               columns on a tilted or thrown floor)
contact        (f, family)     [observables.contact]                    pipeline.tables.contact
mechanisms     f               [observables.jumps] or .lyapunov         pipeline.tables.mechanisms
locking        (f, family)     [observables.collisions]; only by name   pipeline.tables.collisions
=============  ==============  ==================================================================

``locking`` (the spiral's locking from the post-collision states) is computed when asked for
by name (``tables(store, ["locking"])``, ``reduced(path, ["locking"])``): ``bbb reduce`` and
the default of :func:`tables` give the other four, as before, so a study's committed tables
(written from ``reduce_store``) keep their files.  Every column's unit:
:mod:`pipeline.tables.units`.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..store.study_store import StudyStore
from ..workflow.observables.registry import feeds, own_tables, selected
from ..workflow.study import Study
from .collisions import locking_table
from .contact import contact_table
from .counters import counters_table
from .diffusion import diffusion_table
from .mechanisms import mechanisms_table

__all__ = ["Table", "TABLES", "table_names", "tables", "index_of"]


@dataclass(frozen=True)
class Table:
    """One table a store may give: its name, the columns that say which row (``("f",)`` or
    ``("f", "family")``), whether a study's store has it, how it is made (from the store and
    its done markers), and whether it is made unless asked for by name."""

    name: str
    index: tuple[str, ...]
    has: Callable[[Study], bool]
    make: Callable[[StudyStore, np.ndarray], pd.DataFrame]
    by_default: bool = True


TABLES: tuple[Table, ...] = (
    Table("counters", ("f", "family"), lambda s: feeds(s, "counters"), counters_table),
    Table("diffusion", ("f",), lambda s: feeds(s, "diffusion"), diffusion_table),
    Table("contact", ("f", "family"), lambda s: feeds(s, "contact"), contact_table),
    Table("mechanisms", ("f",), lambda s: feeds(s, "mechanisms"), mechanisms_table),
    Table("locking", ("f", "family"), lambda s: feeds(s, "locking"),
          lambda store, done: locking_table(store), by_default=False),
    # the observables' own tables (pipeline.workflow.observables), in store order
    *(Table(o.name, o.index, lambda s, o=o: o in selected(s), o.table) for o in own_tables()),
)
_BY_NAME = {t.name: t for t in TABLES}


def table_names(study: Study, every: bool = False) -> list[str]:
    """The tables a store of ``study`` gives, in order: those made by default, or with
    ``every`` also those made only by name."""
    return [t.name for t in TABLES if t.has(study) and (every or t.by_default)]


def tables(store: StudyStore, names: Iterable[str] | None = None,
           done: np.ndarray | None = None) -> dict[str, pd.DataFrame]:
    """{name: table} of ``store``: ``names`` (default: :func:`table_names`), each from the
    particles of done chunks (``done``: the store's done markers, read once if not given),
    sorted by f (refined frequencies are appended to the store's frequency axis); a grid
    store's by its axes, then f (a long table: one column per axis, after f).

    Raises ValueError naming a table the store does not have."""
    study = store.study
    wanted = table_names(study) if names is None else list(names)
    have = table_names(study, every=True)
    unknown = [n for n in wanted if n not in have]
    if unknown:
        raise ValueError(f"{store.path}: no table {', '.join(map(repr, unknown))}; "
                         f"allowed: {', '.join(have)}")
    done = store.done() if done is None else done
    order = [a for a, _ in study.grid] + ["f"]  # a grid's lines, each along f
    out = {}
    for name in wanted:
        df = _BY_NAME[name].make(store, done)
        out[name] = df.sort_values(order, kind="stable").reset_index(drop=True)
    return out


def index_of(name: str, study: Study | None = None) -> tuple[str, ...]:
    """The columns that say which row of table ``name`` (``("f",)`` or ``("f", "family")``;
    for a grid ``study``, its axes follow f: ``("f", "alpha", "family")``)."""
    index = _BY_NAME[name].index
    axes = tuple(a for a, _ in study.grid) if study is not None else ()
    return index[:1] + axes + index[1:]
