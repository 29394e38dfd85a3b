"""The transport figure is drawn as real PNG + PDF files from diffusion tables."""

import numpy as np
import pandas as pd

from pipeline.studies.transport.claims import COMBINED, HOPPING, LINES
from pipeline.studies.transport.figures import draw


def test_draw_writes_the_figure_files_from_a_map_missing_a_line_and_the_sliding_map(tmp_path):
    f = np.arange(50.0, 60.1, 2.0)
    v = -np.linspace(0.0, 5.0, f.size)
    t = pd.DataFrame({"f": f, "v": v, "v_lo": v - 0.1, "v_hi": v + 0.1, "D_drift": 1.0 + f,
                      "D_drift_lo": f, "D_drift_hi": 2.0 + f, "steady": f < 56})
    long = pd.concat([t.assign(**LINES[sc]) for sc in HOPPING[1:] + COMBINED])
    paths = draw({"transport_diffusion": long}, {}, tmp_path)
    assert sorted(p.name for p in paths) == ["fig_transport.pdf", "fig_transport.png",
                                             "fig_transport_reversal.pdf",
                                             "fig_transport_reversal.png",
                                             "fig_transport_sliding.pdf",
                                             "fig_transport_sliding.png"]
    assert all(p.stat().st_size > 1000 for p in paths)


def test_the_sliding_figure_draws_each_models_held_and_sliding_fractions_below_v(tmp_path):
    from pipeline.studies.transport.claims import SLIDING, SLIDING_LABELS
    from pipeline.studies.transport.figures import figure_sliding

    f = np.arange(20.0, 80.1, 10.0)
    v = pd.DataFrame({"f": f, "v": f / 10, "v_lo": f / 10 - 0.1, "v_hi": f / 10 + 0.1})
    contact = {}
    for k, (sc, _, _) in enumerate(SLIDING):
        held, slid = np.linspace(0.9, 0.1, f.size) / (k + 1), np.linspace(0.0, 0.5, f.size) * k
        contact[sc] = pd.DataFrame({"f": f[::-1], "held_frac": held[::-1], "slide_frac": slid[::-1],
                                    "held_frac_lo": held[::-1] - 0.01, "held_frac_hi": held[::-1] + 0.01,
                                    "slide_frac_lo": slid[::-1], "slide_frac_hi": slid[::-1] + 0.01})
    fig = figure_sliding({sc: v for sc, _, _ in SLIDING}, tmp_path, contact=contact)
    assert len(fig.axes) == 2 and (tmp_path / "fig_transport_sliding.png").stat().st_size > 1000
    lines = {ln.get_label(): ln for ln in fig.axes[1].get_lines()}
    for sc, _, _ in SLIDING:
        for col, what in (("held_frac", "held"), ("slide_frac", "sliding")):
            ln = lines[f"{SLIDING_LABELS[sc]}: {what}"]
            t = contact[sc].sort_values("f")
            assert np.array_equal(ln.get_xdata(), t["f"]) and np.array_equal(ln.get_ydata(), t[col])


def test_points_whose_D_about_the_drift_is_not_diffusive_are_crossed(tmp_path):
    from pipeline.studies.transport.claims import HOPPING
    from pipeline.studies.transport.figures import figure_transport

    f = np.arange(50.0, 60.1, 2.0)
    t = pd.DataFrame({"f": f, "v": -f, "v_lo": -f - 0.1, "v_hi": -f + 0.1, "D_drift": f,
                      "D_drift_lo": f - 1, "D_drift_hi": f + 1, "steady": True,
                      "diffusive": pd.array([True, None, False, True, False, True], "boolean")})
    fig = figure_transport({HOPPING[1]: t}, tmp_path)
    for ax, col in zip(fig.axes, ("v", "D_drift"), strict=True):
        crossed = [ln for ln in ax.get_lines() if ln.get_marker() == "x"]
        assert len(crossed) == 1 and list(crossed[0].get_xdata()) == [54.0, 58.0]
        assert list(crossed[0].get_ydata()) == list(t[col][[2, 4]])


def test_the_transport_map_draws_the_sign_changes_the_hopping_boundary_and_the_throw_number(
        tmp_path):
    from pipeline.studies.transport.figures import figure_reversal
    from pipeline.studies.transport.reversal import REVERSAL_LINES, throw_number_frequency

    f = np.arange(30.0, 100.1, 2.0)
    tables, contact = {}, {}
    for n, vals in REVERSAL_LINES.items():
        v = np.where(f <= 60.0, 6.0, -300.0) if vals["throw"] == 60.0 else np.full(f.size, -9.0)
        tables[n] = pd.DataFrame({"f": f, "v": v, "v_lo": v - 1.0, "v_hi": v + 1.0,
                                  "steady": f < 90})
        air = np.where(f >= 56.0, 0.4, 0.0)
        contact[n] = pd.DataFrame({"f": f, "held_frac": 1 - air, "slide_frac": 0.0,
                                   "held_frac_lo": 1 - air, "held_frac_hi": 1 - air,
                                   "slide_frac_lo": 0.0, "slide_frac_hi": 0.0})
    fig = figure_reversal(tables, contact, tmp_path)
    assert (tmp_path / "fig_transport_reversal.png").stat().st_size > 1000
    ax = fig.axes[0]
    by = {}
    for ln in ax.get_lines():
        by.setdefault(ln.get_gid(), []).append(ln)
    along_f = {tuple(ln.get_xdata()) for ln in by["reversal:f"]}
    assert along_f == {(60.0, 62.0)}  # ψ = 60° only
    along_psi = {(ln.get_xdata()[0], tuple(ln.get_ydata())) for ln in by["reversal:psi"]}
    assert along_psi == {(fi, (75.0, 60.0)) for fi in f if fi <= 60.0} | {
        (fi, (60.0, 45.0)) for fi in f if fi <= 60.0}
    assert {tuple(ln.get_xdata()) for ln in by["hopping"]} == {(54.0, 56.0)}
    gv = by["throw_number"][0]
    i = int(np.argmin(np.abs(gv.get_ydata() - 90.0)))
    assert gv.get_xdata()[i] == throw_number_frequency(2.0, gv.get_ydata()[i])
