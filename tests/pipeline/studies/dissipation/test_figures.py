"""The D(f, α) figures are drawn as real PNG + PDF files, with their landmarks."""

import pandas as pd

from pipeline.studies.dissipation.cuts import compare_cut
from pipeline.studies.dissipation.figures import figure_cuts, figure_map

from .synthetic import ALPHAS, F, dmap


def _lock():
    return pd.DataFrame([{"f": f, "alpha": a, "k_max": (f - 30.0) / (25.0 - 10 * a)}
                         for a in ALPHAS for f in F])


def test_the_map_is_drawn_with_units_thresholds_and_k_lines(tmp_path):
    fig = figure_map({"dissipation_diffusion": dmap(), "dissipation_locking_locking": _lock()},
                     tmp_path)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "f (Hz)" and ax.get_ylabel().startswith("α")
    assert fig.axes[1].get_ylabel() == "D (mm²/s)"  # the colorbar
    labels = {ln.get_label() for ln in ax.get_lines()}
    assert {"f(Γ')", "Γ = 1"} <= labels
    assert any(t.get_text().startswith("k=") for t in ax.texts)  # labelled k_max contours
    assert (tmp_path / "fig_dissipation.png").stat().st_size > 10_000
    assert (tmp_path / "fig_dissipation.pdf").is_file()


def test_no_map_no_figure(tmp_path):
    assert figure_map({}, tmp_path) is None
    assert not list(tmp_path.iterdir())


def test_the_cuts_mark_the_frequencies_that_disagree(tmp_path):
    line = dmap(refined=False).query("alpha == 0.7").reset_index(drop=True)
    scale = line["f"].map(lambda f: 1.5 if f == 70.0 else 1.0)
    ref = line.assign(D=line["D"] * scale, D_lo=line["D_lo"] * scale, D_hi=line["D_hi"] * scale)
    cmp_ = compare_cut(line, ref, 9.0, 9.0).assign(cut="figure2")
    fig = figure_cuts({"dissipation_diffusion": dmap(), "dissipation_cuts": cmp_},
                      {"figure2": ref}, tmp_path)
    crosses = [ln for ln in fig.axes[0].get_lines() if ln.get_label() == "disagree"]
    assert list(crosses[0].get_xdata()) == [70.0]
    assert (tmp_path / "fig_dissipation_cuts.png").stat().st_size > 10_000


def test_cuts_that_agree_everywhere_mark_nothing(tmp_path):
    line = dmap(refined=False).query("alpha == 0.7").reset_index(drop=True)
    cmp_ = compare_cut(line, line, 9.0, 9.0).assign(cut="figure2")
    fig = figure_cuts({"dissipation_diffusion": dmap(), "dissipation_cuts": cmp_},
                      {"figure2": line}, tmp_path)
    assert not [ln for ln in fig.axes[0].get_lines() if ln.get_label() == "disagree"]
