"""The measured speed/accuracy trade (``bbb accuracy``): every preset and every knob against a
reference run, through the real pipeline.

The workflow (``workflows/accuracy.toml``) is the *reference*: its frequencies, families and
accuracy (preset ``reference``, possibly with overrides).  Each *variant* is the same scene
with another accuracy table, run into its own store by :func:`pipeline.run.run_study` and
reduced by :func:`pipeline.reduce.diffusion_table`:

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
the figure ``accuracy.png`` (error versus cost, Pareto front marked).  Units: D in mm²/s,
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

from ...accuracy import ACCURACY_PRESETS
from ...workflow import Study, parse_workflow

__all__ = [
    "Variant", "default_variants", "variant_study", "run_accuracy_study", "compare",
    "summarize", "scaling_table", "per_particle_D", "pareto_front", "plot_accuracy", "accuracy_figure",
    "ROW_COLUMNS", "SUMMARY_COLUMNS", "SCALING_COLUMNS", "KNOB_N", "KNOB_T",
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
#: statistical (N) and finite-time (t_max) behaviour measured on the reference store
SCALING_COLUMNS = (
    "f", "family", "axis", "value",           # axis "N" (particles) or "T" (t_max, s)
    "sd_rel",         # N: spread of D over disjoint subsets / D_ref; T: se of the bias
    "hw_rel",         # mean 95 % CI half-width / D (percentile bootstrap over particles)
    "bias_rel",       # T: mean over particles of D_i(T) - D_i(t_ref), / D_ref (paired)
    "exponent",       # N: fitted slope of log sd_rel vs log N (expect -1/2), same per group
)


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
    from ...scenes import toml_dump as _toml_dump  # the workflow-shaped TOML writer

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
    from ...reduce import counters_table, diffusion_table
    from ...run import _connect, run_study
    from ...store import StudyStore

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
    client, cluster = _connect(None, workers, False) if scheduler is None else (None, None)
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
    for d in dirs:
        d.mkdir(parents=True, exist_ok=True)
        for name, df in (("accuracy", rows), ("accuracy_summary", summary),
                         ("accuracy_scaling", scaling)):
            df.to_parquet(d / f"{name}.parquet", index=False)
            df.to_csv(d / f"{name}.csv", index=False)
    if figure is not None:
        plot_accuracy(summary, figure)
    echo(f"accuracy: wrote accuracy*.parquet/.csv to {out}"
         + (f" and {figure}" if figure is not None else ""))
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


def per_particle_D(x: np.ndarray, times: np.ndarray, analysis) -> np.ndarray:
    """Each particle's own TAMSD slope D_i, mm²/s (``bbb reduce``'s D is their mean), with
    the workflow's discard and fractional fit lags."""
    from bbb import stats

    T = analysis.duration(times[-1] - times[0])
    # bbb.stats' own per-particle fit, so that these are exactly the estimator's D_i
    reg = stats._regime(x.shape[1], times, analysis.fit_from * T, analysis.fit_to * T,
                        analysis.discard)
    return stats._per_particle_fit(np.asarray(x, dtype=float), reg)[0]


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


