"""The survey area of the survey-design chapter: a polygon in local metres, with an optional
geographic origin.

Frames
------
Local frame: ``x`` east, ``y`` north, metres (the frame of :mod:`sss_locus.experiments.datamodel.terrain`
and :mod:`sss_locus.experiments.reconstruction.terrain_survey`). An area given in longitude/latitude (WGS 84,
degrees) is projected to it with ``pyproj`` by an azimuthal equidistant projection centred on
the area's ``origin`` (distances from the origin exact; a few-kilometre area is distorted by
well under a millimetre per metre). An area given in metres may carry an origin too; without
one, the formats that need longitude/latitude are refused (:meth:`SurveyArea.to_lonlat`).

Files (:func:`load_area`)
-------------------------
TOML::

    [area]
    name = "Harbour approach"
    vertices_m = [[0, 0], [800, 0], [800, 500], [0, 500]]    # or:
    # vertices_lonlat = [[-111.80, 40.25], ...]              # WGS 84 degrees, lon first
    origin_lonlat = [-111.80, 40.25]                         # optional with vertices_m
    water_depth_m = 12.0                                     # mean water depth over the area, m
    water_beyond_m = 50.0                                    # optional: navigable water past the edge, m
    # optional: where the vehicle may go (a walled harbour's water; default: the area, grown by
    # water_beyond_m when given, else open water) and how far it keeps off walls and holes, m:
    # navigable_m = [[-20, -20], [820, -20], [820, 520], [-20, 520]]   # or navigable_lonlat
    # wall_clearance_m = 5.0
    # or, instead of water_depth_m, a bathymetry grid (a raster in any CRS; relative to this file):
    # bathymetry = "harbour.tif"
    # bathymetry_values = "depth"                            # "depth" (positive down) or "elevation"

``water_depth_m`` (optional; also a GeoJSON feature's property) is the mean depth of the
seafloor below the sea surface over the area, which sets the altitudes a vehicle can fly; a run
may give it instead (:func:`with_water_depth`). An area without one is refused by the survey
design (no hidden default). Instead of ``water_depth_m``, ``bathymetry`` names a raster
file of the depths (a path relative to the area file; also a GeoJSON feature's property) with
``bathymetry_values`` its sign convention (``"depth"``, positive down, or ``"elevation"``, positive
up): read and checked by :mod:`sss_locus.experiments.survey_design.bathymetry` when the area is
loaded; the area's ``water_depth_m`` is then the grid's mean over the area and its
``water_depth_source`` names the file, its SHA-256 and the depths' range. **Navigable water** (:meth:`SurveyArea.water`): the area is where to survey; ``navigable_m``
(a ring in the local frame) or ``navigable_lonlat`` (WGS 84 degrees, also a GeoJSON feature's
property) is the water the vehicle may use, e.g. a walled harbour's basin (it must contain the
area; the area's holes, a pier or an island, are land within it). Lines, run-ins, turns and
transits keep ``wall_clearance_m`` off its edge and off every hole, and the mission's geofence
never reaches past it (:mod:`sss_locus.experiments.survey_design.route`). Without a
``wall_clearance_m`` in the file, :func:`load_area` takes ``survey_design.wall_clearance_m`` of
the run's data (an assumption, stated there). ``water_beyond_m`` (optional) is how far past the area's outer edge
the water is navigable: survey lines, run-ins and turns stay within it (0: the edge is a shore);
without it the water around the area is open and lines run as far as their swath reaches.

GeoJSON (RFC 7946: longitude/latitude, WGS 84): a ``Polygon``, or a ``Feature`` /
``FeatureCollection`` whose first polygon is the area; its origin is the polygon's first vertex
unless the feature's properties give ``origin_lonlat``. Holes (inner rings) are kept.

``holes_m`` (rings in metres of the local frame) may go with either kind of vertices; with
``vertices_lonlat`` they are in the frame around the origin; ``holes_lonlat`` (rings of WGS 84
degrees) goes with ``vertices_lonlat``.

Validation: the ``[area]`` table (and a GeoJSON area's coordinates and the properties above) is
validated by the data model first (:class:`sss_locus.experiments.datamodel.models.Area`: member
types, rings of finite numbers, longitudes and latitudes in range, the bounds of the numbers,
which keys go together, at most :data:`MAX_VERTICES` vertices; bounds documented in
``data/README.md``), then the polygon: every ring closed or not, at least three distinct
vertices, a valid polygon (:func:`shapely.is_valid`: no self-intersection), holes inside the
outline and not along it, an area of at least :data:`MIN_AREA_M2`, every vertex within
:data:`MAX_ORIGIN_DISTANCE_M` of the origin when there is one, in a file of at most
:data:`MAX_FILE_BYTES`, GeoJSON members of their RFC 7946 types; each refused in one line naming
the file, the key and the rule.
"""

