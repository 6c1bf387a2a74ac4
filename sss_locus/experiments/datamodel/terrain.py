"""Seafloor models ``z = h(x, y)`` and features placed on them (the reconstruction chapter).

World frame: ``x`` east, ``y`` north, ``z`` up, metres; the survey area is centred on the
origin. Every model is a :class:`Terrain`: a vectorised height function of horizontal position,
evaluated by :meth:`Terrain.height_m`. The analytic cases are

``flat``
    ``h = 0``;
``slope``
    a plane through the origin rising at ``slope_deg`` toward the horizontal direction
    ``azimuth_deg`` (counter-clockwise from ``+x``): ``h = tan(slope) (x cos a + y sin a)``;
``mound``
    a Gaussian mound ``h = height exp(-((x - x0)^2 + (y - y0)^2) / (2 sigma^2))``;
``step``
    a trench of depth ``height_m`` and floor width ``width_m`` along the line through the origin
    at ``azimuth_deg``: ``h = -height`` where the horizontal distance to that line is at most
    ``width / 2``, else 0 (vertical walls);

and ``random`` is a seeded stationary Gaussian random field with RMS relief ``sigma`` and
Gaussian correlation ``C(d) = sigma^2 exp(-(d / ell)^2)`` (``ell`` the correlation length),
synthesised spectrally on a periodic grid (white Gaussian noise shaped in the Fourier domain by
the square root of the power spectrum ``exp(-|k|^2 ell^2 / 4)``; the grid is padded by
``3 ell`` on every side so the wrap-around correlation is below ``exp(-9)``), its mean removed
and its RMS over the grid scaled to exactly ``sigma``, then bilinearly interpolated. Values in
``data/terrain.toml`` (all assumptions), which a user's ``--data`` file or ``--set`` may override
by key (:mod:`sss_locus.experiments.datamodel.userdata`); :func:`load_terrain_config` reads them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from sss_locus.paths import DATA_DIR
from sss_locus.experiments.datamodel import datadoc
from sss_locus.experiments.datamodel import models

TERRAIN_FILE: Path = DATA_DIR / "terrain.toml"
KINDS = ("flat", "slope", "mound", "step", "random")

def _number(value, name: str, lo: float = -math.inf, hi: float = math.inf) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not math.isfinite(value) or not lo <= value <= hi:
        raise ValueError(f"{name} must be a finite number in [{lo}, {hi}]; got {value!r}")
    return float(value)


@dataclass(frozen=True)
class Terrain:
    """A seafloor height field ``z = h(x, y)`` (world frame, metres).

    Build one with :func:`flat_terrain`, :func:`slope_terrain`, :func:`mound_terrain`,
    :func:`step_terrain` or :func:`random_terrain`.

    Attributes
    ----------
    kind : str
        One of :data:`KINDS`.
    params : dict
        The model's parameters (as given to its constructor).
    grid : tuple or None
        ``random`` and ``bathymetry`` (a survey area's grid,
        :mod:`sss_locus.experiments.survey_design.bathymetry`; beyond it, the nearest edge) only: ``(x0, y0, spacing, heights (ny, nx))``, the grid's lower-left corner.
    """

    kind: str
    params: dict = field(default_factory=dict)
    grid: tuple | None = field(default=None, repr=False, compare=False)

    def height_m(self, x, y) -> np.ndarray:
        """Seafloor height ``h(x, y)`` (m) at horizontal positions ``x``, ``y`` (m, broadcast).

        Raises ``ValueError`` for non-finite positions, or (``random``) positions outside the
        synthesised grid, naming its extent.

        Parameters
        ----------
        x, y : array_like
            Horizontal positions, world frame (``x`` east, ``y`` north), metres; shapes
            broadcast together.

        Returns
        -------
        numpy.ndarray, shape ``broadcast(x, y).shape``
            Heights ``z`` (up), metres. A ``bathymetry`` grid gives its nearest edge cell beyond
            its extent.
        """
        x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
            raise ValueError("x and y must be finite positions in metres")
        p = self.params
        if self.kind == "flat":
            return np.zeros(x.shape)
        if self.kind == "slope":
            a = math.radians(p["azimuth_deg"])
            return math.tan(math.radians(p["slope_deg"])) * (x * math.cos(a) + y * math.sin(a))
        if self.kind == "mound":
            d2 = (x - p["x0_m"]) ** 2 + (y - p["y0_m"]) ** 2
            return p["height_m"] * np.exp(-d2 / (2.0 * p["sigma_m"] ** 2))
        if self.kind == "step":
            a = math.radians(p["azimuth_deg"])
            dist = np.abs(-x * math.sin(a) + y * math.cos(a))
            return np.where(dist <= p["width_m"] / 2.0, -p["height_m"], 0.0)
        if self.kind == "bathymetry":  # a grid read from a file: beyond it, its nearest edge cell
            x0, y0, dx, h = self.grid
            x = np.clip(x, x0, x0 + (h.shape[1] - 1) * dx)
            y = np.clip(y, y0, y0 + (h.shape[0] - 1) * dx)
        return _bilinear(self.grid, x, y)

    def point_on_seafloor(self, x, y) -> np.ndarray:
        """Points ``(x, y, h(x, y))``, shape ``broadcast(x, y).shape + (3,)``.

        Parameters
        ----------
        x, y : array_like
            Horizontal positions, world frame, metres; shapes broadcast together.

        Returns
        -------
        numpy.ndarray, shape ``broadcast(x, y).shape + (3,)``
            Points on the seafloor, world frame, metres (errors as :meth:`height_m`).
        """
        x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
        return np.stack([x, y, self.height_m(x, y)], axis=-1)


def _bilinear(grid, x, y) -> np.ndarray:
    x0, y0, dx, h = grid
    ny, nx = h.shape
    fx, fy = (x - x0) / dx, (y - y0) / dx
    outside = (fx < 0) | (fx > nx - 1) | (fy < 0) | (fy > ny - 1)
    if np.any(outside):
        raise ValueError(f"positions outside the random terrain's grid x in [{x0:g}, "
                         f"{x0 + (nx - 1) * dx:g}] m, y in [{y0:g}, {y0 + (ny - 1) * dx:g}] m "
                         f"(e.g. ({x[outside].flat[0]:g}, {y[outside].flat[0]:g})); "
                         "enlarge extent_m")
    i = np.minimum(np.floor(fx).astype(np.intp), nx - 2)
    j = np.minimum(np.floor(fy).astype(np.intp), ny - 2)
    tx, ty = fx - i, fy - j
    return ((1 - ty) * ((1 - tx) * h[j, i] + tx * h[j, i + 1])
            + ty * ((1 - tx) * h[j + 1, i] + tx * h[j + 1, i + 1]))


def flat_terrain() -> Terrain:
    """The flat seafloor ``h = 0``.

    Returns
    -------
    Terrain
        Kind ``flat``, no parameters.
    """
    return Terrain("flat", {})


def slope_terrain(slope_deg: float, azimuth_deg: float = 90.0) -> Terrain:
    """A plane through the origin rising at ``slope_deg`` in [0, 60] toward ``azimuth_deg``.

    Parameters
    ----------
    slope_deg : float
        Inclination from the horizontal, degrees, in [0, 60] (0: flat).
    azimuth_deg : float
        Horizontal direction of steepest rise, degrees counter-clockwise from ``+x`` (east),
        in [-360, 360]; default 90 (rising north).

    Returns
    -------
    Terrain
        Kind ``slope``.
    """
    return Terrain("slope", {"slope_deg": _number(slope_deg, "slope_deg", 0.0, 60.0),
                             "azimuth_deg": _number(azimuth_deg, "azimuth_deg", -360.0, 360.0)})


def mound_terrain(height_m: float, sigma_m: float, x0_m: float = 0.0, y0_m: float = 0.0) -> Terrain:
    """A Gaussian mound of ``height_m`` (negative: a hollow) and half-width ``sigma_m`` > 0.

    Parameters
    ----------
    height_m : float
        Height of the top above ``z = 0``, metres (negative: a hollow; 0: flat).
    sigma_m : float
        Standard deviation of the Gaussian, metres, > 0.
    x0_m, y0_m : float
        Centre, world frame, metres.

    Returns
    -------
    Terrain
        Kind ``mound``.
    """
    if _number(sigma_m, "sigma_m") <= 0:
        raise ValueError(f"sigma_m must be > 0 m; got {sigma_m!r}")
    return Terrain("mound", {"height_m": _number(height_m, "height_m"), "sigma_m": float(sigma_m),
                             "x0_m": _number(x0_m, "x0_m"), "y0_m": _number(y0_m, "y0_m")})


def step_terrain(height_m: float, width_m: float, azimuth_deg: float = 0.0) -> Terrain:
    """A trench ``height_m`` deep and ``width_m`` (>= 0) wide along the line at ``azimuth_deg``.

    Parameters
    ----------
    height_m : float
        Depth of the trench floor below ``z = 0``, metres (negative: a ridge).
    width_m : float
        Floor width, metres, >= 0 (0: only the line itself is lowered).
    azimuth_deg : float
        Direction of the trench's axis through the origin, degrees counter-clockwise from
        ``+x``, in [-360, 360].

    Returns
    -------
    Terrain
        Kind ``step``.
    """
    return Terrain("step", {"height_m": _number(height_m, "height_m"),
                            "width_m": _number(width_m, "width_m", 0.0),
                            "azimuth_deg": _number(azimuth_deg, "azimuth_deg", -360.0, 360.0)})


def random_terrain(rms_relief_m: float, correlation_length_m: float, extent_m: float,
                   grid_spacing_m: float, seed: int) -> Terrain:
    """A seeded Gaussian random field (see the module docstring).

    Parameters
    ----------
    rms_relief_m : float
        RMS height over the grid, >= 0 (0 gives a flat seafloor on the same grid).
    correlation_length_m : float
        ``ell`` of ``C(d) = sigma^2 exp(-(d / ell)^2)``, > 0.
    extent_m : float
        Side of the square (centred on the origin) where heights are defined, > 0.
    grid_spacing_m : float
        Grid step, > 0 and at most ``correlation_length_m / 2``; the grid has at most 4096
        points a side (with its padding).
    seed : int
        Seed of ``numpy.random.default_rng``.

    Returns
    -------
    Terrain
        Kind ``random``, with its grid (world frame, centred on the origin, padded by
        ``3 correlation_length_m`` on every side); heights outside the grid raise.
    """
    sigma = _number(rms_relief_m, "rms_relief_m", 0.0)
    ell = _number(correlation_length_m, "correlation_length_m", 0.0)
    ext = _number(extent_m, "extent_m", 0.0)
    dx = _number(grid_spacing_m, "grid_spacing_m", 0.0)
    if ell <= 0 or ext <= 0 or dx <= 0:
        raise ValueError("correlation_length_m, extent_m and grid_spacing_m must be > 0; got "
                         f"{ell}, {ext}, {dx}")
    if dx > ell / 2:
        raise ValueError(f"grid_spacing_m must be at most correlation_length_m / 2 = {ell / 2:g} m "
                         f"to resolve the relief; got {dx}")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"seed must be an integer >= 0; got {seed!r}")
    n = int(math.ceil((ext + 6 * ell) / dx)) + 1
    if n > 4096:
        raise ValueError(f"the random terrain grid would have {n} points a side (> 4096): raise "
                         f"grid_spacing_m ({dx}) or lower extent_m ({ext}) / correlation_length_m ({ell})")
    rng = np.random.default_rng(seed)
    k = 2 * np.pi * np.fft.fftfreq(n, d=dx)
    k2 = k[:, None] ** 2 + k[None, :] ** 2
    spectrum = np.fft.fft2(rng.standard_normal((n, n))) * np.exp(-k2 * ell * ell / 8.0)
    h = np.fft.ifft2(spectrum).real
    h -= h.mean()
    rms = math.sqrt(float(np.mean(h * h)))
    h = h * (sigma / rms) if rms > 0 else h * 0.0
    x0 = -(n - 1) * dx / 2.0
    return Terrain("random", {"rms_relief_m": sigma, "correlation_length_m": ell, "extent_m": ext,
                              "grid_spacing_m": dx, "seed": int(seed)}, grid=(x0, x0, dx, h))


def place_features(terrain: Terrain, n: int, area_m: float, seed: int) -> np.ndarray:
    """``n`` features on the seafloor, horizontally uniform over the square of side ``area_m``
    centred on the origin: shape (n, 3), world frame, metres.

    Parameters
    ----------
    terrain : Terrain
        The seafloor the features lie on.
    n : int
        Number of features, >= 0 (0 gives shape (0, 3)).
    area_m : float
        Side of the square, metres, >= 0.
    seed : int
        Seed of ``numpy.random.default_rng``.

    Returns
    -------
    numpy.ndarray, shape (n, 3)
        Feature positions, world frame, metres.
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
        raise ValueError(f"n must be an integer >= 0; got {n!r}")
    area = _number(area_m, "area_m", 0.0)
    rng = np.random.default_rng(seed)
    xy = (rng.random((int(n), 2)) - 0.5) * area
    return terrain.point_on_seafloor(xy[:, 0], xy[:, 1])


