"""The analyses of bbb: what is measured on trajectories the kernel (:mod:`bbb.dynamics`,
run by :func:`bbb.simulate`) made.  None of them is hashed into the kernel identity
(:mod:`bbb.provenance`): they never change a stored trajectory, only what is read off it.

================== =========================================================================
``stats``          MSD, D and its bootstrap CI, the rare-mover rule, the ergodicity verdict
``stationarity``   D of the two halves of the run, and whether they differ
``transport``      drift velocity and D about the drift (vibro-conveyor)
``greenkubo``      Taylor–Green–Kubo expansion of D over jumps
``gk_contrast``    which part of D (random walk or memory) makes an extremum
``locking``        creeping band, maximal launch speed, flight times, locking ratio k
``approx``         the flat-floor spiral and k = 2 v f / g (paper Eqs. 7–9)
``extrema``        significant extrema of a noisy curve with CIs
``liftoff_onset``  the lowest frequency at which a particle at rest can lift off
``period1``        where the flat-floor 1/1 orbit exists (Γ₁) and stays stable (Γ')
``lyapunov``       largest Lyapunov exponent from two nearby trajectories
``moving``         which particles move: operational definitions of "moving particles"
``moving_d``       the share that moves and D of the moving particles, with intervals
``states``         each time window's state: stuck/creeping, locked 1/1 or period-k, chaotic,
                   diffusing
================== =========================================================================

The calibrated rules ship beside their modules (transport_rules.json, gk_contrast_rule.json,
states_rule.json, stats/*_calibration.json).  Nothing is imported here: ``import bbb.analysis.X``.
"""
