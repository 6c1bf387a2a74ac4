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

**Lines as surveyors fly them** (``reach_m > 0``): with ``reach_m`` the horizontal reach of the
swath (its far edge), every line of the set whose swath reaches the area is run, also lines
outside it (``c`` in ``(c_min - reach, c_max + reach)``; the lines lie at ``c_min + (k + 1/2 +
offset) spacing`` for every integer ``k``), so that the area's edge is covered by the same
number of lines as its interior; a line runs over the along-track extent of the part of the area
its swath reaches (the area cut by the band ``|c' - c| <= reach``; a concave area can give
several pieces), extended by ``run_m`` before and after (the run-in and run-out); the line is
then cut where it would cross a hole of the area (an island or an exclusion zone: the vehicle
does not cross it).

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


def _intervals(pieces, e, run_m: float) -> list[tuple[float, float]]:
    """Along-track intervals (along ``e``) covered by the projections of ``pieces`` (shapely
    geometries), each widened by ``run_m``, overlapping ones merged, in increasing order."""
    spans = []
    for g in pieces:
        a = np.asarray(g.exterior.coords if g.geom_type == "Polygon" else g.coords) @ e
        spans.append([a.min() - run_m, a.max() + run_m])
    spans.sort()
    out: list[list[float]] = []
    for a, b in spans:
        if out and a <= out[-1][1]:
            out[-1][1] = max(out[-1][1], b)
        else:
            out.append([a, b])
    return [(a, b) for a, b in out]


def _line_pieces(area: SurveyArea, c: float, e, n, a0: float, a1: float, reach_m: float, run_m: float):
    """The pieces (shapely LineStrings) of the line at across position ``c`` (module docstring)."""
    import shapely

    if reach_m <= 0:  # the line clipped to the area
        piece = shapely.LineString([c * n + a0 * e, c * n + a1 * e]).intersection(area.polygon)
        return [g for g in getattr(piece, "geoms", [piece]) if g.geom_type == "LineString"]
    band = shapely.Polygon([(c - reach_m) * n + a0 * e, (c - reach_m) * n + a1 * e,
                            (c + reach_m) * n + a1 * e, (c + reach_m) * n + a0 * e])
    seen = band.intersection(area.polygon)
    parts = [g for g in getattr(seen, "geoms", [seen]) if g.geom_type == "Polygon" and not g.is_empty]
    lines = [shapely.LineString([c * n + a * e, c * n + b * e]) for a, b in _intervals(parts, e, run_m)]
    holes = shapely.MultiPolygon([shapely.Polygon(r) for r in area.polygon.interiors])
    out = []
    for g in lines:
        cut = g.difference(holes) if not holes.is_empty else g
        out += [h for h in getattr(cut, "geoms", [cut]) if h.geom_type == "LineString"]
    return out


def line_set(area: SurveyArea, heading_deg: float, spacing_m: float, *, offset: float = 0.0,
             name: str = "main", reach_m: float = 0.0, run_m: float = 0.0) -> pd.DataFrame:
    """Parallel lines over ``area`` (module docstring; ``reach_m`` > 0: the lines as flown, with
    the swath's reach and a run-in/run-out of ``run_m``); one row per segment, columns
    :data:`LINE_COLUMNS` (``set`` is ``name``; ``line`` counts the lines from 0 in run order)."""
    if not (isinstance(spacing_m, (int, float, np.floating)) and math.isfinite(spacing_m) and spacing_m > 0):
        raise ValueError(f"spacing_m must be a finite number > 0; got {spacing_m!r}")
    if not (isinstance(heading_deg, (int, float, np.floating)) and math.isfinite(heading_deg)):
        raise ValueError(f"heading_deg must be a finite number; got {heading_deg!r}")
    for label, v in (("reach_m", reach_m), ("run_m", run_m)):
        if not (isinstance(v, (int, float, np.floating)) and math.isfinite(v) and v >= 0):
            raise ValueError(f"{label} must be a finite number >= 0; got {v!r}")
    e, n = _unit(float(heading_deg))
    xy = np.asarray(area.polygon.exterior.coords)
    across, along = xy @ n, xy @ e
    c_min, c_max = across.min(), across.max()
    a0, a1 = along.min() - 1.0 - run_m, along.max() + 1.0 + run_m
    if reach_m > 0:  # every line whose swath reaches the area
        k = np.arange(math.floor((-reach_m) / spacing_m - 0.5 - offset),
                      math.ceil((c_max - c_min + reach_m) / spacing_m - 0.5 - offset) + 1)
        cs = c_min + (k + 0.5 + offset) * spacing_m
        cs = cs[(cs > c_min - reach_m) & (cs < c_max + reach_m)]
    else:  # the first line half a spacing inside; a line on the far edge adds nothing inside
        k = np.arange(int(math.floor((c_max - c_min) / spacing_m - 0.5 - offset)) + 2)
        cs = c_min + (k + 0.5 + offset) * spacing_m
        cs = cs[cs < c_max - 1e-9 * max(1.0, abs(c_max))]
    rows, line = [], 0
    for c in cs:
        parts = [g for g in _line_pieces(area, c, e, n, a0, a1, reach_m, run_m) if g.length >= MIN_SEGMENT_M]
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
