"""Which scenes the paper's study runs: the lowest module of the study, read by its study
record (``study``) and its tests."""

from __future__ import annotations

__all__ = ["SCENES"]

#: the scenes this study runs, in order
SCENES = ("figure2", "ergodicity", "figure3", "locking", "figure2_matyas2004",
          "locking_matyas2004", "finescale")
