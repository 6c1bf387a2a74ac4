"""Mission files of a survey plan, in the formats planners import (the survey-design chapter).

Why here: the experiments layer computes plans as numbers (segments in local metres); turning
them into files a ground station reads is output, like figure export, and these files are
published beside the plan's figure with its manifest and BibTeX entry
(:func:`sss_locus.pipeline.publish.publish.publish`, ``attachments=``), so they carry the same
provenance: commit, parameters, data files with SHA-256.

Waypoints (:func:`waypoints`): the whole track of
:func:`sss_locus.experiments.survey_design.route.flight_path` in flying order: the start and end
of every segment, the points of every U-turn of the platform's turn radius, and the transit
legs (inside the fence, around holes). ``kind`` says which. Depth is the vehicle reference
point's depth below the sea surface (``water depth - altitude``; 0 for a surface vessel; over a
bathymetry grid, a terrain-following vehicle's depth at each waypoint: the local depth minus
its altitude). ``course_true_deg`` is the **compass course** from a waypoint to the next:
degrees clockwise from true north (the geodesic's initial azimuth on WGS 84); the last
waypoint repeats its predecessor's. Every point is checked inside the inclusion fence and
outside the exclusion fences (:func:`~sss_locus.experiments.survey_design.route.check_inside`)
before any file is made.

Formats (:data:`FORMATS`):

``csv``
    ``seq, kind, set, line, segment, east_m, north_m, depth_m``, plus ``lon``, ``lat`` (WGS 84
    degrees) and ``course_true_deg`` when the area has an origin.
``geojson``
    RFC 7946 FeatureCollection (:mod:`sss_locus.pipeline.publish.geojson7946`: counter-clockwise
    exteriors, cut at the antimeridian, 7 decimals, densified to 0.1 m): the area, the inclusion
    fence, the exclusion fences, one LineString per segment (properties ``set, line, segment,
    course_true_deg, length_m``) and the whole track (with its ``lines_m``, ``turns_m``,
    ``transits_m`` and ``total_m``, the plan's cost: the track as flown).
``plan``
    QGroundControl plan (JSON) for an ArduPilot vehicle: ``MAV_CMD_DO_CHANGE_SPEED`` (178,
    ground speed, the survey speed) first, one ``MAV_CMD_NAV_WAYPOINT`` (16, ``frame`` 3: global,
    altitude relative to home) per waypoint, ``MAV_CMD_NAV_RETURN_TO_LAUNCH`` (20) last (the
    end-of-mission behaviour); the inclusion fence and one exclusion fence per hole.
``waypoints``
    ``QGC WPL 110`` text (Mission Planner, ArduPilot): row 0 is home (frame 0), then the same
    items as the ``.plan``; the fences are in the ``.plan`` and the GeoJSON only (this format
    has none).

The ``plan`` and ``waypoints`` formats are written only for a platform that runs ArduPilot
(``ardupilot=True``; a surface boat: ``vehicleType`` 11, MAV_TYPE_SURFACE_BOAT, altitude
0); a vehicle with its own planner (a REMUS- or Iver-class AUV) gets the CSV and GeoJSON, to
convert into its planner's own format, which this project does not write. Home is the first
waypoint (the launch point is not known). The geographic formats need the area's origin and are
refused in one line without it.
"""

from __future__ import annotations

import json
from collections.abc import Iterable

import numpy as np
import pandas as pd

from sss_locus.pipeline.publish.geojson7946 import line_geometry, polygon_geometry

FORMATS = ("csv", "geojson", "plan", "waypoints")
GEOGRAPHIC = ("geojson", "plan", "waypoints")
ARDUPILOT = ("plan", "waypoints")
NAV_WAYPOINT = 16
NAV_RETURN_TO_LAUNCH = 20
DO_CHANGE_SPEED = 178
#: MAV_TYPE of an ArduPilot surface boat in the .plan (MAV_TYPE_SURFACE_BOAT).
MAV_TYPE_SURFACE_BOAT = 11


