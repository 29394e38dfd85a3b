"""Compare the committed tables (figures/*.csv) of the working tree with those of a git revision.

    python -m benchmarks.bits.compare_tables --base REV [--dir figures] [--lines]

Prints one line per table: identical, or which columns were added / removed and, for the
columns both hold, how many cells differ and the largest relative difference.  Timing columns
(wall time of the tasks) are never reproducible and are listed apart.  A regeneration of the
figures after a change that must not alter results (a refactor, a new kernel layout) should
print "identical" for every table; after a change of results it says exactly where.

With ``--lines``: the lines of the map tables instead -- every further study that slices its
map scenes' long tables into per-line tables (a ``line_tables`` function in its claims module,
e.g. ``transport_diffusion.csv`` -> ``transport_t0_diffusion`` at tilt 0, throw 90) has each
line compared with the revision's CSV of the same name (the per-scene table the line replaced),
the same way; a line without such a CSV at the revision is "new line".
"""

from __future__ import annotations

import argparse
import io
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

#: columns that hold wall times (not reproducible)
TIMING = ("task_seconds",)


def _at_rev(rev: str, path: str) -> str | None:
    try:
        return subprocess.run(["git", "show", f"{rev}:{path}"], check=True, capture_output=True,
                              text=True).stdout
    except subprocess.CalledProcessError:
        return None


def _tracked(rev: str, folder: str) -> list[str]:
    out = subprocess.run(["git", "ls-tree", "--name-only", f"{rev}:{folder}"], check=True,
                         capture_output=True, text=True).stdout.split()
    return sorted(f"{folder}/{n}" for n in out if n.endswith(".csv"))


def _cells_differ(a: pd.Series, b: pd.Series) -> tuple[int, float]:
    """(cells that differ, largest relative difference of the numeric ones)."""
    if pd.api.types.is_numeric_dtype(a) and pd.api.types.is_numeric_dtype(b):
        x, y = a.to_numpy(np.float64), b.to_numpy(np.float64)
        same = (x == y) | (np.isnan(x) & np.isnan(y))
        both = ~same & np.isfinite(x) & np.isfinite(y)
        rel = np.abs(x[both] - y[both]) / np.maximum(np.abs(x[both]), np.abs(y[both]))
        return int((~same).sum()), float(rel.max()) if rel.size else (np.nan if (~same).any() else 0.0)
    def text(s: pd.Series) -> pd.Series:
        return s.astype(object).fillna("<NA>").astype(str)

    same = (text(a) == text(b)).to_numpy()
    return int((~same).sum()), np.nan


def compare(base: str, folder: str) -> list[str]:
    lines = []
    new = sorted(str(p) for p in Path(folder).glob("*.csv"))
    old = _tracked(base, folder)
    for path in sorted(set(new) | set(old)):
        if path not in old:
            lines.append(f"{path}: new table")
            continue
        if path not in new:
            lines.append(f"{path}: removed")
            continue
        a = pd.read_csv(io.StringIO(_at_rev(base, path)))
        b = pd.read_csv(path)
        lines.append(f"{path}: {_difference(a, b)}")
    return lines


def compare_lines(base: str, folder: str) -> list[str]:
    """Each line of the further studies' map tables in ``folder`` against the revision's CSV of
    the same key (module docstring); one line of text per line of a map table."""
    import importlib

    from pipeline.studies.registry import STUDIES as EXTRA_STUDIES
    from pipeline.tables.files import read_study_tables

    out = []
    for study in EXTRA_STUDIES:
        claims = importlib.import_module(f"pipeline.studies.{study}.claims")
        if not hasattr(claims, "line_tables"):
            continue
        maps = read_study_tables(folder, claims.SCENES)
        for key, b in sorted(claims.line_tables(maps).items()):
            path = f"{folder}/{key}.csv"
            text = _at_rev(base, path)
            if text is None:
                out.append(f"{path} (a line of a map, {len(b)} rows): new line")
                continue
            a = pd.read_csv(io.StringIO(text))
            out.append(f"{path} (a line of a map, {len(b)} rows): {_difference(a, b)}")
    return out


def _difference(a: pd.DataFrame, b: pd.DataFrame) -> str:
    """"identical" (perhaps with timing columns that differ), or how ``b`` differs from ``a``."""
    notes = []
    added = [c for c in b.columns if c not in a.columns]
    gone = [c for c in a.columns if c not in b.columns]
    if added:
        notes.append(f"columns added {added}")
    if gone:
        notes.append(f"columns removed {gone}")
    if len(a) != len(b):
        notes.append(f"rows {len(a)} -> {len(b)}")
    else:
        diffs, timing = [], []
        for c in a.columns:
            if c not in b.columns:
                continue
            n, rel = _cells_differ(a[c], b[c])
            if n:
                (timing if c in TIMING else diffs).append(f"{c} ({n} cells, max rel {rel:.2g})")
        if diffs:
            notes.append("differ: " + ", ".join(diffs))
        if timing:
            notes.append("timing only: " + ", ".join(timing))
    identical = not notes or all(n.startswith("timing only") for n in notes)
    return (f"{'identical' if identical else ''}{'; '.join(notes) if not identical else ''}"
            + (f" ({notes[0]})" if identical and notes else ""))


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--base", required=True, help="git revision to compare with")
    ap.add_argument("--dir", default="figures", help="folder of the tables (default figures)")
    ap.add_argument("--lines", action="store_true", help="compare the lines of the map tables "
                    "with the revision's per-scene tables of the same name")
    args = ap.parse_args(argv)
    for line in (compare_lines if args.lines else compare)(args.base, args.dir):
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
