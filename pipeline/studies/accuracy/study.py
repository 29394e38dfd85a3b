"""The measured speed/accuracy trade (``bbb accuracy``): every preset and every knob against a
reference run, through the real pipeline.

The workflow (``workflows/accuracy.toml``) is the *reference*: its frequencies, families and
accuracy (preset ``reference``, possibly with overrides).  Each *variant* is the same scene
with another accuracy table, run into its own store by :func:`pipeline.execute.run.run_study` and
reduced by :func:`pipeline.tables.reduce.diffusion_table`:

* ``preset`` variants: ``draft``, ``standard``, ``paper`` exactly as a workflow gets them;
* ``knob`` variants: the reference accuracy with ``n_particles = KNOB_N`` particles and
  ``t_max = KNOB_T`` s, and ONE numerical knob changed.  Their seeds (chunk 0, same chunk
  size) are the reference's first chunk, so each is compared *paired* with the reference's
  first KNOB_N particles over its first KNOB_T s (``pair`` columns): same initial
  conditions, same duration, only the knob differs.

Ensemble size and duration are not run as variants: a shorter run of the same chunk is
exactly a prefix of the reference's trajectories, and fewer particles are a subset, so
:func:`scaling_table` measures them on the reference store itself (the statistical error
versus N, the half-width and the finite-time bias versus t_max).

Outputs (``out_dir``; the tables also beside the figure, in ``figures/``):
``accuracy.parquet/.csv`` (one row per variant, frequency, family: columns in
:data:`ROW_COLUMNS`), ``accuracy_summary.parquet/.csv`` (one row per variant:
:data:`SUMMARY_COLUMNS`), ``accuracy_scaling.parquet/.csv`` (:data:`SCALING_COLUMNS`), and
the figure ``accuracy.png`` (error versus cost, Pareto front marked).  The scaling table is
:mod:`.scaling`, the figure :mod:`.figures`; both names stay importable from here.  Units: D in mm²/s,
times in s (CPU time = summed ``chunk_seconds`` of the tasks, the simulation only).
"""

from __future__ import annotations

import math
import os
import tomllib
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from ...tables.reduce import NO_PARQUET, has_parquet
from ...workflow.accuracy import ACCURACY_PRESETS
from ...workflow.load import parse_workflow
from ...workflow.study import Study
from .figures import accuracy_figure, plot_accuracy  # importable from here too
from .scaling import SCALING_COLUMNS, per_particle_D, scaling_table

__all__ = [
    "Variant", "default_variants", "variant_study", "run_accuracy_study", "compare",
    "summarize", "scaling_table", "per_particle_D", "pareto_front", "plot_accuracy", "accuracy_figure",
    "ROW_COLUMNS", "SUMMARY_COLUMNS", "SCALING_COLUMNS", "COLUMN_UNITS", "KNOB_N", "KNOB_T",
]

#: ensemble size and duration of the single-knob variants (the paired comparison)
KNOB_N = 256
KNOB_T = 100.0

#: per (variant, f, family)
ROW_COLUMNS = (
    "variant", "kind", "knob", "value", "f", "family", "n_particles", "t_max",
    "stationary",     # the reference's D over its first half agrees with its whole-run D
    "D", "D_lo", "D_hi", "hw_rel",            # D with its CI; half-width / |D|
    "D_ref", "hw_ref",                        # the reference's D and CI half-width
    "err_rel",                                # (D - D_ref) / D_ref
    "z_ref",                                  # (D - D_ref) / hw_ref: the error unit
    "z_stat",                                 # (D - D_ref) / sqrt(se^2 + se_ref^2), se = hw/1.96
    "D_pair", "z_pair",                       # knob variants: the paired reference and z
    "cpu_s", "collisions", "collisions_per_cpu_s",
)
#: per variant
SUMMARY_COLUMNS = (
    "variant", "kind", "knob", "value", "n_particles", "t_max", "cpu_s", "wall_s",
    "collisions", "collisions_per_cpu_s",
    "err_rms",        # RMS of z_ref over the stationary rows with D_ref significantly > 0
    "err_max",        # max |z_ref| over those rows
    "rel_err_max",    # max |err_rel| over those rows
    "hw_rel_max",     # the variant's own largest relative CI half-width over those rows
    "err_rms_all",    # RMS of z_ref over all rows with D_ref significantly > 0
    "systematic",     # some row differs from its comparison by more than 3 sigma (z_stat/z_pair)
    "pareto",         # on the Pareto front of (cpu_s, err_rms)
)


