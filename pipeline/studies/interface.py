"""What a study is: the one contract ``make figures``, the report and the claims registry read.

A study is a folder ``pipeline/studies/<name>/`` whose package defines ``STUDY``, a
:class:`Study`, and whose name is listed in :data:`pipeline.studies.registry.STUDIES`.  The
record names its scenes (run by ``make figures`` in the registry's order), the tables its
claims read (made from the stores, written beside REPORT.md and read back from there), its
figures with their captions, its claims (records of the claims registry) and its REPORT.md
section (a :class:`~pipeline.claims.section.Section`: its own words, the verdicts laid out
from the claim records).  Claims are judged by one function,
:func:`pipeline.claims.claim.evaluate` (claims, context); a study supplies the context.

Types: tables are ``{key: DataFrame}``, stores ``{scene: path}``, verdicts ``{line: rows}``
(one line, ``None``, for a study judged once).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import pandas as pd

from ..claims.claim import Claim, Row, evaluate
from ..claims.section import Section, section_lines
from ..tables.files import read_study_tables, write_csv, write_study_tables

__all__ = ["Study", "Tables", "Stores", "Verdicts", "scene_tables"]

Tables = Mapping[str, pd.DataFrame]
Stores = Mapping[str, str]
Verdicts = Mapping[str | None, Sequence[Row]]


def scene_tables(scenes: Sequence[str]) -> Callable[[Stores], dict[str, pd.DataFrame]]:
    """The default tables of a study: every reduce table of each of its scenes, keyed
    ``<table>`` when named after its scene, else ``<scene>_<table>``."""
    def make(stores: Stores, echo: Callable[[str], None] = print) -> dict[str, pd.DataFrame]:
        from ..tables.files import study_key
        from ..tables.reduce import reduce_store

        return {study_key(name, tname): df for name in scenes
                for tname, df in reduce_store(stores[name], echo=echo).items()}
    return make


@dataclass(frozen=True)
class Study:
    """One study, as ``make figures`` and the report see it.

    name     -- its folder under pipeline/studies/ (and its claims' study in the registry)
    scenes   -- the scenes it runs, in order (their files in its ``scenes/`` or workflows/)
    section  -- its REPORT.md section: heading, own words, layout of the verdicts
    claims   -- its claim records (those it judges; registered ids, or another study's records
                re-judged, taken from the registry)
    context  -- (tables, stores) -> the context its claims are judged in
    draw     -- (tables, stores, out_dir) -> the figure files it drew; it may add tables to
                ``tables`` (read off the stores: its claims' inputs)
    reads    -- the keys of the tables its claims and section read
    captions -- figure file stem -> caption
    make_tables -- (stores, echo) -> its tables from the stores (default: every reduce table
                of its scenes, :func:`scene_tables`)
    files    -- {key: CSV file name} when its tables have names of their own; default the
                scene naming of :mod:`pipeline.tables.files`
    lines    -- tables -> {line label: that line's tables}: its claims are judged on each line
                (a contact model, a protocol) instead of once
    verdicts -- tables -> verdicts read from a committed table of records, when the study
                judges while drawing (its records are one of its tables)
    facts    -- (tables, verdicts) -> the values its section's words name
    further  -- (tables, verdicts) -> lines after the verdicts (tables that are no claims, a
                paragraph generated from the tables and the records)
    labels   -- the claims' short names in a ``by claim``/``by line`` section
    needs_stores -- {claim quantity: why}: claims whose measure reads a store, not a table;
                regenerated from the committed tables their rows are kept from the report
    """

    name: str
    scenes: tuple[str, ...]
    section: Section
    claims: tuple[Claim, ...] = ()
    context: Callable[[Tables, Stores], dict] = lambda tables, stores: {"tables": tables}
    draw: Callable[[dict, Stores, Path], list[Path]] = lambda tables, stores, out: []
    reads: tuple[str, ...] = ()
    captions: Mapping[str, str] = field(default_factory=dict)
    make_tables: Callable[..., dict[str, pd.DataFrame]] | None = None
    files: Mapping[str, str] | None = None
    lines: Callable[[Tables], Mapping[str, Tables]] | None = None
    verdicts: Callable[[Tables], Verdicts] | None = None
    facts: Callable[[Tables, Verdicts], Mapping[str, object]] | None = None
    further: Callable[[Tables, Verdicts], list[str]] | None = None
    labels: tuple[str, ...] = ()
    needs_stores: Mapping[str, str] = field(default_factory=dict)

    # -- tables ---------------------------------------------------------------------------
    def tables(self, stores: Stores, echo: Callable[[str], None] = print
               ) -> dict[str, pd.DataFrame]:
        """Its tables made from the stores (before ``draw`` adds its own)."""
        make = self.make_tables or scene_tables(self.scenes)
        return make(stores, echo)

    def write_tables(self, out_dir: str | os.PathLike, tables: Tables) -> list[Path]:
        """Write its tables as the committed CSVs into ``out_dir``; returns the paths."""
        if self.files is None:
            return write_study_tables(out_dir, tables, self.scenes)
        unknown = sorted(set(tables) - set(self.files))
        if unknown:
            raise KeyError(f"study {self.name}: tables {', '.join(unknown)} have no file name "
                           f"(its files: {', '.join(self.files)})")
        return [write_csv(df, Path(out_dir) / self.files[k]) for k, df in tables.items()]

    def read_tables(self, out_dir: str | os.PathLike) -> dict[str, pd.DataFrame]:
        """Its tables read back from the CSVs in ``out_dir`` (those present)."""
        if self.files is None:
            return read_study_tables(out_dir, self.scenes)
        out = Path(out_dir)
        return {k: pd.read_csv(out / fn) for k, fn in self.files.items() if (out / fn).is_file()}

    # -- claims and report ----------------------------------------------------------------
    def judge(self, tables: Tables, stores: Stores | None = None) -> dict[str | None, list[Row]]:
        """Its verdicts: {line: rows}, {None: rows} when judged once."""
        if self.verdicts is not None:
            return {k: list(v) for k, v in self.verdicts(tables).items()}
        if self.lines is not None:
            return {label: evaluate(self.claims, self.context(t, {}))
                    for label, t in self.lines(tables).items()}
        return {None: evaluate(self.claims, self.context(tables, stores or {}))}

    def report(self, tables: Tables, stores: Stores | None = None,
               verdicts: Verdicts | None = None) -> list[str]:
        """Its REPORT.md section, from its verdicts (judged here unless given) and tables."""
        v = self.judge(tables, stores) if verdicts is None else verdicts
        facts = self.facts(tables, v) if self.facts else {}
        further = self.further(tables, v) if self.further else []
        return section_lines(self.section, v, facts, further, self.labels)
