"""The survey-design chapter's plan drawn on real coordinates: a WGS 84 graticule (longitude and
latitude lines, labelled in degrees) over the local east/north metres, and a scale bar.

The local frame is the area's azimuthal equidistant projection
(:mod:`sss_locus.experiments.survey_design.area`): distances from the origin are true, so the scale bar
reads true metres; the graticule lines are the projected meridians and parallels.
"""

from __future__ import annotations

import math

import numpy as np


LABEL_BOX = dict(boxstyle="square,pad=0.15", facecolor="white", edgecolor="none", alpha=0.85)
"""The background of a graticule label: the plan under it does not run through its text."""


LEGEND_X = 1.05
"""Where a legend right of a map's axes starts (axes fraction): past the parallels' labels."""


def _nice_step(span: float, n: int = 5) -> float:
    """A 1-2-5 step that cuts ``span`` into about ``n`` parts."""
    raw = span / n
    mag = 10 ** math.floor(math.log10(raw))
    return min((m * mag for m in (1, 2, 5, 10)), key=lambda s: abs(raw / s - 1))


def _deg(value: float, pos: str, neg: str) -> str:
    hemi = pos if value >= 0 else neg
    return f"{abs(value):.4f}°{hemi}".replace(".0000°", "°")


def add_graticule(ax, area, *, colour: str = "0.45") -> None:
    """Meridians and parallels of the area's neighbourhood on ``ax`` (local metres), labelled
    meridians inside the top edge on a white box (:data:`LABEL_BOX`), parallels outside the right
    edge, upright (a legend beside the axes starts at :data:`LEGEND_X`); nothing without an origin.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes in the area's local frame (east, north in m), its limits already set (kept).
    area : SurveyArea
        The area (``origin_lonlat``, ``to_lonlat``, ``to_local``).
    colour : str
        Colour of the lines and labels.
    """
    if area.origin_lonlat is None:
        return
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    cx, cy = np.meshgrid(np.linspace(x0, x1, 9), np.linspace(y0, y1, 9))
    lon, lat = area.to_lonlat(cx.ravel(), cy.ravel())
    lon, lat = np.unwrap(np.asarray(lon), period=360.0), np.asarray(lat)
    for values, is_lon in ((lon, True), (lat, False)):
        lo, hi = float(values.min()), float(values.max())
        step = _nice_step(hi - lo, 4)
        for v in np.arange(math.ceil(lo / step) * step, hi, step):
            t = np.linspace(lat.min(), lat.max(), 60) if is_lon else np.linspace(lon.min(), lon.max(), 60)
            glon, glat = (np.full_like(t, v), t) if is_lon else (t, np.full_like(t, v))
            gx, gy = area.to_local((glon + 180.0) % 360.0 - 180.0, glat)
            ax.plot(gx, gy, color=colour, lw=0.5, ls=":", zorder=1)
            wrapped = (v + 180.0) % 360.0 - 180.0
            label = _deg(wrapped, "E", "W") if is_lon else _deg(v, "N", "S")
            if is_lon:
                k = int(np.argmax(gy))
                if gx[k] > x0 + 0.85 * (x1 - x0):  # its label would run out of the axes
                    continue
                ax.annotate(label, (gx[k], y1), xytext=(2, -2), textcoords="offset points", fontsize=9,
                            color=colour, ha="left", va="top", zorder=6, bbox=LABEL_BOX)
            else:
                k = int(np.argmax(gx))  # outside the right edge, upright along it: off the plan
                if not y0 + 0.08 * (y1 - y0) < gy[k] < y1 - 0.08 * (y1 - y0):  # would run past a corner
                    continue
                ax.annotate(label, (x1, gy[k]), xytext=(2, 0), textcoords="offset points", fontsize=9,
                            color=colour, ha="left", va="center", rotation=90, annotation_clip=False)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)


def add_scale_bar(ax, *, loc: str = "lower right") -> float:
    """A scale bar of a 1-2-5 length about a fifth of the axes' width (local metres); returns
    its length, m.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes in local metres, its limits already set.
    loc : str
        Where the bar goes (a matplotlib legend location).

    Returns
    -------
    float
        The bar's length (m).
    """
    from mpl_toolkits.axes_grid1.anchored_artists import AnchoredSizeBar

    x0, x1 = ax.get_xlim()
    length = _nice_step(x1 - x0, 5)
    text = f"{length / 1e3:g} km" if length >= 1000 else f"{length:g} m"
    ax.add_artist(AnchoredSizeBar(ax.transData, length, text, loc=loc, pad=0.4, frameon=True, size_vertical=0,
                                  fontproperties={"size": 9}))
    return length
