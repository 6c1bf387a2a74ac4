"""Mission files of a survey plan, in the formats planners import (the survey-design chapter).

Why here: the experiments layer computes plans as numbers (segments in local metres); turning
them into files a ground station reads is output, like figure export, and these files are
published beside the plan's figure with its manifest and BibTeX entry
(:func:`sss_locus.pipeline.publish.publish`, ``attachments=``), so they carry the same
provenance: commit, parameters, data files with SHA-256.

Waypoints (:func:`waypoints`): the start and end of every segment, in run order (the turns
between them are the vehicle's own). Depth is the vehicle reference point's depth below the sea
surface over the mean seafloor (``water depth - altitude``; 0 for a surface vessel).

Formats (:data:`FORMATS`):

``csv``
    ``seq, set, line, segment, point, east_m, north_m, depth_m`` (local metres), plus ``lon``,
    ``lat`` (WGS 84 degrees) when the area has an origin.
``geojson``
    RFC 7946 FeatureCollection in longitude/latitude: the area polygon and one LineString per
    segment (properties: set, line, segment, heading, length).
``plan``
    QGroundControl plan (JSON): ``fileType`` ``"Plan"``, ``mission`` with ``plannedHomePosition``
    and one ``SimpleItem`` per waypoint (``command`` 16 = MAV_CMD_NAV_WAYPOINT, ``frame`` 3 =
    global, altitude relative to home, seven ``params``: hold, acceptance radius, pass radius,
    yaw, latitude, longitude, altitude); the area polygon as an inclusion geofence.
``waypoints``
    ``QGC WPL 110`` text (Mission Planner, ArduPilot): one line per item, 12 tab-separated fields
    ``index, current, frame, command, p1, p2, p3, p4, lat, lon, alt, autocontinue``; row 0 is
    home (frame 0).

Altitude in ``plan`` and ``waypoints`` is ``-depth`` (m relative to home at the surface), the
ArduSub convention for a submerged vehicle; 0 for a surface vessel. The three geographic formats
need the area's origin and are refused in one line without it.
"""

from __future__ import annotations

import json
from collections.abc import Iterable

import numpy as np
import pandas as pd

FORMATS = ("csv", "geojson", "plan", "waypoints")
GEOGRAPHIC = ("geojson", "plan", "waypoints")
NAV_WAYPOINT = 16
#: MAV_TYPE of the vehicle in the .plan: a surface boat (11) or a submarine (12).
MAV_TYPE = {"surface": 11, "submerged": 12}


def waypoints(area, lines: pd.DataFrame, depth_m: float) -> pd.DataFrame:
    """The plan's waypoints (module docstring), with ``lon``/``lat`` when ``area`` has an origin."""
    rows = []
    for _, r in lines.iterrows():
        for point, x, y in (("start", r.x0_m, r.y0_m), ("end", r.x1_m, r.y1_m)):
            rows.append({"set": r["set"], "line": int(r.line), "segment": int(r.segment), "point": point,
                         "east_m": float(x), "north_m": float(y), "depth_m": float(depth_m)})
    out = pd.DataFrame(rows)
    out.insert(0, "seq", np.arange(len(out)))
    if area.origin_lonlat is not None:
        out["lon"], out["lat"] = area.to_lonlat(out.east_m.to_numpy(), out.north_m.to_numpy())
    return out


def _need_origin(area, fmt: str) -> None:
    if area.origin_lonlat is None:
        raise ValueError(f"format {fmt!r} needs longitude/latitude, but area {area.name!r} has no origin: "
                         "add origin_lonlat = [lon, lat] to the area file (or export csv only)")


def csv_text(points: pd.DataFrame) -> str:
    return points.to_csv(index=False, float_format="%.8f")


