"""Which survey lines see which seafloor points: features for the objectives, a grid for coverage.

Observation (:func:`observe_lines`): every (point, segment) pair is observed as in
:func:`sss_locus.experiments.reconstruction.terrain_survey.observe_features` (the exact in-beam ping of
:func:`~sss_locus.experiments.passes.straight_pass.observe_pass`, the side the point lies on, the
vehicle at ``altitude_m`` above the seafloor below it, or, for a platform of fixed depth, above
the mean seafloor ``z = 0``; the in-beam elevation uniform in the beam, seeded), with one more
condition: the transducer at the ping must lie on the segment (its along-track position within
``[0, length]`` of the segment's start). A segment therefore sees a point only when the vehicle
actually passes abeam of it inside the area.

Coverage (:func:`coverage`) is **measured** on a square grid of points inside the area (the
cell centres of spacing ``grid_m``): the share of the area seen by at least one line, by two or
more, and the share seen by none (holes, counted as connected groups of unseen cells, 4-connected).
Each segment is observed against the cells within the sonar's maximum range of it only (no ping
reaches farther; the in-beam elevations seeded per segment), so the cost grows with the area, not
with the area times the number of lines.
Where the lines' swaths overlap the nadir gap is filled; where they do not, it shows as holes.
The nadir gap of a line is the band ``|offset| < near`` under the vehicle that neither side's
fan reaches, ``near`` from :func:`~sss_locus.experiments.passes.straight_pass.swath_m` on a flat
seafloor at the plan's altitude.

Out of reach (:func:`out_of_reach`): a cell whose seafloor no line can see wherever it runs, because
the vehicle's height above it (for a platform of fixed depth, ``altitude_m - h(x, y)``: a deeper
seafloor is farther below) leaves neither side a swath on a flat seafloor there (:func:`side_reach_m`: the closed form of
:func:`~sss_locus.experiments.passes.straight_pass.swath_m`, no ground offset inside both the fan and
``min_range_m``..``max_range_m``, or the transducer not above it). Such cells are gaps of
every plan; :func:`coverage` reports their share apart.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from sss_locus.experiments.passes.straight_pass import swath_m
from sss_locus.experiments.survey_design.area import SurveyArea
from sss_locus.experiments.datamodel.terrain import Terrain
from sss_locus.experiments.reconstruction.terrain_survey import observe_features
from sss_locus.experiments.passes.view_sets import Views


class _Segments:
    """The segments of a line table as :func:`observe_features` reads a layout (``lines()``)."""

    def __init__(self, heading_deg, start_m, length_m):
        self.heading = np.atleast_1d(np.asarray(heading_deg, float))
        self.start = np.asarray(start_m, float).reshape(-1, 2)
        self.length = np.atleast_1d(np.asarray(length_m, float))
        self.start_offset_m = 0.0  # lines() gives each segment's start itself

    @classmethod
    def of(cls, lines: pd.DataFrame) -> "_Segments":
        return cls(lines["heading_deg"].to_numpy(float), lines[["x0_m", "y0_m"]].to_numpy(float),
                   lines["length_m"].to_numpy(float))

    def lines(self):
        return self.heading, self.start


def observe_lines(platform, terrain: Terrain, xy, lines: pd.DataFrame, altitude_m: float,
                  pitch_deg: float, same_altitude: bool, seed: int, centre=(0.0, 0.0)) -> tuple[Views, np.ndarray, dict]:
    """Every segment of ``lines`` (:func:`~sss_locus.experiments.survey_design.lines.line_set` rows)
    against every seafloor point below ``xy`` (``(n, 2)``, area frame, m); see the module docstring.

    ``centre`` (area frame, m) is where the terrain's origin lies: the terrain, the views and the
    returned features are in the frame centred there (area frame minus ``centre``).

    Returns the :class:`~sss_locus.experiments.passes.view_sets.Views` (``(n, L)``), ``seen`` (n, L) and
    the info of :func:`observe_features` with ``on_segment`` (n, L) added.

    Parameters
    ----------
    platform : Platform
        The sonar platform.
    terrain : Terrain
        The seafloor, in the frame centred at ``centre``.
    xy : array_like
        Feature positions, shape (n, 2), area frame, m.
    lines : pandas.DataFrame
        Segments, one row each (``heading_deg``, ``x0_m``, ``y0_m``, ``length_m``), area frame.
    altitude_m : float
        The vehicle's altitude above the seafloor, m.
    pitch_deg : float
        The vehicle's pitch, degrees.
    same_altitude : bool
        True for a vehicle at one depth (altitude above the mean seafloor, not the local one).
    seed : int
        Seed of the observation draws.
    centre : tuple of float
        ``(x, y)``, area frame, m: the terrain's origin.

    Returns
    -------
    views : Views
        The views, shape (n, L) for L segments, in the frame centred at ``centre``.
    seen : numpy.ndarray
        Boolean (n, L): feature i is seen from segment j.
    info : dict
        :func:`observe_features`' info with ``on_segment`` (n, L).
    """
    return _observe(platform, terrain, xy, _Segments.of(lines), altitude_m, pitch_deg, same_altitude, seed, centre)


def _observe(platform, terrain, xy, seg: _Segments, altitude_m, pitch_deg, same_altitude, seed, centre):
    """:func:`observe_lines` on segments given as arrays (no table lookups in the coverage's loop)."""
    c = np.asarray(centre, float)
    xy = np.asarray(xy, float) - c
    seg = _Segments(seg.heading, seg.start - c, seg.length)
    points = terrain.point_on_seafloor(xy[:, 0], xy[:, 1])
    views, seen, info = observe_features(platform, terrain, points, seg, altitude_m, same_altitude,
                                         seed, pitch_deg=pitch_deg)
    h = np.radians(seg.heading)
    e = np.stack([np.cos(h), np.sin(h)], -1)
    along = np.einsum("nlj,lj->nl", views.origin[..., :2] - seg.start[None], e)
    on = (along >= 0.0) & (along <= seg.length[None])
    info["on_segment"] = on
    return views, seen & on, info


def grid_points(area: SurveyArea, grid_m: float) -> tuple[np.ndarray, np.ndarray, tuple[int, int]]:
    """Cell centres of a square grid of spacing ``grid_m`` over the area's bounding box: the
    centres ``(m, 2)`` inside the polygon, their flat indices in the box grid, and its shape.

    Parameters
    ----------
    area : SurveyArea
        The area (local metres).
    grid_m : float
        Cell size, m (> 0).

    Returns
    -------
    xy : numpy.ndarray
        Cell centres inside the polygon, shape (m, 2), local metres.
    flat : numpy.ndarray
        Their flat indices into the box grid, shape (m,).
    shape : tuple of int
        ``(ny, nx)`` of the box grid.

    Raises
    ------
    ValueError
        ``grid_m`` not a finite positive number, or more than 4 000 000 cells.
    """
    import shapely

    if not (isinstance(grid_m, (int, float)) and math.isfinite(grid_m) and grid_m > 0):
        raise ValueError(f"grid_m must be a finite number > 0; got {grid_m!r}")
    x0, y0, x1, y1 = area.polygon.bounds
    nx, ny = max(1, int(math.ceil((x1 - x0) / grid_m))), max(1, int(math.ceil((y1 - y0) / grid_m)))
    if nx * ny > 4_000_000:
        raise ValueError(f"grid_m = {grid_m:g} m gives {nx * ny} cells over the area; use a coarser grid")
    xs, ys = x0 + (np.arange(nx) + 0.5) * grid_m, y0 + (np.arange(ny) + 0.5) * grid_m
    X, Y = np.meshgrid(xs, ys)
    inside = shapely.contains_xy(area.polygon, X.ravel(), Y.ravel())
    return np.stack([X.ravel()[inside], Y.ravel()[inside]], -1), np.flatnonzero(inside), (ny, nx)


def nadir_gap_m(platform, altitude_m: float) -> float:
    """Half-width of the nadir gap, m: the smaller near edge of the two sides' swaths on a flat
    seafloor (0 when a fan reaches past nadir).

    Parameters
    ----------
    platform : Platform
        The sonar platform.
    altitude_m : float
        Altitude above a flat seafloor, m.

    Returns
    -------
    float
        Half-width of the gap, m (>= 0).
    """
    near = [float(swath_m(platform, [port], [altitude_m])[0][0]) for port in (True, False)]
    return max(0.0, min(near))


def side_reach_m(platform, side: str) -> tuple[float, float]:
    """The heights (m) of the vehicle's reference point above a flat seafloor between which the
    ``side`` transducer's fan sees it (open interval): the closed form of
    :func:`~sss_locus.experiments.passes.straight_pass.swath_m`'s ``near < far``. Above the
    transducer (and, with a minimum range, above ``min_range_m sin(tilt - azimuth/2)``), and
    below ``depth_m + max_range_m sin(min(tilt + azimuth/2, 90°))`` (deeper, even the steepest
    look-down ray ends before the seafloor); an empty interval for a fan that never looks down.

    Parameters
    ----------
    platform : Platform
        The sonar platform.
    side : str
        A key of ``platform.transducers`` (``"port"`` or ``"starboard"``).

    Returns
    -------
    low, high : float
        Heights of the reference point above the seafloor, m; ``low == high`` (empty) for a fan
        that never looks down.
    """
    son, t = platform.sonar, platform.transducers[side]
    steep, shallow = t.tilt_deg + son.azimuth_deg / 2, t.tilt_deg - son.azimuth_deg / 2
    if steep <= 0:
        return t.depth_m, t.depth_m
    low = t.depth_m + (son.min_range_m * math.sin(math.radians(shallow)) if shallow > 0 else 0.0)
    return low, t.depth_m + son.max_range_m * math.sin(math.radians(min(steep, 90.0)))


def reach_limits_m(platform) -> tuple[float, float]:
    """The lowest and highest heights (m) of the reference point at which some side's fan sees
    a flat seafloor (:func:`side_reach_m` over the sides).

    Parameters
    ----------
    platform : Platform
        The sonar platform.

    Returns
    -------
    low, high : float
        Heights of the reference point above the seafloor, m.
    """
    windows = [side_reach_m(platform, side) for side in platform.transducers]
    return min(w[0] for w in windows), max(w[1] for w in windows)


def out_of_reach(platform, terrain: Terrain, xy, altitude_m: float, same_altitude: bool,
                 centre=(0.0, 0.0)) -> np.ndarray:
    """Whether and why no line of any plan can see the seafloor below each of ``xy`` (``(n, 2)``,
    area frame, m), by the module docstring's rule: ``(n,)`` int, 0 in reach, -1 too shallow (the
    vehicle at or below the lowest height of :func:`reach_limits_m` above it), +1 too deep.

    Parameters
    ----------
    platform : Platform
        The sonar platform.
    terrain : Terrain
        The seafloor, in the frame centred at ``centre``.
    xy : array_like
        Seafloor positions, shape (n, 2), area frame, m.
    altitude_m : float
        The vehicle's altitude, m (above the mean seafloor when ``same_altitude``).
    same_altitude : bool
        True for a vehicle at one depth.
    centre : tuple of float
        ``(x, y)``, area frame, m: the terrain's origin.

    Returns
    -------
    numpy.ndarray
        Shape (n,), int: 0 in reach, -1 too shallow, +1 too deep.
    """
    xy = np.asarray(xy, float) - np.asarray(centre, float)
    alt = np.full(len(xy), float(altitude_m))
    if same_altitude:  # a fixed-depth vehicle: the deeper the seafloor, the farther below
        alt = alt - terrain.height_m(xy[:, 0], xy[:, 1])
    seen = np.zeros(len(xy), bool)
    for side in platform.transducers:
        low, high = side_reach_m(platform, side)
        seen |= (alt > low) & (alt < high)
    return np.where(seen, 0, np.where(alt <= reach_limits_m(platform)[0], -1, 1))


def coverage(platform, terrain: Terrain, area: SurveyArea, lines: pd.DataFrame, altitude_m: float,
             pitch_deg: float, same_altitude: bool, *, grid_m: float, seed: int = 0,
             centre=(0.0, 0.0)) -> dict:
    """Measured coverage of ``lines`` over ``area`` (module docstring).

    Parameters
    ----------
    platform : Platform
        The sonar platform.
    terrain : Terrain
        The seafloor, in the frame centred at ``centre``.
    area : SurveyArea
        The area (local metres).
    lines : pandas.DataFrame
        The plan's segments (``heading_deg``, ``x0_m``, ``y0_m``, ``length_m``), area frame.
    altitude_m : float
        The vehicle's altitude, m.
    pitch_deg : float
        The vehicle's pitch, degrees.
    same_altitude : bool
        True for a vehicle at one depth.
    grid_m : float
        Coverage cell size, m.
    seed : int
        Seed of the observation draws (one stream per segment).
    centre : tuple of float
        ``(x, y)``, area frame, m: the terrain's origin.

    Returns
    -------
    dict
        ``once``, ``twice`` (shares of the area seen by >= 1, >= 2 lines), ``holes`` (share seen
        by none), ``n_holes`` (connected unseen groups), ``nadir_gap_m`` (half-width), ``grid_m``,
        ``out_of_reach`` (share of the area no plan can see: :func:`out_of_reach`),
        ``out_of_reach_m2`` (that share of the area's area, m²), ``too_shallow`` and ``too_deep``
        (its two parts, shares of the area),
        ``grid``: a DataFrame ``x_m, y_m, n_lines, out_of_reach`` of the grid cells inside the area.
    """
    from scipy import ndimage

    xy, flat, shape = grid_points(area, grid_m)
    count = np.zeros(len(xy), np.int64)
    reach = float(platform.sonar.max_range_m)  # no ping reaches farther from the vehicle
    for j, (h, x0, y0, length) in enumerate(lines[["heading_deg", "x0_m", "y0_m", "length_m"]].to_numpy(float)):
        e = np.array([math.cos(math.radians(h)), math.sin(math.radians(h))])
        d = xy - [x0, y0]
        along, across = d @ e, d @ np.array([-e[1], e[0]])
        near = np.flatnonzero((along >= -reach) & (along <= length + reach) & (np.abs(across) <= reach))
        if near.size:
            sd = int(np.random.SeedSequence([seed, j]).generate_state(1)[0])
            _, seen, _ = _observe(platform, terrain, xy[near], _Segments(h, [x0, y0], length), altitude_m,
                                  pitch_deg, same_altitude, sd, centre)
            count[near] += seen[:, 0]
    unseen = np.zeros(shape[0] * shape[1], bool)
    unseen[flat[count == 0]] = True
    _, n_holes = ndimage.label(unseen.reshape(shape))
    why = out_of_reach(platform, terrain, xy, altitude_m, same_altitude, centre)
    beyond = why != 0
    return {"out_of_reach": float(np.mean(beyond)), "out_of_reach_m2": float(np.mean(beyond) * area.polygon.area),
            "too_shallow": float(np.mean(why < 0)), "too_deep": float(np.mean(why > 0)),
            "once": float(np.mean(count >= 1)), "twice": float(np.mean(count >= 2)),
            "holes": float(np.mean(count == 0)), "n_holes": int(n_holes),
            "nadir_gap_m": nadir_gap_m(platform, altitude_m), "grid_m": float(grid_m),
            "grid": pd.DataFrame({"x_m": xy[:, 0], "y_m": xy[:, 1], "n_lines": count, "out_of_reach": beyond})}
