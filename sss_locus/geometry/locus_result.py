"""What :func:`~sss_locus.geometry.locus.two_view_locus` returns: statuses and the result arrays."""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np

from .validation import as_float_array, check_memory

MAX_ARCS = 8
"""Width of the arc arrays: eight half-space conditions (four per aperture) bound at most eight
disjoint arcs."""


class LocusStatus(enum.IntEnum):
    """What the two range spheres and the apertures give for one configuration."""

    CIRCLE = 0
    """The spheres meet in a circle; ``length`` is the part of it inside both apertures (and
    inside any extra half-spaces given; it may be 0)."""
    TANGENT = 1
    """The spheres touch in one point (``center``); ``length`` is 0, ``n_arcs`` is 1 if the
    point is inside both apertures (its arc has ``arc_start == arc_end == 0``), else 0."""
    NO_INTERSECTION = 2
    """The spheres do not meet (the ranges are inconsistent with the pose); empty locus."""
    COINCIDENT_ORIGINS = 3
    """The sensor origins coincide: the plane is undefined (equal ranges give the whole sphere,
    unequal ranges nothing). Reported as an empty locus with zero centre, normal and radius."""
    OUT_OF_RANGE = 4
    """The circle exists but a measured range lies outside its aperture's
    ``[min_range, max_range]``: nothing was observable, empty locus."""


