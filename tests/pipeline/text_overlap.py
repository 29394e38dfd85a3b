"""Overlapping text in a matplotlib Figure, measured with the renderer.

Every visible, non-empty Text artist of the figure -- titles, axis labels, legend entries,
annotations and the tick labels actually drawn (those inside the view limits) -- is measured
with ``get_window_extent`` on the Agg renderer.  Two texts whose boxes intersect by more than
``tol`` points in both directions overlap; so does a text crossing the frame (a spine) of
another axes, as an inset's tick labels lying across the main axis do.
"""

from __future__ import annotations

from matplotlib.axis import Axis
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.spines import Spine
from matplotlib.text import Text

#: intersections up to this much (points, in both x and y) are not counted: glyph boxes of
#: neighbouring labels may touch by rounding
TOL_PT = 0.5


def _drawn_tick_labels(fig: Figure) -> tuple[list[tuple[Text, object]], set[int]]:
    drawn, every = [], set()
    for axis in fig.findobj(Axis):
        for tick in axis.get_major_ticks() + axis.get_minor_ticks():
            every.update({id(tick.label1), id(tick.label2)})
        # the ticks the axis draws: those within its view interval (private, stable since mpl 2)
        for tick in axis._update_ticks():
            drawn += [(t, axis.axes) for t in (tick.label1, tick.label2) if t.get_visible()]
    return drawn, every


def visible_texts(fig: Figure) -> list[tuple[Text, object]]:
    """(Text, the Axes it belongs to or None) of every Text artist a render of ``fig`` draws
    with some text in it."""
    if not isinstance(fig.canvas, FigureCanvasAgg):
        FigureCanvasAgg(fig)
    fig.draw_without_rendering()  # lays out ticks, legends, annotations as savefig would
    ticks, every_tick = _drawn_tick_labels(fig)
    others = [(t, t.axes) for t in fig.findobj(Text) if id(t) not in every_tick]
    out = []
    for t, ax in ticks + others:
        if not t.get_text().strip() or not t.get_visible():
            continue
        if ax is not None and not ax.get_visible():
            continue
        out.append((t, ax))
    return out


def overlaps(fig: Figure, tol: float = TOL_PT) -> list[tuple[str, str, float, float]]:
    """Pairs (text a, text b or ``spine of <axes>``, overlap width, overlap height) of drawn
    texts whose boxes intersect each other, or the spine of another axes, by more than ``tol``
    points in x and in y (widths in points)."""
    found_texts = visible_texts(fig)
    texts = [t for t, _ in found_texts]
    owners = [ax for _, ax in found_texts]
    renderer = fig.canvas.get_renderer()
    boxes = [t.get_window_extent(renderer) for t in texts]
    px = fig.dpi / 72.0
    found = []

    def cut(a, b):
        w = min(a.x1, b.x1) - max(a.x0, b.x0)
        h = min(a.y1, b.y1) - max(a.y0, b.y0)
        return w / px, h / px

    for i in range(len(texts)):
        for j in range(i + 1, len(texts)):
            w, h = cut(boxes[i], boxes[j])
            if w > tol and h > tol:
                found.append((texts[i].get_text(), texts[j].get_text(), w, h))
    spines = [s for s in fig.findobj(Spine) if s.get_visible() and s.axes.get_visible()]
    for t, owner, box in zip(texts, owners, boxes, strict=True):
        for sp in spines:
            if sp.axes is owner:
                continue
            w, h = cut(box, sp.get_window_extent(renderer))
            # a spine is a line: crossing it means overlapping its width, however thin
            if w > 0 and h > 0 and max(w, h) > tol:
                name = sp.axes.get_label() or type(sp.axes).__name__
                found.append((t.get_text(), f"spine {sp.spine_type} of {name}", w, h))
    return found
