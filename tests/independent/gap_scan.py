"""Brute force: the first contact of a flight with the moving floor found by scanning the gap
on a fine time grid and bisecting the first sign change (numpy only; the reference the heyoka
detector is checked against).  A dip of the gap below 0 shorter than the grid step is missed:
the grid is ``n`` points over the flight's duration bound."""

from __future__ import annotations

import math

import numpy as np

from tests.independent.floors import Drive


def gap(shape, drive: Drive, x0, y0, vx, vy, theta0, tau):
    """G(τ) = height of the particle above the floor at the same offset, mm (floor's frame)."""
    gx, gy = drive.gravity
    ax, ay = drive.amplitude
    th = theta0 + drive.omega * tau
    x = x0 + vx * tau - 0.5 * gx * tau * tau
    y = y0 + vy * tau - 0.5 * gy * tau * tau
    return y + ay * np.sin(th) - shape.height(x + ax * np.sin(th))


def first_contact(shape, drive: Drive, x0, y0, vx, vy, theta0, n: int = 200_000) -> float:
    """τ (s) of the first sign change G > 0 → G ≤ 0 after τ = 0, bisected to the float grain."""
    _, gy = drive.gravity
    _, ay = drive.amplitude
    drop = y0 - shape.bottom + abs(ay)
    tau_max = (vy + math.sqrt(vy * vy + 2.0 * gy * drop)) / gy * 1.001 + 1e-12
    tau = np.linspace(0.0, tau_max, n)
    below = np.nonzero(gap(shape, drive, x0, y0, vx, vy, theta0, tau[1:]) <= 0.0)[0]
    if below.size == 0:
        raise AssertionError("the scan found no contact before its duration bound")
    i = below[0] + 1
    a, b = tau[i - 1], tau[i]
    while True:
        m = 0.5 * (a + b)
        if not a < m < b:
            return b
        if gap(shape, drive, x0, y0, vx, vy, theta0, np.array(m)) <= 0.0:
            b = m
        else:
            a = m
