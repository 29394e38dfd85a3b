"""When is a remade calibration JSON the committed one?  Provenance keys aside, equal within a
stated tolerance; and the one way every calibration JSON is written.

The tolerance: every number within a relative 1e-9 (absolute 1e-300 at zero) of the committed
one, NaN where it is NaN; every string, boolean, null, key and list length the same.  The makers
are seeded, so a remake on the same numpy and numba gives the same bits; the margin covers a
different BLAS or a kernel change that moves only the last bits of a float (the trajectory
checker's tolerance was the same to 13 digits on two kernels).  Provenance -- what day, which
CPU, which git revision made it, which dated results file it printed to -- is not compared.
"""

from __future__ import annotations

import json
import math

#: top-level keys that record when, where and from which revision a JSON was made
PROVENANCE = frozenset({"date", "cpu", "cpus", "kernel", "source"})
REL_TOL = 1e-9
ABS_TOL = 1e-300


def dump(data: dict) -> str:
    """The text of a calibration JSON as ``make calibrate`` writes it."""
    return json.dumps(data, indent=1, ensure_ascii=False) + "\n"


def differences(made, committed, path: str = "") -> list[str]:
    """What differs between a remade JSON and the committed one, one line per difference
    (empty: the same within :data:`REL_TOL`); at the top level :data:`PROVENANCE` is skipped."""
    where = path or "(top)"
    if isinstance(made, dict) and isinstance(committed, dict):
        skip = PROVENANCE if not path else frozenset()
        out = [f"{path}/{k}: only in the remake" for k in made.keys() - committed.keys() - skip]
        out += [f"{path}/{k}: only in the committed JSON" for k in committed.keys() - made.keys() - skip]
        for k in sorted(made.keys() & committed.keys() - skip):
            out += differences(made[k], committed[k], f"{path}/{k}")
        return out
    if isinstance(made, list) and isinstance(committed, list):
        if len(made) != len(committed):
            return [f"{where}: {len(made)} items, committed {len(committed)}"]
        return [d for i, (a, b) in enumerate(zip(made, committed, strict=True))
                for d in differences(a, b, f"{path}[{i}]")]
    numbers = (int, float)
    if (isinstance(made, numbers) and isinstance(committed, numbers)
            and not isinstance(made, bool) and not isinstance(committed, bool)):
        if math.isnan(made) and math.isnan(committed):
            return []
        if math.isclose(made, committed, rel_tol=REL_TOL, abs_tol=ABS_TOL):
            return []
        return [f"{where}: {made!r}, committed {committed!r}"]
    if type(made) is not type(committed) or made != committed:
        return [f"{where}: {made!r}, committed {committed!r}"]
    return []
