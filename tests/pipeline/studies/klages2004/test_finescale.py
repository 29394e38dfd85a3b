"""The fine-scale study's counts of significant extrema per Hz, on synthetic D(f) with known
extrema (issue 12, item 3)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pipeline.studies.klages2004.finescale import (
    extrema_per_hz,
    figure_finescale,
    located_extrema,
    new_extrema,
    subsample,
)


def _window(spike_at: float = 59.05):
    """58-64 Hz on the 0.05 Hz grid: a broad maximum at 61 Hz seen at every resolution, and a
    spike of +20 mm²/s at ``spike_at`` that only the grids holding it see; CIs +-1 mm²/s."""
    f = np.round(np.arange(58000, 64001, 50) / 1000, 3)
    D = 200.0 + 40.0 * np.exp(-(((f - 61.0) / 0.8) ** 2))
    D[np.isclose(f, spike_at)] += 20.0
    return f, D, D - 1.0, D + 1.0


def test_the_subsample_at_h_is_the_grid_of_step_h_from_the_origin():
    f = np.array([58.0, 58.05, 58.1, 58.2, 58.4, 58.45, 58.8])
    assert f[subsample(f, 0.4, 58.0)].tolist() == [58.0, 58.4, 58.8]
    assert f[subsample(f, 0.1, 58.0)].tolist() == [58.0, 58.1, 58.2, 58.4, 58.8]


def test_an_extremum_between_the_coarse_points_is_counted_only_at_the_resolution_holding_it():
    counts = extrema_per_hz(*_window(), n_boot=100)
    assert [c.h for c in counts] == [0.4, 0.2, 0.1, 0.05]
    # at 0.05 Hz the spike at 59.05 adds a maximum and the valley between it and the broad
    # maximum a minimum: 3 extrema; the coarser grids do not hold the spike: 1
    assert [c.count for c in counts] == [1, 1, 1, 3]
    assert [c.n_points for c in counts] == [16, 31, 61, 121]
    for c in counts:  # the CIs are far apart from noise at +-1 mm²/s: the bootstrap agrees
        assert c.lo <= c.count <= c.hi and c.hi - c.lo <= 1
    assert counts[-1].per_hz[0] == 3 / 6.0


def test_each_extremum_is_located_within_half_the_gaps_to_its_neighbours():
    ext = located_extrema(*_window(spike_at=59.1))
    spike = next(e for e in ext if abs(e.f - 59.1) < 1e-9)
    assert spike.kind == "max"
    assert np.isclose(spike.f_lo, 59.075) and np.isclose(spike.f_hi, 59.125)
    broad = next(e for e in ext if abs(e.f - 61.0) < 0.2)
    assert broad.f_lo < 61.0 < broad.f_hi  # the flat top: neighbours whose CIs overlap


def test_the_figure_is_drawn_to_png_and_pdf(tmp_path):
    f, D, lo, hi = _window()
    table = pd.DataFrame({"f": f, "D": D, "D_lo": lo, "D_hi": hi})
    fig = figure_finescale(table, tmp_path)
    assert len(fig.axes) == 2
    assert (tmp_path / "fig_finescale.png").stat().st_size > 0
    assert (tmp_path / "fig_finescale.pdf").stat().st_size > 0


def test_the_extrema_only_the_fine_resolution_shows_are_counted_with_a_paired_interval():
    assert new_extrema(*_window(), n_boot=100) == (2, 2.0, 2.0)
    f, D, lo, hi = _window()
    smooth = D.copy()
    smooth[np.isclose(f, 59.05)] -= 20.0  # no spike: nothing new at 0.05 Hz
    assert new_extrema(f, smooth, smooth - 1.0, smooth + 1.0, n_boot=100)[0] == 0