from __future__ import annotations

import functools
import json
import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from sss_locus.experiments.datamodel import models
from sss_locus.experiments.datamodel.inputs import missing_file, read_toml
from sss_locus.experiments.datamodel.sourced import checked, validated
from sss_locus.experiments.survey_design.settings import load_settings

MIN_AREA_M2 = 100.0
"""Smallest area accepted, m^2 (10 m x 10 m): smaller is taken for a unit mistake."""
MAX_VERTICES = models.MAX_VERTICES
"""Most vertices (all rings) an area may have (:data:`sss_locus.experiments.datamodel.models.MAX_VERTICES`)."""
MIN_CLEARANCE_M = 0.5
"""Least clearance off the navigable water's edge, m, whatever ``wall_clearance_m`` says: a track
on the fence itself would leave it by the mission files' coordinate rounding (1e-7 degrees)."""
MAX_FILE_BYTES = 16_000_000
"""Largest area file read, bytes (a file of :data:`MAX_VERTICES` vertices is about 4 MB)."""
MAX_ORIGIN_DISTANCE_M = 100_000.0
"""Farthest a vertex may lie from ``origin_lonlat``, metres: the azimuthal equidistant projection
keeps distances from the origin exact and distorts others by about (d / 6371 km)^2 / 6, under
4e-5 (4 cm per km) within 100 km; thousands of km away a 900 m line would come out 676 m."""


@functools.lru_cache(maxsize=32)
def _projection(origin_lonlat):
    """Forward and inverse transformers of the area's local frame (cached: making one costs ~25 ms)."""
    from pyproj import Transformer

    lon, lat = origin_lonlat
    local = f"+proj=aeqd +lat_0={lat} +lon_0={lon} +datum=WGS84 +units=m +no_defs"
    fwd = Transformer.from_crs("EPSG:4326", local, always_xy=True)
    inv = Transformer.from_crs(local, "EPSG:4326", always_xy=True)
    return fwd, inv


def _check_origin(origin, where: str):
    if origin is None:
        return None
    return checked(models.LonLat, _plain(origin), f"{where}: origin_lonlat")


def _plain(value):
    """``value`` with its numpy arrays as (nested) lists, for the data model's checks."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


def _ring(kind, ring, where: str) -> np.ndarray:
    """``ring`` checked as the data model's ``kind`` (e.g. ``LocalRing``), as a (k, 2) array."""
    return np.asarray(checked(kind, _plain(ring), where), float).reshape(-1, 2)


def _rings(kind, rings, where: str) -> list[np.ndarray]:
    """``rings`` checked as the data model's ``kind`` (e.g. ``LocalRings``), as (k, 2) arrays."""
    return [np.asarray(r, float).reshape(-1, 2) for r in checked(kind, _plain(rings), where)]


def _check_vertex_count(rings, where: str) -> None:
    why = models.too_many_vertices(rings)
    if why:
        raise ValueError(f"{where}: {why}")


