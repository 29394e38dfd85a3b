"""``python -m pipeline.make_figures [--fast]``: every figure and figures/REPORT.md.

The entry point over the studies (as ``pipeline.cli`` is over engine and studies); the work is
done by :mod:`pipeline.studies.klages2004.make_figures`, which runs the paper's scenes, reduces
them, draws the figures and writes the report.  Code imports that module; this one only runs it.
"""

if __name__ == "__main__":
    from pipeline.studies.klages2004.make_figures import main

    raise SystemExit(main())
