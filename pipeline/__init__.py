"""bbb's study pipeline: workflow TOML -> Dask tasks -> Zarr store -> reduce -> figures.

From Python (``pipeline/api.py``)::

    from pipeline import open_study, reduced, reduced_dataset, run_study
"""

from .api import load_study, open_study, plot_store, reduced, reduced_dataset, run_study

__all__ = ["load_study", "open_study", "plot_store", "reduced", "reduced_dataset", "run_study"]