def load_terrain_config(path: str | Path | None = None) -> dict:
    """The ``terrain`` and ``survey`` tables of ``data/terrain.toml`` merged with the active user
    data (:mod:`sss_locus.experiments.datamodel.userdata`), or of the file ``path`` only, validated by
    :func:`parse_terrain_config`.

    Parameters
    ----------
    path : str or pathlib.Path, optional
        A terrain file to read alone; default the merged data (whose entries ``terrain`` and
        ``survey`` are then noted as read).

    Returns
    -------
    dict
        As :func:`parse_terrain_config`.
    """
    return datadoc.load_table(parse_terrain_config, path, "terrain", "survey")


def parse_terrain_config(doc: dict) -> dict:
    """The validated ``terrain`` and ``survey`` tables of a parsed document: ``{"slope": {...},
    "mound": {...}, "step": {...}, "random": {...}, "survey": {...}, "provenance": {key: note}}``.

    Raises ``ValueError`` naming the full key path of a missing, unknown or out-of-range entry.

    Parameters
    ----------
    doc : dict
        A parsed data document holding ``terrain`` and ``survey`` tables.

    Returns
    -------
    dict
        Per terrain kind its parameter values (plain numbers, units in the names), ``survey``,
        and ``provenance``: dotted key -> source or assumption note.
    """
    data = models.validate_document(doc, ("terrain", "survey"))
    tables = {kind: getattr(data.terrain, kind) for kind in models.Terrain.model_fields}
    out: dict = {"provenance": {}}
    for kind, t in tables.items():
        out[kind] = models.values(t)
        out["provenance"].update(models.provenance(t, f"terrain.{kind}"))
    out["survey"] = models.values(data.survey)
    out["provenance"].update(models.provenance(data.survey, "survey"))
    return out