@dataclass(frozen=True)
class SurveyArea:
    """A survey area (see the module docstring).

    Attributes
    ----------
    polygon : shapely.Polygon
        In the local frame, metres.
    origin_lonlat : tuple of float or None
        Longitude, latitude (degrees, WGS 84) of the local origin; ``None``: metres only.
    name : str
    source : str
        Where it was read from (a file path, or ``"vertices"``).
    sha256 : str
        SHA-256 of the file it was read from (``""`` if none).
    path : str
        That file, found (:func:`load_area`; ``""`` if none).
    water_depth_m : float or None
        Mean water depth over the area, m (``None``: not given).
    water_depth_source : str
        Where the depth comes from (the area file, a run parameter).
    water_beyond_m : float or None
        Navigable water past the outer edge, m (``None``: open water).
    navigable_wkt : str
        The navigable water's outline (WKT, local metres), ``""``: see :meth:`water`.
    wall_clearance_m : float or None
        How far the vehicle keeps off the navigable water's edge and the holes, m (``None``: not
        given; :func:`load_area` then takes the run's ``survey_design.wall_clearance_m``).
    bathymetry : tuple
        ``()``, or the bathymetry grid's ``(path found, file as published, SHA-256, values)``.
    """

    polygon: object
    origin_lonlat: tuple[float, float] | None = None
    name: str = "survey area"
    source: str = "vertices"
    sha256: str = ""
    path: str = ""
    water_depth_m: float | None = None
    water_depth_source: str = ""
    water_beyond_m: float | None = None
    bathymetry: tuple = ()
    navigable_wkt: str = ""
    wall_clearance_m: float | None = None

    @property
    def clearance_m(self) -> float:
        """The clearance the track keeps in navigable water, m: ``wall_clearance_m``, at least
        :data:`MIN_CLEARANCE_M`."""
        return max(self.wall_clearance_m or 0.0, MIN_CLEARANCE_M)

    def water(self):
        """The navigable water (a shapely Polygon, local metres, the area's holes cut out): the
        ``navigable`` outline, else the area's outer ring grown by ``water_beyond_m``; ``None``
        when neither is given (open water).

        Returns
        -------
        shapely.Polygon or shapely.MultiPolygon or None
            The navigable water in local metres, or ``None`` (open water).
        """
        import shapely

        if self.navigable_wkt:
            outline = shapely.from_wkt(self.navigable_wkt)
        elif self.water_beyond_m is not None:
            outline = shapely.Polygon(self.polygon.exterior).buffer(self.water_beyond_m, quad_segs=4)
        else:
            return None
        holes = [shapely.Polygon(r) for r in self.polygon.interiors]
        return outline.difference(shapely.union_all(holes)) if holes else outline

    @property
    def area_m2(self) -> float:
        return float(self.polygon.area)

    def to_lonlat(self, x, y) -> tuple[np.ndarray, np.ndarray]:
        """Local east/north metres to longitude/latitude degrees; refused without an origin.

        Parameters
        ----------
        x : array_like
            Local east, m.
        y : array_like
            Local north, m (same shape).

        Returns
        -------
        lon, lat : numpy.ndarray
            Longitude and latitude, degrees, the input shape.

        Raises
        ------
        ValueError
            The area has no ``origin_lonlat``.
        """
        if self.origin_lonlat is None:
            raise ValueError(f"area {self.name!r} has no origin: longitude/latitude outputs need "
                             "origin_lonlat = [lon, lat] in the area file")
        _, inv = _projection(tuple(self.origin_lonlat))
        lon, lat = inv.transform(np.asarray(x, float), np.asarray(y, float))
        return np.asarray(lon), np.asarray(lat)

    def to_local(self, lon, lat) -> tuple[np.ndarray, np.ndarray]:
        """Longitude/latitude degrees to local east/north metres; refused without an origin.

        Parameters
        ----------
        lon : array_like
            Longitude, degrees.
        lat : array_like
            Latitude, degrees (same shape).

        Returns
        -------
        x, y : numpy.ndarray
            Local east and north, m, the input shape.

        Raises
        ------
        ValueError
            The area has no ``origin_lonlat``.
        """
        if self.origin_lonlat is None:
            raise ValueError(f"area {self.name!r} has no origin: longitude/latitude need origin_lonlat = [lon, lat]")
        fwd, _ = _projection(tuple(self.origin_lonlat))
        x, y = fwd.transform(np.asarray(lon, float), np.asarray(lat, float))
        return np.asarray(x), np.asarray(y)

    def input_files(self) -> list[tuple[str, str]]:
        """The files this area was read from, as a figure's manifest records them.

        Returns
        -------
        list of (str, str)
            ``(path, role)``: the area file (role ``"area"``) and, when it names one, its
            bathymetry grid (role ``"bathymetry"``); empty for an area made from vertices.
        """
        files = [(self.path, "area")] if self.path else []
        if self.bathymetry and self.bathymetry[0]:
            files.append((self.bathymetry[0], "bathymetry"))
        return files

    def key(self) -> dict:
        """A JSON-able description (for caches and manifests).

        Returns
        -------
        dict
            Name, polygon WKT (local metres), origin (degrees), source, SHA-256, water depth (m) and
            its source, ``water_beyond_m``, bathymetry, navigable WKT and ``wall_clearance_m``;
            :func:`area_from_key` inverts it.
        """
        return {"name": self.name, "wkt": self.polygon.wkt, "origin_lonlat": self.origin_lonlat,
                "source": self.source, "sha256": self.sha256, "water_depth_m": self.water_depth_m,
                "water_depth_source": self.water_depth_source, "water_beyond_m": self.water_beyond_m,
                "bathymetry": list(self.bathymetry), "navigable_wkt": self.navigable_wkt,
                "wall_clearance_m": self.wall_clearance_m}


