"""Tiny study stores for the figure and report tests, made once per test session through
the real pipeline (run_study on a LocalCluster, then reduce_store or reduced_dataset): a D(f)
study, and a map whose absent points come from the store itself."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
from PIL import Image

# Fig. 3's frequencies 54 (1/1 spot for launched particles), 60 (VHO), 72 (two-loop spiral)
# and 78; two families; positions for D(f) and collisions for the locking analysis.
TINY_FIGURES = """\
[study]
name = "tiny_figures"
seed = 11

[params]
preset = "klages2004"

[frequencies]
values = [54.0, 60.0, 72.0, 78.0]

[families.rest]
initial = "rest"

[families.launched]
initial = "launched"
launch_speed = [0.0, 150.0]

[accuracy]
preset = "draft"
n_particles = 8
chunk_size = 8
t_max = 12.0
sample_dt = 0.5
n_resamples = 50

[observables.positions]

[observables.collisions]
record = 400
record_from = 2.0
"""


# The map: contact x mu on a tilted floor (v and D_drift too), two families.  mu
# applies under Coulomb only, so the store holds stick and slide at mu = 0 and Coulomb at
# mu = 0.3: the cells (stick, 0.3), (slide, 0.3) and (coulomb, 0) of the map are absent.
TINY_MAP = """\
[study]
name = "tiny_map"
seed = 7

[params]
preset = "klages2004"
tilt = 2.0

[frequencies]
values = [54.0, 60.0]

[grid]
contact = ["stick", "slide", "coulomb"]
mu = [0.3]

[families.rest]
initial = "rest"

[families.launched]
initial = "launched"
launch_speed = [0.0, 150.0]

[accuracy]
preset = "draft"
n_particles = 8
chunk_size = 8
t_max = 10.0
sample_dt = 0.5
n_resamples = 50

[observables.positions]
"""


def tiny_map(tmp_path_factory) -> str:
    """The path of the TINY_MAP store, run once per session (one worker)."""
    from pipeline.api import run_study

    base = Path(tmp_path_factory.getbasetemp()) / "tiny_map"
    store = base / "tiny_map.zarr"
    if not (base / "ready").exists():
        base.mkdir(parents=True, exist_ok=True)
        run_study(TINY_MAP, store, workers=1, echo=lambda s: None)
        (base / "ready").write_text("ok\n")
    return str(store)


def tiny_store(tmp_path_factory) -> tuple[str, dict[str, pd.DataFrame]]:
    """(store path, {"diffusion": D(f) table, "locking": locking table}), built once."""
    from pipeline.execute.run import run_study
    from pipeline.tables.collisions import locking_table
    from pipeline.tables.reduce import reduce_store
    from pipeline.workflow.load import parse_workflow

    base = Path(tmp_path_factory.getbasetemp()) / "tiny_figures"
    store = base / "tiny_figures.zarr"
    if not (base / "ready").exists():
        base.mkdir(parents=True, exist_ok=True)
        run_study(parse_workflow(TINY_FIGURES), store, workers=2, progress=False,
                  dashboard=False, echo=lambda s: None)
        reduce_store(store, base / "tables", echo=lambda s: None)
        locking_table(store).to_csv(base / "tables" / "locking.csv", index=False)
        (base / "ready").write_text("ok\n")
    tables = {"diffusion": pd.read_parquet(base / "tables" / "diffusion.parquet"),
              "locking": pd.read_csv(base / "tables" / "locking.csv")}
    return str(store), tables


def assert_png_drawn(path, min_size=(400, 300)) -> None:
    """The PNG opens, is at least ``min_size`` pixels and is not blank: a good share of its
    pixels are not background and they are not all one colour."""
    with Image.open(path) as im:
        assert im.size[0] >= min_size[0] and im.size[1] >= min_size[1], im.size
        a = np.asarray(im.convert("L"), dtype=float)
    ink = a < 200
    assert ink.mean() > 0.01, f"{path}: only {100 * ink.mean():.2f} % of pixels drawn"
    assert a.std() > 10.0, f"{path}: nearly uniform image"


# The new floor shapes, level and vibrated vertically: a sawtooth whose peak sits 0.3 or 0.5 of
# the period from its left valley (the off-centre teeth drive a drift v without tilt: a signed
# map), and a sine without a grid (a D(f) curve).  Three frequencies: a map drawn to scale.
#: what the tiny floor scenes share after their [params] (and [grid])
FLOOR_TAIL = """
[frequencies]
values = [60.0, 70.0, 80.0]

[families.rest]
initial = "rest"

[accuracy]
preset = "draft"
n_particles = 8
chunk_size = 8
t_max = 10.0
n_resamples = 50

[observables.positions]
"""


TINY_FLOORS = {
    "sawtooth": """\
[study]
name = "tiny_sawtooth"
seed = 3

[params]
preset = "klages2004"
floor = "sawtooth"
depth = 0.3

[grid]
peak = [0.3, 0.5]
""" + FLOOR_TAIL,
    "sine": """\
[study]
name = "tiny_sine"
seed = 4

[params]
preset = "klages2004"
floor = "sine"
depth = 0.3
""" + FLOOR_TAIL}


def tiny_floor(tmp_path_factory, floor: str) -> str:
    """The path of the TINY_FLOORS[floor] store, run once per session (one worker)."""
    from pipeline.api import run_study

    base = Path(tmp_path_factory.getbasetemp()) / f"tiny_{floor}"
    store = base / f"tiny_{floor}.zarr"
    if not (base / "ready").exists():
        base.mkdir(parents=True, exist_ok=True)
        run_study(TINY_FLOORS[floor], store, workers=1, echo=lambda s: None)
        (base / "ready").write_text("ok\n")
    return str(store)