#: units of this study's own columns (the others, f, D, t_max, ..., and the conventions:
#: pipeline.tables.units); ``value`` is the knob's (or, in the scaling table, the axis's) own
#: unit, which another column names: not one quantity, so ""
COLUMN_UNITS = {
    "variant": "", "kind": "", "knob": "", "value": "", "hw_rel": "1", "hw_ref": "mm^2/s",
    "err_rel": "1", "z_ref": "1", "z_stat": "1", "z_pair": "1", "cpu_s": "s", "wall_s": "s",
    "collisions": "1", "collisions_per_cpu_s": "1/s", "err_rms": "1", "err_max": "1",
    "rel_err_max": "1", "hw_rel_max": "1", "err_rms_all": "1", "systematic": "", "pareto": "",
    "axis": "", "sd_rel": "1", "bias_rel": "1", "exponent": "1",
}


@dataclass(frozen=True)
class Variant:
    """One accuracy setting: ``kind`` is reference, preset or knob; ``accuracy`` the table
    written into the workflow (``preset`` plus overrides)."""

    name: str
    kind: str
    accuracy: dict = field(hash=False)
    knob: str = ""
    value: float = math.nan


def default_variants(ref: Study, quick: bool = False) -> list[Variant]:
    """The reference, the presets, and each numerical knob varied alone.

    Knob values bracket the presets: v_stick 1e-1 (too coarse at 58 Hz, docs/physics.md),
    1e-2 (the presets), 1e-3; tol_t 1e-9 (1000x the presets), 1e-11; max_step 1 period (4x
    the presets; exact by construction, so only its cost should change).  ``quick`` keeps
    draft and two knobs (for tests and a first look).
    """
    acc = ref.accuracy
    out = [Variant("reference", "reference", _acc_table(ref))]
    for p in ("draft",) if quick else ("draft", "standard", "paper"):
        out.append(Variant(p, "preset", {"preset": p}))
    base = _acc_table(ref) | {"n_particles": min(KNOB_N, acc.n_particles),
                              "chunk_size": min(KNOB_N, acc.chunk_size),
                              "t_max": min(KNOB_T, acc.t_max)}
    knobs = [("v_stick", 1e-1), ("tol_t", 1e-9)] if quick else [
        ("v_stick", 1e-1), ("v_stick", 1e-2), ("v_stick", 1e-3),
        ("tol_t", 1e-9), ("tol_t", 1e-11), ("max_step", 1.0)]
    for k, v in knobs:
        out.append(Variant(f"{k}-{v:g}", "knob", base | {k: v}, k, float(v)))
    return out


def _acc_table(study: Study) -> dict:
    """The study's accuracy as a workflow [accuracy] table (every knob written out)."""
    a = study.accuracy
    return {"preset": a.preset} | {k: getattr(a, k) for k in ACCURACY_PRESETS["draft"]}


def variant_study(ref_text: str, variant: Variant, source: str = "<accuracy>") -> Study:
    """The reference workflow with its [accuracy] table replaced by the variant's."""
    from ...workflow.scenes import toml_dump as _toml_dump  # the workflow-shaped TOML writer

    doc = tomllib.loads(ref_text)
    doc["accuracy"] = dict(variant.accuracy)
    doc.setdefault("study", {})["name"] = f"{doc['study'].get('name', 'accuracy')}-{variant.name}"
    return parse_workflow(f"# {variant.kind} variant {variant.name} of {source}\n"
                          + _toml_dump(doc), source=f"{source} [{variant.name}]")


