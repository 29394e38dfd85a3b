"""Mirror pairs on the transport scenes: the variance of v they save, and T1's false alarms
without them.

    .venv/bin/python -m benchmarks.calibrations.transport_mirror [--pairs 256] [--pool 1024] [--curves 2000]
                                                    [--scenes a,b] [--write]

Prints the tables (commit them as benchmarks/results/transport-mirror-<date>.txt); with
``--write`` writes the summary to pipeline/studies/transport/mirror.json, which the transport
claims read.

variance   At every frequency of each conveyor scene (its parameters, t_max, samples and fit
           window), ``--pairs`` P mirror pairs (bbb.ensemble.mirror_pairs: P drawn 'rest'
           states and their partners, 2P particles).  At an equal number of simulated
           particles, Var(v) from P pairs / Var(v) from 2P independent particles is
           r = Var(pair mean of v_i) / (Var(v_i) / 2) = 1 + corr(partners' v_i): every partner
           is a member of the family, so Var(v_i) over all 2P particles is the independent
           particles' variance.  95 % CI: bootstrap over pairs (2000).  The scene's ratio is
           the geometric mean over its frequencies where v_i vary (sd ≥ V_MIN = 1e-6 mm/s of
           the claims; D_i: sd ≥ D_MIN = 1e-6 mm²/s), a joint bootstrap; the
           same for D about the drift (D_i of x − v t).  The CPU time of the drawn half and of
           the partners is measured separately (equal cost: same particle count, same CPU).
           Rule, fixed before the runs: mirror = true in a scene when the CI of its v ratio
           lies below 1 and its D ratio is not significantly above 1 (CI reaching ≤ 1).
           The scenes are the lines of the transport maps (claims.LINES), each run as the
           scene without a grid named after its line; a map sets mirror once for all its
           lines (docs/statistics.md says what the transport map keeps).
false alarm  T1's rule (no frequency with a significant v, Bonferroni α = 0.05 over the curve;
           pipeline/studies/transport/claims.py) on the level floor with independent
           particles: at each frequency of the level floor (the transport map's line tilt 0,
           throw 90) ``--pool`` independent particles are simulated; a null curve draws the
           scene's 256 per frequency from that pool (without replacement) and gives each a
           random sign -- on a mirror-symmetric floor a particle and its image are equally
           likely draws, so this is an exact draw from the current-free ensemble's v_i up to
           the pool's finiteness -- then the bootstrap CI of
           `bbb reduce` (percentile, 1000 resamples) and the rule.  ``--curves`` curves; the
           fraction with any significant frequency is the design's false-alarm rate (Wilson
           95 % interval).
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import json
import math
import sys
import time
import zlib
from pathlib import Path

import numpy as np

from bbb import simulate
from bbb.analysis import stats
from bbb.analysis.transport import per_particle_drift
from bbb.ensemble import InitialState, initial_state, mirror_pairs
from benchmarks.calibrations.transport_rules import machine
from benchmarks.common import ROOT
from pipeline.studies.transport.claims import (
    CONVEYORS,
    D_MIN,
    HOPPING,
    LINES,
    MAP,
    SLIDING,
    SLIDING_MAP,
    V_MIN,
    significant_signs,
)
from pipeline.workflow.scenes import load_scene

SCENES = CONVEYORS + tuple(s for s, _, _ in SLIDING)
OUT = ROOT / "pipeline" / "studies" / "transport" / "mirror.json"
N_BOOT = 2000


def line_study(name: str):
    """The transport line ``name`` (claims.LINES) of its map scene as a Study without a grid,
    named after the line (the benchmark's seeds are keyed by that name)."""
    scene = SLIDING_MAP if name in {s for s, _, _ in SLIDING} else MAP
    return dataclasses.replace(load_scene(scene).line(LINES[name]), name=name)


def _fit(study) -> dict:
    an, T = study.analysis, study.analysis.duration(study.accuracy.t_max)
    return dict(fit_from=an.fit_from * T, fit_to=an.fit_to * T, discard=an.discard)


def _seed(*key) -> np.random.SeedSequence:
    return np.random.SeedSequence(2004, spawn_key=tuple(zlib.crc32(str(k).encode()) for k in key))


def _half(st: InitialState, sl: slice) -> InitialState:
    return InitialState(**{k: getattr(st, k)[sl] for k in st.__dataclass_fields__})


def pairs_at(study, f: float, n_pairs: int) -> dict:
    """v_i and D_i (about the drift) of n_pairs mirror pairs at f, and the CPU s of each half."""
    p, acc = study.params(f), study.accuracy
    times = study.sample_times()
    kw = study.families[0].simulate_kwargs()  # the scenes have one family
    st = mirror_pairs(p, 2 * n_pairs, _seed(study.name, f, "pairs"), kw.pop("initial"), **kw)
    xs, cpu = [], []
    for sl in (slice(0, n_pairs), slice(n_pairs, 2 * n_pairs)):
        t0 = time.process_time()
        run = simulate(p, n_pairs, acc.t_max, 0, _half(st, sl), sample_times=times,
                       numerics=acc.numerics())
        cpu.append(time.process_time() - t0)
        xs.append(run.positions)
    x = np.concatenate(xs)
    fit = _fit(study)
    v_i = per_particle_drift(x, times, **fit)
    d_i = stats.per_particle_D(x - v_i.mean() * times[None, :], times, **fit)
    return {"v": v_i, "D": d_i, "cpu": cpu}


def ratio_boot(vals: np.ndarray, rng: np.random.Generator, floor: float
               ) -> tuple[float, np.ndarray]:
    """r = Var(pair means) / (Var(values) / 2) and N_BOOT bootstrap replicates over pairs
    (values: the drawn half then the partners; NaN where their spread is below ``floor``:
    particles at rest, whose v_i and D_i are rounding)."""
    P = vals.size // 2
    pairs = np.stack([vals[:P], vals[P:]], axis=1)

    def r(pp):  # pp: (..., P, 2)
        var_i = np.concatenate([pp[..., 0], pp[..., 1]], axis=-1).var(axis=-1, ddof=1)
        with np.errstate(invalid="ignore", divide="ignore"):
            return pp.mean(axis=-1).var(axis=-1, ddof=1) / (var_i / 2.0)

    if not vals.std(ddof=1) >= floor:
        return math.nan, np.full(N_BOOT, math.nan)
    idx = rng.integers(0, P, size=(N_BOOT, P))
    return float(r(pairs)), r(pairs[idx])


def variance(scenes, n_pairs: int) -> dict:
    out = {}
    for name in scenes:
        study = line_study(name)
        rows, logs = [], {"v": [], "D": []}
        for f in study.frequencies:
            t0 = time.time()
            res = pairs_at(study, f, n_pairs)
            rng = np.random.default_rng(_seed(name, f, "boot"))
            row = {"f": f, "cpu_drawn": res["cpu"][0], "cpu_partners": res["cpu"][1],
                   "v_mean": float(res["v"].mean()), "v_sd": float(res["v"].std(ddof=1))}
            for q, floor in (("v", V_MIN), ("D", D_MIN)):
                r, boot = ratio_boot(res[q], rng, floor)
                lo, hi = (np.nanquantile(boot, [0.025, 0.975]) if np.isfinite(r)
                          else (math.nan, math.nan))
                row.update({f"r_{q}": r, f"r_{q}_lo": float(lo), f"r_{q}_hi": float(hi)})
                if np.isfinite(r) and np.all(np.isfinite(boot)) and r > 0 and np.all(boot > 0):
                    logs[q].append((math.log(r), np.log(boot)))
            rows.append(row)
            print(f"  {name} {f:g} Hz: r_v = {row['r_v']:.3g} [{row['r_v_lo']:.3g}, "
                  f"{row['r_v_hi']:.3g}], r_D = {row['r_D']:.3g} ({time.time() - t0:.0f} s)",
                  file=sys.stderr)
        summary = {"frequencies": rows}
        for q in ("v", "D"):
            if logs[q]:
                est = math.exp(np.mean([a for a, _ in logs[q]]))
                boot = np.exp(np.mean([b for _, b in logs[q]], axis=0))
                lo, hi = np.quantile(boot, [0.025, 0.975])
                summary[q] = {"ratio": est, "lo": float(lo), "hi": float(hi), "n_f": len(logs[q])}
            else:
                summary[q] = {"ratio": math.nan, "lo": math.nan, "hi": math.nan, "n_f": 0}
        summary["mirror"] = bool(summary["v"]["hi"] < 1.0 and not summary["D"]["lo"] > 1.0)
        summary["cpu_partners_over_drawn"] = (sum(r["cpu_partners"] for r in rows)
                                              / sum(r["cpu_drawn"] for r in rows))
        out[name] = summary
    return out


def false_alarm(pool: int, curves: int, n: int = 256) -> dict:
    study = line_study(HOPPING[0])
    times, fit, acc = study.sample_times(), _fit(study), study.accuracy
    pools = []
    for f in study.frequencies:
        p = study.params(f)
        st = initial_state(p, pool, _seed(study.name, f, "pool"), "rest")
        run = simulate(p, pool, acc.t_max, 0, st, sample_times=times, numerics=acc.numerics())
        pools.append(per_particle_drift(run.positions, times, **fit))
        print(f"  pool {f:g} Hz: sd(v_i) = {pools[-1].std():.3g} mm/s", file=sys.stderr)
    rng = np.random.default_rng(_seed("t1", "curves"))
    n = min(n, pool)
    hits, per_f = 0, np.zeros(len(pools))
    for _ in range(curves):
        v, lo, hi = [], [], []
        for vi in pools:
            vals = rng.permutation(vi)[:n] * rng.choice([-1.0, 1.0], n)
            b = stats.bootstrap_mean(vals, n_resamples=acc.n_resamples, ci=study.analysis.ci,
                                     seed=rng.integers(2**63))
            v.append(b.D), lo.append(b.lo), hi.append(b.hi)
        s = significant_signs(v, lo, hi) != 0
        hits += bool(s.any())
        per_f += s
    z = 1.959963984540054
    ph = hits / curves
    den = 1 + z * z / curves
    mid = (ph + z * z / (2 * curves)) / den
    half = z * math.sqrt(ph * (1 - ph) / curves + z * z / (4 * curves * curves)) / den
    return {"rate": ph, "lo": max(0.0, mid - half), "hi": min(1.0, mid + half),
            "curves": curves, "pool": pool, "n_particles": n, "n_frequencies": len(pools),
            "v_min": V_MIN, "per_frequency": {f"{f:g}": float(k / curves)
                                              for f, k in zip(study.frequencies, per_f, strict=True)},
            "sd_v_i": {f"{f:g}": float(vi.std(ddof=1)) for f, vi in zip(study.frequencies, pools,
                                                                          strict=True)}}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pairs", type=int, default=256)
    ap.add_argument("--pool", type=int, default=1024)
    ap.add_argument("--curves", type=int, default=2000)
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--skip-false-alarm", action="store_true")
    ap.add_argument("--write", action="store_true", help=f"write {OUT.name}")
    ap.add_argument("--json", type=Path, help="write the summary here, merged into what it holds "
                    "(make calibrate)")
    args = ap.parse_args(argv)
    t0 = time.time()
    print(f"# mirror pairs on the transport scenes, {machine()}; {args.pairs} pairs per "
          f"frequency, pool {args.pool}, {args.curves} null curves")
    var = variance([s for s in args.scenes.split(",") if s], args.pairs)
    for name, sm in var.items():
        print(f"\n## {name}: Var(v) pairs / independent at equal particle count\n")
        print("| f (Hz) | mean v_i (mm/s) | sd v_i (mm/s) | r_v [95 % CI] | r_D [95 % CI] |")
        print("| --- | --- | --- | --- | --- |")
        for r in sm["frequencies"]:
            print(f"| {r['f']:g} | {r['v_mean']:.4g} | {r['v_sd']:.3g} | {r['r_v']:.3g} "
                  f"[{r['r_v_lo']:.3g}, {r['r_v_hi']:.3g}] | {r['r_D']:.3g} [{r['r_D_lo']:.3g}, "
                  f"{r['r_D_hi']:.3g}] |")
        print(f"\n{name}: geometric mean over {sm['v']['n_f']} f: r_v = {sm['v']['ratio']:.3g} "
              f"[{sm['v']['lo']:.3g}, {sm['v']['hi']:.3g}], r_D = {sm['D']['ratio']:.3g} "
              f"[{sm['D']['lo']:.3g}, {sm['D']['hi']:.3g}]; CPU partners / drawn = "
              f"{sm['cpu_partners_over_drawn']:.3f}; mirror = {str(sm['mirror']).lower()}")
    result = {"source": "benchmarks/calibrations/transport_mirror.py", "date": str(datetime.date.today()),
              "pairs_per_frequency": args.pairs, "variance": var}
    if not args.skip_false_alarm:
        fa = false_alarm(args.pool, args.curves)
        print(f"\n## T1 with independent particles ({HOPPING[0]}): {fa['curves']} null curves\n")
        print(f"false-alarm rate {fa['rate']:.4f} [{fa['lo']:.4f}, {fa['hi']:.4f}] (any of "
              f"{fa['n_frequencies']} frequencies significant; pool {fa['pool']} per f)")
        print("per frequency: " + ", ".join(f"{k} {v:.4f}" for k, v in fa["per_frequency"].items()))
        result["t1_false_alarm"] = fa
    print(f"\n{time.time() - t0:.0f} s")
    path = OUT if args.write else args.json
    if path:
        path = Path(path)
        old = json.loads(path.read_text(encoding="utf-8")) if path.exists() else {}
        old.update({k: v for k, v in result.items() if k != "variance"})
        old.setdefault("variance", {}).update(var)
        path.write_text(json.dumps(old, indent=1) + "\n", encoding="utf-8")
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
