"""Largest Lyapunov exponent λ of the bouncing ball billiard (Benettin's two trajectories).

Each particle (the primary) gets a companion started a distance d0 away; both are run one
floor period at a time with :func:`bbb.simulate`, the separation δ of their states
(x, y, vₓ, v_y) at the end of every period is measured in the natural units L = g/ω² (mm)
and V = g/ω (mm/s), and the companion is put back at distance d0 along δ.  Then
    λ = (1 / t) Σ_periods ln(|δ| / d0)   (1/s),   λ_coll = the same sum / collisions
over the periods after the transient.  Why Benettin and not the tangent map: the map of the
curved moving floor has four kinds of event (flight, collision, sticking cascade cut at
``v_stick``, lift-off) and the kernel's certified search decides between them; two
trajectories through the *same* kernel need no second derivation of all of them, and the
companion lands, sticks and lifts off exactly as a particle does.  Where both apply — the
vertical motion over a flat floor — :func:`flat_floor_tangent_exponent` computes the
exponent from the exact tangent map and the two agree (tests).

Sticking is where the tangent map is singular: a cascade ends in the same stuck state for
every nearby landing, and lift-off happens at a fixed floor phase, so only the separation
along x survives a sticking episode.  If the separation is exactly 0 (both copies stuck at
the same cusp, or in the same state on a flat floor) the particle's λ is −∞: it is counted
in ``n_collapsed`` and left out of the mean.

The kernel only returns positions at sample times and post-collision states, so the state at
the end of a period is rebuilt from the last collision of that period (free flight after it,
or stuck-then-lift-off when it was a sticking collision, with the kernel's own lift-off rule).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..dynamics.liftoff import liftoff_wait
from ..dynamics.options import Floor
from ..ensemble import InitialState, initial_state
from ..numerics import Numerics
from ..params import Params
from ..simulate import simulate
from ..surface import cell_of, floor_depth, shape_of

__all__ = ["Lyapunov", "flat_floor_jacobian", "flat_floor_tangent_exponent", "lyapunov"]

_FLOAT = NDArray[np.float64]
# collisions kept per particle and period; a particle with more is re-run from its last one
_ROWS = 64


@dataclass(frozen=True)
class Lyapunov:
    """Largest Lyapunov exponent of an ensemble, with CIs over particles.

    lam, lam_lo, lam_hi        -- λ per unit time, 1/s (mean over non-collapsed particles)
    per_coll, per_coll_lo, per_coll_hi -- λ per collision (dimensionless)
    lam_i, per_coll_i          -- per particle (−inf where the separation collapsed)
    n_collapsed                -- particles whose separation became exactly 0 at any period
                                  (their companion is then restarted along ``direction``,
                                  but their λ stays −inf)
    collisions                 -- per particle, collisions of the primary after the transient
    duration                   -- time over which λ was averaged, s
    x_range                    -- per particle, max − min of the primary's x (mm) at the period
                                  ends of that time (its start included): how far it moved
    """

    lam: float
    lam_lo: float
    lam_hi: float
    per_coll: float
    per_coll_lo: float
    per_coll_hi: float
    lam_i: _FLOAT
    per_coll_i: _FLOAT
    n_collapsed: int
    collisions: NDArray[np.int64]
    duration: float
    x_range: _FLOAT


def lyapunov(
    params: Params,
    n_particles: int,
    t_max: float,
    seed: int,
    initial: str | InitialState = "rest",
    *,
    discard: float = 0.1,
    d0: float = 1e-8,
    direction: tuple[float, float, float, float] = (0.5, 0.5, 0.5, 0.5),
    numerics: Numerics | None = None,
    n_resamples: int = 1000,
    ci: float = 0.95,
) -> Lyapunov:
    """λ over ``t_max`` s (a whole number of floor periods is used), the first ``discard``
    fraction excluded as transient (the separation is renormalised during it all the same).

    d0        -- separation after each renormalisation, in the units (L, L, V, V)
    direction -- initial separation (x, y, vₓ, v_y) in those units (normalised here)
    """
    numerics = Numerics() if numerics is None else numerics
    period = 1.0 / params.f
    n_periods = int(math.floor(t_max * params.f + 1e-9))
    if n_periods < 2:
        raise ValueError(f"t_max = {t_max!r} s holds fewer than 2 floor periods")
    if not 0.0 <= discard < 1.0:
        raise ValueError(f"discard = {discard!r} must be a fraction in [0, 1)")
    u = np.asarray(direction, dtype=np.float64)
    if u.shape != (4,) or not np.all(np.isfinite(u)) or not np.any(u):
        raise ValueError(f"direction = {direction!r} must be 4 finite numbers, not all 0")
    u = u / np.linalg.norm(u)
    if isinstance(initial, InitialState):
        prim = _as_arrays(initial)
    else:
        prim = _as_arrays(initial_state(params, n_particles, np.random.SeedSequence(seed), initial))
    n = prim["cell"].size
    scale = _scales(params)
    sec = _displace(params, prim, np.tile(u, (n, 1)), d0, scale)
    n_skip = int(math.ceil(discard * n_periods - 1e-9))
    log_sum = np.zeros(n)
    collisions = np.zeros(n, np.int64)
    collapsed = np.zeros(n, bool)
    x_start = prim["cell"] * params.S + prim["d"]
    x_lo, x_hi = (x_start.copy(), x_start.copy()) if n_skip == 0 else (np.full(n, np.inf),
                                                                          np.full(n, -np.inf))
    for k in range(n_periods):
        both = {key: np.concatenate([prim[key], sec[key]]) for key in prim}
        end, coll = _one_period(params, both, period, numerics)
        prim, sec = _halves(end, n)
        delta = _separation(prim, sec, scale, params.S)
        size = np.linalg.norm(delta, axis=1)
        before = np.linalg.norm(_separation(*_halves(both, n), scale, params.S), axis=1)
        newly = (size == 0.0) & ~collapsed
        collapsed |= newly
        if k + 1 >= n_skip:  # the window starts at the end of period n_skip − 1
            x_end = prim["cell"] * params.S + prim["d"]
            x_lo, x_hi = np.minimum(x_lo, x_end), np.maximum(x_hi, x_end)
        if k >= n_skip:
            ok = ~collapsed
            log_sum[ok] += np.log(size[ok] / before[ok])
            collisions += coll[:n]
        unit = np.where(size[:, None] > 0, delta / np.where(size > 0, size, 1.0)[:, None], u)
        sec = _displace(params, prim, unit, d0, scale)
    duration = (n_periods - n_skip) * period
    lam_i = np.where(collapsed, -np.inf, log_sum / duration)
    per_coll_i = np.where(collapsed, -np.inf, log_sum / np.maximum(collisions, 1))
    lam = _mean_ci(lam_i[~collapsed], n_resamples, ci, seed)
    per = _mean_ci(per_coll_i[~collapsed], n_resamples, ci, seed)
    return Lyapunov(*lam, *per, lam_i=lam_i, per_coll_i=per_coll_i,
                    n_collapsed=int(collapsed.sum()), collisions=collisions, duration=duration,
                    x_range=x_hi - x_lo)


def flat_floor_tangent_exponent(rows: _FLOAT, params: Params) -> tuple[float, float]:
    """Exponent of the vertical motion over a flat floor from its exact tangent map.

    rows -- one particle's consecutive post-collision rows (t, x, y, vₓ, v_y, phase) with no
            sticking between them (``SimRun.collisions_dense[i, :n]``)
    The map (t_n, v_n) → (t_{n+1}, v_{n+1}): flight F = y_f(t_n) + v_n τ − gτ²/2 − y_f(t_{n+1})
    = 0, τ = t_{n+1} − t_n, then v_{n+1} = (1+α) u(t_{n+1}) − α(v_n − gτ), u = dy_f/dt.  By
    the implicit-function theorem, with v⁻ = v_n − gτ and a = du/dt:
        ∂t_{n+1}/∂t_n = (v⁻ − u_n)/(v⁻ − u_{n+1}),  ∂t_{n+1}/∂v_n = −τ/(v⁻ − u_{n+1}),
        dv_{n+1} = [(1+α) a_{n+1} + αg] dt_{n+1} − αg dt_n − α dv_n.
    Returns (λ per unit time 1/s, λ per collision), in the metric (ω t, v ω/g).
    """
    g = params.g
    t = rows[:, 0]
    s = rows[:, 5] / params.f  # floor time within the period
    v = rows[:, 4]
    vec = np.array([1.0, 1.0]) / math.sqrt(2.0)
    # in the metric (ω t, v ω/g): J' = diag(ω, ω/g) J diag(1/ω, g/ω)
    metric = np.array([[1.0, g], [1.0 / g, 1.0]])
    total = 0.0
    for n in range(rows.shape[0] - 1):
        vec = (flat_floor_jacobian(t[n + 1] - t[n], v[n], s[n], s[n + 1], params) * metric) @ vec
        size = float(np.hypot(vec[0], vec[1]))
        total += math.log(size)
        vec /= size
    return total / (t[-1] - t[0]), total / (rows.shape[0] - 1)


def flat_floor_jacobian(tau: float, v: float, s0: float, s1: float, p: Params) -> _FLOAT:
    """∂(t_{n+1}, v_{n+1})/∂(t_n, v_n) of the exact flat-floor map (formulas above).

    tau -- flight time (s); v -- launch velocity v_n (mm/s); s0, s1 -- floor times (s) of
    the launch and of the next impact."""
    g, A, w, alpha = p.g, p.A, p.omega, p.alpha
    u0 = -A * w * math.cos(w * s0)
    u1 = -A * w * math.cos(w * s1)
    a1 = A * w * w * math.sin(w * s1)
    vm = v - g * tau
    dt_dt = (vm - u0) / (vm - u1)
    dt_dv = -tau / (vm - u1)
    c = (1 + alpha) * a1 + alpha * g
    return np.array([[dt_dt, dt_dv], [c * dt_dt - alpha * g, c * dt_dv - alpha]])


# ---- one period of the pair ensemble -----------------------------------------------------

_KEYS = ("cell", "d", "y", "vx", "vy", "s", "stuck", "from_surface")


def _as_arrays(st: InitialState) -> dict[str, np.ndarray]:
    return {key: np.array(getattr(st, key)) for key in _KEYS}


def _scales(p: Params) -> _FLOAT:
    L = p.g / p.omega**2
    V = p.g / p.omega
    return np.array([L, L, V, V])


def _separation(a: dict[str, np.ndarray], b: dict[str, np.ndarray], scale: _FLOAT,
                S: float) -> _FLOAT:
    """b − a in (x, y, vₓ, v_y), divided by the natural units (L, L, V, V)."""
    dx = (b["cell"] - a["cell"]) * S + (b["d"] - a["d"])
    return np.stack([dx, b["y"] - a["y"], b["vx"] - a["vx"], b["vy"] - a["vy"]], axis=1) / scale


def _halves(st: dict[str, np.ndarray], n: int) -> tuple[dict, dict]:
    return {k: v[:n] for k, v in st.items()}, {k: v[n:] for k, v in st.items()}


def _surface(p: Params, d: _FLOAT, s: _FLOAT) -> _FLOAT:
    return -p.A * np.sin(p.omega * s) - floor_depth(p, d)


def _displace(p: Params, prim: dict[str, np.ndarray], unit: _FLOAT, d0: float,
              scale: _FLOAT) -> dict[str, np.ndarray]:
    """The companion: the primary moved by d0 along ``unit`` (units L, L, V, V).

    A companion that would start below the surface is moved the other way; if that is below
    too, it is put on the surface — stuck if the primary is stuck (sticking keeps only the
    separation along x), else leaving the surface with its velocity."""
    x0 = prim["cell"] * p.S + prim["d"]
    out = {}
    for sign in (1.0, -1.0):
        step = sign * d0 * unit * scale
        cell, d = cell_of(x0 + step[:, 0], p.S)
        y = prim["y"] + step[:, 1]
        gap = y - _surface(p, d, prim["s"])
        cand = dict(cell=cell, d=d, y=y, vx=prim["vx"] + step[:, 2], vy=prim["vy"] + step[:, 3])
        if sign > 0:
            out = {k: v.copy() for k, v in cand.items()}
            below = gap <= 0.0
            continue
        use = below & (gap > 0.0)
        for k in out:
            out[k][use] = cand[k][use]
        below &= ~use
    stuck = prim["stuck"] & below
    vf = -p.A * p.omega * np.cos(p.omega * prim["s"])
    out["y"] = np.where(below, _surface(p, out["d"], prim["s"]), out["y"])
    out["vx"] = np.where(stuck, 0.0, out["vx"])
    out["vy"] = np.where(stuck, vf, out["vy"])
    out["s"] = prim["s"].copy()
    out["stuck"] = stuck
    out["from_surface"] = below.copy()
    return out


def _one_period(p: Params, st: dict[str, np.ndarray], period: float,
                numerics: Numerics) -> tuple[dict[str, np.ndarray], NDArray[np.int64]]:
    """Run every state one floor period; return the states at its end and the collisions."""
    n = st["cell"].size
    init = InitialState(**{k: st[k] for k in _KEYS})
    run = simulate(p, n, period, 0, init, record_collisions=_ROWS, numerics=numerics)
    coll = run.counters["collisions"].copy()
    last = np.full((n, 6), np.nan)
    has = run.n_recorded > 0
    last[has] = run.collisions_dense[np.flatnonzero(has), run.n_recorded[has] - 1]
    for i in np.flatnonzero(run.n_recorded == _ROWS):
        # more collisions than rows: re-run this one, keeping those after its last kept row
        sub = InitialState(**{k: st[k][i : i + 1] for k in _KEYS})
        while True:
            rerun = simulate(p, 1, period, 0, sub, record_collisions=_ROWS,
                             record_from=float(np.nextafter(last[i, 0], np.inf)),
                             numerics=numerics)
            k = int(rerun.n_recorded[0])
            if k:
                last[i] = rerun.collisions_dense[0, k - 1]
            if k < _ROWS:
                break
    return _end_state(p, st, last, has, period, numerics), coll


def _end_state(p: Params, st: dict[str, np.ndarray], last: _FLOAT, has: NDArray[np.bool_],
               period: float, numerics: Numerics) -> dict[str, np.ndarray]:
    """States at the end of the period, rebuilt from each particle's last collision."""
    w, A, g = p.omega, p.A, p.g
    fl = Floor(float(g), float(A), float(w), shape_of(p), float(p.S), float(p.alpha), float(p.beta))
    # the anchor: the last collision, or the start when there was none
    t_a = np.where(has, last[:, 0], 0.0)
    s_a = np.where(has, last[:, 5] * period, st["s"])
    x_a = np.where(has, last[:, 1], st["cell"] * p.S + st["d"])
    y_a = np.where(has, last[:, 2], st["y"])
    vx_a = np.where(has, last[:, 3], st["vx"])
    vy_a = np.where(has, last[:, 4], st["vy"])
    vf_a = -A * w * np.cos(w * s_a)
    # a sticking collision leaves vₓ = 0 and the floor's velocity exactly; any other leaves
    # a relative normal speed ≥ v_stick
    stuck_a = np.where(has, (vx_a == 0.0) & (np.abs(vy_a - vf_a) < 0.5 * numerics.v_stick),
                       st["stuck"])
    t_end = period
    s_end = st["s"]
    n = t_a.size
    x = np.empty(n)
    y = np.empty(n)
    vx = np.empty(n)
    vy = np.empty(n)
    stuck = np.zeros(n, bool)
    for i in range(n):
        ta, sa, xa, ya, vxa, vya = t_a[i], s_a[i], x_a[i], y_a[i], vx_a[i], vy_a[i]
        if stuck_a[i]:
            wait = liftoff_wait(sa, 0.0, fl, None, False)
            if ta + wait >= t_end:
                stuck[i] = True
                x[i] = xa
                vx[i] = 0.0
                continue
            ta += wait
            sa = (sa + wait) % period
            _, dd = cell_of(xa, p.S)
            ya = -A * math.sin(w * sa) - float(floor_depth(p, dd))
            vxa = 0.0
            vya = -A * w * math.cos(w * sa)
        tau = t_end - ta
        x[i] = xa + vxa * tau
        y[i] = ya + vya * tau - 0.5 * g * tau * tau
        vx[i] = vxa
        vy[i] = vya - g * tau
    cell, d = cell_of(x, p.S)
    surf = _surface(p, d, s_end)
    y = np.where(stuck, surf, y)
    vy = np.where(stuck, -A * w * np.cos(w * s_end), vy)
    # a flight rebuilt a rounding error below the surface: put it on the surface
    on = ~stuck & (y <= surf)
    y = np.where(on, surf, y)
    return dict(cell=cell, d=d, y=y, vx=vx, vy=vy, s=s_end.copy(), stuck=stuck, from_surface=on | stuck)


def _mean_ci(values: _FLOAT, n_resamples: int, ci: float, seed: int) -> tuple[float, float, float]:
    if values.size == 0:
        return (math.nan, math.nan, math.nan)
    rng = np.random.default_rng(np.random.SeedSequence(seed))
    idx = rng.integers(0, values.size, size=(n_resamples, values.size))
    boot = values[idx].mean(axis=1)
    q = (1.0 - ci) / 2.0
    lo, hi = np.quantile(boot, [q, 1.0 - q])
    return float(values.mean()), float(lo), float(hi)