# -------------------------------------------------------------------------------------------
def run_accuracy_study(
    workflow: str | os.PathLike,
    out_dir: str | os.PathLike = "runs/accuracy",
    *,
    variants: Sequence[Variant] | None = None,
    quick: bool = False,
    workers: int | None = None,
    scheduler: str | None = None,
    figure: str | os.PathLike | None = "figures/accuracy.png",
    echo: Callable[[str], None] = print,
) -> dict[str, pd.DataFrame]:
    """Run (or resume) every variant into ``out_dir/stores/<variant>.zarr``, compare, write
    the tables to ``out_dir`` and the figure to ``figure`` (None: no figure).

    Returns {"rows", "summary", "scaling"} (columns: ROW_/SUMMARY_/SCALING_COLUMNS).
    """
    from ...execute.run import connect, run_study
    from ...store.study_store import StudyStore
    from ...tables.counters import counters_table
    from ...tables.diffusion import diffusion_table

    text = Path(workflow).read_text(encoding="utf-8")
    ref = parse_workflow(text, source=str(workflow))
    if not ref.observables.positions:
        raise ValueError(f"{workflow}: the accuracy study needs [observables.positions]")
    out = Path(out_dir)
    (out / "stores").mkdir(parents=True, exist_ok=True)
    variants = list(variants) if variants is not None else default_variants(ref, quick)
    if variants[0].kind != "reference":
        raise ValueError("the first variant must be the reference")
    results = {}
    # One cluster for every variant (a LocalCluster costs seconds to start); each variant is
    # still a separate `run_study`, with its own store, warm-up and timing.
    client, cluster = connect(None, workers, False) if scheduler is None else (None, None)
    address = scheduler or cluster.scheduler_address
    try:
        for v in variants:
            study = variant_study(text, v, str(workflow))
            path = out / "stores" / f"{v.name}.zarr"
            report = run_study(study, path, scheduler=address, progress=False,
                               dashboard=False, echo=lambda s: None)
            store = StudyStore.open(path)
            done = store.done()
            wall = _stored_wall(store, report)
            results[v.name] = (v, study, store, diffusion_table(store, done),
                               counters_table(store, done), wall)
            echo(f"accuracy: {v.name}: {report.summary()}")
    finally:
        if cluster is not None:
            client.close()
            cluster.close()
    rows = compare(results)
    summary = summarize(rows, {k: r[5] for k, r in results.items()})
    scaling = scaling_table(results["reference"][2])
    # the tables go to out_dir and beside the figure (figures/ is committed, runs/ is not)
    dirs = [out] + ([Path(figure).parent] if figure is not None else [])
    parquet = has_parquet()
    for d in dirs:
        d.mkdir(parents=True, exist_ok=True)
        for name, df in (("accuracy", rows), ("accuracy_summary", summary),
                         ("accuracy_scaling", scaling)):
            if parquet:
                df.to_parquet(d / f"{name}.parquet", index=False)
            df.to_csv(d / f"{name}.csv", index=False)
    if figure is not None:
        plot_accuracy(summary, figure)
    echo(f"accuracy: wrote accuracy*{'.parquet/' if parquet else '.'}csv to {out}"
         + (f" and {figure}" if figure is not None else ""))
    if not parquet:
        echo(f"accuracy: {NO_PARQUET}")
    return {"rows": rows, "summary": summary, "scaling": scaling}


def _stored_wall(store, report) -> float:
    """Compute wall time of the run that filled the store (kept in an attribute, so a resumed
    study reports the original run's time, not the no-op's)."""
    g = store.group("r+")
    if report.computed:
        g.attrs["accuracy_compute_wall"] = report.compute_wall
    return float(g.attrs.get("accuracy_compute_wall", math.nan))


# -------------------------------------------------------------------------------------------
def compare(results: dict) -> pd.DataFrame:
    """One row per (variant, f, family) with its error against the reference (ROW_COLUMNS)."""
    ref_v, ref_study, ref_store, ref_diff, _, _ = results["reference"]
    ref_rows = _family_rows(ref_diff, ref_study)
    pairs = _paired_reference(ref_store, results)
    stationary = _stationary(ref_store)
    rows = []
    for name, (v, study, _store, diff, counters, _wall) in results.items():
        for (f, fam), r in _family_rows(diff, study).items():
            rr = ref_rows[(f, fam)]
            c = counters[(counters.f == f) & (counters.family == fam)].iloc[0]
            coll = c.collisions_per_s * c.n_particles * c.t_max
            hw, hw_ref = (r["D_hi"] - r["D_lo"]) / 2, (rr["D_hi"] - rr["D_lo"]) / 2
            err = r["D"] - rr["D"]
            sig = math.hypot(hw, hw_ref) / 1.96
            row = dict(variant=name, kind=v.kind, knob=v.knob, value=v.value, f=f,
                       family=fam, n_particles=study.accuracy.n_particles,
                       t_max=study.accuracy.t_max, stationary=stationary[(f, fam)],
                       D=r["D"], D_lo=r["D_lo"], D_hi=r["D_hi"],
                       hw_rel=_div(hw, abs(r["D"])), D_ref=rr["D"], hw_ref=hw_ref,
                       err_rel=_div(err, rr["D"]), z_ref=_div(err, hw_ref),
                       z_stat=_div(err, sig), D_pair=math.nan, z_pair=math.nan,
                       cpu_s=c.task_seconds, collisions=coll,
                       collisions_per_cpu_s=_div(coll, c.task_seconds))
            if (name, f, fam) in pairs:
                d_pair, se_pair = pairs[(name, f, fam)]
                row["D_pair"] = d_pair
                row["z_pair"] = _div(r["D"] - d_pair, math.hypot(hw / 1.96, se_pair))
            rows.append(row)
    return pd.DataFrame(rows, columns=list(ROW_COLUMNS))


def _stationary(ref_store) -> dict:
    """{(f, family): bool}: is the reference's D over the first half of its run within 3
    standard errors (paired, per particle) of its D over the whole run?  Where it is not --
    launched particles at 54-55 Hz fall into the creeping state one by one, so D keeps falling
    with the observation time -- D is a property of t_max, and a preset's error there measures
    its t_max, not its accuracy."""
    study = ref_store.study
    g = ref_store.group()
    times = study.sample_times()
    half = int(np.searchsorted(times, study.accuracy.t_max / 2 + 1e-9))
    out = {}
    for fi, f in enumerate(study.frequencies):
        for mi, fam in enumerate(study.families):
            x = np.asarray(g["positions"][fi, mi])
            diff = (per_particle_D(x[:, :half], times[:half], study.analysis)
                    - per_particle_D(x, times, study.analysis))
            out[(f, fam.name)] = bool(abs(diff.mean()) <= 3 * diff.std(ddof=1)
                                      / math.sqrt(diff.size))
    return out


