"""The gallery: one figure of each kind ``bbb plot`` draws, from shipped scenes run small, and
the page docs/gallery.md that shows them.

    python -m pipeline.gallery [--work runs/gallery] [--docs docs] [--workers 2]

Each entry of :data:`ENTRIES` names a shipped scene, the figure of ``bbb plot`` it shows and
what to read in it.  The scenes run at gallery size (:data:`GALLERY_SIZE`: fewer particles,
shorter runs than their drafts; the frequencies and grid as shipped), each in its own store
under ``--work`` (kept: a second call only plots; an interrupted one resumes), then
:func:`pipeline.plot.figures.plot_dataset` draws each entry's figure of its store, as
``bbb plot`` would, and the gallery copies it to ``docs/gallery/<kind>.png``.  The page says how big each run
was (points x particles x simulated seconds), read from the stores, not typed in.
"""

from __future__ import annotations

import argparse
import shutil
import sys
import time
from dataclasses import dataclass, replace
from pathlib import Path

__all__ = ["Entry", "ENTRIES", "GALLERY_SIZE", "gallery_study", "run_scenes", "write_gallery",
           "main"]

ROOT = Path(__file__).resolve().parents[1]


@dataclass(frozen=True)
class Entry:
    """One figure of the gallery: its ``kind`` (the PNG's name), the shipped ``scene`` (a path
    from the repository's root), the ``figure`` of ``bbb plot`` it shows (the file's stem) and
    what it shows, in words."""
    kind: str
    scene: str
    figure: str
    title: str
    text: str


#: the accuracy keys every gallery scene runs with (the rest as shipped)
GALLERY_SIZE = {"n_particles": 8, "chunk_size": 8, "t_max": 10.0}

_CONTACT = "pipeline/studies/contact/scenes/draft/contact.toml"
_REVERSAL = "pipeline/studies/transport/scenes/draft/transport_reversal.toml"
ENTRIES = (
    Entry("curve", "workflows/smoke.toml", "curve_D_vs_frequency", "D(f) with its CI",
          "D against f, the band its 95 % bootstrap CI over particles; an open marker flags a "
          "point (non-ergodic, non-stationary, not diffusive), a cross on the lower edge a "
          "point whose estimator failed, a gap a point the store does not have. The axis is "
          "logarithmic where D spans more than two decades, linear otherwise."),
    Entry("families", "workflows/smoke.toml", "curve_D_family_vs_frequency",
          "D(f) per initial-condition family",
          "One curve per family (from rest, launched upward), each with its CI."),
    Entry("comparison", _CONTACT, "curve_D_vs_frequency_by_contact",
          "The contact models compared",
          "A named grid axis and the axis that applies under one of its names only (μ under "
          "Coulomb friction) drawn as one comparison: one curve per model, stick, slide and "
          "Coulomb at each μ, in one figure."),
    Entry("map", _CONTACT, "map_D_frequency-contact", "D over f and the models",
          "A heat map with the relative CI half-width beside it. Each cell stands for one "
          "computed value: the frequencies are drawn to scale, a cell reaching no farther than "
          "the grid's median spacing, and a range of f where nothing was computed (past 60 "
          "Hz) is hatched as not computed."),
    Entry("signed_map", _REVERSAL, "map_v_frequency-throw_contact=stick",
          "The drift v over f and the throw angle",
          "A signed quantity in a diverging colour map centred at 0 (negative: downhill); the "
          "markers, black with a white edge, flag points on every colour (a triangle: the "
          "particles accelerate, v is a mean velocity there)."),
    Entry("signed_curve", "workflows/sawtooth.toml", "curve_v_vs_frequency_by_peak",
          "A ratchet's drift per tooth shape",
          "v against f on the sawtooth floor, one line per position of the tooth's peak: the "
          "scene asks whether off-centre teeth drive a drift without tilt (centred ones cannot: "
          "mirror symmetry makes v = 0 exactly). Signed: a linear axis with its 0 marked."),
    Entry("curve_by_axis", "workflows/sine.toml", "curve_D_vs_frequency_by_depth",
          "D(f) per value of a grid axis",
          "The sine floor at two depths: one curve per value of the grid axis, in a sequential "
          "colour order."),
)


