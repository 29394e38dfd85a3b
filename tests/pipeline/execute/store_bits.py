"""The bits of small stores, one scene per combination of observables: every array's bytes and
metadata as digests, written once by the engine before its observables became plug-ins, and
compared by tests/pipeline/execute/test_store_bits.py with what the engine writes now.

``python -m tests.pipeline.execute.store_bits --write`` (from the repository's root) rewrites
``data/store_digests.json``; without ``--write`` it prints the differences from it.  The
scenes are run chunk by chunk through :func:`pipeline.execute.task.compute_chunk`, the Dask
task itself (Dask adds no bits of its own).
"""

from __future__ import annotations

import hashlib
import json
import sys
import tempfile
from pathlib import Path

import numpy as np
import zarr

DATA = Path(__file__).with_name("data") / "store_digests.json"
#: arrays whose values are not a function of the workflow (wall times)
NOT_REPRODUCIBLE = {"chunk_seconds"}

_BASE = """\
[study]
name = "{name}"
seed = 11

[params]
preset = "klages2004"
{params}
[frequencies]
values = [54.0, 60.0]

[families.rest]
initial = "rest"

[families.launched]
initial = "launched"
launch_speed = [0.0, 150.0]

[accuracy]
preset = "draft"
n_particles = 8
chunk_size = 4
t_max = 3.0
sample_dt = 0.05
n_resamples = 50
{more}"""

#: name -> workflow TOML: every observable at least once, the collision jumps both longer and
#: shorter than the recorded collisions, a grid (its period axis as long as its highest f's)
SCENES: dict[str, str] = {
    "every_observable": _BASE.format(name="every_observable", params="", more="""
[observables.positions]

[observables.collisions]
record = 12
record_from = 0.5
x_jumps = 20

[observables.contact]

[observables.jumps]

[observables.lyapunov]
particles = 3
"""),
    "collisions_alone": _BASE.format(name="collisions_alone", params='contact = "slide"\n', more="""
[observables.collisions]
record = 30
x_jumps = 5
"""),
    "grid_jumps": _BASE.format(name="grid_jumps", params="", more="""
[grid]
alpha = [0.5, 0.7]

[observables.positions]

[observables.jumps]

[observables.contact]
"""),
}


def array_digest(arr: zarr.Array) -> dict:
    """The digest of one array: sha256 of its values (numbers: their bytes, little-endian, C
    order; strings: their JSON list) and its metadata (dims, shape, dtype, chunks, fill, attributes)."""
    a = np.asarray(arr[...])
    if a.dtype.kind in "biufc":
        data = np.ascontiguousarray(a, dtype=a.dtype.newbyteorder("<")).tobytes()
    else:
        data = json.dumps([str(x) for x in a.ravel()]).encode()
    meta = {"dims": list(arr.metadata.dimension_names or ()), "shape": list(arr.shape),
            "dtype": str(arr.dtype), "chunks": list(arr.chunks),
            "fill": repr(arr.fill_value), "attributes": dict(arr.attrs)}
    return {"values": hashlib.sha256(data).hexdigest(),
            "meta": hashlib.sha256(json.dumps(meta, sort_keys=True).encode()).hexdigest()}


def store_digests(path) -> dict:
    """{"arrays": {name: digest}, "workflow_fingerprint": ...} of the store at ``path``."""
    g = zarr.open_group(str(path), mode="r")
    arrays = {name: array_digest(arr) for name, arr in sorted(g.arrays())
              if name not in NOT_REPRODUCIBLE}
    return {"arrays": arrays, "workflow_fingerprint": g.attrs["workflow_fingerprint"]}


def build_store(name: str, path) -> None:
    """The store of scene ``name`` at ``path``, every chunk computed by the Dask task."""
    from pipeline.execute.task import compute_chunk
    from pipeline.store.study_store import StudyStore
    from pipeline.workflow.load import parse_workflow

    study = parse_workflow(SCENES[name], f"{name}.toml")
    store = StudyStore.create_or_open(path, study)
    for fi in range(len(study.points)):
        for mi in range(len(study.families)):
            for ci in range(study.accuracy.n_chunks):
                compute_chunk(store, fi, mi, ci)


def all_digests() -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        out = {}
        for name in SCENES:
            build_store(name, Path(tmp) / f"{name}.zarr")
            out[name] = store_digests(Path(tmp) / f"{name}.zarr")
        return out


def main(argv: list[str]) -> int:
    now = all_digests()
    if "--write" in argv:
        DATA.write_text(json.dumps(now, indent=1, sort_keys=True) + "\n", encoding="utf-8")
        print(f"wrote {DATA.name}: {sum(len(s['arrays']) for s in now.values())} arrays")
        return 0
    then = json.loads(DATA.read_text(encoding="utf-8"))
    diff = [f"{s}.{a}" for s in then for a in then[s]["arrays"]
            if now.get(s, {}).get("arrays", {}).get(a) != then[s]["arrays"][a]]
    print("\n".join(diff) or "identical")
    return 1 if diff else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
