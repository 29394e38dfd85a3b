"""bbb — the bouncing ball billiard (Klages, Barna & Mátyás 2004): physics library."""

from .ensemble import FAMILIES
from .numerics import Numerics
from .params import PRESETS, Params
from .record import SimRun
from .simulate import simulate

__version__ = "0.1.0"
__all__ = ["FAMILIES", "PRESETS", "Numerics", "Params", "SimRun", "simulate", "__version__"]
