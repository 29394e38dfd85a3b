"""bbb verify's first-cell check on a thrown floor: the cell rides on the floor."""

from __future__ import annotations

import zarr

from pipeline.execute.run import run_study
from pipeline.store.verify import verify_store
from pipeline.workflow.load import parse_workflow

from ..helpers import QUIET, TINY, write_as_a_run


def test_a_thrown_floors_start_within_its_along_plane_amplitude_passes_and_beyond_fails(tmp_path):
    """ψ = 30°: the floor starts up to A cos ψ = 0.087 mm off along its plane, so particles
    placed in the first cell of the floor may start at |x(0)| up to S/2 + 0.087 mm."""
    study = parse_workflow(TINY.replace('preset = "klages2004"',
                                        'preset = "klages2004"\ntilt = 2.0\nthrow = 30.0'))
    path = tmp_path / "thrown.zarr"
    run_study(study, str(path), workers=1, **QUIET)
    g = zarr.open_group(str(path), mode="r")
    assert abs(g["positions"][:, :, :, 0]).max() > 1.0  # some start beyond S/2 = 1 mm
    assert verify_store(str(path)).ok
    write_as_a_run(path, "positions", (0, 0, 0, 0), 1.0 + 0.0867)  # beyond S/2 + A cos 30°
    report = verify_store(str(path))
    assert any("start outside the first cell" in str(p) for p in report.problems)