def geojson_text(area, lines: pd.DataFrame, properties: dict | None = None) -> str:
    _need_origin(area, "geojson")
    ring = np.asarray(area.polygon.exterior.coords)
    lon, lat = area.to_lonlat(ring[:, 0], ring[:, 1])
    holes = [np.column_stack(area.to_lonlat(*np.asarray(r.coords).T)).tolist() for r in area.polygon.interiors]
    features = [{"type": "Feature", "properties": {"name": area.name, "role": "survey area",
                                                   "origin_lonlat": list(area.origin_lonlat), **(properties or {})},
                 "geometry": {"type": "Polygon", "coordinates": [np.column_stack([lon, lat]).tolist(), *holes]}}]
    for _, r in lines.iterrows():
        lo, la = area.to_lonlat([r.x0_m, r.x1_m], [r.y0_m, r.y1_m])
        features.append({"type": "Feature",
                         "properties": {"role": "survey line", "set": r["set"], "line": int(r.line),
                                        "segment": int(r.segment), "heading_deg": float(r.heading_deg),
                                        "length_m": float(r.length_m)},
                         "geometry": {"type": "LineString", "coordinates": np.column_stack([lo, la]).tolist()}})
    return json.dumps({"type": "FeatureCollection", "features": features}, indent=1) + "\n"


def plan_text(area, points: pd.DataFrame, *, submerged: bool, speed_m_s: float) -> str:
    """QGroundControl ``.plan`` JSON (module docstring)."""
    _need_origin(area, "plan")
    home = [float(points.lat.iloc[0]), float(points.lon.iloc[0]), 0.0]
    items = [{"AMSLAltAboveTerrain": None, "Altitude": 0.0 - float(p.depth_m), "AltitudeMode": 1, "autoContinue": True,
              "command": NAV_WAYPOINT, "doJumpId": i + 1, "frame": 3,
              "params": [0, 0, 0, None, float(p.lat), float(p.lon), 0.0 - float(p.depth_m)], "type": "SimpleItem"}
             for i, p in enumerate(points.itertuples())]
    ring = np.asarray(area.polygon.exterior.coords)[:-1]
    lon, lat = area.to_lonlat(ring[:, 0], ring[:, 1])
    doc = {"fileType": "Plan", "groundStation": "QGroundControl", "version": 1,
           "geoFence": {"circles": [], "polygons": [{"inclusion": True, "polygon": np.column_stack([lat, lon]).tolist(),
                                                     "version": 1}], "version": 2},
           "mission": {"cruiseSpeed": float(speed_m_s), "firmwareType": 3, "hoverSpeed": float(speed_m_s),
                       "items": items, "plannedHomePosition": home,
                       "vehicleType": MAV_TYPE["submerged" if submerged else "surface"], "version": 2},
           "rallyPoints": {"points": [], "version": 2}}
    return json.dumps(doc, indent=4) + "\n"


def waypoints_text(area, points: pd.DataFrame) -> str:
    """``QGC WPL 110`` text (module docstring); row 0 is home at the first waypoint, at the surface."""
    _need_origin(area, "waypoints")
    rows = [(0, 1, 0, NAV_WAYPOINT, 0, 0, 0, 0, points.lat.iloc[0], points.lon.iloc[0], 0.0, 1)]
    rows += [(i + 1, 0, 3, NAV_WAYPOINT, 0, 0, 0, 0, p.lat, p.lon, 0.0 - p.depth_m, 1)
             for i, p in enumerate(points.itertuples())]
    fmt = lambda v: f"{v:.8f}" if isinstance(v, float) else str(v)  # noqa: E731
    return "QGC WPL 110\n" + "".join("\t".join(fmt(v) for v in row) + "\n" for row in rows)


def mission_files(area, lines: pd.DataFrame, *, depth_m: float, submerged: bool, speed_m_s: float,
                  formats: Iterable[str] | None = None, properties: dict | None = None) -> dict[str, str]:
    """The plan's mission files by name (``mission.csv``, ``mission.geojson``, ``mission.plan``,
    ``mission.waypoints``): ``formats`` (default: every format the area allows, the geographic
    ones only with an origin). A requested format is checked before any file is made."""
    wanted = list(formats) if formats is not None else [f for f in FORMATS
                                                         if f not in GEOGRAPHIC or area.origin_lonlat is not None]
    for f in wanted:
        if f not in FORMATS:
            raise ValueError(f"formats must be among {list(FORMATS)}; got {f!r}")
        if f in GEOGRAPHIC:
            _need_origin(area, f)
    points = waypoints(area, lines, depth_m)
    make = {"csv": lambda: csv_text(points), "geojson": lambda: geojson_text(area, lines, properties),
            "plan": lambda: plan_text(area, points, submerged=submerged, speed_m_s=speed_m_s),
            "waypoints": lambda: waypoints_text(area, points)}
    return {f"mission.{f}": make[f]() for f in wanted}