def _check_holes(rings, where: str) -> None:
    """Refuse, naming the ring, an outline that crosses itself, a hole that crosses itself, one
    not inside the outline, or one that shares a stretch of the outline (a pier from the wall:
    a notch of the outline, not a hole). Holes are counted from 1 in the order given."""
    import shapely

    shell = shapely.Polygon(rings[0])
    if not shell.is_valid:
        raise ValueError(f"{where}: the polygon is not valid ({shapely.is_valid_reason(shell)}); "
                         "vertices must go round the boundary once without crossing it")
    for k, ring in enumerate(rings[1:], 1):
        hole = shapely.Polygon(ring)
        if not hole.is_valid:
            raise ValueError(f"{where}: hole {k} is not valid ({shapely.is_valid_reason(hole)}); its vertices "
                             "must go round it once without crossing it")
        if not shell.contains(hole):
            out = hole.difference(shell).area / hole.area
            raise ValueError(f"{where}: hole {k} is not inside the area's outline ({out:.0%} of it lies outside); "
                             "a hole (a pier, an island) must lie within the area")
        if hole.boundary.intersection(shell.boundary).length > 0:
            raise ValueError(f"{where}: hole {k} runs along the area's outline; a pier or a wall that reaches the "
                             "edge is a notch of the outline (draw the outline round it), not a hole")


