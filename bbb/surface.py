"""The vibrating corrugated floor: its motion (jitted) and numpy faces of its shape.

The floor moves rigidly with y_f(t) = -A sin(2π f t) (mm).  Arcs of radius R (mm) are
centred at x = kS with their tops at y_f; a point at offset d = x - kS (|d| ≤ S/2)
lies c(d) = R - sqrt(R² - d²) below the top.  Cusps (valleys) sit at x = (k + 1/2) S.
``R = inf`` is a flat floor (c ≡ 0).  All jitted functions take time as the offset
``s`` (s) within the current floor period, never a huge absolute time.  The arcs' jitted
formulae are bbb.dynamics.floors.arc's.  Other floor shapes
(sine, sawtooth: bbb.dynamics.floors) share the cells; :func:`shape_of` is a Params' shape
record for the kernel, :func:`floor_depth` its depth below the tops at any offset.
"""

from __future__ import annotations

import math

import numpy as np

from .jit import inlined
from .params import Params

__all__ = ["depth", "floor_depth", "floor_height", "shape_of", "surface_height", "surface_normal",
           "cell_of"]


@inlined
def floor_y(s, A, w):
    # Sec. 2: y_f = -A sin(2πft)
    return -A * math.sin(w * s)


@inlined
def floor_v(s, A, w):
    return -A * w * math.cos(w * s)


@inlined
def floor_a(s, A, w):
    return A * w * w * math.sin(w * s)


# ---- thin numpy wrappers for analysis, plots and tests --------------------------------


def cell_of(x: np.ndarray | float, S: float) -> tuple[np.ndarray, np.ndarray]:
    """Cell index k (nearest arc centre kS) and offset d = x - kS in [-S/2, S/2), mm."""
    x = np.asarray(x, dtype=np.float64)
    k = np.floor(x / S + 0.5)
    return k.astype(np.int64), x - k * S


def depth(d: np.ndarray | float, R: float) -> np.ndarray:
    """Depth c(d) (mm) of the arc below its top at offset d (mm) from its centre."""
    d = np.asarray(d, dtype=np.float64)
    if math.isinf(R):
        return np.zeros_like(d)
    q = np.sqrt(np.maximum(0.0, (R - np.abs(d)) * (R + np.abs(d))))
    return d * d / (R + q)


def shape_of(p: Params):
    """The kernel's record of the floor's shape (bbb.dynamics.floors): the arc's radius R
    (a float; inf on a flat floor) or a sine's or sawtooth's record."""
    from .dynamics.floors import sawtooth, sine  # bbb.dynamics reads this module's arc formulae

    if p.floor == "sine":
        return sine.record(p.depth, p.S)
    if p.floor == "sawtooth":
        return sawtooth.record(p.depth, p.peak, p.S)
    return float(p.R)


def floor_depth(p: Params, d: np.ndarray | float) -> np.ndarray:
    """Depth c(d) (mm) of the floor below its tops at offset d (mm) from a cell's centre, on
    every floor shape (the arc's is :func:`depth`)."""
    if p.floor in ("arc", "flat"):
        return depth(d, p.R)
    from .dynamics.floors import depths

    d = np.asarray(d, dtype=np.float64)
    return depths(shape_of(p), d.ravel()).reshape(d.shape)


def floor_height(p: Params, t: np.ndarray | float) -> np.ndarray:
    """Height y_f(t) (mm) of the arc tops at time t (s)."""
    t = np.asarray(t, dtype=np.float64)
    s = np.mod(t, 1.0 / p.f)
    return -p.A * np.sin(p.omega * s)


def surface_height(p: Params, x: np.ndarray | float, t: np.ndarray | float) -> np.ndarray:
    """Height (mm) of the floor surface at position x (mm) and time t (s)."""
    _, d = cell_of(x, p.S)
    return floor_height(p, t) - floor_depth(p, d)


def surface_normal(p: Params, x: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
    """Outward unit normal (n_x, n_y) of the floor under x (mm)."""
    _, d = cell_of(x, p.S)
    if p.floor in ("sine", "sawtooth"):
        from .dynamics.floors import normals

        nx, ny = normals(shape_of(p), np.ravel(d))
        return nx.reshape(np.shape(d)), ny.reshape(np.shape(d))
    if p.flat:
        return np.zeros_like(d), np.ones_like(d)
    q = np.sqrt(np.maximum(0.0, (p.R - np.abs(d)) * (p.R + np.abs(d))))
    return d / p.R, q / p.R
