"""The two onset predictions as claims, judged on the onset of every grid line of the scenes
``onset_map`` (the arcs: α × R) and ``onset_sine`` (the sine floor: α × depth).

Rules, fixed and committed before either map ran (registered in the commit each claim's
``registered`` names); the predicted frequencies are read from ``predictions.json``
(:mod:`.predictions`, computed from :mod:`bbb.analysis.onset_theory`), the band is ± the
scenes' grid step along f (:func:`.lines.step_of`: 1 Hz):

O1   (a) horizontal, at the arcs' cusp.  The cusp is a wedge: a vertical impact at any offset
     from it, however small, is kicked toward it by (α + β) U sin θc cos θc, so no vertical
     motion with a flight is horizontally stable there; the rest point loses horizontal
     stability at the first lift-off.  Prediction: on every (α, R) line of onset_map the onset
     lies within f(Γ = 1) ± step (49.8 Hz at A = 0.1 mm), whatever α and R.
O1s  (a) horizontal, at the sine's valley (a smooth minimum, curvature κ = (depth/2)(2π/S)²).
     The chattering cycle reached from rest is horizontally stable there wherever it exists
     (|λ| < 1 over [f(Γ = 1), f_c(α)), predictions.json), so the horizontal mechanism starts
     nothing below f_c: on every (α, depth) line of onset_sine the onset lies at or above
     f_c(α) − step (a one-sided band).
O2   (b) vertical.  Motion starts where the chattering cycle from rest stops ending within
     its period, f_c(α) (the exact flat-floor map; independent of R).  Prediction: on every
     (α, R) line of onset_map the onset lies within f_c(α) ± step.
O2s  (b) vertical on the sine floor: on every (α, depth) line of onset_sine the onset lies
     within f_c(α) ± step (independent of the depth).

Each line is a part, judged by the verdict rule of :func:`pipeline.claims.claim.judge` (its
onset CI against the band); the parts combine by the generic rule (all agree: agrees; a mix:
partly); a line without an onset (no point above the threshold) disagrees ('not found'); a
line the scene lists but the table lacks makes the claim 'not measured' (the rule is stated
over all lines).
"""

from __future__ import annotations

import math

from ...claims.claim import Band, Claim, Measured, Part, Quantity, measure
from .cases import horizontal_cases, sine_floor_cases, vertical_cases, vertical_sine_cases
from .lines import AXES, grid_lines, onset, step_of
from .predictions import load

__all__ = ["MAP", "SINE", "CLAIMS", "context", "predicted"]

MAP, SINE = "onset_map", "onset_sine"


def predicted(which: str, alpha: float, preds: dict) -> float:
    """The predicted onset (Hz) of ``which`` ("liftoff": f(Γ = 1); "chatter": f_c(α))."""
    if which == "liftoff":
        return float(preds["f_liftoff"])
    return float(preds["alpha"][f"{alpha:g}"]["f_c"])


def _listed(ctx, scene: str) -> list[tuple[float, float]]:
    """The (α, axis) lines the claim judges: ``ctx["listed"][scene]``, else the scene's grid."""
    given = ctx.get("listed", {}).get(scene)
    if given is not None:
        return [tuple(map(float, x)) for x in given]
    from ...workflow.scenes import load_scene

    grid = dict(load_scene(scene).grid)
    return [(float(a), float(v)) for a in grid["alpha"] for v in grid[AXES[scene]]]


@measure("onset.lines")
def onset_lines(claim: Claim, ctx) -> Measured:
    """One part per listed line: its onset (with CI) against the prediction ± step
    (``options``: which prediction, ``side`` "both" or "above", an optional ``shift`` in Hz
    added to the prediction -- a perturbed theory)."""
    scene = claim.scene
    axis = AXES[scene]
    table = ctx["tables"].get(f"{scene}_diffusion")
    if table is None:
        return Measured(missing=f"no {scene} map reduced")
    lines = grid_lines(table, axis)
    preds = ctx.get("predictions") or load()
    step = float(ctx.get("step", {}).get(scene) or step_of(scene))
    shift = float(claim.options.get("shift", 0.0))
    unit = "mm"
    parts = []
    for a, v in _listed(ctx, scene):
        label = f"α = {a:g}, {axis} = {v:g} {unit}"
        fp = predicted(claim.options["which"], a, preds) + shift
        if claim.options.get("side", "both") == "above":
            band = Band(fp - step, math.inf, f"at or above {fp:.1f} − {step:g} Hz", "Hz")
        else:
            band = Band.around(fp, step, f"± the grid step {step:g} Hz", "Hz")
        line = lines.get((a, v))
        if line is None:
            parts.append(Part(label, Quantity(math.nan), "line not in the map"))
            continue
        q = onset(line)
        found = math.isfinite(q.value)
        parts.append(Part(label, q, (q.text("g") if found else "no onset") +
                          f" vs {fp:.1f} Hz", band=band, found=found))
    return Measured(parts)


_REG = "2026-11-28 6abded2"
_WHY = "± the scenes' grid step along f (1 Hz), stated before the run"
CLAIMS = [
    Claim("(a) horizontal at the cusp: the wedge makes every vertical motion with a flight "
          "horizontally unstable, so motion starts at the first lift-off f(Γ = 1), on every "
          "(α, R) line", onset_lines, MAP, Band(-math.inf, math.inf, _WHY),
          options={"which": "liftoff"}, id="O1", registered=_REG, all_parts=True,
          scope={"scenes": [MAP], "lines": "every (alpha, R) of the scene's grid",
                 "families": ["rest"], "band": "f(Gamma=1) +- grid step"},
          cases=horizontal_cases),
    Claim("(a) horizontal at the sine's valley: the chattering cycle is horizontally stable "
          "wherever it exists, so nothing starts below f_c(α), on every (α, depth) line",
          onset_lines, SINE, Band(-math.inf, math.inf, "at or above f_c(α) − the grid step"),
          options={"which": "chatter", "side": "above"}, id="O1s", registered=_REG,
          all_parts=True,
          scope={"scenes": [SINE], "lines": "every (alpha, depth) of the scene's grid",
                 "families": ["rest"], "band": "onset >= f_c(alpha) - grid step"},
          cases=sine_floor_cases),
    Claim("(b) vertical: motion starts where the chattering cycle from rest stops ending "
          "within its period, f_c(α), whatever R, on every (α, R) line", onset_lines, MAP,
          Band(-math.inf, math.inf, _WHY), options={"which": "chatter"}, id="O2",
          registered=_REG, all_parts=True,
          scope={"scenes": [MAP], "lines": "every (alpha, R) of the scene's grid",
                 "families": ["rest"], "band": "f_c(alpha) +- grid step"},
          cases=vertical_cases),
    Claim("(b) vertical on the sine floor: the onset at f_c(α), whatever the depth, on every "
          "(α, depth) line", onset_lines, SINE, Band(-math.inf, math.inf, _WHY),
          options={"which": "chatter"}, id="O2s", registered=_REG, all_parts=True,
          scope={"scenes": [SINE], "lines": "every (alpha, depth) of the scene's grid",
                 "families": ["rest"], "band": "f_c(alpha) +- grid step"},
          cases=vertical_sine_cases),
]


def context(tables, stores=None) -> dict:
    """The context the claims are judged in: the two maps' diffusion tables."""
    return {"tables": {f"{s}_diffusion": tables.get(f"{s}_diffusion") for s in (MAP, SINE)}}
