"""The transport figure is drawn as real PNG + PDF files from diffusion tables."""

import numpy as np
import pandas as pd

from pipeline.studies.transport import SCENES, draw


def test_draw_writes_the_figure_files_even_with_a_scene_missing(tmp_path):
    f = np.arange(50.0, 60.1, 2.0)
    v = -np.linspace(0.0, 5.0, f.size)
    t = pd.DataFrame({"f": f, "v": v, "v_lo": v - 0.1, "v_hi": v + 0.1, "D_drift": 1.0 + f,
                      "D_drift_lo": f, "D_drift_hi": 2.0 + f, "steady": f < 56})
    tables = {f"{sc}_diffusion": t for sc in SCENES[1:]}
    paths = draw(tables, {}, tmp_path)
    assert sorted(p.name for p in paths) == ["fig_transport.pdf", "fig_transport.png",
                                             "fig_transport_sliding.pdf",
                                             "fig_transport_sliding.png"]
    assert all(p.stat().st_size > 1000 for p in paths)