@dataclass(frozen=True)
class LocusResult:
    """The ambiguity locus for a batch of two-view configurations (leading shape ``S``).

    All vectors are in sensor 1's frame (x boresight, y left, z up), lengths in metres, angles in
    radians. The circle is ``p1(alpha) = center + radius (cos(alpha) basis1 + sin(alpha) basis2)``.

    Attributes
    ----------
    u : ndarray, shape S + (3,)
        ``R^T t``; the plane is ``2 u . p1 = C``.
    C : ndarray, shape S
        ``r2**2 - r1**2 - |t|**2`` (m^2).
    center, normal, basis1, basis2 : ndarray, shape S + (3,)
        Circle centre (m) and unit normal, and the in-plane unit vectors of its parametrisation.
        Zero where the origins coincide.
    radius : ndarray, shape S
        Circle radius (m); 0 unless the status is ``CIRCLE`` (or ``OUT_OF_RANGE`` with a circle).
    exists : ndarray of bool, shape S
        The spheres meet (in a circle or a tangent point).
    status : ndarray of int8, shape S
        :class:`LocusStatus` codes.
    in_range : ndarray of bool, shape S
        Both measured ranges lie within their apertures' range limits.
    length : ndarray, shape S
        Locus length (m): arc length of the circle inside both apertures. Never NaN.
    n_arcs : ndarray of int, shape S
        Number of disjoint arcs; ``> 1`` means the locus is fragmented. A circle wholly inside
        both apertures is one arc.
    arc_start, arc_end : ndarray, shape S + (W,)
        Arc end points in ``alpha``: ``arc_start`` in [-pi, pi), ``arc_start < arc_end <=
        arc_start + 2 pi``; NaN-padded beyond ``n_arcs``. ``W`` is ``MAX_ARCS``, or
        ``MAX_ARCS + K`` when ``K`` extra half-spaces were given.
    """

    u: np.ndarray
    C: np.ndarray
    center: np.ndarray
    normal: np.ndarray
    basis1: np.ndarray
    basis2: np.ndarray
    radius: np.ndarray
    exists: np.ndarray
    status: np.ndarray
    in_range: np.ndarray
    length: np.ndarray
    n_arcs: np.ndarray
    arc_start: np.ndarray
    arc_end: np.ndarray
    R: np.ndarray
    t: np.ndarray

    @property
    def shape(self) -> tuple[int, ...]:
        """Batch shape ``S``."""
        return self.length.shape

    def point_at(self, alpha, frame: int = 1) -> np.ndarray:
        """Points of the circle at angles ``alpha``, in sensor ``frame``'s coordinates (m).

        Parameters
        ----------
        alpha : array_like of real, shape S or S + (n,)
            Circle angles (rad). NaN gives a NaN point (as for the padding of the arc arrays);
            infinity, complex, boolean and other non-real values are refused.
        frame : {1, 2}
            Sensor frame of the returned points.

        Returns
        -------
        ndarray, shape ``alpha.shape + (3,)``
        """
        _check_frame(frame)
        self._needs_geometry("point_at")
        alpha = as_float_array(alpha, "alpha", finite=False)
        if np.isinf(alpha).any():
            raise ValueError("alpha must be finite angles in radians (or NaN); found infinity")
        extra = alpha.ndim - len(self.shape)
        if extra < 0 or alpha.shape[: len(self.shape)] != self.shape:
            raise ValueError(f"alpha must have shape {self.shape} + (...); got {alpha.shape}")
        expand = (Ellipsis,) + (None,) * extra + (slice(None),)
        r = self.radius[(Ellipsis,) + (None,) * extra][..., None]
        p = self.center[expand] + r * (
            np.cos(alpha)[..., None] * self.basis1[expand] + np.sin(alpha)[..., None] * self.basis2[expand]
        )
        if frame == 1:
            return p
        R = self.R[(Ellipsis,) + (None,) * extra + (slice(None), slice(None))]
        return np.einsum("...ij,...j->...i", R, p) + self.t[expand]

    def points(self, n_per_arc: int = 64, frame: int = 1) -> np.ndarray:
        """Points along every arc of the locus, for figures.

        Parameters
        ----------
        n_per_arc : int, >= 2
            Points per arc (an integer, not a bool or float).
        frame : {1, 2}
            Sensor frame of the returned points.

        Returns
        -------
        ndarray, shape S + (W, n_per_arc, 3)
            Evenly spaced in ``alpha`` from each arc's start to its end, in sensor ``frame``'s
            coordinates (m); NaN for arcs beyond ``n_arcs``. Empty for an empty batch.
        """
        if isinstance(n_per_arc, bool) or not (isinstance(n_per_arc, (int, np.integer))
                                               and n_per_arc >= 2):
            raise ValueError(f"n_per_arc must be an integer >= 2; got {n_per_arc!r}")
        _check_frame(frame)
        self._needs_geometry("points")
        n = int(n_per_arc)
        check_memory(64.0 * int(np.prod(self.arc_start.shape)) * n,  # 64 B a point (tracemalloc)
                     f"points(n_per_arc={n}) for {int(np.prod(self.arc_start.shape))} arcs")
        s = np.linspace(0.0, 1.0, n)
        alpha = self.arc_start[..., None] + (self.arc_end - self.arc_start)[..., None] * s
        width = self.arc_start.shape[-1]
        flat = alpha.reshape(self.shape + (width * n,))
        return self.point_at(flat, frame).reshape(self.shape + (width, n, 3))

    def _needs_geometry(self, method: str) -> None:
        if self.center is None or self.arc_start is None:
            raise ValueError(f"{method}() needs the circle's geometry, which a result of "
                             "two_view_locus(..., outputs='lengths') does not keep; call it with "
                             "outputs='all' (the default)")

    def angle_of(self, p1) -> np.ndarray:
        """Circle angle ``alpha`` (rad) of points ``p1`` by projection onto the circle's plane.

        ``p1``: finite real coordinates (m) in frame 1, shape broadcasting with ``S + (3,)``.

        Parameters
        ----------
        p1 : array_like, shape broadcasting with S + (3,)
            Points in sensor 1's frame, metres (finite real numbers).

        Returns
        -------
        numpy.ndarray, shape S (broadcast)
            ``alpha`` in radians, in ``(-pi, pi]`` (``atan2`` of the two in-plane components);
            a point on the circle's axis gives ``0`` (``atan2(0, 0)``).
        """
        self._needs_geometry("angle_of")
        d = as_float_array(p1, "p1", tail=(3,)) - self.center
        return np.arctan2(np.sum(d * self.basis2, axis=-1), np.sum(d * self.basis1, axis=-1))


def _check_frame(frame) -> None:
    if isinstance(frame, bool) or frame not in (1, 2):
        raise ValueError(f"frame must be 1 or 2; got {frame!r}")
