"""Towed sensors: the towfish's position from the ship's, its heading and the layback (numbers only).

A sightings table may carry ``layback_m`` (>= 0): its position columns are then the tow
point's (the ship's), and the sensor is ``layback_m`` metres behind it, horizontally, along
the sensor's heading (Triton's XTF description of ``Layback``: "distance over ground from ship
to fish ... the sensor position is then computed using the current sensor heading and this
layback value"). :func:`apply_layback` moves the reference point there in the local frame.

In an XTF file (:func:`xtf_layback`) the layback is ``Layback`` where it is not 0, else the
horizontal length of a straight cable ``CableOut`` (+ ``CableOutHundredths``) from the surface
to the fish at ``SensorDepth``, ``sqrt(cable^2 - depth^2)`` (an upper bound: a real cable
sags). Some recorders already write the towfish's position into ``SensorX/Ycoordinate`` and
the ship's into ``ShipX/Ycoordinate``; such a file is recognised (the two positions lie about
the layback apart) and not shifted twice. ``towfish``:

``"auto"`` (default)
    no layback: the sensor position as recorded; sensor and ship positions the same (or no
    ship position): shifted by the layback; about the layback apart: already the towfish's;
    anything else is refused, with the ping named and how to choose;
``"recorded"``
    ``SensorX/Ycoordinate`` is the towfish's position (never shifted);
``"apply_layback"``
    ``SensorX/Ycoordinate`` is the tow point's; always shifted by the layback.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

CHOICES = ("auto", "recorded", "apply_layback")
SAME_M = 0.5
"""Sensor and ship positions closer than this (m) are the same point."""


def xtf_layback(ping, nav_units: int) -> tuple[float, str, float]:
    """The layback (m) of one XTF ping, where it comes from (``"Layback"``, ``"CableOut"`` or
    ``""``), and the horizontal distance (m) between its sensor and ship positions (NaN when
    the ship position is not recorded).

    Parameters
    ----------
    ping : pyxtf.XTFPingHeader
        The ping (``Layback``, ``CableOut``, ``SensorDepth``, sensor and ship positions).
    nav_units : int
        The file's ``NavUnits``: 3 longitude/latitude degrees (geodesic distance on WGS84), else
        metres.

    Returns
    -------
    layback : float
        m, >= 0 (0 when neither field is given).
    source : str
        ``"Layback"``, ``"CableOut"`` or ``""``.
    apart_m : float
        Sensor-to-ship distance, m; NaN without a ship position.
    """
    cable = float(ping.CableOut) + float(getattr(ping, "CableOutHundredths", 0)) / 100.0
    if np.isfinite(ping.Layback) and ping.Layback > 0:
        layback, source = float(ping.Layback), "Layback"
    elif cable > 0:
        layback, source = float(np.sqrt(max(cable ** 2 - float(ping.SensorDepth) ** 2, 0.0))), "CableOut"
    else:
        layback, source = 0.0, ""
    sx, sy, shx, shy = (float(v) for v in (ping.SensorXcoordinate, ping.SensorYcoordinate,
                                           ping.ShipXcoordinate, ping.ShipYcoordinate))
    if not all(np.isfinite([shx, shy])) or (shx == 0.0 and shy == 0.0):
        return layback, source, np.nan
    if nav_units == 3:
        from pyproj import Geod

        if not (abs(sy) <= 90 and abs(shy) <= 90):
            return layback, source, np.nan
        return layback, source, float(Geod(ellps="WGS84").inv(sx, sy, shx, shy)[2])
    return layback, source, float(np.hypot(sx - shx, sy - shy))


def towfish_decision(layback: float, apart_m: float, choice: str) -> tuple[float, str]:
    """The layback still to apply (m) and how the sensor position was read (``choice`` of
    :data:`CHOICES`); ``ValueError`` (without a location) when ``"auto"`` cannot tell.

    Parameters
    ----------
    layback : float
        The ping's layback, m.
    apart_m : float
        Sensor-to-ship distance, m (NaN: unknown).
    choice : str
        One of :data:`CHOICES`.

    Returns
    -------
    shift_m : float
        Layback still to apply, m (0 when the position is already the towfish's).
    how : str
        How the position was read, in words.

    Raises
    ------
    ValueError
        Unknown ``choice``, or ``"auto"`` when the distances disagree.
    """
    if choice not in CHOICES:
        raise ValueError(f"towfish must be one of {list(CHOICES)}; got {choice!r}")
    if layback <= 0 or choice == "recorded":
        return 0.0, "recorded"
    if choice == "apply_layback" or not np.isfinite(apart_m) or apart_m < SAME_M:
        return layback, "shifted by the layback"
    if abs(apart_m - layback) <= max(1.0, 0.2 * layback):
        return 0.0, "recorded (already the towfish's)"
    raise ValueError(f"SensorX/Ycoordinate is {apart_m:.3g} m from ShipX/Ycoordinate but the layback is {layback:.3g} m: "
                     "cannot tell whether the sensor position is the towfish's; set -p towfish '\"recorded\"' "
                     "(it is) or '\"apply_layback\"' (it is the tow point's)")


def apply_layback(table: pd.DataFrame) -> pd.DataFrame:
    """Move each sighting's reference point ``layback_m`` behind the given position along its
    grid heading (local frame: ``east_m``, ``north_m``, ``grid_heading_deg``); the given
    position is kept as ``tow_east_m``, ``tow_north_m``. A table without ``layback_m`` is
    returned as it is.

    Parameters
    ----------
    table : pandas.DataFrame
        Sightings in the local frame (``east_m``, ``north_m``, ``grid_heading_deg`` clockwise from
        grid north, ``layback_m`` m).

    Returns
    -------
    pandas.DataFrame
        A copy with the moved ``east_m``/``north_m`` and ``tow_east_m``/``tow_north_m``; the input
        itself without ``layback_m``.
    """
    if "layback_m" not in table.columns:
        return table
    t = table.copy()
    lb = t["layback_m"].to_numpy(float)
    h = np.radians(t["grid_heading_deg"].to_numpy(float))
    t["tow_east_m"], t["tow_north_m"] = t["east_m"], t["north_m"]
    t["east_m"] = t["east_m"].to_numpy(float) - lb * np.sin(h)
    t["north_m"] = t["north_m"].to_numpy(float) - lb * np.cos(h)
    return t