# -------------------------------------------------------------------------------------------
def scaling_table(ref_store, n_values: Sequence[int] | None = None,
                  t_values: Sequence[float] | None = None, n_resamples: int = 400,
                  seed: int = 5) -> pd.DataFrame:
    """Statistical versus systematic error, measured on the reference store alone.

    N axis: the reference's particles split into disjoint subsets of n; the spread of D over
    subsets (relative to the full D) should fall like n^-1/2, and so should the bootstrap
    half-width.  T axis: each particle's D_i over the first T seconds minus its D_i over the
    whole run (paired: same particles), averaged -- the finite-time bias of the fit at
    fractional lags -- with its standard error, and the half-width at that T.
    """
    from bbb import stats

    study = ref_store.study
    g = ref_store.group()
    times = study.sample_times()
    n_all, t_all = study.accuracy.n_particles, study.accuracy.t_max
    n_values = n_values or [n for n in (16, 32, 64, 128, 256, 512) if n <= n_all // 4]
    t_values = t_values or [t for t in (12.5, 25.0, 50.0, 100.0) if t < t_all]
    rng = np.random.default_rng(seed)
    rows = []
    for fi, f in enumerate(study.frequencies):
        for mi, fam in enumerate(study.families):
            x = np.asarray(g["positions"][fi, mi])
            d_all = per_particle_D(x, times, study.analysis)
            D = d_all.mean()
            if not D > 2 * d_all.std(ddof=1) / math.sqrt(d_all.size):
                continue  # D not significantly > 0: no relative errors to scale
            group = []
            for n in n_values:
                subs = d_all[rng.permutation(n_all)[: (n_all // n) * n]].reshape(-1, n).mean(1)
                hw = _hw(stats, x[:n], times, study, n_resamples, seed)
                group.append(dict(f=f, family=fam.name, axis="N", value=float(n),
                                  sd_rel=float(subs.std(ddof=1) / D), hw_rel=hw / D,
                                  bias_rel=float((subs.mean() - D) / D)))
            if len(group) >= 2:
                k = np.polyfit(np.log([r["value"] for r in group]),
                               np.log([r["sd_rel"] for r in group]), 1)[0]
                for r in group:
                    r["exponent"] = float(k)
            rows += group
            for T in t_values:
                n_t = int(np.searchsorted(times, T + 1e-9))
                d_t = per_particle_D(x[:, :n_t], times[:n_t], study.analysis)
                diff = d_t - d_all
                hw = _hw(stats, x[:, :n_t], times[:n_t], study, n_resamples, seed)
                rows.append(dict(f=f, family=fam.name, axis="T", value=float(T),
                                 sd_rel=float(diff.std(ddof=1) / math.sqrt(diff.size) / D),
                                 hw_rel=hw / D, bias_rel=float(diff.mean() / D),
                                 exponent=math.nan))
    return pd.DataFrame(rows, columns=list(SCALING_COLUMNS))


def _hw(stats, x, times, study, n_resamples, seed) -> float:
    an = study.analysis
    T = an.duration(times[-1] - times[0])
    ci = stats.bootstrap_D(x, times, n_resamples=n_resamples, ci=an.ci, seed=seed,
                           fit_from=an.fit_from * T, fit_to=an.fit_to * T, discard=an.discard)
    return float((ci.hi - ci.lo) / 2)


# -------------------------------------------------------------------------------------------
def plot_accuracy(summary: pd.DataFrame, path: str | os.PathLike) -> Path:
    """Draw :func:`accuracy_figure` and write it to ``path`` (PNG, 130 dpi)."""
    fig = accuracy_figure(summary)
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(p, dpi=130)
    return p


def accuracy_figure(summary: pd.DataFrame):
    """Error (RMS of |D - D_ref| / CI_ref half-width) versus CPU time, one point per variant,
    the Pareto front joined; presets as large markers, knob variants small.  A Figure made
    without pyplot; each variant's name goes to the first free spot around its marker."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    s = summary[summary.variant != "reference"].copy()
    fig = Figure(figsize=(7.5, 5))
    FigureCanvasAgg(fig)
    fig.set_label("accuracy")
    ax = fig.subplots()
    labels = []
    for kind, mk, size in (("preset", "o", 80), ("knob", "s", 35)):
        k = s[s.kind == kind]
        ax.scatter(k.cpu_s, k.err_rms, marker=mk, s=size, label=kind + "s",
                   c=np.where(k.pareto, "tab:red", "tab:blue"), zorder=3)
        labels += [(r.variant, r.cpu_s, r.err_rms) for _, r in k.iterrows()]
    front = s[s.pareto].sort_values("cpu_s")
    ax.plot(front.cpu_s, front.err_rms, "-", color="tab:red", lw=1.2, label="Pareto front",
            zorder=2)
    ax.axhline(1.0, color="0.6", ls=":", lw=1)
    ax.set_xscale("log")
    if (s.err_rms > 0).all():
        ax.set_yscale("log")
    ax.set_xlabel("CPU time of the study's frequencies, s (sum of task simulation times)")
    ax.set_ylabel("error: RMS |D - D_ref| / (95 % CI half-width of D_ref),\n"
                  "stationary frequencies")
    ax.set_title("Accuracy versus cost (knob variants: reference numerics, one knob changed)",
                 fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    _place_labels(fig, ax, labels)
    return fig


def _place_labels(fig, ax, labels) -> None:
    """Annotate (text, x, y) points, each at the first of a few offsets around its marker
    where it overlaps no label placed before it (points of labels that share a spot, such as
    two variants of equal cost and error, would otherwise be printed over each other)."""
    renderer = fig.canvas.get_renderer()
    offsets = [((4, 4), "left", "bottom"), ((4, -4), "left", "top"),
               ((-4, 4), "right", "bottom"), ((-4, -4), "right", "top"),
               ((4, 12), "left", "bottom"), ((4, -12), "left", "top")]
    placed = []
    for text, x, y in labels:
        for (dx, dy), ha, va in offsets:
            a = ax.annotate(text, (x, y), xytext=(dx, dy), textcoords="offset points",
                            fontsize=8, ha=ha, va=va)
            box = a.get_window_extent(renderer)
            if not any(box.overlaps(b) for b in placed):
                break
            a.remove()
        else:
            a = ax.annotate(text, (x, y), xytext=offsets[0][0], textcoords="offset points",
                            fontsize=8)
            box = a.get_window_extent(renderer)
        placed.append(box)
