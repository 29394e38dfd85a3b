"""Checks of a scene's physics before anything runs: a run that cannot mean anything is
refused, a scene that is probably not what was meant is warned about, one line each.

Called by ``bbb run`` (:func:`pipeline.execute.run.run_study`, and before any batch job of
``--cluster``: :func:`pipeline.execute.cluster.work_left`) and ``bbb plan``
(:func:`pipeline.execute.pilot.plan_rates`).  The rules, fixed before they were tried on any
scene (docs/physics.md, "Checks before a run"):

nothing moves   (refused: :class:`NothingMoves`, exit 2) when at every point of the scene
                f < the lift-off frequency of its floor (:func:`bbb.analysis.liftoff_onset.liftoff_frequency`:
                the lowest f at which a particle at rest anywhere on the arcs, tilted or thrown,
                feels the floor let go; Γ = 1 on a level floor vibrated vertically, whatever
                the arcs' curvature), contact = "stick" (a particle at rest is carried with the
                floor, on a tilted or thrown floor too) and every family starts at rest: then
                no particle ever leaves its place on the floor.
below lift-off  (warning) every point is below lift-off but sliding (contact = "slide" or
                "coulomb") or a family started in flight (dropped, launched) can still move
                particles: sliding transport below lift-off is a regime of its own; a bouncing
                particle may decay onto the floor for good.
Γ > 50          (warning) at some point: far beyond the scenes this model is checked on (the
                paper's floor reaches Γ = 4.03 at 100 Hz); A is in mm, f in Hz.
radians         (warning) an angle (tilt, throw; in [params] or a [grid] axis) whose value is
                nonzero, below π/2 in magnitude and no multiple of 0.5°: it reads like radians
                (tilt = 0.1 is 0.1°, not 5.7°).  Every shipped scene is silent
                (tests/pipeline/workflow/test_sanity.py).

The suggestion of a refusal: where the scene sets A, the A × 10^k (k = 1, 2, 3, smallest)
at which some point of the scene lifts off -- a slipped decimal point is the likeliest cause
(the paper's own A = 0.01 for 0.1); where it sets Γ, the Γ of lift-off; else the lift-off
frequency.  Units: A in mm, f in Hz, angles in degrees.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable

from bbb.analysis.liftoff_onset import liftoff_frequency
from bbb.params import Params

from .schema import line_of
from .study import Study, WorkflowError

__all__ = ["GAMMA_HIGH", "ANGLE_KEYS", "NothingMoves", "scene_warnings", "nothing_moves",
           "refuse_nothing_moves", "check_scene", "looks_like_radians"]

#: above this Γ at some point a scene is warned about
GAMMA_HIGH = 50.0
#: the paper's floor at its highest frequency (Fig. 2 ends at 100 Hz), for the warning's scale
PAPER_GAMMA = Params.preset("klages2004", f=100.0).gamma
#: the [params] keys in degrees (pipeline.workflow.keys.PARAM_UNITS)
ANGLE_KEYS = ("tilt", "throw")
#: an angle that is a multiple of this (degrees) does not look like radians
ANGLE_GRAIN = 0.5


class NothingMoves(WorkflowError):
    """A scene in which no particle can ever move: refused before anything runs."""


def _stderr(line: str) -> None:
    print(line, file=sys.stderr)


def looks_like_radians(value: float) -> bool:
    """Whether an angle given in degrees reads like radians: nonzero, |value| < π/2 and no
    multiple of 0.5° (module docstring)."""
    v = abs(float(value))
    return 0.0 < v < math.pi / 2 and not math.isclose(v / ANGLE_GRAIN, round(v / ANGLE_GRAIN),
                                                       abs_tol=1e-9)


def _amplitude_key(study: Study) -> tuple[str, tuple[str, ...]]:
    """The key that sets the floor's amplitude, and its TOML path (for the line)."""
    grid = dict(study.grid)
    for name in ("A", "Gamma"):
        if name in study.overrides:
            return name, ("params", name)
        if name in grid:
            return name, ("grid", name)
    return "frequencies", ("frequencies",)


def _where(study: Study, path: tuple[str, ...]) -> str:
    line = line_of(study.text, path)
    return f"{study.source}:{line}" if line else study.source


