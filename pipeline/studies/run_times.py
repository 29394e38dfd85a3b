"""The table of measured wall times in docs/reproducing.md (:data:`PAGE`), generated from
``figures/run_log.json``.

One row per scene of the first registered study (the paper's, whose scenes are the README's
figures), one per further study (its scenes summed), the shared Dask
cluster's start-up and shut-down, and the sum, all read off the log that ``make_figures``
writes beside the figures (per scene: wall time of the run that computed its chunks, the chunks
it computed, the workers, the reduce time).  A scene whose store an earlier ``make_figures``
computed carries that invocation's times, marked.  The page holds the table between
:data:`BEGIN` and :data:`END`; ``make_figures`` rewrites it there when it writes the repository's
``figures/`` (:func:`update_readme`), and tests/pipeline/studies/test_run_times.py
checks that the committed page matches the committed log.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

__all__ = ["BEGIN", "END", "PAGE", "table", "update_readme"]

#: the page that holds the table, relative to the repository
PAGE = "docs/reproducing.md"

BEGIN = "<!-- run times: generated from figures/run_log.json by make_figures; do not edit -->"
END = "<!-- end of run times -->"


def _duration(s: float) -> str:
    return f"{s:.0f} s" if s < 60 else f"{s / 60:.1f} min ({s:.0f} s)"


def _row(label: str, entries: list[Mapping]) -> str:
    wall = sum(e.get("wall_s", 0.0) for e in entries)
    red = sum(e.get("reduce_s", 0.0) for e in entries)
    done = sum(e.get("computed", 0) for e in entries)
    chunks = sum(e.get("chunks", 0) for e in entries)
    # a scene whose chunks a separate run computed ran none here: its 0 workers say nothing
    workers = sorted({e["workers"] for e in entries
                      if "workers" in e and not e.get("separate_run")})
    earlier = sum(bool(e.get("earlier_invocation")) for e in entries)
    separate = sum(bool(e.get("separate_run")) for e in entries)
    note = ("" if not earlier else " (computed by an earlier invocation)" if earlier == len(entries)
            else f" ({earlier} of {len(entries)} scenes computed by an earlier invocation)")
    if separate:
        note += (" (chunks computed by a separate `bbb run`: see the maps' costs below)"
                 if separate == len(entries) else f" ({separate} of {len(entries)} scenes' "
                 "chunks computed by a separate `bbb run`: see the maps' costs below)")
    return (f"| {label} | {_duration(wall)}{note} | {done} of {chunks} | "
            f"{'/'.join(map(str, workers)) or '–'} | "
            f"{f'{red:.0f} s' if red else '–'} |")


def table(log: Mapping) -> list[str]:
    """The markdown table of the run times in ``log`` (run_log.json as a dict)."""
    from .registry import studies

    first, *further = studies()
    scenes = log.get("scenes", {})
    lines = ["| scenes | wall time of the runs | chunks computed (of the scene's most) | workers "
             "| reduce |",
             "| --- | --- | --- | --- | --- |"]
    lines += [_row(f"`{name}`", [scenes[name]]) for name in first.scenes if name in scenes]
    for study in further:
        names = [n for n in study.scenes if n in scenes]
        if names:
            lines.append(_row(f"{study.name} ({len(names)} scene{'s' if len(names) > 1 else ''})",
                              [scenes[n] for n in names]))
    if "cluster_s" in log:
        lines.append(f"| the shared Dask cluster's start-up and shut-down | {log['cluster_s']:.0f} s "
                     "| | | |")
    if "wall_s" in log:
        lines.append(f"| **all of the above** | **{_duration(log['wall_s'])}** | | | |")
    if "this_invocation_s" in log:
        lines.append(f"| the last `make figures` (drawing and the report included) | "
                     f"{_duration(log['this_invocation_s'])} | | | |")
    if "cpus" in log:
        # when the run was made stays in the log (its "written"): the page shows no run dates
        lines += ["", f"Measured on {log['cpus']} CPUs."]
    return lines


def update_readme(readme: str | os.PathLike, log: Mapping) -> bool:
    """Replace the table between BEGIN and END in ``readme`` (a Markdown file: :data:`PAGE`)
    by :func:`table` of ``log``; False (nothing written) if the file has no such markers."""
    path = Path(readme)
    text = path.read_text(encoding="utf-8")
    if BEGIN not in text or END not in text:
        return False
    head, rest = text.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    path.write_text(head + "\n".join([BEGIN, *table(log), END]) + tail, encoding="utf-8")
    return True
