"""Studies built on the engine, one folder each: its scenes (``scenes/*.toml``), its claims as
data, its figures and report.  A study imports the engine (``pipeline.*``) and ``bbb``'s public
names; the engine never imports a study (it finds their scenes as files: ``pipeline.workflow.scenes``).

klages2004 -- Klages, Barna & Mátyás (2004): Figs. 1–3, D(f), locking, ergodicity, REPORT.md
accuracy   -- the measured speed/accuracy trade behind the presets (``bbb accuracy``)
"""
