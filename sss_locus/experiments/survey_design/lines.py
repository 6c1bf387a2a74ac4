"""Survey lines over an area and the track that joins them (the survey-design chapter).

Frames: the local frame of :mod:`sss_locus.experiments.survey_design.area` (``x`` east, ``y`` north,
metres). Headings are degrees counter-clockwise from east (the convention of
:mod:`sss_locus.experiments.passes.straight_pass`); a line's heading is its direction of travel.

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
swath (its far edge) and ``near_m`` its near edge (the nadir gap), the lines lie at ``c_min + (k +
1/2 + offset) spacing`` for every integer ``k`` whose swath reaches the area, also outside it, so
that the area's edge is seen by as many lines as its interior (:func:`flown_positions`: of the
lines outside, from the farthest in, a line is dropped when every across-track position of the
area is still seen by at least ``m`` lines of the plan's sets run at this heading, ``m`` the
fewest the unbounded pattern gives any position; e.g. 2 for a 200 % plan); a line runs over the along-track extent of the part of the area
its swath reaches (the area cut by the band ``|c' - c| <= reach``; a concave area can give
several pieces), extended by ``run_m`` before and after (the run-in and run-out); the line is
then cut where it would come within ``run_m`` of a hole of the area (an island or an exclusion
zone: the vehicle does not cross it, and runs out before it; at least the area's
``wall_clearance_m`` off it) and, when the area gives navigable water
(:meth:`~sss_locus.experiments.survey_design.area.SurveyArea.water`: ``navigable_m`` or
``water_beyond_m``), where it would come within ``wall_clearance_m`` of its edge (a wall, a
shore). Where the U-turn to the next line would not fit in that water, the lines' ends are
pulled back until it does (:func:`sss_locus.experiments.survey_design.turns.fit_turns`).

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

This is the formula of the track's length; the survey design costs a plan by the track its mission
flies instead (:func:`sss_locus.experiments.survey_design.route.track_cost`: the same U-turns,
plus the transits and the return to the start, leg by leg).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from sss_locus.experiments.survey_design.area import SurveyArea

LINE_COLUMNS = ("set", "line", "segment", "x0_m", "y0_m", "x1_m", "y1_m", "heading_deg", "length_m")
MIN_SEGMENT_M = 1.0
"""Clipped pieces shorter than this are dropped (a line grazing a vertex)."""


def heading_from_compass_deg(compass_deg) -> float:
    """A compass heading (degrees clockwise from north, as a surveyor gives it and as every
    output of the chapter writes it) as this module's heading (degrees counter-clockwise from
    east, in [0, 360)): ``(90 - compass) mod 360``; 0 (north) gives 90, 90 (east) gives 0.

    Parameters
    ----------
    compass_deg : float
        Compass heading, degrees clockwise from the local frame's north (true north at the
        area's origin).

    Returns
    -------
    float
        Heading, degrees counter-clockwise from east (``+x``).
    """
    if isinstance(compass_deg, bool) or not isinstance(compass_deg, (int, float, np.integer, np.floating)) \
            or not math.isfinite(compass_deg):
        raise ValueError(f"a compass heading must be a finite number of degrees; got {compass_deg!r}")
    return float((90.0 - float(compass_deg)) % 360.0) + 0.0


def uturn_length_m(d_m, radius_m) -> np.ndarray:
    """Length of the shortest turn between anti-parallel lines ``d_m`` apart (module docstring).

    Parameters
    ----------
    d_m : array_like
        Distance between the lines, m (sign ignored).
    radius_m : array_like
        Turn radius, m (broadcast with ``d_m``).

    Returns
    -------
    numpy.ndarray
        Turn length, m, the broadcast shape; ``pi r`` + the straight part when ``d >= 2 r``, a
        keyhole turn when the lines are closer; 0 for ``d = r = 0``.
    """
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
    clear = area.clearance_m
    holes = shapely.MultiPolygon([shapely.Polygon(r).buffer(max(run_m, clear)) for r in area.polygon.interiors])
    water = area.water()
    water = None if water is None else water.buffer(-clear)  # the wall clearance kept
    out = []
    for g in lines:
        cut = g.intersection(water) if water is not None else g
        cut = cut.difference(holes) if not holes.is_empty else cut
        out += [h for h in getattr(cut, "geoms", [cut]) if h.geom_type == "LineString"]
    return out


def _count(u, cs, near_m: float, reach_m: float) -> np.ndarray:
    d = np.abs(u[:, None] - np.asarray(cs)[None, :])
    return ((d >= near_m) & (d <= reach_m)).sum(axis=1)


def flown_positions(c_min: float, c_max: float, sets, reach_m: float, near_m: float) -> list[np.ndarray]:
    """Across-track positions (m, along the heading's left normal) of the lines of ``sets``
    (``(spacing_m, offset)`` pairs run at one heading) as flown (module docstring), one array per
    set, increasing.

    Parameters
    ----------
    c_min : float
        The area's lowest across-track coordinate, m.
    c_max : float
        Its highest, m.
    sets : sequence of tuple
        ``(spacing_m, offset)`` per line set (offset in spacings).
    reach_m : float
        The swath's far edge from the track, m.
    near_m : float
        The nadir gap's half width, m.

    Returns
    -------
    list of numpy.ndarray
        Across-track positions, m, one increasing array per set.
    """
    pos = lambda sp, off, lo, hi: c_min + (np.arange(math.floor((lo - c_min) / sp - 0.5 - off),  # noqa: E731
                                                      math.ceil((hi - c_min) / sp - 0.5 - off) + 1) + 0.5 + off) * sp
    step = min(1.0, (c_max - c_min) / 100.0) if c_max > c_min else 1.0
    u = np.linspace(c_min, c_max, max(2, int(math.ceil((c_max - c_min) / step)) + 1))
    wide = np.concatenate([pos(sp, off, c_min - reach_m - 2 * sp, c_max + reach_m + 2 * sp) for sp, off in sets])
    m = int(_count(u, wide, near_m, reach_m).min())
    cand = [c[(c > c_min - reach_m) & (c < c_max + reach_m)] for c in (pos(sp, off, c_min - reach_m - sp,
                                                                          c_max + reach_m + sp) for sp, off in sets)]
    keep = [np.ones(len(c), bool) for c in cand]
    outside = sorted(((max(c_min - c, c - c_max), i, j) for i, cs in enumerate(cand) for j, c in enumerate(cs)
                      if c < c_min or c > c_max), reverse=True)
    for _, i, j in outside:
        keep[i][j] = False
        if _count(u, np.concatenate([c[k] for c, k in zip(cand, keep)]), near_m, reach_m).min() < m:
            keep[i][j] = True
    return [c[k] for c, k in zip(cand, keep)]


def across_extent(area: SurveyArea, heading_deg: float) -> tuple[float, float]:
    """The area's extent across lines of ``heading_deg`` (along the left normal), m.

    Parameters
    ----------
    area : SurveyArea
        The area (local metres).
    heading_deg : float
        Line heading, degrees counter-clockwise from east.

    Returns
    -------
    lo, hi : float
        Across-track extent, m.
    """
    _, n = _unit(float(heading_deg))
    across = np.asarray(area.polygon.exterior.coords) @ n
    return float(across.min()), float(across.max())


def line_set(area: SurveyArea, heading_deg: float, spacing_m: float, *, offset: float = 0.0,
             name: str = "main", reach_m: float = 0.0, run_m: float = 0.0, near_m: float = 0.0,
             across_m=None) -> pd.DataFrame:
    """Parallel lines over ``area`` (module docstring; ``reach_m`` > 0: the lines as flown, with
    the swath's reach and a run-in/run-out of ``run_m``; ``across_m`` the lines' across-track
    positions, default :func:`flown_positions` of this set alone); one row per segment, columns
    :data:`LINE_COLUMNS` (``set`` is ``name``; ``line`` counts the lines from 0 in run order).

    Parameters
    ----------
    area : SurveyArea
        The area (local metres).
    heading_deg : float
        Line heading, degrees counter-clockwise from east.
    spacing_m : float
        Line spacing, m (> 0).
    offset : float
        Shift of the lines, in spacings.
    name : str
        The set's name (``set`` column).
    reach_m : float
        Swath reach, m (0: lines over the polygon only).
    run_m : float
        Run-in and run-out, m.
    near_m : float
        Nadir gap half width, m.
    across_m : array_like or None
        Across-track positions of the lines, m.

    Returns
    -------
    pandas.DataFrame
        Segments in the area frame (``x0_m``, ``y0_m``, ``x1_m``, ``y1_m``, ``heading_deg``,
        ``length_m``, ...), alternate lines reversed; empty when no segment of at least
        :data:`MIN_SEGMENT_M` is left.

    Raises
    ------
    ValueError
        A non-finite or non-positive spacing, heading, reach or run.
    """
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
    if across_m is not None:
        cs = np.sort(np.asarray(across_m, float))
    elif reach_m > 0:  # the lines whose swath reaches the area, as flown
        cs = flown_positions(c_min, c_max, [(spacing_m, offset)], reach_m, near_m)[0]
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
    ``turns_m`` (U-turns and junctions), ``total_m``, and ``n_segments``.

    Parameters
    ----------
    lines : pandas.DataFrame
        Segments in run order (:func:`line_set`).
    turn_radius_m : float
        Turn radius, m (>= 0).

    Returns
    -------
    dict
        ``lines_m``, ``turns_m``, ``total_m`` (m) and ``n_segments``; zeros for no lines.
    """
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
