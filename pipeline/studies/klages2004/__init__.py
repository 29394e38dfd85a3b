"""Klages, Barna & Mátyás (2004), *Spiral modes in the diffusion of a granular particle on a
vibrating surface*: the paper's scenes (``scenes/``), its claims as data (``claims``), its
figures (``figures``), the report (``report``) and the run that makes them all
(``make_figures``)."""
