"""The field of view of one sidescan transducer."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from .validation import InputTypeError, as_float_array, as_real_array, row_exponents

RADIANS_FAN_DEG = math.pi
"""An azimuth aperture of at most this many "degrees" is read as a likely radian value (a
sidescan fan of up to 180 deg is at most pi rad; no sidescan fan is 3 deg wide)."""

RADIANS_SHAPE_RATIO = 10.0
"""... together with an elevation aperture at most 1/this of the azimuth aperture: the shape
of a sidescan beam (fan over beam is 100 for 50 x 0.5 deg, 481 for 130 x 0.27 deg), which the
ratio keeps in radians too."""


@dataclass(frozen=True)
class Aperture:
    """Field of view of a sidescan transducer, in its own sensor frame.

    Sensor frame (the paper's, Sec. III-A): ``x`` along the boresight, ``y`` in the plane of the
    wide azimuth fan, ``z = x × y`` along the narrow elevation beam. A point at range ``r``,
    azimuth ``theta`` and elevation ``phi`` has ``x = r cos(theta) cos(phi)``,
    ``y = r sin(theta) cos(phi)``, ``z = r sin(phi)``. Azimuth is the wide fan (across-track),
    elevation the narrow beam (along-track). Drawn with the fan horizontal (the paper's figure),
    ``y`` is to the left and ``z`` up; on a vehicle the fan is the vertical across-track plane, so
    ``y`` points down and inboard and ``z`` along-track (``data/README.md``,
    :mod:`sss_locus.experiments.datamodel.platforms`; ``Transducer.world_pose`` composes it with a vehicle
    pose).

    Parameters
    ----------
    azimuth_deg : float
        FULL azimuth aperture in degrees, in (0, 360]. A point is inside when
        ``|theta| <= azimuth_deg / 2``. Apertures wider than 180 deg (a non-convex wedge) are
        supported.
    elevation_deg : float
        FULL elevation aperture in degrees, in (0, 180]. Inside when ``|phi| <= elevation_deg/2``.
    max_range : float
        Maximum range in metres, > ``min_range``.
    min_range : float, default 0.0
        Minimum range in metres, >= 0.

    All four must be real numbers (Python or NumPy ints and floats); booleans, complex numbers,
    strings, dates and other types raise
    :class:`~sss_locus.geometry.validation.InputTypeError` (a ``TypeError``, also a
    ``ValueError``), values out of range a ``ValueError``, each naming the field.

    Warns
    -----
    UserWarning
        When the two angles look like a sidescan beam given in radians: ``azimuth_deg <= pi``
        (:data:`RADIANS_FAN_DEG`) and ``elevation_deg <= azimuth_deg / 10``
        (:data:`RADIANS_SHAPE_RATIO`), e.g. ``Aperture(2.27, 0.0047, 150)`` for the EdgeTech
        2205's 130 x 0.27 deg. Real sidescan fans are tens of degrees wide, so degree values
        never meet both conditions; a narrow non-sidescan aperture (e.g. 2 x 2 deg) does not
        meet the second.

    Examples
    --------
    >>> Aperture(azimuth_deg=130.0, elevation_deg=0.27, max_range=150.0)  # EdgeTech 2205
    Aperture(azimuth_deg=130.0, elevation_deg=0.27, max_range=150.0, min_range=0.0)
    """

    azimuth_deg: float
    elevation_deg: float
    max_range: float
    min_range: float = 0.0

    def __post_init__(self) -> None:
        for name in ("azimuth_deg", "elevation_deg", "max_range", "min_range"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
                raise InputTypeError(
                    f"Aperture.{name} must be a real number (int or float); got "
                    f"{type(value).__name__} {value!r}"
                )
            if not math.isfinite(value):
                raise ValueError(f"Aperture.{name} must be finite; got {value!r}")
            object.__setattr__(self, name, float(value))
        if not 0.0 < self.azimuth_deg <= 360.0:
            raise ValueError(f"Aperture.azimuth_deg must be in (0, 360] degrees; got {self.azimuth_deg}")
        if not 0.0 < self.elevation_deg <= 180.0:
            raise ValueError(
                f"Aperture.elevation_deg must be in (0, 180] degrees; got {self.elevation_deg}"
            )
        if self.min_range < 0.0:
            raise ValueError(f"Aperture.min_range must be >= 0 m; got {self.min_range}")
        if not self.max_range > self.min_range:
            raise ValueError(
                f"Aperture.max_range must be > min_range ({self.min_range} m); got {self.max_range}"
            )
        if (self.azimuth_deg <= RADIANS_FAN_DEG
                and self.elevation_deg <= self.azimuth_deg / RADIANS_SHAPE_RATIO):
            warnings.warn(
                f"Aperture(azimuth_deg={self.azimuth_deg:g}, elevation_deg={self.elevation_deg:g}) "
                "looks like a sidescan beam given in radians; the angles are FULL apertures in "
                f"degrees (did you mean {math.degrees(self.azimuth_deg):.4g} x "
                f"{math.degrees(self.elevation_deg):.4g} deg?)",
                UserWarning, stacklevel=3,
            )

    @property
    def half_azimuth_rad(self) -> float:
        """Half the azimuth aperture, radians."""
        return math.radians(self.azimuth_deg) / 2.0

    @property
    def half_elevation_rad(self) -> float:
        """Half the elevation aperture, radians."""
        return math.radians(self.elevation_deg) / 2.0

    def range_ok(self, r) -> np.ndarray:
        """True where ``min_range <= r <= max_range`` (``r``: real numbers in metres, any shape;
        False for NaN).

        Parameters
        ----------
        r : array_like, any shape
            Ranges, metres (real numbers; NaN and infinity allowed).

        Returns
        -------
        numpy.ndarray of bool, shape of ``r``
            False for NaN and for ranges outside the limits.
        """
        r = as_real_array(r, "r")
        return (r >= self.min_range) & (r <= self.max_range)

    def contains(self, points) -> np.ndarray:
        """Whether points, given in this sensor's frame, lie inside the aperture.

        Evaluated directly from the angles: ``theta = atan2(y, x)``, ``phi = arcsin(z / r)``.
        A point on the ``z`` axis (azimuth undefined) counts as inside in azimuth; the origin is
        inside only if ``min_range == 0``.

        Parameters
        ----------
        points : array_like, shape (..., 3)
            Cartesian coordinates in metres: finite real numbers, any magnitude (``|p|`` is
            formed at a power-of-two scale where its square would overflow or underflow).

        Returns
        -------
        numpy.ndarray of bool, shape (...)
        """
        p = as_float_array(points, "points", tail=(3,))
        e = row_exponents(p[..., 0], p[..., 1], p[..., 2])  # |p| without overflow or underflow
        r = np.linalg.norm(p, axis=-1) if e is None else np.ldexp(
            np.linalg.norm(np.ldexp(p, -e[..., None]), axis=-1), e)
        theta = np.arctan2(p[..., 1], p[..., 0])
        with np.errstate(invalid="ignore", divide="ignore"):
            phi = np.arcsin(np.clip(np.where(r > 0, p[..., 2] / r, 0.0), -1.0, 1.0))
        return (
            (np.abs(theta) <= self.half_azimuth_rad)
            & (np.abs(phi) <= self.half_elevation_rad)
            & self.range_ok(r)
        )

    def halfspace_normals(self) -> tuple[np.ndarray, np.ndarray, bool]:
        """Linear form of the angular bounds, used by the exact crop.

        Returns
        -------
        elevation : ndarray, shape (2, 4)
            Rows ``(a_x, a_y, a_z, s)`` meaning ``a . p + s * r >= 0`` with ``r = |p|``:
            ``-z + r sin(phi_max) >= 0`` and ``z + r sin(phi_max) >= 0`` (for a full 180 deg
            elevation, where the bound is vacuous, ``a = 0``).
        azimuth : ndarray, shape (2, 3)
            Rows ``a`` meaning ``a . p >= 0``: ``x sin(theta_max) - y cos(theta_max) >= 0`` and
            ``x sin(theta_max) + y cos(theta_max) >= 0``.
        azimuth_is_union : bool
            For a full azimuth aperture up to 180 deg the wedge is the intersection of the two
            azimuth half-spaces; for a wider one, the union.
        """
        s_el = math.sin(self.half_elevation_rad)
        elevation = np.array([[0.0, 0.0, -1.0, s_el], [0.0, 0.0, 1.0, s_el]])
        if self.elevation_deg == 180.0:
            # |phi| <= 90 deg holds everywhere. Written as -z + r >= 0 it would touch every circle
            # through the poles, where rounding opens a spurious sqrt(eps)-wide gap; 0 + r >= 0
            # states the same condition without that tangency.
            elevation[:, :3] = 0.0
        st, ct = math.sin(self.half_azimuth_rad), math.cos(self.half_azimuth_rad)
        if self.azimuth_deg == 360.0:  # exact: the union of y >= 0 and y <= 0 is everything
            st, ct = 0.0, -1.0
        azimuth = np.array([[st, -ct, 0.0], [st, ct, 0.0]])
        return elevation, azimuth, self.azimuth_deg > 180.0
