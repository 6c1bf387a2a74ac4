"""The field of view of one sidescan transducer."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .validation import as_float_array


@dataclass(frozen=True)
class Aperture:
    """Field of view of a sidescan transducer, in its own sensor frame.

    Sensor frame (the paper's, Sec. III-A): ``x`` along the boresight, ``y`` to the left, ``z``
    up. A point at range ``r``, azimuth ``theta`` and elevation ``phi`` has
    ``x = r cos(theta) cos(phi)``, ``y = r sin(theta) cos(phi)``, ``z = r sin(phi)``. Azimuth is
    the wide fan (across-track), elevation the narrow beam (along-track).

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
                raise ValueError(f"Aperture.{name} must be a real number; got {value!r}")
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

    @property
    def half_azimuth_rad(self) -> float:
        """Half the azimuth aperture, radians."""
        return math.radians(self.azimuth_deg) / 2.0

    @property
    def half_elevation_rad(self) -> float:
        """Half the elevation aperture, radians."""
        return math.radians(self.elevation_deg) / 2.0

    def range_ok(self, r) -> np.ndarray:
        """True where ``min_range <= r <= max_range`` (``r`` in metres, any shape)."""
        r = np.asarray(r, dtype=np.float64)
        return (r >= self.min_range) & (r <= self.max_range)

    def contains(self, points) -> np.ndarray:
        """Whether points, given in this sensor's frame, lie inside the aperture.

        Evaluated directly from the angles: ``theta = atan2(y, x)``, ``phi = arcsin(z / r)``.
        A point on the ``z`` axis (azimuth undefined) counts as inside in azimuth; the origin is
        inside only if ``min_range == 0``.

        Parameters
        ----------
        points : array_like, shape (..., 3)
            Cartesian coordinates in metres.

        Returns
        -------
        numpy.ndarray of bool, shape (...)
        """
        p = as_float_array(points, "points", tail=(3,))
        r = np.linalg.norm(p, axis=-1)
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
