"""U-turns between anti-parallel survey lines as points on the vehicle's path.

A vehicle of minimum turning radius ``R`` leaves a line at ``P`` heading ``e`` and joins the
next line, a lateral distance ``d`` away, heading ``-e`` (:func:`uturn_points`):

* ``d >= 2R``: a quarter circle toward the next line, a straight of ``d - 2R``, a quarter circle
  (length ``pi R + d - 2R``);
* ``d < 2R``: the bulb (omega) turn: an arc turning away from the next line by ``alpha``, an arc
  the other way by ``pi + 2 alpha`` and an arc by ``alpha`` again, ``cos(alpha) = (d + 2R) /
  (4R)`` (length ``R (pi + 4 alpha)``, the shortest Dubins path for these end poses; the same
  formulas as :func:`sss_locus.experiments.survey_design.lines.uturn_length_m`).

With the two line ends staggered along-track, the two-arc Dubins path's tangent runs
diagonally (:func:`uturn_points`). Arcs are sampled every ``step_deg`` degrees.
"""

from __future__ import annotations

import math

import numpy as np


def _arc(centre, start, sense: float, sweep_rad: float, step_deg: float) -> np.ndarray:
    """Points after ``start`` on the circle about ``centre``, turning ``sweep_rad`` in
    ``sense`` (+1 counter-clockwise), the end point included."""
    r = np.asarray(start, float) - centre
    k = max(1, int(math.ceil(math.degrees(sweep_rad) / step_deg)))
    a = math.atan2(r[1], r[0]) + sense * sweep_rad * np.arange(1, k + 1) / k
    return centre + np.linalg.norm(r) * np.column_stack([np.cos(a), np.sin(a)])


def _lsl(P, e, Q, n, R: float, step_deg: float):
    """The Dubins path turning twice toward ``n`` (the next line's side): arc, tangent, arc; its
    points after ``P`` and its length."""
    sigma = 1.0 if (e[0] * n[1] - e[1] * n[0]) > 0 else -1.0  # +1: the next line to the left
    c1, c2 = P + R * n, Q - R * n
    gap = c2 - c1
    dist = float(np.hypot(*gap))
    left = lambda v: sigma * np.array([-v[1], v[0]])  # noqa: E731
    ang = lambda v: math.atan2(v[1], v[0])  # noqa: E731
    if dist < 1e-9:
        return _arc(c1, P, sigma, math.pi, step_deg), math.pi * R
    u = gap / dist
    sweep1 = (sigma * (ang(u) - ang(e))) % (2 * math.pi)
    sweep2 = (sigma * (ang(-e) - ang(u))) % (2 * math.pi)
    t1 = c1 - R * left(u)
    pts = list(_arc(c1, P, sigma, sweep1, step_deg)) if sweep1 > 1e-9 else []
    if pts:
        pts[-1] = t1  # the first arc ends at the tangent point: once, not a zero-length leg after it
    else:
        pts.append(t1)
    pts += list(_arc(c2, c2 - R * left(u), sigma, sweep2, step_deg)) if sweep2 > 1e-9 else [Q]
    return np.asarray(pts), R * (sweep1 + sweep2) + dist


def uturn_points(p_end, heading_deg: float, q_start, radius_m: float, *, step_deg: float = 15.0) -> np.ndarray:
    """The path from ``p_end`` (end of a line of heading ``heading_deg``, deg counter-clockwise
    from east) to ``q_start`` (start of the next, anti-parallel line), both ``(2,)`` m, as the
    points after ``p_end`` up to and including ``q_start``; ``(k, 2)``. The shorter of the
    Dubins path that turns twice toward the next line (arc, tangent, arc: with ends level, the
    quarter circles and straight of the module docstring; with a stagger, the tangent runs
    diagonally, so the vehicle does not run along the next line's track beyond its start) and,
    for lines closer than ``2R``, the bulb turn with the stagger run straight.

    Parameters
    ----------
    p_end : array_like
        End of the line, local metres, shape (2,).
    heading_deg : float
        The line's heading, degrees counter-clockwise from east.
    q_start : array_like
        Start of the next line, local metres, shape (2,).
    radius_m : float
        Turn radius, m (<= 0: a straight step across).
    step_deg : float
        Angular step of the arc points, degrees.

    Returns
    -------
    numpy.ndarray
        Points, local metres, shape (k, 2), ending at ``q_start``.
    """
    P, Q = np.asarray(p_end, float), np.asarray(q_start, float)
    h = math.radians(heading_deg)
    e = np.array([math.cos(h), math.sin(h)])
    gap = Q - P
    a, lat = float(gap @ e), float(gap @ np.array([-e[1], e[0]]))
    s = 1.0 if lat >= 0 else -1.0
    n = s * np.array([-e[1], e[0]])  # toward the next line
    d, R = abs(lat), float(radius_m)
    if R <= 0:
        return np.asarray([P + d * n, Q])
    best, best_len = _lsl(P, e, Q, n, R, step_deg)
    if d < 2 * R:
        pts = []
        start = P + max(a, 0.0) * e
        if a > 0:
            pts.append(start)
        alpha = math.acos((d + 2 * R) / (4 * R))
        c1 = start - R * n
        c3 = start + (d + R) * n
        c2 = 0.5 * (c1 + c3) + math.sqrt(4 * R ** 2 - (0.5 * (d + 2 * R)) ** 2) * e
        sense = 1.0 if (start - c1)[0] * e[1] - (start - c1)[1] * e[0] > 0 else -1.0
        pts += list(_arc(c1, start, sense, alpha, step_deg))
        pts += list(_arc(c2, pts[-1], -sense, math.pi + 2 * alpha, step_deg))
        pts += list(_arc(c3, pts[-1], sense, alpha, step_deg))
        pts.append(Q)
        if R * (math.pi + 4 * alpha) + abs(a) < best_len:
            best = np.asarray(pts)
    if np.hypot(*(best[-1] - Q)) > 1e-6:
        best = np.vstack([best, Q])
    return best