def area_from_vertices(vertices_m, *, origin_lonlat=None, holes_m=(), name: str = "survey area",
                       source: str = "vertices") -> SurveyArea:
    """A :class:`SurveyArea` from local vertices (metres, ``(k, 2)``), validated.

    Parameters
    ----------
    vertices_m : array_like
        The outer ring, shape (k, 2), local east/north metres, k >= 3 distinct vertices (a closing
        repeat of the first vertex is dropped).
    origin_lonlat : sequence of float or None
        ``[lon, lat]`` (degrees) of the local origin; ``None`` for a purely local area.
    holes_m : sequence of array_like
        Inner rings (islands, exclusions), each (k_i, 2), local metres.
    name : str
        The area's name.
    source : str
        Where the vertices came from (named in the errors).

    Returns
    -------
    SurveyArea
        The validated area (polygon in local metres).

    Raises
    ------
    ValueError
        Too few or non-finite vertices, an invalid polygon, an area below :data:`MIN_AREA_M2`, or a
        vertex farther than :data:`MAX_ORIGIN_DISTANCE_M` from a given origin.
    """
    import shapely

    where = source if source != "vertices" else "area"
    holes = _plain(holes_m)
    _check_vertex_count([vertices_m, *(holes if isinstance(holes, list) else [])], where)
    clean = []
    for v in [_ring(models.LocalRing, vertices_m, f"{where}: vertices"),
              *_rings(models.LocalRings, holes, f"{where}: holes_m")]:
        if len(v) > 1 and np.array_equal(v[0], v[-1]):
            v = v[:-1]
        if len(np.unique(v, axis=0)) < 3:
            raise ValueError(f"{where}: a polygon needs at least 3 distinct vertices; got {len(np.unique(v, axis=0))}")
        clean.append(v)
    _check_holes(clean, where)
    poly = shapely.Polygon(clean[0], holes=clean[1:])
    if not poly.is_valid:
        raise ValueError(f"{where}: the polygon is not valid ({shapely.is_valid_reason(poly)}); "
                         "vertices must go round the boundary once without crossing it")
    if poly.area < MIN_AREA_M2:
        raise ValueError(f"{where}: the polygon's area is {poly.area:.3g} m^2, below {MIN_AREA_M2:g} m^2 "
                         "(are the vertices in metres?)")
    origin = _check_origin(origin_lonlat, where)
    reach = float(np.max(np.hypot(*np.vstack(clean).T)))
    if origin is not None and reach > MAX_ORIGIN_DISTANCE_M * (1 + 1e-9):
        raise ValueError(f"{where}: a vertex lies {reach / 1000:,.0f} km from the local origin (origin_lonlat "
                         f"{list(origin)}); with an origin every vertex must be within {MAX_ORIGIN_DISTANCE_M / 1000:g} km "
                         "of it (the local frame's distortion grows with the distance)")
    return SurveyArea(poly, origin, str(name), source)


def area_from_lonlat(vertices_lonlat, origin_lonlat=None, *, holes_lonlat=(), holes_m=(),
                     name: str = "survey area", source: str = "vertices") -> SurveyArea:
    """A :class:`SurveyArea` from longitude/latitude vertices (degrees); the origin defaults to
    the first vertex. Holes may be given in longitude/latitude (``holes_lonlat``) or in metres
    of the local frame around the origin (``holes_m``). Every vertex must lie within
    :data:`MAX_ORIGIN_DISTANCE_M` of the origin.

    Parameters
    ----------
    vertices_lonlat : array_like
        The outer ring, shape (k, 2), ``[lon, lat]`` degrees.
    origin_lonlat : sequence of float or None
        ``[lon, lat]`` (degrees) of the local origin; ``None``: the first vertex.
    holes_lonlat : sequence of array_like
        Inner rings in degrees, each (k_i, 2).
    holes_m : sequence of array_like
        Inner rings in local metres around the origin, each (k_i, 2).
    name : str
        The area's name.
    source : str
        Where the vertices came from (named in the errors).

    Returns
    -------
    SurveyArea
        The area, polygon projected to local east/north metres (transverse Mercator at the origin).

    Raises
    ------
    ValueError
        Bad coordinates, or a vertex farther than :data:`MAX_ORIGIN_DISTANCE_M` from the origin.
    """
    import pyproj

    holes = _plain(holes_lonlat)
    _check_vertex_count([vertices_lonlat, *(holes if isinstance(holes, list) else []),
                         *(holes_m if isinstance(holes_m, (list, tuple)) else ())], source)
    rings = [_ring(models.LonLatRing, vertices_lonlat, f"{source}: vertices_lonlat"),
             *_rings(models.LonLatRings, holes, f"{source}: holes_lonlat")]
    origin = _check_origin(rings[0][0] if origin_lonlat is None else origin_lonlat, source)
    every = np.vstack(rings)
    _, _, dist = pyproj.Geod(ellps="WGS84").inv(np.full(len(every), origin[0]), np.full(len(every), origin[1]),
                                                 every[:, 0], every[:, 1])
    far = int(np.argmax(dist))
    if dist[far] > MAX_ORIGIN_DISTANCE_M:
        raise ValueError(f"{source}: vertex {every[far].tolist()} lies {dist[far] / 1000:,.0f} km from origin_lonlat "
                         f"{list(origin)}; every vertex must be within {MAX_ORIGIN_DISTANCE_M / 1000:g} km of it "
                         "(the local frame's distortion grows with the distance); put the origin in the area")
    fwd, _ = _projection(origin)
    local = [np.stack(fwd.transform(r[:, 0], r[:, 1]), -1) for r in rings]
    return area_from_vertices(local[0], origin_lonlat=origin, holes_m=[*local[1:], *holes_m], name=name,
                              source=source)


