"""D(f) of a stored study with and without the rare-mover rule, and the adaptive stopping
decisions the rule would take on it.  Reads the store only (never writes into it).

    python -m benchmarks.checks.rare_store STORE OUT.csv [--no-rare]

OUT.csv holds f, D, D_lo, D_hi (mm²/s), n_particles, n_eff and rare (whether the rule widened
the CI), computed exactly as `bbb reduce`'s diffusion table computes D and its CI (same
particles, seed, fit, level, method and resamples), so ``--no-rare`` reproduces the store's
reduced D columns.  Printed: per frequency the stored stop (chunks used, reason) and the one
the rule replays from the first chunks (:func:`pipeline.execute.adaptive.advance`); "needs more" when
the replay asks for chunks the store does not hold.
"""

from __future__ import annotations

import argparse
import csv
import sys

import numpy as np

from bbb.analysis import stats
from bbb.analysis.stats.bootstrap import with_rare_movers
from bbb.analysis.stats.rare import effective_movers, is_rare
from pipeline.execute.adaptive import OPEN, STOP_LEGEND, advance
from pipeline.execute.waves import _prefix, rule_of, unit_ci
from pipeline.store.study_store import StudyStore
from pipeline.workflow.identity import reduce_seed


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("store")
    ap.add_argument("out")
    ap.add_argument("--no-rare", action="store_true", help="the bootstrap alone (as before)")
    a = ap.parse_args(argv)
    store = StudyStore.open(a.store)
    study = store.study
    an, acc = study.analysis, study.accuracy
    times = study.sample_times()
    T = an.duration(acc.t_max)
    fit = dict(fit_from=an.fit_from * T, fit_to=an.fit_to * T, discard=an.discard)
    done = store.done()
    g = store.group()
    used, reason = np.asarray(g["n_chunks_used"][...]), np.asarray(g["stop_reason"][...])
    rule = rule_of(study)
    rows = []
    print(f"{'f/Hz':>7} {'N':>5} {'n_eff':>7} {'rare':>5} {'D':>10} {'D_lo':>10} {'D_hi':>10}"
          "  stored stop -> replayed with the rule")
    for fi, f in enumerate(study.frequencies):
        parts = [store.read_done("positions", fi, mi, done[fi, mi])
                 for mi in range(len(study.families))]
        x = np.concatenate([p for p in parts if p.shape[0] >= 2])
        ci = stats.bootstrap_D(x, times, n_resamples=acc.n_resamples, ci=an.ci,
                               seed=reduce_seed(study, f), method=an.ci_method, rare=False,
                               **fit)
        d_i = stats.per_particle_D(x, times, **fit)
        rare = not a.no_rare and is_rare(d_i)
        if not a.no_rare:
            ci = with_rare_movers(d_i, ci, an.ci)
        stops = []
        for mi in range(len(study.families)):
            st = advance(rule, None, _prefix(done[fi, mi]),
                         lambda n, fi=fi, mi=mi: unit_ci(store, fi, mi, n))
            new = "needs more" if st.reason == OPEN else f"{st.n} {STOP_LEGEND[st.reason]}"
            stops.append(f"{used[fi, mi]} {STOP_LEGEND[int(reason[fi, mi])]} -> {new}")
        n_eff = effective_movers(d_i)
        rows.append(dict(f=f, D=ci.D, D_lo=ci.lo, D_hi=ci.hi, n_particles=x.shape[0],
                         n_eff=n_eff, rare=rare))
        print(f"{f:7.2f} {x.shape[0]:5d} {n_eff:7.1f} {'yes' if rare else '':>5} {ci.D:10.3g}"
              f" {ci.lo:10.3g} {ci.hi:10.3g}  {'; '.join(stops)}", flush=True)
    with open(a.out, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
