"""Every committed map table holds exactly the points its committed scene makes: the scene's
listed points (its ``[grid]`` x ``[frequencies]``), plus, for a scene with ``[grid.refine]``,
the points the refinement rule (:func:`pipeline.execute.grid_refine.refine_grid`) adds when it
is replayed on the table's own D and CI, round after round, until it adds nothing.  A table
left over from another rule or an earlier bug (points the scene cannot make, or points it
makes missing) fails here."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pipeline.execute.grid_refine import VALUE_DIGITS, refine_grid
from pipeline.workflow.load import load_workflow
from pipeline.workflow.point import Point
from tests.pipeline.map_scenes import MAP_SCENES, ROOT

FIGURES = ROOT / "figures"


def _tables(scene: str) -> list[Path]:
    name = Path(scene).stem
    return [p for p in (FIGURES / f"{name}_diffusion.csv", FIGURES / f"{name}_counters.csv")
            if p.is_file()]


def _key(f: float, grid) -> tuple:
    vals = tuple((a, v if isinstance(v, str) else round(float(v), VALUE_DIGITS)) for a, v in grid)
    return (int(round(f * 1000)), *vals)


def _table_points(df: pd.DataFrame, axes: list[str]) -> dict[tuple, int]:
    out = {}
    for i, r in enumerate(df[["f", *axes]].itertuples(index=False)):
        out.setdefault(_key(r[0], tuple(zip(axes, r[1:], strict=True))), i)
    return out


#: a failed estimator's numbers, as `bbb reduce` writes them into the status (its columns blank)
_FAILED_FIT = re.compile(r"fit D = (\S+) \[(\S+), (\S+)\]")


def _value(r: pd.Series, col: str) -> tuple[float, float, float]:
    """(value, lo, hi) of ``col`` at a table row as the run's refinement read it: a failed
    estimator's blank D is the fit's own numbers (kept in D_status to 3 digits)."""
    if col == "D" and isinstance(r.get("D_status"), str) and math.isnan(r["D"]):
        m = _FAILED_FIT.search(r["D_status"])
        if m:
            return tuple(float(v) for v in m.groups())
    return r[col], r[f"{col}_lo"], r[f"{col}_hi"]


def _replayed(study, df: pd.DataFrame, axes: list[str]) -> set[tuple]:
    """The scene's points, grown by its refinement rule replayed on the table's D (pooled, as
    the run's waves read it) until nothing is added; a point the rule adds that the table
    lacks stops the replay (it is then missing from the result, and the test names it)."""
    have = _table_points(df, axes)
    points = list(study.points)
    rule = study.grid_refine
    if rule is None:
        return {_key(p.f, p.grid) for p in points}
    col = "D" if rule.quantity == "D" else "v"
    own = {"f": study.base_frequencies, **{a: vs for a, vs in study.grid}}
    for _ in range(50):
        rows = []
        for p in points:
            i = have.get(_key(p.f, p.grid))
            r = df.iloc[i] if i is not None else None
            rows.append((math.nan,) * 3 if r is None else _value(r, col))
        new = refine_grid(points, np.array(rows, dtype=np.float64), rule,
                          ci=study.analysis.ci, own=own)
        if not new:
            break
        points += [Point(f, g, None) for f, g in new]
    return {_key(p.f, p.grid) for p in points}


@pytest.mark.parametrize("scene", [s for s in MAP_SCENES if _tables(s)])
def test_a_committed_map_table_holds_exactly_the_points_its_scene_makes(scene):
    study = load_workflow(ROOT / scene)
    axes = [a for a, _ in study.grid]
    for table in _tables(scene):
        df = pd.read_csv(table, comment="#")
        if "family" in df.columns:  # a counters table: one row per (point, family)
            df = df.drop_duplicates(subset=["f", *axes]).reset_index(drop=True)
        made = _replayed(study, pd.read_csv(_tables(scene)[0], comment="#"), axes)
        held = set(_table_points(df, axes))
        extra, missing = sorted(held - made)[:5], sorted(made - held)[:5]
        assert held == made, (f"{table.relative_to(ROOT)}: {len(held - made)} points its scene "
                              f"does not make (e.g. {extra}), {len(made - held)} it makes "
                              f"missing (e.g. {missing})")