def _member(doc: dict, key: str, kind: type, source: str, where: str):
    """``doc[key]`` if it is absent/None (returned as None) or of type ``kind``, else a one-line
    refusal naming the member and the type found."""
    value = doc.get(key)
    if value is not None and not isinstance(value, kind):
        raise ValueError(f"{source}: GeoJSON {where}{key!r} must be {_KIND_NAMES[kind]}; got "
                         f"{type(value).__name__} {value!r:.60}")
    return value


_KIND_NAMES = {dict: "an object", list: "an array", str: "a string"}


def _from_geojson(doc, source: str) -> SurveyArea:
    geom, props = doc, {}
    if doc.get("type") == "FeatureCollection":
        features = _member(doc, "features", list, source, "") or []
        for i, f in enumerate(features):
            if not isinstance(f, dict):
                raise ValueError(f"{source}: GeoJSON features[{i}] must be an object (a Feature); got "
                                 f"{type(f).__name__} {f!r:.60}")
            _member(f, "geometry", dict, source, f"features[{i}].")
        polys = [f for f in features if (f.get("geometry") or {}).get("type") == "Polygon"]
        if not polys:
            raise ValueError(f"{source}: the FeatureCollection holds no Polygon feature")
        doc = polys[0]
    if doc.get("type") == "Feature":
        geom = _member(doc, "geometry", dict, source, "Feature.") or {}
        props = _member(doc, "properties", dict, source, "Feature.") or {}
    if geom.get("type") != "Polygon" or not geom.get("coordinates"):
        raise ValueError(f"{source}: expected a GeoJSON Polygon (or a Feature of one); got type {geom.get('type')!r}")
    rings = geom["coordinates"]
    if not isinstance(rings, list) or not all(isinstance(r, list) for r in rings):
        raise ValueError(f"{source}: GeoJSON Polygon 'coordinates' must be an array of rings (arrays of "
                         f"[longitude, latitude] positions); got {rings!r:.60}")
    table = {k: props[k] for k in _PROPERTIES if k in props}  # other properties are the user's own
    area = _table(models.Area, {**table, "vertices_lonlat": rings[0], "holes_lonlat": rings[1:]}, source, "")
    return _from_table(area, str(props.get("name", Path(source).stem)), source)


#: The properties of a GeoJSON area read as the keys of an area file's ``[area]`` table.
_PROPERTIES = ("origin_lonlat", "water_depth_m", "water_beyond_m", "bathymetry", "bathymetry_values", "navigable_m",
               "navigable_lonlat", "wall_clearance_m")


def _table(model, doc, source: str, where: str):
    """``doc`` validated by the data model's ``model`` (a refusal names the file ``source``)."""
    try:
        return validated(model, doc, where)
    except ValueError as exc:
        raise ValueError(f"{source}: {exc}") from None


def _from_table(table: models.Area, name: str, source: str) -> SurveyArea:
    """The area of a validated ``[area]`` table (its polygon checked, its navigable water placed)."""
    if table.vertices_m is not None:
        area = area_from_vertices(table.vertices_m, origin_lonlat=table.origin_lonlat, holes_m=table.holes_m,
                                  name=name, source=source)
    else:
        area = area_from_lonlat(table.vertices_lonlat, table.origin_lonlat, holes_m=table.holes_m,
                                holes_lonlat=table.holes_lonlat, name=name, source=source)
    area = _navigable_from(area, table, source)
    if table.bathymetry is not None:  # found and read by load_area
        area = replace(area, bathymetry=(table.bathymetry, table.bathymetry, "", table.bathymetry_values))
    if table.water_beyond_m is not None:
        area = replace(area, water_beyond_m=table.water_beyond_m)
    if table.water_depth_m is None:
        return area
    return with_water_depth(area, table.water_depth_m, f"{source}: water_depth_m")