def waypoints(area, lines: pd.DataFrame, depth_m, turn_radius_m: float):
    """The plan's waypoints (module docstring), with ``lon``/``lat``/``course_true_deg`` when
    ``area`` has an origin; also the inclusion fence and the exclusion fences (local metres).
    ``depth_m``: the vehicle's depth, m, one number or a function of local east/north metres
    (arrays) giving it at each waypoint (a terrain-following vehicle over a bathymetry grid:
    :func:`sss_locus.experiments.survey_design.front.vehicle_depth_m`)."""
    from sss_locus.experiments.survey_design.route import check_inside, flight_path

    path, fence, holes = flight_path(area, lines, turn_radius_m)
    check_inside(path, fence, holes, what=f"the track over {area.name!r}")
    depth = depth_m(path.east_m.to_numpy(), path.north_m.to_numpy()) if callable(depth_m) else \
        np.full(len(path), float(depth_m))
    out = path.assign(east_m=path.east_m.round(6) + 0.0, north_m=path.north_m.round(6) + 0.0,  # no -0.0
                      depth_m=np.round(np.asarray(depth, float), 3) + 0.0)
    out.insert(0, "seq", np.arange(len(out)))
    if area.origin_lonlat is not None:
        from pyproj import Geod

        lon, lat = area.to_lonlat(out.east_m.to_numpy(), out.north_m.to_numpy())
        out["lon"], out["lat"] = lon, lat
        az, _, _ = Geod(ellps="WGS84").inv(lon[:-1], lat[:-1], lon[1:], lat[1:])
        az = np.mod(np.asarray(az, float), 360.0)
        out["course_true_deg"] = np.append(az, az[-1:]) if len(az) else [0.0]
    return out, fence, holes


def _need_origin(area, fmt: str) -> None:
    if area.origin_lonlat is None:
        raise ValueError(f"format {fmt!r} needs longitude/latitude, but area {area.name!r} has no origin: "
                         "add origin_lonlat = [lon, lat] to the area file (or export csv only)")


def csv_text(points: pd.DataFrame) -> str:
    return points.to_csv(index=False, float_format="%.8f")


def geojson_text(area, lines: pd.DataFrame, points: pd.DataFrame, fence, holes, properties: dict | None = None) -> str:
    """RFC 7946 FeatureCollection (module docstring)."""
    from pyproj import Geod

    _need_origin(area, "geojson")
    feat = lambda geom, props: {"type": "Feature", "properties": props, "geometry": geom}  # noqa: E731
    from sss_locus.experiments.survey_design.route import track_cost

    features = [feat(polygon_geometry(area, area.polygon), {"name": area.name, "role": "survey area",
                                                           "origin_lonlat": list(area.origin_lonlat),
                                                           **({"water_depth_m": area.water_depth_m}
                                                              if area.water_depth_m is not None else {}),
                                                           **(properties or {})}),
                feat(polygon_geometry(area, fence), {"role": "inclusion fence"})]
    features += [feat(polygon_geometry(area, h), {"role": "exclusion fence", "hole": k + 1}) for k, h in enumerate(holes)]
    geod = Geod(ellps="WGS84")
    for _, r in lines.iterrows():
        lo, la = area.to_lonlat([r.x0_m, r.x1_m], [r.y0_m, r.y1_m])
        course = float(geod.inv(lo[0], la[0], lo[1], la[1])[0]) % 360.0
        features.append(feat(line_geometry(area, [[r.x0_m, r.y0_m], [r.x1_m, r.y1_m]]),
                             {"role": "survey line", "set": r["set"], "line": int(r.line), "segment": int(r.segment),
                              "course_true_deg": round(course, 3), "length_m": round(float(r.length_m), 3)}))
    features.append(feat(line_geometry(area, points[["east_m", "north_m"]].to_numpy()),
                         {"role": "track", "note": "lines, turns and transits in flying order",
                          **{k: round(v, 3) for k, v in track_cost(points).items() if k.endswith("_m")}}))
    return json.dumps({"type": "FeatureCollection", "features": features}, indent=1) + "\n"


def _items(points: pd.DataFrame, speed_m_s: float) -> list[tuple]:
    """The mission items after home: ``(command, frame, p1..p4, lat, lon, alt)``."""
    items = [(DO_CHANGE_SPEED, 2, 1.0, float(speed_m_s), -1.0, 0.0, 0.0, 0.0, 0.0)]
    items += [(NAV_WAYPOINT, 3, 0.0, 0.0, 0.0, 0.0, float(p.lat), float(p.lon), 0.0 - float(p.depth_m))
              for p in points.itertuples()]
    return items + [(NAV_RETURN_TO_LAUNCH, 2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)]


def _ring_latlon(area, polygon) -> list:
    ring = np.asarray(polygon.exterior.coords)[:-1]
    lon, lat = area.to_lonlat(ring[:, 0], ring[:, 1])
    return np.column_stack([lat, lon]).tolist()


