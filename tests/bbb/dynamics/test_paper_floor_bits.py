"""The paper's floor (tilt 0, throw 90°: bbb.kernel, not the conveyor) under every contact model
gives the same bits as the kernel these hashes were stored from (tests/bbb/data/
paper_floor_bits.json, written by this module run as a script): a kernel change that is meant
to touch only the conveyor must leave every trajectory of the paper's scenes, and so every
table of Fig. 2, unchanged.  The hashes depend on the compiler and libm as well as on the
kernel, so the test runs only where numba, numpy and the machine match the stored ones.

    PYTHONPATH=. .venv/bin/python tests/bbb/dynamics/test_paper_floor_bits.py   # rewrite the hashes
"""

from __future__ import annotations

import hashlib
import json
import platform
from importlib import metadata
from pathlib import Path

import numpy as np
import pytest

from bbb import Params, simulate

STORE = Path(__file__).parents[1] / "data" / "paper_floor_bits.json"
#: (name, Params.preset("klages2004", **changes), family, particles, t_max in s)
RUNS = (
    ("stick 60 Hz launched", dict(f=60.0), "launched", 8, 2.0),
    ("stick 80 Hz rest", dict(f=80.0), "rest", 8, 2.0),
    ("stick 54 Hz dropped", dict(f=54.0), "dropped", 8, 2.0),
    ("stick R=S/2 70 Hz", dict(f=70.0, R=1.0), "launched", 4, 1.0),
    ("stick flat 70 Hz", dict(f=70.0, R=float("inf")), "launched", 4, 1.0),
    ("slide 54 Hz rest", dict(f=54.0, contact="slide"), "rest", 4, 1.0),
    ("slide 70 Hz launched", dict(f=70.0, contact="slide"), "launched", 4, 1.0),
    ("coulomb 0.3 54 Hz rest", dict(f=54.0, contact="coulomb", mu=0.3), "rest", 4, 1.0),
    ("coulomb 0.05 60 Hz launched", dict(f=60.0, contact="coulomb", mu=0.05), "launched", 4, 1.0),
    ("coulomb 2 flat 60 Hz launched", dict(f=60.0, R=float("inf"), contact="coulomb", mu=2.0),
     "launched", 4, 1.0),
)


def fingerprint(changes: dict, family: str, n: int, t_max: float) -> str:
    """sha256 over positions, recorded events (lift-offs and contact events too), counters and
    contact times of one seeded run."""
    p = Params.preset("klages2004", **changes)
    run = simulate(p, n, t_max, seed=20261125, initial=family,
                   sample_times=np.linspace(0.0, t_max, 41), record_collisions=400,
                   record_liftoffs=True)
    h = hashlib.sha256()
    for a in (run.positions, run.collisions_dense, run.n_recorded,
              *(run.counters[k] for k in sorted(run.counters)),
              *(run.contact_time[k] for k in sorted(run.contact_time))):
        h.update(np.ascontiguousarray(a).tobytes())
    return h.hexdigest()


def environment() -> dict[str, str]:
    return {"numba": metadata.version("numba"), "numpy": metadata.version("numpy"),
            "machine": platform.machine()}


def stored() -> dict:
    return json.loads(STORE.read_text())


@pytest.mark.parametrize("name", [r[0] for r in RUNS])
def test_the_paper_floor_gives_the_stored_bits(name):
    data = stored()
    if data["environment"] != environment():
        pytest.skip(f"hashes stored under {data['environment']}, this is {environment()}")
    _, changes, family, n, t_max = next(r for r in RUNS if r[0] == name)
    assert fingerprint(changes, family, n, t_max) == data["hashes"][name]


if __name__ == "__main__":
    import subprocess

    rev = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                         check=True).stdout.strip()
    out = {"made_by": f"kernel of git revision {rev}", "environment": environment(),
           "hashes": {r[0]: fingerprint(*r[1:]) for r in RUNS}}
    STORE.write_text(json.dumps(out, indent=1) + "\n")
    print(json.dumps(out, indent=1))
