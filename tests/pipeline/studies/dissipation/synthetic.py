"""Synthetic D(f, α) maps with known onsets, maxima and ergodicity (the study's cases module)."""

from pipeline.studies.dissipation.cases import ALPHAS, F, dmap, line

__all__ = ["ALPHAS", "F", "dmap", "line"]