def terrain_from_config(kind: str, config: dict, *, extent_m: float = 1000.0, seed: int = 0,
                        **overrides) -> Terrain:
    """The terrain ``kind`` (one of :data:`KINDS`) with the parameters of ``config``
    (:func:`load_terrain_config`), any of them replaced by ``overrides``.

    Parameters
    ----------
    kind : str
        One of :data:`KINDS`.
    config : dict
        :func:`load_terrain_config`'s result.
    extent_m : float
        ``random`` only: side of the square where heights are defined, metres.
    seed : int
        ``random`` only: seed of the field.
    **overrides
        Parameters of ``kind`` replacing the configured ones (names as in ``config[kind]``).

    Returns
    -------
    Terrain

    Raises
    ------
    ValueError
        An unknown ``kind`` or override name, or a parameter out of its range.
    """
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {list(KINDS)}; got {kind!r}")
    if kind == "flat":
        return flat_terrain()
    params = {**config[kind], **overrides}
    unknown = set(overrides) - set(config[kind])
    if unknown:
        raise ValueError(f"unknown {kind} parameters {sorted(unknown)}; allowed: {sorted(config[kind])}")
    if kind == "slope":
        return slope_terrain(**params)
    if kind == "mound":
        return mound_terrain(**params)
    if kind == "step":
        return step_terrain(**params)
    return random_terrain(params["rms_relief_m"], params["correlation_length_m"], extent_m,
                          params["grid_spacing_m"], seed)
