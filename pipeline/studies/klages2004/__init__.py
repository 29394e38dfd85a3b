"""Klages, Barna & Mátyás (2004), *Spiral modes in the diffusion of a granular particle on a
vibrating surface*: the paper's scenes (``scenes/``), its claims as data (``claims``), its
figures (``figures``), its report section (``report``) and the study record the registry
reads (``study``: :data:`STUDY`)."""

from .study import STUDY

__all__ = ["STUDY"]
