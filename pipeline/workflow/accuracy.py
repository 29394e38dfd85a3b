"""Named accuracy presets: every knob that trades computing time for accuracy, in one place.

A workflow names a preset (``accuracy = "draft"``) or a preset plus single-knob overrides
(``[accuracy] preset = "standard"`` and e.g. ``n_particles = 2048``).  The numbers are chosen
from the measured trade (``bbb accuracy``, ``docs/accuracy.md``).

Knobs and units:

n_particles  -- particles per (frequency, family), count
chunk_size   -- particles per Dask task and per store chunk; must divide n_particles
t_max        -- simulated time per particle, s
sample_dt    -- spacing of the position samples for the MSD, s (samples at 0, dt, ..., t_max)
tol_t        -- root-finding tolerance on the collision time, s       (bbb.Numerics)
v_stick      -- sticking threshold of creeping cascades, mm/s          (bbb.Numerics)
max_step     -- first bracketing step of the collision search, periods (bbb.Numerics)
n_resamples  -- bootstrap resamples per diffusion coefficient, count
"""

from __future__ import annotations

__all__ = ["ACCURACY_PRESETS", "ACCURACY_KNOBS", "NUMERICS_KNOBS", "DEFAULT_ACCURACY"]

# Why these numbers (measured 2026-11-22; docs/accuracy.md has the tables):
#
# * Statistics: D is the mean of per-particle TAMSD slopes fitted over lags that are fixed
#   *fractions* (5-25 %) of the analysed duration, so its relative standard error is
#   ~0.8 / sqrt(n_particles) at every f >= 58 Hz and does NOT shrink with t_max (a longer
#   run only moves the fit to longer lags).  The 95 % half-width is ~1.6 / sqrt(N): 3 % of D
#   at the worst of Fig. 2's 84 frequencies with D > 10 % of max D needs N = 4096.
# * Finite-time bias: with fractional fit lags a short run fits lags inside the spiral modes'
#   velocity correlations: D is low by 23 % at t_max = 12.5 s, 6 % at 25 s, <= 1 % from 50 s
#   on (paired per-particle comparison against 400 s over 84 frequencies of Fig. 2).  So
#   t_max = 50 s in every preset but the reference: longer runs buy nothing, shorter ones a
#   bias that the CI does not show (draft is 64 x 50 s rather than 128 x 25 s: same cost).
# * v_stick only sets how many tiny collisions a creeping cascade costs (collisions ~ log
#   (1/v_stick)); 1e-2 agrees with 1e-5 within the statistics everywhere measured, 1e-1
#   doubles the sticking episodes at 58 Hz (docs/physics.md), so 1e-2 for draft..paper.
# * tol_t and max_step change no D beyond the statistics (the search is certified, so
#   max_step is a pure speed knob, and 1 period is no faster than 0.25).  A loose tol_t is
#   not cheaper: at 1e-9 single particles fell into spurious cascades of ~1e6 collisions
#   (72, 80 Hz), so 1e-12 everywhere; the kernel rate is the same at 1e-10 and 1e-12.
# * Cost: Fig. 2 from rest costs ~0.016 CPU-s per particle-second summed over its 124
#   frequencies, 79 % of it in the 20 creeping frequencies 50-57.6 Hz where D = 0 from rest.
# * chunk_size: tasks of >= ~0.5 s at f >= 60 (cheap frequencies), so that the per-task
#   Dask + Zarr overhead stays a few per cent; at most ~30 s at the creeping frequencies so
#   that the sweep's tail (one task) is short.
ACCURACY_PRESETS: dict[str, dict[str, float | int]] = {
    "draft": dict(
        n_particles=64, chunk_size=64, t_max=50.0, sample_dt=0.5,
        tol_t=1e-12, v_stick=1e-2, max_step=0.25, n_resamples=200,
    ),
    "standard": dict(
        n_particles=1024, chunk_size=512, t_max=50.0, sample_dt=0.5,
        tol_t=1e-12, v_stick=1e-2, max_step=0.25, n_resamples=1000,
    ),
    "paper": dict(
        n_particles=4096, chunk_size=512, t_max=50.0, sample_dt=0.5,
        tol_t=1e-12, v_stick=1e-2, max_step=0.25, n_resamples=2000,
    ),
    # The yardstick of `bbb accuracy`: bias-free duration, the tightest numerics.  Costly at
    # the creeping frequencies (~1.5e-3 CPU-s per particle-second at 55 Hz, ~50x f >= 60).
    "reference": dict(
        n_particles=2048, chunk_size=256, t_max=200.0, sample_dt=0.5,
        tol_t=1e-13, v_stick=1e-5, max_step=0.1, n_resamples=2000,
    ),
}

DEFAULT_ACCURACY = "standard"

# Which knobs are integers (counts) and which are bbb.Numerics fields.
INT_KNOBS = ("n_particles", "chunk_size", "n_resamples")
NUMERICS_KNOBS = ("tol_t", "v_stick", "max_step")
ACCURACY_KNOBS = tuple(ACCURACY_PRESETS["draft"])