def turn_fits(free, p_end, heading_deg: float, q_start, radius_m: float) -> bool:
    """Whether the U-turn of :func:`uturn_points` from ``p_end`` to ``q_start`` stays in ``free``
    (a shapely geometry: the water the vehicle may use, its clearance already taken off).

    Parameters
    ----------
    free : shapely.Geometry
        The water the vehicle may use.
    p_end : array_like
        End of the line, local metres, shape (2,).
    heading_deg : float
        The line's heading, degrees counter-clockwise from east.
    q_start : array_like
        Start of the next line, local metres, shape (2,).
    radius_m : float
        Turn radius, m.

    Returns
    -------
    bool
        True when the turn stays inside ``free``.
    """
    import shapely

    pts = uturn_points(p_end, heading_deg, q_start, radius_m)
    return bool(free.buffer(1e-6).covers(shapely.LineString(np.vstack([np.asarray(p_end, float), pts]))))


def fit_turns(lines, free, radius_m: float, *, max_pull_m: float | None = None):
    """The U-turns of a line table made to fit in the navigable water ``free`` (shapely, the
    wall clearance taken off): where the turn from a line's end to the next (anti-parallel)
    line's start leaves ``free``, both ends are pulled back along their lines, in steps of half
    the turn radius, until it fits (the lines get shorter; at most ``max_pull_m``, default 4
    radii, and never below 1 m of line).

    Parameters
    ----------
    lines : pandas.DataFrame
        Segments in run order, columns of :data:`sss_locus.experiments.survey_design.lines.LINE_COLUMNS`
        (headings degrees counter-clockwise from east; local metres).
    free : shapely geometry
        Where the vehicle may be.
    radius_m : float
        The vehicle's turn radius, m.
    max_pull_m : float or None
        Most pull-back per end, m; ``None``: 4 turn radii.

    Returns
    -------
    lines : pandas.DataFrame
        A copy with the pulled-back ends and their ``length_m``.
    misfits : list of str
        One sentence per turn that fits nowhere, naming the lines (the track then joins them by
        a transit inside the water, :mod:`.route`).
    """
    L = lines.reset_index(drop=True).copy()
    R = float(radius_m)
    pull_max = 4 * R if max_pull_m is None else float(max_pull_m)
    misfits = []
    start, end = L[["x0_m", "y0_m"]].to_numpy(float).copy(), L[["x1_m", "y1_m"]].to_numpy(float).copy()
    head, sets, nums = L.heading_deg.to_numpy(float), L["set"].to_numpy(), L.line.to_numpy()
    for k in range(1, len(L)):
        dh = (head[k] - head[k - 1] + 180.0) % 360.0 - 180.0
        if R <= 0 or sets[k - 1] != sets[k] or abs(abs(dh) - 180.0) > 1e-6:
            continue
        h = math.radians(head[k - 1])
        e = np.array([math.cos(h), math.sin(h)])
        p, q = end[k - 1].copy(), start[k].copy()
        room = min(float(np.hypot(*(end[k - 1] - start[k - 1]))), float(np.hypot(*(end[k] - start[k])))) - 1.0
        pull, fits = 0.0, turn_fits(free, p, head[k - 1], q, R)
        while not fits and pull + R / 2 <= min(pull_max, room):
            pull += R / 2
            fits = turn_fits(free, p - pull * e, head[k - 1], q - pull * e, R)
        if not fits:
            misfits.append(f"the turn from {sets[k - 1]} line {int(nums[k - 1])} to line {int(nums[k])} does not fit in "
                           f"the navigable water, even with the lines' ends pulled back {pull:.3g} m: a transit joins them")
        elif pull > 0:
            end[k - 1], start[k] = p - pull * e, q - pull * e
    L[["x0_m", "y0_m"]], L[["x1_m", "y1_m"]] = start, end
    L["length_m"] = np.hypot(*(end - start).T)
    return L, misfits