def _family_rows(diff: pd.DataFrame, study: Study) -> dict:
    """{(f, family): {D, D_lo, D_hi}} from a diffusion table's per-family columns."""
    out = {}
    for _, r in diff.iterrows():
        for fam in study.families:
            n = fam.name
            out[(float(r.f), n)] = {"D": r[f"D_{n}"], "D_lo": r[f"D_{n}_lo"],
                                    "D_hi": r[f"D_{n}_hi"]}
    return out


def _paired_reference(ref_store, results: dict) -> dict:
    """{(variant, f, family): (D, se)} of the reference restricted to a knob variant's
    particles and duration (same seeds: the first n_particles, the first t_max seconds)."""
    ref = ref_store.study
    g = ref_store.group()
    times = ref.sample_times()
    out = {}
    for name, (v, study, *_rest) in results.items():
        if v.kind != "knob":
            continue
        acc = study.accuracy
        if acc.chunk_size != ref.accuracy.chunk_size and acc.n_particles > acc.chunk_size:
            continue  # other chunk seeds: no pairing
        n_t = int(np.searchsorted(times, acc.t_max + 1e-9))
        for fi, f in enumerate(ref.frequencies):
            for mi, fam in enumerate(ref.families):
                x = np.asarray(g["positions"][fi, mi, :acc.n_particles, :n_t])
                d_i = per_particle_D(x, times[:n_t], ref.analysis)
                out[(name, f, fam.name)] = (float(d_i.mean()),
                                            float(d_i.std(ddof=1) / math.sqrt(d_i.size)))
    return out


def _div(a: float, b: float) -> float:
    return float(a / b) if b and np.isfinite(b) else math.nan


# -------------------------------------------------------------------------------------------
def summarize(rows: pd.DataFrame, walls: dict[str, float]) -> pd.DataFrame:
    """One row per variant (SUMMARY_COLUMNS).  The error is taken over the rows whose
    reference D is significantly positive (its CI excludes 0): where D = 0 (particles
    creeping for ever) every variant agrees and relative errors mean nothing; and over the
    stationary rows (``err_rms_all``: all of them)."""
    out = []
    for name, r in rows.groupby("variant", sort=False):
        sig_all = r[(r.D_ref - r.hw_ref) > 0]
        sig = sig_all[sig_all.stationary]
        zs = sig.z_ref.abs()
        comp = sig.z_pair.where(sig.kind == "knob", sig.z_stat).abs()
        out.append(dict(
            variant=name, kind=r.kind.iloc[0], knob=r.knob.iloc[0], value=r.value.iloc[0],
            n_particles=int(r.n_particles.iloc[0]), t_max=float(r.t_max.iloc[0]),
            cpu_s=float(r.cpu_s.sum()), wall_s=walls.get(name, math.nan),
            collisions=float(r.collisions.sum()),
            collisions_per_cpu_s=_div(r.collisions.sum(), r.cpu_s.sum()),
            err_rms=float(np.sqrt(np.mean(zs**2))) if len(zs) else math.nan,
            err_max=float(zs.max()) if len(zs) else math.nan,
            rel_err_max=float(sig.err_rel.abs().max()) if len(sig) else math.nan,
            hw_rel_max=float(sig.hw_rel.max()) if len(sig) else math.nan,
            err_rms_all=float(np.sqrt(np.mean(sig_all.z_ref**2))) if len(sig_all) else math.nan,
            systematic=bool((comp > 3).any()) if name != "reference" else False,
        ))
    df = pd.DataFrame(out)
    cand = df.variant != "reference"
    df["pareto"] = False
    df.loc[cand, "pareto"] = pareto_front(df.cpu_s[cand].to_numpy(), df.err_rms[cand].to_numpy())
    return df[list(SUMMARY_COLUMNS)]


def pareto_front(cost: np.ndarray, error: np.ndarray) -> np.ndarray:
    """True for the points no other point dominates (cost and error both <=, one <).
    NaN errors are never on the front."""
    cost, error = np.asarray(cost, float), np.asarray(error, float)
    ok = np.isfinite(cost) & np.isfinite(error)
    front = np.zeros(cost.size, dtype=bool)
    for i in np.flatnonzero(ok):
        dom = ok & (cost <= cost[i]) & (error <= error[i]) & ((cost < cost[i]) | (error < error[i]))
        front[i] = not dom.any()
    return front
