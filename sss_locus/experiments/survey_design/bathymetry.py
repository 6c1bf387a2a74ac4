"""A bathymetry grid of a survey area: the water depth under every point, from a raster file.

The area file names it (:mod:`sss_locus.experiments.survey_design.area`)::

    bathymetry = "harbour.tif"        # a single-band raster (GeoTIFF, ...), path relative to the area file
    bathymetry_values = "depth"       # "depth": metres below the sea surface, positive down;
                                      # "elevation": metres above the sea surface, negative in the water

Reading (:func:`load_bathymetry`): the raster's band 1, in any CRS the file declares, is
reprojected with :func:`rasterio.warp.reproject` (bilinear; nodata cells, and NaN, take no part)
onto a square grid in the area's local frame (the azimuthal equidistant projection about its
``origin_lonlat``, east/north metres): the area's bounding box widened by a quarter of its size
plus 100 m, at the raster's own resolution (no finer than :data:`MAX_CELLS` cells allow, no
coarser than a tenth of the area's smaller side). Where that grid has no value (land, nodata,
beyond the raster) it takes the depth of the nearest cell that has one (only the vehicle's
positions outside the area read those: a terrain-following AUV's altitude); beyond the grid, the
depth of its nearest edge cell.

Checks, each a one-line error naming the file, before any plan is made: the file opens as a
raster with a CRS; the area has an ``origin_lonlat`` (to place the local frame on the globe);
band 1 holds some value; every grid cell inside the area has a value (the raster covers the
area); every depth over the area is in (0, :data:`MAX_DEPTH_M`] m (a grid of the other sign
convention is named as such).

The depth used (:class:`Bathymetry`): the design's seafloor is ``z = h(x, y) = mean - depth(x,
y)`` (``z`` up, ``z = 0`` the mean seafloor over the area, the sea surface at ``z = mean``), a
:class:`~sss_locus.experiments.datamodel.terrain.Terrain` of kind ``"bathymetry"`` (:meth:`Bathymetry.terrain`):
the swath of a surface vessel at each cell follows that cell's depth, a terrain-following AUV
flies its altitude above the local seafloor and its depth rating is checked against the
shallowest and deepest points.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from sss_locus.experiments.datamodel import models
from sss_locus.experiments.datamodel.sourced import checked

VALUES = models.BATHYMETRY_VALUES
"""``bathymetry_values``: ``depth`` (positive down) or ``elevation`` (positive up, negative in water)."""
MAX_DEPTH_M = 12000.0
"""Deepest depth accepted, m."""
MAX_CELLS = 1_000_000
"""Most cells of the local grid a raster is reprojected onto."""


@dataclass(frozen=True, eq=False)
class Bathymetry:
    """A bathymetry grid in an area's local frame (module docstring).

    Attributes
    ----------
    file : str
        The raster as published (its repository path, else its name).
    sha256 : str
        SHA-256 of the raster's bytes.
    values : str
        One of :data:`VALUES`, as the area file gave it.
    x0_m, y0_m, spacing_m : float
        Local east/north of cell ``[0, 0]``'s centre and the cell size, m.
    depth_m : numpy.ndarray
        ``(ny, nx)`` depths below the sea surface, m, positive down; row ``j`` at north
        ``y0_m + j spacing_m``, column ``i`` at east ``x0_m + i spacing_m``; every cell filled.
    area_depths_m : numpy.ndarray
        The depths of the cells whose centres lie inside the area, m.
    """

    file: str
    sha256: str
    values: str
    x0_m: float
    y0_m: float
    spacing_m: float
    depth_m: np.ndarray
    area_depths_m: np.ndarray

    @property
    def mean_m(self) -> float:
        """Mean depth over the area, m (the design's reference depth, ``z = 0``)."""
        return float(np.mean(self.area_depths_m))

    def stats(self) -> dict:
        """``min``, ``median``, ``mean``, ``max`` of the depth over the area, m.

        Returns
        -------
        dict
            ``{"min", "median", "mean", "max"}`` -> depth, m (positive down).
        """
        d = self.area_depths_m
        return {"min": float(d.min()), "median": float(np.median(d)), "mean": float(d.mean()), "max": float(d.max())}

    def describe(self) -> str:
        """The depth used, in words: ``"bathymetry grid harbour.tif (SHA-256 0123456789ab, depth):
        4.1-17.9 m over the area, median 11 m, mean 11 m"``.

        Returns
        -------
        str
            The sentence.
        """
        s = self.stats()
        return (f"bathymetry grid {self.file} (SHA-256 {self.sha256[:12]}, {self.values} values): depth "
                f"{s['min']:.3g}–{s['max']:.3g} m over the area, median {s['median']:.3g} m, mean {s['mean']:.3g} m")

    def depth_at(self, x, y) -> np.ndarray:
        """Depth (m, positive down) at local east/north ``x``, ``y`` (m, broadcast): bilinear
        between cell centres, the nearest edge cell's beyond the grid.

        Parameters
        ----------
        x : array_like
            Local east, m.
        y : array_like
            Local north, m.

        Returns
        -------
        numpy.ndarray
            Depth, m, the broadcast shape.
        """
        return self.mean_m - self.terrain((0.0, 0.0)).height_m(x, y)

    def terrain(self, centre):
        """The seafloor ``h = mean - depth`` as a :class:`~sss_locus.experiments.datamodel.terrain.Terrain`
        (kind ``"bathymetry"``) in the frame centred on ``centre`` (area frame, m), as the design
        places its terrain.

        Parameters
        ----------
        centre : tuple of float
            ``(x, y)``, area frame, m.

        Returns
        -------
        Terrain
            Heights, m (up, relative to the mean depth), in the centred frame.
        """
        from sss_locus.experiments.datamodel.terrain import Terrain

        cx, cy = (float(v) for v in centre)
        grid = (self.x0_m - cx, self.y0_m - cy, self.spacing_m, self.mean_m - self.depth_m)
        return Terrain("bathymetry", {"file": self.file, "sha256": self.sha256}, grid=grid)


def _grid_geometry(polygon, native_m: float) -> tuple[float, float, float, int, int]:
    x0, y0, x1, y1 = polygon.bounds
    pad = 0.25 * max(x1 - x0, y1 - y0) + 100.0
    x0, y0, x1, y1 = x0 - pad, y0 - pad, x1 + pad, y1 + pad
    dx = min(max(native_m, math.sqrt((x1 - x0) * (y1 - y0) / MAX_CELLS)), 0.1 * min(*np.ptp(
        np.asarray(polygon.exterior.coords), axis=0)))
    nx, ny = int(math.ceil((x1 - x0) / dx)), int(math.ceil((y1 - y0) / dx))
    return x0, y1, dx, nx, ny


def _fill_nearest(a: np.ndarray) -> np.ndarray:
    from scipy import ndimage

    bad = ~np.isfinite(a)
    if not bad.any():
        return a
    idx = ndimage.distance_transform_edt(bad, return_distances=False, return_indices=True)
    return a[tuple(idx)]


def load_bathymetry(path: str | Path, values: str, area, *, shown: str | None = None) -> Bathymetry:
    """Read the raster ``path`` over ``area`` (a :class:`~sss_locus.experiments.survey_design.area.SurveyArea`
    with an origin), checked (module docstring); ``shown`` the file's name in messages and captions
    (default ``path``).

    Parameters
    ----------
    path : str or pathlib.Path
        The raster file (GeoTIFF or any GDAL raster).
    values : str
        One of :data:`VALUES`: ``"depth"`` (m, positive down) or ``"elevation"`` (m, positive up).
    area : SurveyArea
        The area, with ``origin_lonlat``.
    shown : str or None
        The file's name in messages.

    Returns
    -------
    Bathymetry
        The grid over the area (local metres), its SHA-256 and depth statistics.

    Raises
    ------
    ValueError
        Unknown ``values``, a missing file, an area without an origin, or a grid that fails the checks.
    """
    shown = str(path) if shown is None else shown
    checked(models.BathymetryValues, values, f"{shown}: bathymetry_values")
    p = Path(path)
    if not p.is_file():
        from sss_locus.experiments.datamodel.inputs import missing_file

        raise ValueError(missing_file(shown, "bathymetry file"))
    if area.origin_lonlat is None:
        raise ValueError(f"{shown}: a bathymetry grid needs the area's origin_lonlat = [lon, lat] (to place the "
                         "area's local metres on the grid's coordinates)")
    import hashlib

    return _load(str(p.resolve()), hashlib.sha256(p.read_bytes()).hexdigest(), values, area.polygon.wkt,
                 tuple(area.origin_lonlat), shown)


@functools.lru_cache(maxsize=8)
def _load(path: str, sha256: str, values: str, wkt: str, origin: tuple, shown: str) -> Bathymetry:
    import rasterio
    import shapely
    from rasterio.errors import RasterioError
    from rasterio.transform import Affine
    from rasterio.warp import Resampling, calculate_default_transform, reproject, transform_bounds

    polygon = shapely.from_wkt(wkt)
    local = f"+proj=aeqd +lat_0={origin[1]} +lon_0={origin[0]} +datum=WGS84 +units=m +no_defs"
    try:
        with rasterio.open(path) as src:
            if src.crs is None:
                raise ValueError(f"{shown}: the raster has no CRS (coordinate reference system); save it with one "
                                 "(e.g. EPSG:4326 or its UTM zone)")
            band = src.read(1, masked=True).astype(float).filled(np.nan)
            if not np.isfinite(band).any():
                raise ValueError(f"{shown}: band 1 holds no value (every cell is nodata or NaN)")
            tr, w, h = calculate_default_transform(src.crs, local, src.width, src.height, *src.bounds)
            native = float(abs(tr.a))
            gx0, gy1, dx, nx, ny = _grid_geometry(polygon, native)
            out = np.full((ny, nx), np.nan)
            reproject(band, out, src_transform=src.transform, src_crs=src.crs, src_nodata=np.nan,
                      dst_transform=Affine(dx, 0.0, gx0, 0.0, -dx, gy1), dst_crs=local, dst_nodata=np.nan,
                      resampling=Resampling.bilinear)
            extent = transform_bounds(src.crs, "EPSG:4326", *src.bounds)
    except RasterioError as exc:
        raise ValueError(f"{shown}: not a raster rasterio can read ({str(exc).splitlines()[0]})") from None
    depth = out[::-1] * (1.0 if values == "depth" else -1.0)  # rows south to north, positive down
    x0, y0 = gx0 + 0.5 * dx, gy1 - (ny - 0.5) * dx
    X, Y = np.meshgrid(x0 + dx * np.arange(nx), y0 + dx * np.arange(ny))
    inside = shapely.contains_xy(polygon, X, Y)
    over = depth[inside]
    if over.size == 0 or np.isnan(over).any():
        share = 1.0 if over.size == 0 else float(np.isnan(over).mean())
        raise ValueError(f"{shown} does not cover the area: {share:.0%} of it has no value (nodata or beyond the "
                         f"grid, which spans longitude {extent[0]:.5f} to {extent[2]:.5f}, latitude {extent[1]:.5f} to "
                         f"{extent[3]:.5f}); the grid must hold a depth everywhere in the area")
    if over.min() <= 0 or over.max() > MAX_DEPTH_M:
        raw = over * (1.0 if values == "depth" else -1.0)
        other = "elevation" if values == "depth" else "depth"
        raise ValueError(f"{shown}: bathymetry_values = {values!r} needs values over the area in "
                         + ("(0, 12000] m (positive down)" if values == "depth" else "[-12000, 0) m (negative in the water)")
                         + f"; the grid's are {raw.min():.4g} to {raw.max():.4g} m"
                         + (f" (is it {other}? set bathymetry_values = {other!r})" if np.all(over < 0) else
                            " (land, or a datum above the sea surface, inside the area)"))
    return Bathymetry(shown, sha256, values, float(x0), float(y0), float(dx), _fill_nearest(depth), over.copy())
