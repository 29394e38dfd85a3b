"""The validated workflow, :class:`Study`: what a scene asks for, resolved, and what follows
from it -- the parameters at each frequency, the sample times, every chunk's seed, the
serialised form a store keeps, and the fingerprint of what determines the stored numbers.

A Study is made by :func:`pipeline.workflow.load.parse_workflow` (which validates the TOML) or
read back from a store (:meth:`Study.from_dict`).  Frequencies in Hz (multiples of 1 mHz),
times in s, lengths in mm.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from bbb.params import Params

from .identity import chunk_seed, f_key
from .keys import Accuracy, Analysis, Family, Observables, RefineTable
from .schema import as_dict

__all__ = ["Study"]


@dataclass(frozen=True)
class Study:
    """A validated workflow.  Frequencies are in Hz, rounded to 1 mHz."""

    name: str
    source: str
    seed: int
    preset: str
    overrides: dict[str, float | str]
    frequencies: tuple[float, ...]
    families: tuple[Family, ...]
    accuracy: Accuracy
    observables: Observables
    analysis: Analysis
    #: adaptive frequency refinement ([frequencies] refine), or None
    refine: RefineTable | None = None
    #: frequencies added by refinement, Hz, in the order they joined the store; they follow
    #: the workflow's own grid in ``frequencies``
    refined: tuple[float, ...] = ()
    text: str = field(default="", compare=False, repr=False)

    # -- derived quantities -------------------------------------------------------------------
    def params(self, f: float) -> Params:
        return Params.preset(self.preset, f=float(f), **self.overrides)

    @property
    def base_params(self) -> dict[str, float]:
        """The resolved parameters except f (which varies over the grid)."""
        d = Params.preset(self.preset, f=1.0, **self.overrides).as_dict()
        del d["f"]
        return d

    @property
    def f_mhz(self) -> tuple[int, ...]:
        return tuple(f_key(f) for f in self.frequencies)

    @property
    def base_frequencies(self) -> tuple[float, ...]:
        """The workflow's own frequencies, Hz (``frequencies`` without the refined ones)."""
        added = {f_key(f) for f in self.refined}
        return tuple(f for f in self.frequencies if f_key(f) not in added)

    @property
    def adaptive(self) -> bool:
        """Whether chunks are computed in waves (target_ci) or frequencies added (refine)."""
        return self.accuracy.adaptive or self.refine is not None

    def with_refined(self, added: tuple[float, ...]) -> Study:
        """The study whose store also holds the refined frequencies ``added`` (Hz, in store
        order), appended after the workflow's own."""
        base = self.base_frequencies
        return replace(self, frequencies=base + tuple(added), refined=tuple(added))

    def sample_times(self) -> np.ndarray:
        """Position sample times, s: 0, dt, ..., t_max."""
        n = round(self.accuracy.t_max / self.accuracy.sample_dt)
        return np.arange(n + 1, dtype=np.float64) * self.accuracy.sample_dt

    def seed_sequence(self, f: float, family: Family, chunk: int) -> np.random.SeedSequence:
        """The seed of one chunk, keyed by values (f in mHz, family name hash, chunk index), so
        adding frequencies or families never changes the results of the others."""
        return chunk_seed(self, f, family, chunk)

    @property
    def mirror_symmetric(self) -> bool:
        """Whether the floor is mirror-symmetric (level, vibrated vertically: no tilt, throw
        90°), under any contact model: a particle's mirror image then moves as its reflection."""
        return not Params.preset(self.preset, f=1.0, **self.overrides).transport

    def pairing(self, family: Family) -> str:
        """How ``family``'s particles enter the estimates (bbb.analysis.transport.PAIRING): "mirror
        symmetry" (images counted, not simulated), "pairs" (each chunk's second half are the
        mirror partners of its first half, bbb.ensemble.mirror_pairs) or "independent"."""
        from bbb.analysis.transport import INDEPENDENT, PAIRS, SYMMETRY

        mirror = self.mirror_symmetric if family.mirror is None else family.mirror
        return INDEPENDENT if not mirror else SYMMETRY if self.mirror_symmetric else PAIRS

    def with_frequencies(self, frequencies: tuple[float, ...]) -> Study:
        """The same study at some of its frequencies (Hz): every chunk keeps its seed, so it
        computes the same numbers as in the whole sweep."""
        mhz = {f_key(f) for f in frequencies}
        return replace(self, frequencies=tuple(f for f in self.base_frequencies
                                               if f_key(f) in mhz), refined=())

    # -- serialisation ------------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """Everything resolved (preset numbers written out), JSON-able."""
        d = {
            "name": self.name,
            "source": self.source,
            "seed": self.seed,
            "params": {"preset": self.preset, **self.overrides},
            "resolved_params": self.base_params,
            "frequencies": list(self.frequencies),
            "families": [_drop_none(as_dict(fam)) for fam in self.families],
            "accuracy": as_dict(self.accuracy),
            "observables": as_dict(self.observables),
            "analysis": as_dict(self.analysis),
        }
        # only when used, so that the stored workflow of every older scene stays as it was
        if self.refine is not None:
            d["refine"] = as_dict(self.refine)
        if self.refined:
            d["refined"] = list(self.refined)
        return d

    @classmethod
    def from_dict(cls, d: dict[str, Any], text: str = "") -> Study:
        params = dict(d["params"])
        preset = params.pop("preset")
        fams = tuple(
            Family(
                name=fd["name"],
                initial=fd["initial"],
                drop_height=_tuple_or_none(fd.get("drop_height")),
                launch_speed=_tuple_or_none(fd.get("launch_speed")),
                mirror=fd.get("mirror"),
                description=fd.get("description", ""),
            )
            for fd in d["families"]
        )
        return cls(
            name=d["name"],
            source=d["source"],
            seed=int(d["seed"]),
            preset=preset,
            overrides={k: v if k == "contact" else float(v) for k, v in params.items()},
            frequencies=tuple(float(f) for f in d["frequencies"]),
            families=fams,
            accuracy=Accuracy(**d["accuracy"]),
            observables=Observables(**d["observables"]),
            analysis=Analysis(**d["analysis"]),
            refine=RefineTable(**d["refine"]) if d.get("refine") is not None else None,
            refined=tuple(float(f) for f in d.get("refined", ())),
            text=text,
        )

    def data_identity(self) -> dict[str, Any]:
        """The parts that determine the stored numbers (not the name, not reduce settings)."""
        acc = as_dict(self.accuracy, identity=True)
        del acc["preset"], acc["n_resamples"]
        d = {
            "seed": self.seed,
            "params": self.base_params,
            "f_mhz": [f_key(f) for f in self.base_frequencies],
            "families": [self._family_identity(fam) for fam in self.families],
            "accuracy": acc,
            "observables": as_dict(self.observables, identity=True),
        }
        if self.adaptive:
            # Which chunks and frequencies get computed depends on the CI of D, so on the
            # settings of that CI too (absent for fixed-N scenes: their fingerprints stay).
            an = self.analysis
            d["stopping"] = {"n_resamples": self.accuracy.n_resamples, "ci": an.ci,
                             "ci_method": an.ci_method, "discard": an.discard,
                             "fit_from": an.fit_from, "fit_to": an.fit_to}
        if self.refine is not None:
            d["refine"] = as_dict(self.refine)
        return d

    def _family_identity(self, fam: Family) -> dict[str, Any]:
        # mirror changes the stored numbers only where the partners are simulated ("pairs");
        # images counted by symmetry, or none, leave the store (and its fingerprint) as before
        d = _drop_none(as_dict(fam, identity=True))
        d.pop("mirror", None)
        if self.pairing(fam) == "pairs":
            d["mirror"] = True
        return d

    def fingerprint(self) -> str:
        blob = json.dumps(self.data_identity(), sort_keys=True, default=_json_default)
        return hashlib.sha256(blob.encode()).hexdigest()


def _drop_none(d: dict) -> dict:
    return {k: (list(v) if isinstance(v, tuple) else v) for k, v in d.items() if v is not None}


def _tuple_or_none(v):
    return None if v is None else tuple(float(x) for x in v)


def _json_default(o):
    if isinstance(o, tuple):
        return list(o)
    raise TypeError(type(o))