def _navigable_from(area: SurveyArea, table: models.Area, source: str) -> SurveyArea:
    """``area`` with the navigable water and the wall clearance of ``table`` (module docstring)."""
    import shapely

    if table.wall_clearance_m is not None:
        area = replace(area, wall_clearance_m=table.wall_clearance_m)
    key = "navigable_m" if table.navigable_m is not None else "navigable_lonlat"
    ring = getattr(table, key)
    if ring is None:
        return area
    if key == "navigable_lonlat":  # the table has an origin (models.Area)
        ring = np.column_stack(area.to_local(*np.asarray(ring, float).T))
    water = area_from_vertices(ring, source=f"{source}: {key}").polygon
    outside = area.polygon.difference(water.buffer(1e-6))
    if not outside.is_empty:
        far = max(shapely.Point(q).distance(water) for q in shapely.get_coordinates(outside))
        raise ValueError(f"{source}: the navigable water must contain the area; {outside.area:.0f} m^2 of the area lie "
                         f"outside it, up to {far:.1f} m")
    return replace(area, navigable_wkt=water.wkt)


def with_water_depth(area: SurveyArea, depth_m, source: str) -> SurveyArea:
    """``area`` with its mean water depth ``depth_m`` (m, in (0, 12000]) from ``source``; a bad
    value is refused in one line naming ``source``.

    Parameters
    ----------
    area : SurveyArea
        The area (without a bathymetry grid).
    depth_m : float
        Mean water depth, m, in (0, 12000].
    source : str
        Where the depth came from (recorded in ``water_depth_source``).

    Returns
    -------
    SurveyArea
        A copy with ``water_depth_m`` and ``water_depth_source``.

    Raises
    ------
    ValueError
        A bad depth, or an area with a bathymetry grid.
    """
    if area.bathymetry:
        raise ValueError(f"{source}: the area {area.name!r} gives a bathymetry grid ({area.bathymetry[1]}), whose depths "
                         "are used; drop this water depth")
    return replace(area, water_depth_m=checked(models.WaterDepthM, depth_m, source), water_depth_source=source)


def load_area(path: str | Path) -> SurveyArea:
    """Read a survey area from a TOML or GeoJSON file (see the module docstring). A relative path
    is looked up from the working directory, then from the repository's root (so the
    shipped ``data/examples/survey_area.toml`` is found from any run). The area records the
    file's SHA-256 (``sha256``), where it was found (``path``) and, in ``source`` and
    ``water_depth_source``, the file as published (:func:`sss_locus.paths.public_path`: its
    repository path, else its name only).

    Parameters
    ----------
    path : str or pathlib.Path
        A ``.toml`` or ``.geojson`` area file.

    Returns
    -------
    SurveyArea
        The area (local metres), with ``source``, ``sha256``, ``path`` and, when given, its water
        depth or bathymetry grid and wall clearance.

    Raises
    ------
    ValueError
        A missing, too large or invalid file, in one line naming it.
    """
    import hashlib

    from sss_locus.paths import REPO_ROOT, public_path

    p = Path(path).expanduser()
    if not p.is_absolute():
        tries = [Path.cwd(), REPO_ROOT]  # a run's kernel gets it resolved (pipeline.run.userfiles)
        p = next((d / p for d in tries if (d / p).is_file()), p)
    if not p.is_file():
        raise ValueError(missing_file(path if str(path).strip() else "", "area file"))
    if p.stat().st_size > MAX_FILE_BYTES:
        raise ValueError(f"area file {path} has {p.stat().st_size:,} bytes, more than {MAX_FILE_BYTES:,}; "
                         f"an area needs at most {MAX_VERTICES:,} vertices: simplify its boundary")
    area = _load_area(p, str(path))  # its errors name the file as given
    shown = public_path(p.resolve())  # what captions, pages and manifests name: never a local absolute path
    depth_source = f"{shown}: water_depth_m" if area.water_depth_source else ""
    if area.water() is not None and area.wall_clearance_m is None:  # walls: the run's clearance
        area = replace(area, wall_clearance_m=float(load_settings()["wall_clearance_m"]))
    if area.bathymetry:  # the grid beside the area file, read and checked now
        from sss_locus.experiments.survey_design.bathymetry import load_bathymetry

        grid = (p.parent / Path(area.bathymetry[0]).expanduser()).resolve()
        grid_shown = public_path(grid)
        b = load_bathymetry(grid, area.bathymetry[3], area, shown=grid_shown)
        area = replace(area, bathymetry=(str(grid), grid_shown, b.sha256, b.values), water_depth_m=b.mean_m)
        depth_source = b.describe()
    return replace(area, source=shown, water_depth_source=depth_source,
                   sha256=hashlib.sha256(p.read_bytes()).hexdigest(), path=str(p.resolve()))