def plan_text(area, points: pd.DataFrame, fence, holes, *, speed_m_s: float) -> str:
    """QGroundControl ``.plan`` JSON for an ArduPilot boat (module docstring)."""
    _need_origin(area, "plan")
    home = [float(points.lat.iloc[0]), float(points.lon.iloc[0]), 0.0]
    items = []
    for i, (cmd, frame, *rest) in enumerate(_items(points, speed_m_s)):
        params = [*rest[:4], *rest[4:]]
        if cmd == NAV_WAYPOINT:
            params[3] = None  # yaw: the vehicle's own
        items.append({"autoContinue": True, "command": cmd, "doJumpId": i + 1, "frame": frame, "params": params,
                      "type": "SimpleItem",
                      **({"AMSLAltAboveTerrain": None, "Altitude": params[6], "AltitudeMode": 1}
                         if cmd == NAV_WAYPOINT else {})})
    polygons = [{"inclusion": True, "polygon": _ring_latlon(area, fence), "version": 1}]
    polygons += [{"inclusion": False, "polygon": _ring_latlon(area, h), "version": 1} for h in holes]
    doc = {"fileType": "Plan", "groundStation": "QGroundControl", "version": 1,
           "geoFence": {"circles": [], "polygons": polygons, "version": 2},
           "mission": {"cruiseSpeed": float(speed_m_s), "firmwareType": 3, "hoverSpeed": float(speed_m_s),
                       "items": items, "plannedHomePosition": home, "vehicleType": MAV_TYPE_SURFACE_BOAT,
                       "version": 2},
           "rallyPoints": {"points": [], "version": 2}}
    return json.dumps(doc, indent=4) + "\n"


def waypoints_text(area, points: pd.DataFrame, *, speed_m_s: float) -> str:
    """``QGC WPL 110`` text (module docstring); row 0 is home at the first waypoint, at the surface."""
    _need_origin(area, "waypoints")
    rows = [(0, 1, 0, NAV_WAYPOINT, 0.0, 0.0, 0.0, 0.0, float(points.lat.iloc[0]), float(points.lon.iloc[0]), 0.0, 1)]
    rows += [(i + 1, 0, frame, cmd, *rest, 1) for i, (cmd, frame, *rest) in enumerate(_items(points, speed_m_s))]
    fmt = lambda v: f"{v:.8f}" if isinstance(v, float) else str(v)  # noqa: E731
    return "QGC WPL 110\n" + "".join("\t".join(fmt(v) for v in row) + "\n" for row in rows)


def default_formats(area, ardupilot: bool) -> list[str]:
    """Every format the area and the platform allow: the geographic ones only with an origin,
    ``plan`` and ``waypoints`` only for an ArduPilot vehicle."""
    return [f for f in FORMATS if (f not in GEOGRAPHIC or area.origin_lonlat is not None)
            and (f not in ARDUPILOT or ardupilot)]


def mission_files(area, lines: pd.DataFrame, *, depth_m: float, turn_radius_m: float, speed_m_s: float,
                  ardupilot: bool, formats: Iterable[str] | None = None,
                  properties: dict | None = None) -> dict[str, str]:
    """The plan's mission files by name (``mission.csv``, ``mission.geojson``, ``mission.plan``,
    ``mission.waypoints``): ``formats`` (default :func:`default_formats`). A requested format
    is checked before any file is made; an ArduPilot format for a vehicle that does not run
    ArduPilot is refused."""
    wanted = list(formats) if formats is not None else default_formats(area, ardupilot)
    for f in wanted:
        if f not in FORMATS:
            raise ValueError(f"formats must be among {list(FORMATS)}; got {f!r}")
        if f in GEOGRAPHIC:
            _need_origin(area, f)
        if f in ARDUPILOT and not ardupilot:
            raise ValueError(f"format {f!r} is an ArduPilot mission, and this vehicle does not run ArduPilot "
                             "(ardupilot=False): use csv or geojson")
    points, fence, holes = waypoints(area, lines, depth_m, turn_radius_m)
    make = {"csv": lambda: csv_text(points),
            "geojson": lambda: geojson_text(area, lines, points, fence, holes, properties),
            "plan": lambda: plan_text(area, points, fence, holes, speed_m_s=speed_m_s),
            "waypoints": lambda: waypoints_text(area, points, speed_m_s=speed_m_s)}
    return {f"mission.{f}": make[f]() for f in wanted}
