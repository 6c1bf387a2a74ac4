"""The whole track of a plan, with its fences: what a mission file tells the vehicle to fly.

Track (:func:`flight_path`): the segments of a line table in run order, then a transit back to
the first line's start (the mission's home: ArduPilot's return to launch flies straight, which
could leave the fence or cross a hole); between two
anti-parallel lines the U-turn of :func:`~.turns.uturn_points`; any other junction (segments of
one line on either side of a hole or a notch, the transit from the main to the cross lines) is
a transit: the shortest polyline from one end to the next start that stays inside the
inclusion fence shrunk by the turn radius and outside every hole grown by the turn radius plus
``margin_m`` (a visibility graph over those polygons' vertices, solved with
:func:`scipy.sparse.csgraph.dijkstra`); a straight leg when that is already free.

Fences (:func:`fences`): in open water the **inclusion fence** is the area's outer ring joined
with every line and U-turn of the track and the water between the area and every leg outside
it, grown by ``R + margin_m`` (room for the vehicle's own turns and for the transits; no slit
between the area's edge and a line run outside it; a line segment that lies apart, beyond a
notch, joined to the rest by a corridor as wide along the shortest way), its outer ring simplified to at most
``max_vertices`` vertices while still containing it. When the area gives navigable water
(:meth:`~sss_locus.experiments.survey_design.area.SurveyArea.water`: ``navigable_m`` or
``water_beyond_m``), the track keeps the area's ``wall_clearance_m`` off its edge and its holes
(lines cut and their ends pulled back for the turns by
:func:`~sss_locus.experiments.survey_design.turns.fit_turns`; a U-turn that still leaves it
replaced by a transit inside it), and the fence is the navigable water's outline itself, never
past it (with more than ``max_vertices`` vertices: shrunk by half the clearance and simplified
by a quarter, still holding the track); the **exclusion
fences** are the area's holes. :func:`check_inside` is the check every mission writer runs: every point of
the track inside the inclusion fence and outside every exclusion fence, else a one-line error.

Cost (:func:`track_cost`): the length of that track, leg by leg, as the vehicle flies it: the
lines, the U-turns, and the transits (including the return to the first line's start); the
survey design's cost and time of every plan come from it, not from a formula.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from sss_locus.experiments.survey_design.turns import uturn_points

PATH_COLUMNS = ("kind", "set", "line", "segment", "east_m", "north_m")
"""``kind``: ``line start``, ``line end``, ``turn``, ``transit`` or ``return`` (after the last
line, back to the first line's start, the mission's home, inside the fence)."""


def fences(area, legs, turn_radius_m: float, *, margin_m: float = 5.0, max_vertices: int = 60):
    """Inclusion fence (shapely Polygon) and exclusion fences (list of Polygons), local metres
    (module docstring); ``legs`` the lines and turns (a shapely geometry) the fence must hold.

    Parameters
    ----------
    area : SurveyArea
        The area (local metres).
    legs : shapely.Geometry
        Lines and turns the fence must hold.
    turn_radius_m : float
        Turn radius, m.
    margin_m : float
        Margin beyond the grown track, m.
    max_vertices : int
        Most vertices of the inclusion fence.

    Returns
    -------
    fence : shapely.Polygon
        The inclusion fence.
    holes : list of shapely.Polygon
        The exclusion fences (the area's holes).
    """
    import shapely

    outer = shapely.Polygon(area.polygon.exterior)
    water = area.water()
    if water is not None:  # the navigable water: the fence never reaches past it
        water = max(getattr(water, "geoms", [water]), key=lambda g: g.area)
        return _water_fence(shapely.Polygon(water.exterior), legs, area.clearance_m, max_vertices), \
            [shapely.Polygon(r) for r in area.polygon.interiors]
    else:
        grow = turn_radius_m + margin_m  # each piece grown on its own, then joined: fast, and no closer
        grown = shapely.union_all([outer.buffer(grow, join_style="mitre"),
                                   *shapely.buffer(shapely.get_parts(legs), grow, cap_style="square", join_style="mitre"),
                                   *_to_area(outer, legs)])
        parts = sorted(getattr(grown, "geoms", [grown]), key=lambda g: g.area, reverse=True)
        main = parts[0]
        for part in parts[1:]:  # a line's segment beyond a notch, apart from the rest: bridged, never dropped
            bridge = shapely.shortest_line(main, part).buffer(turn_radius_m + margin_m, quad_segs=4)
            main = shapely.union_all([main, part, bridge])
        grown = main
    grown = shapely.Polygon(grown.exterior) if grown.geom_type == "Polygon" else shapely.Polygon(
        max(grown.geoms, key=lambda g: g.area).exterior)
    tol, fence = margin_m, grown
    for _ in range(40):  # coarser until few enough vertices, always containing the grown ring
        cand = grown.buffer(tol, join_style="mitre").simplify(tol)
        if cand.geom_type == "Polygon" and cand.covers(grown) and len(cand.exterior.coords) - 1 <= max_vertices:
            fence = shapely.Polygon(cand.exterior)
            break
        tol *= 1.5
    return fence, [shapely.Polygon(r) for r in area.polygon.interiors]


def _to_area(outer, legs) -> list:
    """The water between the area and every piece of ``legs`` outside it: per piece, the convex
    hull of it and the points of the area's outline nearest its ends. A line run half a spacing
    outside the area's edge and joined to the rest only by its U-turns would otherwise leave a
    slit in the fence between it and the edge, open at one end and as long as the line (a
    10 m x 3 km slit on a 900 kHz ROV's plan whose first line ran 32 m off the edge)."""
    import shapely

    out = []
    for piece in shapely.get_parts(shapely.line_merge(legs.difference(outer))):
        ends = shapely.points(np.asarray(piece.coords)[[0, -1]])
        near = shapely.get_coordinates(shapely.shortest_line(ends, outer.exterior))[1::2]
        out.append(shapely.MultiPoint(np.vstack([np.asarray(piece.coords), near])).convex_hull)
    return out


def _water_fence(outline, legs, clearance_m: float, max_vertices: int):
    """The inclusion fence in navigable water: its outline, or, when that has more than
    ``max_vertices`` vertices, the outline shrunk by half the clearance and simplified by a
    quarter of it (so it stays inside the outline and still holds the track, which keeps the
    whole clearance), when that holds ``legs``."""
    if len(outline.exterior.coords) - 1 <= max_vertices or clearance_m <= 0:
        return outline
    import shapely

    cand = outline.buffer(-clearance_m / 2, join_style="mitre").simplify(clearance_m / 4)
    ok = cand.geom_type == "Polygon" and outline.buffer(1e-6).covers(cand) and cand.buffer(1e-6).covers(legs)
    return shapely.Polygon(cand.exterior) if ok else outline


def _transit(a, b, free, nodes, room) -> list:
    """Shortest polyline from ``a`` to ``b`` inside the polygon ``free`` (widened by ``room``
    about ``a`` and ``b``: the ends may lie near a hole or on a shore) through ``nodes`` and the
    points of ``free`` nearest ``a`` and ``b`` (an end on the shore first steps into ``free``,
    rather than reaching only the far corners a straight leg along the shore can see)."""
    import shapely
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import dijkstra

    ok = free.union(shapely.Point(a).buffer(room[0])).union(shapely.Point(b).buffer(room[0])).intersection(room[1])
    ok = ok.buffer(1e-6)
    shapely.prepare(ok)  # many segments are tested against it
    if ok.covers(shapely.LineString([a, b])):
        return [b]
    entries = [] if free.is_empty else [shapely.get_coordinates(shapely.shortest_line(free, shapely.points([a, b])))[::2]]
    pts = np.vstack([a, b, *entries, nodes])
    k = len(pts)
    i, j = np.triu_indices(k, 1)
    segs = shapely.linestrings(np.stack([pts[i], pts[j]], 1))
    vis = shapely.covers(ok, segs)
    w = np.linalg.norm(pts[i] - pts[j], axis=1)
    g = csr_matrix((w[vis], (i[vis], j[vis])), shape=(k, k))
    dist, pred = dijkstra(g, directed=False, indices=0, return_predecessors=True)
    if not np.isfinite(dist[1]):  # no free way: straight (check_inside will say so)
        return [b]
    path, node = [], 1
    while node != 0:
        path.append(pts[node])
        node = pred[node]
    return path[::-1]


def flight_path(area, lines: pd.DataFrame, turn_radius_m: float, *, margin_m: float = 5.0,
                step_deg: float = 15.0) -> tuple[pd.DataFrame, object, list]:
    """The plan's track (module docstring): a table of :data:`PATH_COLUMNS` in flying order, the
    inclusion fence and the exclusion fences.

    Parameters
    ----------
    area : SurveyArea
        The area (local metres).
    lines : pandas.DataFrame
        Segments in run order.
    turn_radius_m : float
        Turn radius, m.
    margin_m : float
        Fence margin, m.
    step_deg : float
        Angular step of the turn points, degrees.

    Returns
    -------
    path : pandas.DataFrame
        Track points (:data:`PATH_COLUMNS`, ``east_m``/``north_m`` local metres) in flying order.
    fence : shapely.Polygon
        The inclusion fence.
    holes : list of shapely.Polygon
        The exclusion fences.
    """
    import shapely

    R = float(turn_radius_m)
    L = lines.reset_index(drop=True)
    water = area.water()  # the navigable water less the wall clearance (None: open water)
    water = None if water is None else water.buffer(0.01 - area.clearance_m)
    joins: dict[int, tuple[str, np.ndarray]] = {}
    for k in range(1, len(L)):
        a, b = L.iloc[k - 1], L.iloc[k]
        dh = (b.heading_deg - a.heading_deg + 180.0) % 360.0 - 180.0
        if abs(abs(dh) - 180.0) < 1e-6:
            pts = uturn_points([a.x1_m, a.y1_m], a.heading_deg, [b.x0_m, b.y0_m], R, step_deg=step_deg)
            if water is None or water.covers(shapely.LineString(np.vstack([[a.x1_m, a.y1_m], pts]))):
                joins[k] = ("turn", pts)  # else a transit inside the water
    legs = [shapely.LineString([(r.x0_m, r.y0_m), (r.x1_m, r.y1_m)]) for r in L.itertuples()]
    legs += [shapely.LineString(np.vstack([[L.x1_m[k - 1], L.y1_m[k - 1]], p])) for k, (_, p) in joins.items()]
    fence, holes = fences(area, shapely.MultiLineString(legs), R, margin_m=margin_m)
    navigable = fence if water is None else water  # a shore: transits stay in the water itself
    free = navigable.buffer(-R, join_style="mitre")
    room = navigable
    if holes:
        free = free.difference(shapely.union_all([h.buffer(R + margin_m, quad_segs=2) for h in holes]))
        room = navigable.difference(shapely.union_all(holes).buffer(1.0))
    rings = [free] if free.geom_type == "Polygon" else list(getattr(free, "geoms", []))
    nodes = np.vstack([np.asarray(r.coords)[:-1] for p in rings for r in (p.exterior, *p.interiors)]) if rings \
        else np.zeros((0, 2))
    rows = []
    for k, r in L.iterrows():
        tag = (r["set"], int(r.line), int(r.segment))
        p0, p1 = np.array([r.x0_m, r.y0_m]), np.array([r.x1_m, r.y1_m])
        if k > 0:
            end = np.array([L.x1_m[k - 1], L.y1_m[k - 1]])
            kind, pts = joins.get(k, ("transit", None))
            if pts is None:
                pts = np.asarray(_transit(end, p0, free, nodes, (R + margin_m + 1.0, room)))
            rows += [(kind, *tag, float(x), float(y)) for x, y in pts[:-1] if np.hypot(x - end[0], y - end[1]) > 1e-6]
        rows += [("line start", *tag, *map(float, p0)), ("line end", *tag, *map(float, p1))]
    if len(L) > 1:  # back to the first point (home) inside the fence: the mission's RTL then has no leg to fly
        end, home = np.array([L.x1_m.iloc[-1], L.y1_m.iloc[-1]]), np.array([L.x0_m.iloc[0], L.y0_m.iloc[0]])
        back = np.asarray(_transit(end, home, free, nodes, (R + margin_m + 1.0, room)))
        rows += [("return", *rows[-1][1:4], float(x), float(y)) for x, y in back]
    return pd.DataFrame(rows, columns=list(PATH_COLUMNS)), fence, holes


def check_inside(path: pd.DataFrame, fence, holes, *, what: str = "track") -> None:
    """Refuse, in one line, a track with a point or leg outside ``fence`` or inside a hole.

    Parameters
    ----------
    path : pandas.DataFrame
        Track points (``east_m``, ``north_m``), at least one.
    fence : shapely.Polygon
        The inclusion fence.
    holes : list of shapely.Polygon
        The exclusion fences.
    what : str
        What the message names.

    Raises
    ------
    ValueError
        The track leaves the fence or crosses a hole.
    """
    import shapely

    xy = path[["east_m", "north_m"]].to_numpy()
    legs = shapely.LineString(xy) if len(xy) > 1 else shapely.Point(xy[0])
    if not fence.buffer(1e-6).covers(legs):
        raise ValueError(f"{what}: {legs.difference(fence).length:.1f} m of the track leave the inclusion fence")
    for k, h in enumerate(holes):
        inside = legs.intersection(h.buffer(-1e-6))
        if not inside.is_empty:
            raise ValueError(f"{what}: the track crosses hole {k + 1} of the area for {inside.length:.1f} m")


def track_cost(path: pd.DataFrame) -> dict[str, float]:
    """Lengths of a :func:`flight_path` track, m, leg by leg (module docstring): ``lines_m`` (legs
    ending at a ``line end``), ``turns_m`` (U-turns), ``transits_m`` (transits and the return),
    ``total_m`` (their sum, the polyline's length), and ``n_segments`` (line segments).

    Parameters
    ----------
    path : pandas.DataFrame
        The track of :func:`flight_path`, columns :data:`PATH_COLUMNS`, in flying order.

    Returns
    -------
    dict
        The lengths above (m) and ``n_segments``.
    """
    xy = path[["east_m", "north_m"]].to_numpy(float)
    kind = path["kind"].to_numpy()
    leg = np.hypot(*np.diff(xy, axis=0).T) if len(xy) > 1 else np.zeros(0)
    into, before = kind[1:], kind[:-1]
    # a leg into a line's start closes the junction it ends (a U-turn's last arc, or a transit)
    closes = np.where(np.isin(before, ("turn", "transit")), before, "transit")
    what = np.where(into == "line start", closes, into)
    lines = float(leg[what == "line end"].sum())
    turns = float(leg[what == "turn"].sum())
    transits = float(leg[np.isin(what, ("transit", "return"))].sum())
    return {"lines_m": lines, "turns_m": turns, "transits_m": transits, "total_m": float(leg.sum()),
            "n_segments": int(np.sum(kind == "line start"))}


def turn_misfits(area, lines: pd.DataFrame, turn_radius_m: float) -> list[str]:
    """The U-turns of ``lines`` that do not fit in the area's navigable water with its wall
    clearance, one sentence each naming the lines (:func:`~.turns.fit_turns`; open water: none);
    the track joins those lines by a transit inside the water.

    Parameters
    ----------
    area : SurveyArea
        The area (local metres).
    lines : pandas.DataFrame
        Segments in run order.
    turn_radius_m : float
        Turn radius, m.

    Returns
    -------
    list of str
        One sentence per U-turn that does not fit; empty in open water or without lines.
    """
    from sss_locus.experiments.survey_design.turns import fit_turns

    water = area.water()
    if water is None or lines.empty:
        return []
    return fit_turns(lines, water.buffer(-area.clearance_m), turn_radius_m)[1]
