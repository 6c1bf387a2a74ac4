"""A sidescan survey over a non-flat seafloor: which passes see which feature, and from where.

Layout (:class:`SurveyLayout`, values in ``data/terrain.toml``): parallel main lines at heading
0 deg / 180 deg (alternating, a lawn-mower pattern) spaced ``line_spacing_m`` across the square
survey area, and cross lines at 90 deg / 270 deg spaced ``cross_line_spacing_m``; every line
runs ``margin_m`` beyond the area. World frame of :mod:`sss_locus.experiments.datamodel.terrain`
(``x`` east, ``y`` north, ``z`` up, seafloor ``z = h(x, y)``).

Each (feature, line) pair is observed at the ping of :func:`~sss_locus.experiments.passes.straight_pass.
observe_pass` (the exact in-beam ping, platform frames as in the other chapters), with

* the observing side the one the feature lies on, its ground offset the across-track distance;
* the vehicle level (pitch 0, or a constant ``pitch_deg``; a terrain-following AUV would
  pitch on slopes, left out) at a
  height set by the seafloor: for a platform whose envelope holds one altitude
  (``same_altitude``, the surface boat) the reference point is at ``altitude_m`` above the mean
  seafloor ``z = 0`` (the water depth), otherwise (the AUV, terrain following) ``altitude_m``
  above the seafloor directly below the point of the line abeam the feature;
* the in-beam elevation uniform in the beam (seeded), as in the three-view study.

A line *sees* a feature when the ping exists and the feature is within the azimuth aperture
and the range limits (:data:`~sss_locus.experiments.passes.straight_pass.REJECTION_REASONS`). Acoustic
shadowing is an open choice (``shadowing``): ``"off"`` (default) ignores it; ``"on"`` also
drops a view when the terrain rises above the straight ray from the transducer to the feature
anywhere except within ``SHADOW_CLEARANCE_M`` of the feature (checked at
``SHADOW_SAMPLES`` points along the ray). Data association is assumed known: every view of a
feature is attributed to it without error.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from sss_locus.experiments.passes.straight_pass import level_attitude_matrices, observe_pass
from sss_locus.experiments.datamodel.terrain import Terrain
from sss_locus.experiments.passes.view_sets import Views

SHADOWING = ("off", "on")
SHADOW_SAMPLES = 48
SHADOW_CLEARANCE_M = 1.0


@dataclass(frozen=True)
class SurveyLayout:
    """Survey lines over a square area centred on the origin (metres; see the module docstring)."""

    area_m: float
    line_spacing_m: float
    cross_line_spacing_m: float
    margin_m: float = 0.0

    def __post_init__(self) -> None:
        for name in ("area_m", "line_spacing_m", "cross_line_spacing_m", "margin_m"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) \
                    or not math.isfinite(v) or v < 0 or (v == 0 and name != "margin_m"):
                raise ValueError(f"SurveyLayout.{name} must be a finite number > 0 (margin_m >= 0); got {v!r}")
            object.__setattr__(self, name, float(v))

    def lines(self) -> tuple[np.ndarray, np.ndarray]:
        """Headings (deg) and one point of each line (``(L, 2)``, m): main lines first (south to
        north, alternating 0 / 180 deg), then cross lines (west to east, 90 / 270 deg).

        Returns
        -------
        headings_deg : numpy.ndarray
            Line headings, degrees, shape (L,).
        points : numpy.ndarray
            One point on each line, local metres centred on the area, shape (L, 2).
        """
        out_h, out_c = [], []
        for spacing, base in ((self.line_spacing_m, 0.0), (self.cross_line_spacing_m, 90.0)):
            m = int(math.floor(self.area_m / spacing + 1e-9)) + 1
            pos = (np.arange(m) - (m - 1) / 2.0) * spacing
            for j, c in enumerate(pos):
                out_h.append(base + 180.0 * (j % 2))
                out_c.append([0.0, c] if base == 0.0 else [c, 0.0])
        return np.array(out_h), np.array(out_c)

    def key(self) -> dict:
        """The layout as plain data (for cache keys and records).

        Returns
        -------
        dict
            ``area_m``, ``line_spacing_m``, ``cross_line_spacing_m``, ``margin_m`` (m).
        """
        return {k: getattr(self, k) for k in ("area_m", "line_spacing_m", "cross_line_spacing_m", "margin_m")}

    @property
    def start_offset_m(self) -> float:
        """How far (m) before the point :meth:`lines` gives each line starts: half the area plus
        the margin (the line's run-in), the origin of the dead-reckoning distance ``along_m``."""
        return self.area_m / 2.0 + self.margin_m


def observe_features(platform, terrain: Terrain, features, layout: SurveyLayout, altitude_m: float,
                     same_altitude: bool, seed: int, shadowing: str = "off",
                     pitch_deg: float = 0.0) -> tuple[Views, np.ndarray, dict]:
    """Every line of ``layout`` against every feature.

    Parameters
    ----------
    platform : Platform
    terrain : Terrain
    features : array_like, shape (n, 3)
        Feature positions on the seafloor, world frame, m.
    layout : SurveyLayout
    altitude_m : float
        Vehicle reference point above the seafloor (terrain following) or above the mean
        seafloor (``same_altitude``), m; > 0.
    same_altitude : bool
        The vehicle holds one height (a surface vessel) instead of following the terrain.
    seed : int
        Seed of the in-beam elevations.
    shadowing : {"off", "on"}
    pitch_deg : float
        Vehicle pitch on every line, degrees, positive nose-up (default 0: level; the survey
        design lets a vehicle that can choose it hold another).

    Returns
    -------
    views : Views
        Shapes (n, L, ...) for the L lines (true poses, world frame).
    seen : ndarray of bool, shape (n, L)
    info : dict
        ``reason`` (n, L) int8 (-1 seen, else the straight-pass rejection code, 4 = shadowed),
        ``shadowed`` (n, L) bool (views lost to shadowing only), ``heading_deg`` (L,),
        ``sensor_height_m`` (n, L): the transducer's height above the seafloor below it (the
        altimeter reading of the flat-seafloor baseline), ``along_m`` (n, L): the distance
        travelled along the line from its start (``margin_m`` before the area) to the ping abeam
        the feature (the dead-reckoning distance of :mod:`~sss_locus.experiments.passes.pass_noise`).
    """
    if shadowing not in SHADOWING:
        raise ValueError(f"shadowing must be one of {list(SHADOWING)}; got {shadowing!r}")
    if not (isinstance(altitude_m, (int, float)) and math.isfinite(altitude_m) and altitude_m > 0):
        raise ValueError(f"altitude_m must be a finite number > 0; got {altitude_m!r}")
    f = np.asarray(features, float)
    if f.ndim != 2 or f.shape[1] != 3 or not np.all(np.isfinite(f)):
        raise ValueError(f"features must be a finite array of shape (n, 3); got {f.shape}")
    heading, centre = layout.lines()
    n, L = f.shape[0], heading.size
    h = np.radians(heading)
    e = np.stack([np.cos(h), np.sin(h)], -1)
    nrm = np.stack([-np.sin(h), np.cos(h)], -1)
    rel = f[:, None, :2] - centre[None]
    across = np.einsum("nlj,lj->nl", rel, nrm)  # positive: feature to port
    along = np.einsum("nlj,lj->nl", rel, e)
    nadir = centre[None] + along[..., None] * e[None]
    if same_altitude:
        vehicle_z = np.full((n, L), float(altitude_m))
    else:
        vehicle_z = terrain.height_m(nadir[..., 0], nadir[..., 1]) + altitude_m
    rng = np.random.default_rng(seed)
    phi = (2 * rng.random((n, L)) - 1) * math.radians(platform.sonar.elevation_deg / 2)
    head = np.broadcast_to(heading, (n, L))
    ob = observe_pass(platform, (across > 0).ravel(), head.ravel(), np.abs(across).ravel(),
                      (vehicle_z - f[:, None, 2]).ravel(), float(pitch_deg), phi.ravel())
    W = ob["W"].reshape(n, L, 3, 3)
    origin = ob["origin"].reshape(n, L, 3) + f[:, None, :]
    reason = ob["reason"].reshape(n, L).astype(np.int8)
    alt_ok = (vehicle_z - f[:, None, 2]) > 0
    reason = np.where(alt_ok, reason, np.int8(1))
    seen = reason < 0
    shadowed = np.zeros((n, L), bool)
    if shadowing == "on" and seen.any():
        i, j = np.nonzero(seen)
        shadowed[i, j] = ray_blocked(terrain, origin[i, j], f[i])
        reason = np.where(shadowed, np.int8(4), reason)
        seen &= ~shadowed
    V = level_attitude_matrices(head.ravel(), np.full(n * L, float(pitch_deg))).reshape(n, L, 3, 3)
    height = origin[..., 2] - terrain.height_m(origin[..., 0], origin[..., 1])
    views = Views(W=W, origin=origin, vehicle=V, feature=f)
    start = layout.start_offset_m
    return views, seen, dict(reason=reason, shadowed=shadowed, heading_deg=heading, sensor_height_m=height,
                             along_m=np.maximum(along + start, 0.0))


def ray_blocked(terrain: Terrain, origins, targets) -> np.ndarray:
    """Whether the terrain rises above the straight ray from each origin to its target (m, world,
    shapes (p, 3)), except within ``SHADOW_CLEARANCE_M`` of the target, at ``SHADOW_SAMPLES``
    points along the ray.

    Parameters
    ----------
    terrain : Terrain
        The seafloor.
    origins : array_like
        Ray origins, world, m, shape (p, 3).
    targets : array_like
        Ray targets, world, m, shape (p, 3).

    Returns
    -------
    numpy.ndarray
        Boolean, shape (p,).
    """
    o, t = np.asarray(origins, float), np.asarray(targets, float)
    length = np.linalg.norm(t - o, axis=-1)
    stop = np.clip(1.0 - SHADOW_CLEARANCE_M / np.where(length > 0, length, 1.0), 0.0, 1.0)
    s = (np.arange(1, SHADOW_SAMPLES + 1) / (SHADOW_SAMPLES + 1))[None, :] * stop[:, None]
    pts = o[:, None, :] + s[..., None] * (t - o)[:, None, :]
    return np.any(terrain.height_m(pts[..., 0], pts[..., 1]) > pts[..., 2], axis=1)
