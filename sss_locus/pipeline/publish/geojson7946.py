"""Geometry in local metres written as RFC 7946 GeoJSON (for the mission files of
:mod:`sss_locus.pipeline.publish.missions`).

RFC 7946 rules kept here: positions are ``[longitude, latitude]`` (WGS 84 degrees) rounded to
:data:`DECIMALS` decimals (about 1 cm; section 11.2 advises about 6-7); polygon exteriors
counter-clockwise and holes clockwise (section 3.1.6); a geometry that crosses the antimeridian
is cut there into a MultiLineString or MultiPolygon whose parts lie in ``[-180, 180]``
(section 3.1.9). A leg that is straight in the local frame (the vehicle's track) is not
straight in longitude/latitude: it is densified (:func:`densify`) until the straight
longitude/latitude chord between consecutive positions leaves the local straight leg by at most
:data:`MAX_DEVIATION_M`.
"""

from __future__ import annotations

import functools

import numpy as np

DECIMALS = 7
MAX_DEVIATION_M = 0.1


@functools.lru_cache(maxsize=8)
def _to_local(origin):
    from pyproj import Transformer

    return Transformer.from_crs("EPSG:4326", f"+proj=aeqd +lat_0={origin[1]} +lon_0={origin[0]} +datum=WGS84 "
                                "+units=m +no_defs", always_xy=True)


def _chord_midpoints_local(area, lon, lat):
    """Local metres of the midpoints of the lon/lat chords between consecutive positions."""
    lon_u = np.unwrap(np.asarray(lon, float), period=360.0)
    mid_lon, mid_lat = 0.5 * (lon_u[1:] + lon_u[:-1]), 0.5 * (lat[1:] + lat[:-1])
    fwd = _to_local(tuple(area.origin_lonlat))
    x, y = fwd.transform((mid_lon + 180.0) % 360.0 - 180.0, mid_lat)
    return np.column_stack([x, y])


def densify(area, xy) -> tuple[np.ndarray, np.ndarray]:
    """Longitude, latitude (degrees) of the polyline ``xy`` (local metres, ``(k, 2)``) with
    points of the local legs inserted where a lon/lat chord leaves its leg by more than
    :data:`MAX_DEVIATION_M` (each bad leg halved, up to 30 times)."""
    pts = np.asarray(xy, float)
    for _ in range(30):
        lon, lat = area.to_lonlat(pts[:, 0], pts[:, 1])
        lon, lat = np.asarray(lon, float), np.asarray(lat, float)
        mid = _chord_midpoints_local(area, lon, lat)
        true_mid = 0.5 * (pts[1:] + pts[:-1])
        bad = np.linalg.norm(mid - true_mid, axis=1) > 0.5 * MAX_DEVIATION_M
        if not bad.any():
            return lon, lat
        out = [pts[0]]
        for k in range(len(pts) - 1):
            if bad[k]:
                out.append(true_mid[k])
            out.append(pts[k + 1])
        pts = np.asarray(out)
    return lon, lat


def _round(coords) -> list:
    return [[round(float(x), DECIMALS), round(float(y), DECIMALS)] for x, y in coords]


def line_geometry(area, xy) -> dict:
    """A LineString (or, cut at the antimeridian, a MultiLineString) of the local polyline ``xy``."""
    lon, lat = densify(area, xy)
    u = np.unwrap(lon, period=360.0)
    parts, cur = [], [[u[0], lat[0]]]
    for k in range(1, len(u)):
        a, b = np.floor((u[k - 1] + 180.0) / 360.0), np.floor((u[k] + 180.0) / 360.0)
        if a != b:  # crosses lon = 180 + 360 m
            edge = 180.0 + 360.0 * min(a, b)
            t = (edge - u[k - 1]) / (u[k] - u[k - 1])
            la = lat[k - 1] + t * (lat[k] - lat[k - 1])
            cur.append([edge, la])
            parts.append(cur)
            cur = [[edge, la]]
        cur.append([u[k], lat[k]])
    parts.append(cur)
    parts = [_fix_edge(p) for p in parts]
    if len(parts) == 1:
        return {"type": "LineString", "coordinates": _round(parts[0])}
    return {"type": "MultiLineString", "coordinates": [_round(p) for p in parts]}


def _fix_edge(part) -> list:
    """Shift a part of unwrapped longitudes into [-180, 180] (its ends may sit on +-180)."""
    xs = np.array([x for x, _ in part])
    shift = 360.0 * np.round(np.mean(xs) / 360.0)
    return [[x - shift, y] for x, y in part]


def polygon_geometry(area, polygon) -> dict:
    """A Polygon (or, cut at the antimeridian, a MultiPolygon) of ``polygon`` (shapely, local
    metres), rings densified, exterior counter-clockwise, holes clockwise."""
    import shapely
    import shapely.affinity
    from shapely.geometry.polygon import orient

    rings = []
    for ring in (polygon.exterior, *polygon.interiors):
        lon, lat = densify(area, np.asarray(ring.coords))
        rings.append(np.column_stack([np.unwrap(lon, period=360.0), lat]))
    shift = 360.0 * np.round(np.mean(rings[0][:, 0]) / 360.0)
    rings = [r - [shift, 0.0] for r in rings]
    base = rings[0][:, 0]
    rings = [r - [360.0 * np.round((np.mean(r[:, 0]) - np.mean(base)) / 360.0), 0.0] for r in rings]
    poly = shapely.Polygon(rings[0], holes=rings[1:]).buffer(0)
    parts = []
    for k in (-1, 0, 1):
        piece = poly.intersection(shapely.box(-180.0 + 360.0 * k, -90.0, 180.0 + 360.0 * k, 90.0))
        for g in getattr(piece, "geoms", [piece]):
            if g.geom_type == "Polygon" and not g.is_empty:
                parts.append(orient(shapely.affinity.translate(g, -360.0 * k), 1.0))
    coords = [[_round(p.exterior.coords), *[_round(r.coords) for r in p.interiors]] for p in parts]
    if len(coords) == 1:
        return {"type": "Polygon", "coordinates": coords[0]}
    return {"type": "MultiPolygon", "coordinates": coords}
