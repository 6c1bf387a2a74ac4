"""Survey lines over an area and the track that joins them (the survey-design chapter).

Frames: the local frame of :mod:`sss_locus.experiments.survey_area` (``x`` east, ``y`` north,
metres). Headings are degrees counter-clockwise from east (the convention of
:mod:`sss_locus.experiments.straight_pass`); a line's heading is its direction of travel.

Lines (:func:`line_set`)
------------------------
A set of parallel lines at ``heading_deg`` and ``spacing_m``: with ``c_min``, ``c_max`` the
extent of the area across the lines, the lines lie at ``c_min + (k + 1/2 + offset) spacing``
(``offset`` a fraction of the spacing: 0 puts the first line half a spacing inside the area;
1/2 shifts every line by half a spacing, the standard second coverage; a line on the far
edge of the area is not run), each clipped to the polygon with ``shapely``
(a concave area or a hole can cut a line into several segments, run in order along the line).
Consecutive lines are run in opposite directions (a lawn-mower, boustrophedon pattern).

Track (:func:`track_length`)
----------------------------
The lines in order, joined by turns of a vehicle with minimum turning radius ``R``:

* a **U-turn** between anti-parallel lines a lateral distance ``d`` apart: two quarter circles
  and a straight, ``pi R + (d - 2R)``, for ``d >= 2R``; for ``d < 2R`` the bulb (omega) turn
  ``R (pi + 4 alpha)`` with ``cos(alpha) = (d + 2R) / (4R)`` (three arcs of radius ``R``; the
  shortest Dubins path for these end poses); plus the along-track gap between the end of one
  line and the start of the next, run straight (an upper bound for a staggered end);
* any other junction (segments of one line across a notch, or the transit from the main lines
  to the cross lines): the straight distance plus ``R`` times the heading change in radians
  (a turn on the spot replaced by an arc: an approximation of the Dubins distance, stated).

The track length counts the lines and the turns; time is the length over the survey speed.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from .survey_area import SurveyArea

LINE_COLUMNS = ("set", "line", "segment", "x0_m", "y0_m", "x1_m", "y1_m", "heading_deg", "length_m")
MIN_SEGMENT_M = 1.0
"""Clipped pieces shorter than this are dropped (a line grazing a vertex)."""


def uturn_length_m(d_m, radius_m) -> np.ndarray:
    """Length of the shortest turn between anti-parallel lines ``d_m`` apart (module docstring)."""
    d, r = np.broadcast_arrays(np.abs(np.asarray(d_m, float)), np.asarray(radius_m, float))
    with np.errstate(invalid="ignore", divide="ignore"):
        alpha = np.arccos(np.clip((d + 2 * r) / np.where(r > 0, 4 * r, 1.0), -1.0, 1.0))
    return np.where(d >= 2 * r, math.pi * r + d - 2 * r, r * (math.pi + 4 * alpha))


def _unit(heading_deg):
    h = math.radians(heading_deg)
    return np.array([math.cos(h), math.sin(h)]), np.array([-math.sin(h), math.cos(h)])


def line_set(area: SurveyArea, heading_deg: float, spacing_m: float, *, offset: float = 0.0,
             name: str = "main") -> pd.DataFrame:
    """Parallel lines over ``area`` (module docstring); one row per segment, columns
    :data:`LINE_COLUMNS` (``set`` is ``name``; ``line`` counts the lines from 0 in run order)."""
    import shapely

    if not (isinstance(spacing_m, (int, float, np.floating)) and math.isfinite(spacing_m) and spacing_m > 0):
        raise ValueError(f"spacing_m must be a finite number > 0; got {spacing_m!r}")
    if not (isinstance(heading_deg, (int, float, np.floating)) and math.isfinite(heading_deg)):
        raise ValueError(f"heading_deg must be a finite number; got {heading_deg!r}")
    e, n = _unit(float(heading_deg))
    xy = np.asarray(area.polygon.exterior.coords)
    across, along = xy @ n, xy @ e
    c_min, c_max = across.min(), across.max()
    a0, a1 = along.min() - 1.0, along.max() + 1.0
    k = np.arange(int(math.floor((c_max - c_min) / spacing_m - 0.5 - offset)) + 2)
    rows, line = [], 0
    for c in c_min + (k + 0.5 + offset) * spacing_m:
        if c >= c_max - 1e-9 * max(1.0, abs(c_max)):  # a line on the far edge adds nothing inside
            break
        full = shapely.LineString([c * n + a0 * e, c * n + a1 * e])
        piece = full.intersection(area.polygon)
        parts = [g for g in getattr(piece, "geoms", [piece]) if g.geom_type == "LineString"
                 and g.length >= MIN_SEGMENT_M]
        if not parts:
            continue
        reverse = line % 2 == 1
        segs = []
        for g in parts:
            p = np.asarray(g.coords)[[0, -1]]
            p = p[np.argsort(p @ e)]  # forward along e
            segs.append(p[::-1] if reverse else p)
        segs.sort(key=lambda s: float(s[0] @ e), reverse=reverse)
        head = (float(heading_deg) + (180.0 if reverse else 0.0)) % 360.0
        for j, s in enumerate(segs):
            rows.append((name, line, j, *s[0], *s[1], head, float(np.linalg.norm(s[1] - s[0]))))
        line += 1
    return pd.DataFrame(rows, columns=list(LINE_COLUMNS))


def track_length(lines: pd.DataFrame, turn_radius_m: float) -> dict[str, float]:
    """Lengths of the track that runs ``lines`` in order (module docstring): ``lines_m``,
    ``turns_m`` (U-turns and junctions), ``total_m``, and ``n_segments``."""
    if not (isinstance(turn_radius_m, (int, float, np.floating)) and turn_radius_m >= 0):
        raise ValueError(f"turn_radius_m must be a number >= 0; got {turn_radius_m!r}")
    L = lines
    straight = float(L["length_m"].sum())
    turns = 0.0
    for i in range(len(L) - 1):
        a, b = L.iloc[i], L.iloc[i + 1]
        e, n = _unit(a["heading_deg"])
        gap = np.array([b["x0_m"] - a["x1_m"], b["y0_m"] - a["y1_m"]])
        dh = (b["heading_deg"] - a["heading_deg"] + 180.0) % 360.0 - 180.0
        if abs(abs(dh) - 180.0) < 1e-6:
            turns += float(uturn_length_m(gap @ n, turn_radius_m)) + abs(float(gap @ e))
        else:
            turns += float(np.linalg.norm(gap)) + turn_radius_m * math.radians(abs(dh))
    return {"lines_m": straight, "turns_m": turns, "total_m": straight + turns, "n_segments": int(len(L))}