def gallery_study(scene: str | Path):
    """The shipped ``scene`` (a path from the repository's root) at :data:`GALLERY_SIZE`."""
    from .workflow.load import load_workflow

    study = load_workflow(ROOT / scene)
    acc = replace(study.accuracy, target_ci=None, max_particles=None, **GALLERY_SIZE)
    return replace(study, accuracy=acc)


def run_scenes(work: str | Path, workers: int = 2, echo=print) -> dict[str, Path]:
    """Run (or resume) each scene of :data:`ENTRIES` at gallery size in ``work``; returns
    {scene: store path}."""
    from .api import run_study

    stores: dict[str, Path] = {}
    for scene in dict.fromkeys(e.scene for e in ENTRIES):
        study = gallery_study(scene)
        store = Path(work) / f"{study.name}.zarr"
        t0 = time.perf_counter()
        run_study(study, store, workers=workers, echo=lambda s: None)
        echo(f"{scene}: {time.perf_counter() - t0:.0f} s")
        stores[scene] = store
    return stores


def _size(ds) -> tuple[str, float]:
    """(``"<points> points x <N> particles (all families) x <t> s"``, the particle-seconds
    simulated) of a reduced Dataset."""
    import numpy as np

    points = int(ds["present"].any("family").sum()) if "present" in ds else 0
    n = np.asarray(ds["n_particles"].values, float) if "n_particles" in ds else np.array([])
    t = np.asarray(ds["t_max"].values, float) if "t_max" in ds else np.array([])
    ok = np.isfinite(n) & np.isfinite(t)
    n, t = n[ok], t[ok]
    text = (f"{points} points × {int(n.max()) if n.size else '?'} particles (all families) × "
            f"{t.max() if t.size else float('nan'):g} s")
    return text, float((n * t).sum())


def write_gallery(stores: dict[str, Path], docs: str | Path, entries=ENTRIES) -> Path:
    """Draw each entry's figure of its store, copy it to ``docs/gallery/<kind>.png`` and
    write ``docs/gallery.md``; returns the page's path.  Raises FileNotFoundError naming an
    entry whose figure ``bbb plot`` did not draw."""
    from .api import reduced_dataset
    from .plot.figures import plot_dataset

    docs = Path(docs)
    images = docs / "gallery"
    images.mkdir(parents=True, exist_ok=True)
    drawn, sizes = {}, {}
    for scene, store in stores.items():
        ds = reduced_dataset(store)
        out = Path(store).with_suffix("")
        wanted = {e.figure for e in entries if e.scene == scene}
        drawn[scene] = {p.stem: p for p in plot_dataset(ds, out, formats=("png",), names=wanted)}
        sizes[scene] = _size(ds)
    total = sum(cost for _, cost in sizes.values())
    lines = ["# Gallery", "",
             "One figure of each kind `bbb plot STORE` draws, from shipped scenes run small "
             "(every one of them: " + ", ".join(f"{k} = {v:g}" for k, v in GALLERY_SIZE.items())
             + "; their frequencies and grids as shipped), so the numbers are a draft's, not "
             "results. Made by `python -m pipeline.gallery`, which simulates "
             f"{total:,.0f} particle-seconds in all; every figure is titled with its scene and "
             "what the scene fixes.", ""]
    for e in entries:
        src = drawn.get(e.scene, {}).get(e.figure)
        if src is None:
            raise FileNotFoundError(f"{e.scene}: bbb plot draws no {e.figure}.png")
        shutil.copyfile(src, images / f"{e.kind}.png")
        lines += [f"## {e.title}", "", f"![{e.title}](gallery/{e.kind}.png)", "",
                  f"{e.text}", "",
                  f"Scene `{e.scene}` ({sizes[e.scene][0]}), file `{e.figure}.png`.", ""]
    page = docs / "gallery.md"
    page.write_text("\n".join(lines), encoding="utf-8")
    return page


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m pipeline.gallery",
                                description="run the gallery's scenes small and write "
                                            "docs/gallery.md with one figure of each kind")
    p.add_argument("--work", default="runs/gallery", help="where the stores go (kept)")
    p.add_argument("--docs", default=str(ROOT / "docs"), help="the docs folder to write to")
    p.add_argument("--workers", type=int, default=2)
    args = p.parse_args(argv)
    t0 = time.perf_counter()
    stores = run_scenes(args.work, args.workers)
    page = write_gallery(stores, args.docs)
    print(f"wrote {page} and {len(ENTRIES)} images in {time.perf_counter() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