def _suggestion(study: Study, points, f_lift: list[float]) -> str:
    key, _ = _amplitude_key(study)
    if key == "A":
        for k in (1, 2, 3):  # f_lift scales as 1 / sqrt(A)
            if any(p.f >= fl / 10 ** (k / 2) for p, fl in zip(points, f_lift, strict=True)):
                amps = sorted({p.params.A for p in points})
                if len(amps) == 1:
                    return f"did you mean A = {amps[0] * 10**k:g}?"
                return f"did you mean A values {10**k:g} times larger?"
        return "lift-off needs a larger A or f"
    top = max(points, key=lambda p: p.params.gamma)
    fl = f_lift[points.index(top)]
    g_lift = top.params.A * (2 * math.pi * fl) ** 2 / top.params.g
    if key == "Gamma":
        return f"lift-off needs Gamma >= {g_lift:.3g} on this floor"
    return f"lift-off needs f >= {fl:.4g} Hz at A = {top.params.A:g} mm"


def _below(study: Study):
    """(points, their lift-off frequencies) if every point is below lift-off, else None."""
    points = list(study.points)
    if not points:
        return None
    f_lift = [liftoff_frequency(p.params) for p in points]
    if any(p.f >= fl for p, fl in zip(points, f_lift, strict=True)):
        return None
    return points, f_lift


def _gamma_text(points, f_lift) -> str:
    top = max(points, key=lambda p: p.params.gamma)
    fl = f_lift[points.index(top)]
    g_lift = top.params.A * (2 * math.pi * fl) ** 2 / top.params.g
    at = top.label().removeprefix("f = ")
    return f"Γ_max = {top.params.gamma:.3g} at {at}, lift-off from Γ = {g_lift:.3g} ({fl:.4g} Hz)"


def nothing_moves(study: Study) -> NothingMoves | None:
    """The refusal of a scene in which no particle can move (module docstring), or None."""
    below = _below(study)
    if below is None:
        return None
    points, f_lift = below
    if any(p.params.contact != "stick" for p in points):
        return None
    if any(fam.initial != "rest" for fam in study.families):
        return None
    key, path = _amplitude_key(study)
    line = line_of(study.text, path)
    return NothingMoves(
        study.source, key,
        f"no particle can lift off: {_gamma_text(points, f_lift)}; every particle starts at "
        f"rest and sticks, so nothing would move; {_suggestion(study, points, f_lift)}",
        "a scene with some point at or above lift-off, contact = \"slide\" or \"coulomb\", or "
        "a family started in flight (dropped, launched)", line)


def refuse_nothing_moves(study: Study) -> None:
    """Raise :class:`NothingMoves` (exit 2 in the CLI) if no particle of ``study`` can move."""
    refusal = nothing_moves(study)
    if refusal is not None:
        raise refusal


def scene_warnings(study: Study) -> list[str]:
    """The warning lines of ``study`` (module docstring), in the order of the rules."""
    out = []
    below = _below(study)
    if below is not None and nothing_moves(study) is None:
        points, f_lift = below
        movers = []
        if any(p.params.contact != "stick" for p in points):
            movers.append("sliding")
        flying = [fam.name for fam in study.families if fam.initial != "rest"]
        if flying:
            movers.append(f"the families started in flight ({', '.join(flying)})")
        key, path = _amplitude_key(study)
        out.append(f"{_where(study, path)}: {key}: warning: no particle at rest can lift off "
                   f"({_gamma_text(points, f_lift)}); only {' and '.join(movers)} can move "
                   "particles")
    points = list(study.points)
    if points:
        top = max(points, key=lambda p: p.params.gamma)
        if top.params.gamma > GAMMA_HIGH:
            key, path = _amplitude_key(study)
            out.append(f"{_where(study, path)}: {key}: warning: Γ = {top.params.gamma:.3g} at "
                       f"{top.label().removeprefix('f = ')} is above {GAMMA_HIGH:g} (the paper's "
                       f"floor reaches Γ = {PAPER_GAMMA:.3g} at 100 Hz); A is in mm, f in Hz; "
                       "the run continues")
    grid = dict(study.grid)
    for name in ANGLE_KEYS:
        where = (("params", name, study.overrides[name]),) if name in study.overrides else ()
        where += tuple(("grid", name, v) for v in grid.get(name, ()))
        for table, _, value in where:
            if isinstance(value, int | float) and looks_like_radians(value):
                out.append(f"{_where(study, (table, name))}: {name} = {value:g}: warning: "
                           f"angles are in degrees ({value:g} rad = {math.degrees(value):.1f}°); "
                           "the run continues")
    return out


def check_scene(study: Study, echo: Callable[[str], None] | None = None) -> None:
    """Before anything runs: each warning of :func:`scene_warnings` as one line to ``echo``
    (default: stderr), then :func:`refuse_nothing_moves`."""
    for line in scene_warnings(study):
        (echo or _stderr)(line)
    refuse_nothing_moves(study)
