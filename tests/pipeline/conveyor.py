"""A tiny real conveyor (tilt 3°, throw 45°, α = 0.8, contact stick), simulated chunk by chunk
and reduced by the real ``bbb reduce``: at 50 Hz below lift-off (57.4 Hz,
bbb.analysis.liftoff_onset) the particles stay where they are up to rounding; at 80 Hz they hop
and run away downhill, speeding up over the whole run."""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from pipeline.execute.task import compute_chunk
from pipeline.store.study_store import StudyStore
from pipeline.tables.reduce import reduce_store
from pipeline.workflow.load import parse_workflow

CONVEYOR = """\
[study]
name = "conveyor"
seed = 7

[params]
preset = "klages2004"
tilt = 3.0
throw = 45.0
alpha = {alpha}
contact = "stick"

[frequencies]
values = [50.0, 80.0]

[families.rest]
initial = "rest"

[accuracy]
preset = "draft"
n_particles = 8
chunk_size = 8
t_max = 10.0
n_resamples = 200

[observables.positions]
"""
BELOW, ABOVE = 0, 1  # the rows: 50 Hz (below lift-off), 80 Hz (above)


def conveyor_store(path: Path, alpha: float = 0.8) -> str:
    """The conveyor's store at ``path``, every chunk computed; returns its path."""
    study = parse_workflow(CONVEYOR.format(alpha=alpha), source="conveyor.toml")
    store = StudyStore.create_or_open(path, study)
    for fi in range(len(study.points)):
        compute_chunk(store, fi, 0, 0)
    return store.path


def reduce_conveyor(path: str, out: Path) -> tuple[pd.DataFrame, list[str]]:
    """(the diffusion table, the stderr lines of bbb reduce)."""
    lines: list[str] = []
    df = reduce_store(path, out, echo=lambda _: None, warn=lines.append)["diffusion"]
    return df, lines
