"""Named accuracy presets: every knob that trades computing time for accuracy, in one place.

A workflow names a preset (``accuracy = "draft"``) or a preset plus single-knob overrides
(``[accuracy] preset = "standard"`` and e.g. ``n_particles = 2048``).  The numbers below are
provisional; issue 5 measures the trade-off and fixes them.

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

# Sizing (provisional): at f = 60 a particle collides ~70 times per simulated second, and the
# kernel aims at ~1e6 collisions/s/core, so a chunk of c particles over t_max seconds costs
# about c * t_max * 70 / 1e6 s.  Chunks are sized so that one task runs >= ~1 s (Dask costs
# ~1-3 ms per task) at the ensemble sizes of each preset.
ACCURACY_PRESETS: dict[str, dict[str, float | int]] = {
    "draft": dict(
        n_particles=64, chunk_size=64, t_max=100.0, sample_dt=0.5,
        tol_t=1e-10, v_stick=1e-2, max_step=0.25, n_resamples=200,
    ),
    "standard": dict(
        n_particles=256, chunk_size=128, t_max=400.0, sample_dt=0.5,
        tol_t=1e-12, v_stick=1e-3, max_step=0.25, n_resamples=1000,
    ),
    "paper": dict(
        n_particles=512, chunk_size=128, t_max=800.0, sample_dt=0.5,
        tol_t=1e-12, v_stick=1e-3, max_step=0.25, n_resamples=2000,
    ),
    "reference": dict(
        n_particles=2048, chunk_size=256, t_max=2000.0, sample_dt=0.5,
        tol_t=1e-13, v_stick=1e-4, max_step=0.1, n_resamples=5000,
    ),
}

DEFAULT_ACCURACY = "standard"

# Which knobs are integers (counts) and which are bbb.Numerics fields.
INT_KNOBS = ("n_particles", "chunk_size", "n_resamples")
NUMERICS_KNOBS = ("tol_t", "v_stick", "max_step")
ACCURACY_KNOBS = tuple(ACCURACY_PRESETS["draft"])
