"""How large a published figure's text is on the book's page, in CSS pixels.

The book shows each figure as an ``<img>`` that is never wider than the content column
(sphinx-book-theme: ``max-width: 100%``) and never wider than its natural size. The image a
chapter shows is the glued notebook output, drawn at the figure's own ``dpi`` in the tight box
of the exported PNG (the same layout and box at 300 dpi; see
:func:`sss_locus.pipeline.publish.export.export_figure`), so a figure whose
saved picture is ``width_in`` inches wide is shown ``min(column_px, width_in * dpi)`` CSS px wide,
and text of ``size_pt`` points appears

    size_pt / 72 * min(dpi, column_px / width_in)   CSS px.

The sizes are those of the text actually *drawn* (every call of the Agg renderer's ``draw_text``
while the PNG is saved: titles, axis labels, tick labels, legends, colour bars, annotations,
mathtext), so invisible text, empty strings and tick labels outside the axes are not counted.

:data:`CONTENT_WIDTH_PX` was measured with headless Chromium on a built page of the quick book
(sphinx-book-theme as pinned in ``environment.lock``): the rendered width of a wide figure's
``<img>`` in the main column was 660 px in a 1280 px wide window, 729 px at 1366 px and 774 px at
1440 px and wider (the column's maximum). The narrowest of these typical desktop widths is used,
so text that passes is readable on a 1280 px screen.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator, Mapping
from typing import Any

#: Rendered width (CSS px) of a figure in the book's main column at a 1280 px desktop window.
CONTENT_WIDTH_PX = 660.0
#: Smallest readable text on the page (CSS px).
MIN_TEXT_PX = 9.0
POINTS_PER_INCH = 72.0


def rendered_px(size_pt: float, width_in: float, dpi: float, column_px: float = CONTENT_WIDTH_PX) -> float:
    """CSS px height of ``size_pt`` text in a figure shown in a ``column_px`` wide column.

    Parameters
    ----------
    size_pt : float
        Font size (points, 1/72 inch of the figure).
    width_in : float
        Width of the saved (tight) picture, inches.
    dpi : float
        Resolution of the shown picture (the figure's ``dpi``), pixels per inch; the picture's
        natural width is ``width_in * dpi`` CSS px.
    column_px : float
        Width of the content column, CSS px.

    Examples
    --------
    >>> round(rendered_px(10, 13.2, 100, 660), 2)   # scaled down to the column
    6.94
    >>> round(rendered_px(10, 6.0, 100, 660), 2)    # narrower than the column: natural size
    13.89
    """
    for name, value in (("size_pt", size_pt), ("width_in", width_in), ("dpi", dpi), ("column_px", column_px)):
        if not value > 0:
            raise ValueError(f"{name} must be > 0, got {value!r}")
    return size_pt / POINTS_PER_INCH * min(dpi, column_px / width_in)


@contextlib.contextmanager
def recording_text() -> Iterator[list[dict[str, Any]]]:
    """Within the block, record every text the Agg renderer draws as ``{"size_pt", "text"}``."""
    from matplotlib.backends.backend_agg import RendererAgg

    drawn: list[dict[str, Any]] = []
    original = RendererAgg.draw_text

    def draw_text(self, gc, x, y, s, prop, angle, ismath=False, mtext=None):
        if str(s).strip():
            drawn.append({"size_pt": float(prop.get_size_in_points()), "text": str(s)})
        return original(self, gc, x, y, s, prop, angle, ismath=ismath, mtext=mtext)

    RendererAgg.draw_text = draw_text
    try:
        yield drawn
    finally:
        RendererAgg.draw_text = original


def text_record(drawn: list[dict[str, Any]], width_in: float, dpi: float) -> dict[str, Any]:
    """The manifest's ``text`` entry: the smallest drawn text and the picture's size.

    Parameters
    ----------
    drawn : list of dict
        From :func:`recording_text`.
    width_in : float
        Width of the saved picture, inches.
    dpi : float
        The figure's own ``dpi`` (that of the picture the chapter shows).
    """
    smallest = min(drawn, key=lambda d: d["size_pt"], default=None)
    return {
        "width_in": round(float(width_in), 4),
        "dpi": float(dpi),
        "min_size_pt": None if smallest is None else smallest["size_pt"],
        "min_text": None if smallest is None else smallest["text"][:80],
        "n_texts": len(drawn),
    }


def smallest_text_px(manifest: Mapping[str, Any], column_px: float = CONTENT_WIDTH_PX) -> float | None:
    """Rendered size (CSS px) of a published figure's smallest text; None if it has no text."""
    text = manifest.get("text")
    if not isinstance(text, Mapping):
        raise ValueError(f"manifest of {manifest.get('label')!r} has no 'text' record (exported "
                         "before the readability record existed: rerun its notebook)")
    if text.get("min_size_pt") is None:
        return None
    return rendered_px(text["min_size_pt"], text["width_in"], text["dpi"], column_px)
