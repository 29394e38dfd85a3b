"""The workflow scenes (``*.toml``).  A package only so that a wheel installs them as the
package data ``pipeline.workflows`` (see ``[tool.setuptools.package-dir]`` in pyproject.toml);
``pipeline.workflow.scenes.scene_path`` finds them through importlib.resources."""