def _load_area(p: Path, source: str) -> SurveyArea:
    if p.suffix.lower() in (".geojson", ".json"):
        try:
            doc = json.loads(p.read_text(encoding="utf-8-sig"))
        except ValueError as exc:
            raise ValueError(f"{source} is not valid JSON: {exc}") from None
        except RecursionError:
            raise ValueError(f"{source}: the JSON is nested too deeply to be a GeoJSON area (a Polygon "
                             "nests three arrays)") from None
        if not isinstance(doc, dict):
            raise ValueError(f"{source}: a GeoJSON object is expected")
        return _from_geojson(doc, source)
    doc = read_toml(p)
    if not isinstance(doc.get("area"), dict):
        raise ValueError(f"{source}: missing table [area] (with vertices_m or vertices_lonlat)")
    table = _table(models.AreaFile, doc, source, "").area
    return _from_table(table, p.stem if table.name is None else table.name, source)


def area_from_key(key: dict) -> SurveyArea:
    """The area of :meth:`SurveyArea.key` (its polygon from the WKT), validated again.

    Parameters
    ----------
    key : dict
        The output of :meth:`SurveyArea.key`.

    Returns
    -------
    SurveyArea
        The same area (``path`` not kept).
    """
    import shapely

    poly = shapely.from_wkt(key["wkt"])
    area = area_from_vertices(np.asarray(poly.exterior.coords), origin_lonlat=key.get("origin_lonlat"),
                              holes_m=[np.asarray(r.coords) for r in poly.interiors],
                              name=key.get("name", "survey area"), source=key.get("source", "vertices"))
    return replace(area, sha256=key.get("sha256", ""), water_depth_m=key.get("water_depth_m"),
                   water_depth_source=key.get("water_depth_source", ""), water_beyond_m=key.get("water_beyond_m"),
                   bathymetry=tuple(key.get("bathymetry", ())), navigable_wkt=key.get("navigable_wkt", ""),
                   wall_clearance_m=key.get("wall_clearance_m"))


def principal_heading_deg(area: SurveyArea) -> float:
    """Heading (degrees from east, counter-clockwise, in [0, 180)) of the long side of the area's
    minimum rotated rectangle: the direction of the fewest, longest lines.

    Parameters
    ----------
    area : SurveyArea
        The area (local metres).

    Returns
    -------
    float
        Heading, degrees counter-clockwise from east, in [0, 180).
    """
    rect = np.asarray(area.polygon.minimum_rotated_rectangle.exterior.coords)[:4]
    sides = np.diff(np.vstack([rect, rect[:1]]), axis=0)
    long = sides[np.argmax(np.hypot(sides[:, 0], sides[:, 1]))]
    return float(math.degrees(math.atan2(long[1], long[0])) % 180.0)
