"""The makers of every calibration a rule reads, and the list of them that ``make calibrate`` runs.

A verdict rule is calibrated on synthetic data (or floors) with known answers before it is
applied; its numbers are read from a JSON committed beside the code that reads it (bbb and
pipeline never import benchmarks).  Each of those JSONs names its maker -- the key ``maker``:
``{"script": <path from the checkout's root>, "args": [<its inputs: sizes, seeds>]}`` -- and
``make calibrate`` (``python -m benchmarks.calibrations``) remakes every one of them from that
list: the maker runs as ``python -m <module> <args> --json <path>``.  Besides the makers this
folder holds checks of a rule that write no JSON a rule reads (v_status_calibration: the
accelerating rule at small ensembles; guards: the kernel's loop guards against real inputs).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Calibration:
    """One committed calibration JSON (``json``, from the checkout's root), the module that
    makes it and the inputs it was made with (everything but where it writes)."""

    json: str
    module: str
    args: tuple[str, ...] = ()

    @property
    def script(self) -> str:
        """The maker's file, from the checkout's root."""
        return self.module.replace(".", "/") + ".py"

    def maker(self) -> dict:
        """The ``maker`` record its JSON holds."""
        return {"script": self.script, "args": list(self.args)}


#: every calibration JSON a rule (or the trajectory checker of the tests) reads
CALIBRATIONS: tuple[Calibration, ...] = (
    Calibration("bbb/analysis/stats/ergodicity_calibration.json",
                "benchmarks.calibrations.ergodicity_calibration",
                ("--seeds", "100", "--sizes", "64x3,1024x3,4096x1")),
    Calibration("bbb/analysis/stats/rare_movers_calibration.json", "benchmarks.calibrations.rare_movers",
                ("--reps", "200", "--reps-4096", "100", "--seed", "2026")),
    Calibration("bbb/analysis/gk_contrast_rule.json", "benchmarks.calibrations.contrast_calibration",
                ("--replicates", "100", "--particles", "1024", "--steps", "3000")),
    Calibration("bbb/analysis/transport_rules.json", "benchmarks.calibrations.transport_rules",
                ("--seeds", "1000")),
    Calibration("pipeline/studies/transport/mirror.json", "benchmarks.calibrations.transport_mirror",
                ("--pairs", "128", "--pool", "1024", "--curves", "2000")),
    Calibration("pipeline/studies/transport/hopping.json", "pipeline.studies.transport.hopping_calibration"),
    Calibration("pipeline/studies/transport/liftoffs.json", "benchmarks.calibrations.hopping_liftoffs"),
    Calibration("bbb/analysis/states_rule.json", "benchmarks.calibrations.states_calibration",
                ("--particles", "64")),
    Calibration("tests/bbb/data/checker_calibration.json", "benchmarks.calibrations.checker_calibration",
                ("--random", "400")),
)
