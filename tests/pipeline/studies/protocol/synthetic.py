"""Synthetic protocol tables with known answers for the study's tests."""

from __future__ import annotations

import numpy as np
import pandas as pd

F = np.arange(46.0, 62.01, 0.5)


def paper_like(f: np.ndarray) -> np.ndarray:
    """D(f), mm²/s: 0 below 50 Hz, a maximum at 54, a minimum at 58, a maximum at 60."""
    return np.interp(f, [46, 49.5, 50, 54, 58, 60, 62], [0, 0, 60, 400, 80, 300, 150])


def falling(f: np.ndarray) -> np.ndarray:
    """D(f), mm²/s, falling monotonically from 500 to 50."""
    return np.interp(f, [46, 62], [500, 50])


def curves(good=("launched", 10.0, "displaced"), ensembles=("rest", "launched"),
           windows=(5.0, 10.0), outlier: dict | None = None) -> pd.DataFrame:
    """A protocol table (the columns of pipeline.studies.protocol.tables): every protocol
    falling but ``good``, which is paper-like; relative CIs ± 5 % (D = 0: [0, 0.5]);
    ``outlier`` {(ensemble, T, definition, f): D} overrides single points."""
    rows = []
    for e in (*ensembles, "mixture"):
        for T in windows:
            for d in ("all", "displaced", "moving_time"):
                D = paper_like(F) if (e, T, d) == good else falling(F)
                for f, x in zip(F, D, strict=True):
                    x = (outlier or {}).get((e, T, d, float(f)), x)
                    lo, hi = (0.95 * x, 1.05 * x) if x > 0 else (0.0, 0.5)
                    rows.append({"f": f, "Gamma": 0.1 * (2 * np.pi * f) ** 2 / 9800,
                                 "ensemble": e, "T": T, "definition": d, "n": 512,
                                 "n_moving": 256, "share": 0.5, "share_lo": 0.45,
                                 "share_hi": 0.55, "D": x, "D_lo": lo, "D_hi": hi,
                                 "D_status": "ok", "D_all": x / 2, "D_all_lo": lo / 2,
                                 "D_all_hi": hi / 2, "residual": 0.0, "bound": 1.0,
                                 "holds": True, "approx_ok": True})
    return pd.DataFrame(rows)
