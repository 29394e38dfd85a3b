"""bbb — the bouncing ball billiard (Klages, Barna & Mátyás 2004): physics library."""

from importlib import metadata as _metadata

from .ensemble import FAMILIES
from .numerics import Numerics
from .params import PRESETS, Params
from .record import SimRun
from .simulate import simulate

try:  # one source for the version: pyproject.toml, through the installed metadata
    __version__ = _metadata.version("bbb")
except _metadata.PackageNotFoundError:  # a source tree put on sys.path without install
    __version__ = "unknown"
__all__ = ["FAMILIES", "PRESETS", "Numerics", "Params", "SimRun", "simulate", "__version__"]
