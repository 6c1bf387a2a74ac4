"""Three views of one feature: the two-view planes meet in a line, the line meets sphere 1.

Views 1–2 put the feature (frame 1) on the plane ``2 u2 . p = C2`` with ``u2 = R12^T t12`` and
``C2 = r2^2 - r1^2 - |t12|^2`` (:mod:`sss_locus.geometry.locus`); views 1–3 on ``2 u3 . p = C3`` likewise.
Two non-parallel planes meet in the line ``p(s) = p0 + s d``, ``d = (u2 x u3) / |u2 x u3|``,
whose point nearest sensor 1 is

    p0 = (c2 (u3 x w) + c3 (w x u2)) / |w|^2,   w = u2 x u3,  c2 = C2 / 2,  c3 = C3 / 2,

and the line meets the sphere ``|p| = r1`` where ``s = +-h``, ``h = sqrt(r1^2 - |p0|^2)``: two
points, one (tangent line) or none. Every candidate that lies inside all three apertures is a
possible position of the feature; one such candidate resolves it, two leave a two-fold
ambiguity (the mirror images of each other in the plane through sensor 1's origin and the line).
The derivation is checked symbolically in :mod:`sss_locus.geometry.symbolic.three_view_points`.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np

from .validation import (as_float_array, as_positive_array, as_rotation_matrices, broadcast_leading,
                         check_aperture, row_exponents)
from .aperture import Aperture
from .tolerances import (COINCIDENT_ORIGINS_RTOL, COINCIDENT_PLANES_RTOL, LINE_TANGENT_RTOL,
                         PARALLEL_PLANES_SIN_TOL)

class ThreeViewStatus(enum.IntEnum):
    """What the three range spheres give for one configuration (before the aperture test)."""

    TWO_POINTS = 0
    """The line of the two planes cuts sphere 1 in two points (``candidates[..., 0/1, :]``)."""
    ONE_POINT = 1
    """The line is tangent to sphere 1: one point, stored in slot 0 (slot 1 is invalid)."""
    NO_POINT = 2
    """The line misses sphere 1: the three ranges are inconsistent with the poses."""
    PARALLEL_PLANES = 3
    """The two planes are parallel and distinct (e.g. three collinear sensor origins with
    inconsistent ranges): no point. Candidates are zero."""
    COINCIDENT_PLANES = 4
    """The two planes coincide (collinear origins, e.g. three sensors on one straight track,
    or sensors 2 and 3 at the same place with equal ranges): the third view adds nothing and
    the feature stays on the two-view circle of views 1–2, which is
    ``two_view_locus(R12, t12, r1, r2, aperture1, aperture2)`` (to be cropped by aperture 3
    too). No point is returned: candidates are zero and invalid, ``n_valid`` is 0."""
    COINCIDENT_ORIGINS = 5
    """Sensor 2's or sensor 3's origin coincides with sensor 1's: a plane is undefined. No
    point; candidates are zero."""


@dataclass(frozen=True)
class ThreeViewResult:
    """Candidate positions of a feature seen in three views (batch shape ``S``).

    Vectors are in sensor 1's frame (x boresight, y left, z up), metres.

    Attributes
    ----------
    candidates : ndarray, shape S + (2, 3)
        The line–sphere intersections ``p0 + h d`` and ``p0 - h d`` (both ``p0`` for a tangent
        line). Never NaN: zero where there is no point.
    valid : ndarray of bool, shape S + (2,)
        The candidate exists and lies inside all three apertures (angles and range limits). A
        tangent point is reported once (slot 1 is never valid for ``ONE_POINT``).
    n_valid : ndarray of int, shape S
        Number of valid candidates: 1 resolves the feature, 2 is a two-fold ambiguity.
    status : ndarray of int8, shape S
        :class:`ThreeViewStatus` codes.
    line_point, line_direction : ndarray, shape S + (3,)
        ``p0`` (the line's point nearest sensor 1) and the unit direction ``d``; zero where the
        planes are parallel or coincident or an origin coincides.
    plane_angle_deg : ndarray, shape S
        Angle between the two planes, in [0, 90] degrees (0 = parallel). Small angles make the
        line, hence the points, sensitive to range and pose errors.
    line_distance_ratio : ndarray, shape S
        ``|p0| / r1``: 0 when the line passes through sensor 1, 1 at tangency, > 1 when it
        misses the sphere. ``inf`` where there is no line.
    half_separation : ndarray, shape S
        ``h`` (m), half the distance between the two candidates; 0 for ``ONE_POINT`` and where
        there is no point. ``h / r1`` is the tangency margin: near 0 the two candidates merge
        and their positions along the line become sensitive to errors (as ``1 / h``).
    """

    candidates: np.ndarray
    valid: np.ndarray
    n_valid: np.ndarray
    status: np.ndarray
    line_point: np.ndarray
    line_direction: np.ndarray
    plane_angle_deg: np.ndarray
    line_distance_ratio: np.ndarray
    half_separation: np.ndarray

    @property
    def shape(self) -> tuple[int, ...]:
        """Batch shape ``S``."""
        return self.status.shape

    @property
    def resolved(self) -> np.ndarray:
        """True where exactly one candidate survives the apertures."""
        return self.n_valid == 1

    @property
    def point(self) -> np.ndarray:
        """The resolved position, shape ``S + (3,)``: the valid candidate where ``n_valid == 1``,
        else zeros (check :attr:`resolved`)."""
        pick = np.where(self.valid[..., 0], 0, 1)
        p = np.take_along_axis(self.candidates, pick[..., None, None], axis=-2)[..., 0, :]
        return np.where(self.resolved[..., None], p, 0.0)


def _plane(R, t, r1, rk):
    """``u = R^T t`` and ``c = C / 2`` of the plane ``u . p = c`` of views 1 and k."""
    u = np.einsum("...ji,...j->...i", R, t)
    c = 0.5 * (rk * rk - r1 * r1 - np.sum(t * t, axis=-1))
    return u, c


def _transform(R, t, p):
    """``R p + t`` for points ``p`` of shape ``S + (2, 3)``."""
    return np.einsum("...ij,...kj->...ki", R, p) + t[..., None, :]


def _solve(R12, t12, R13, t13, r1, r2, r3, ap1, ap2, ap3) -> dict:
    """The result fields, lengths in metres. Each configuration whose lengths are far from 1 m is
    solved at a power-of-two scale (exact), so that no product of up to five lengths (``p0``)
    overflows or underflows; its lengths are scaled back before the aperture test."""
    e = row_exponents(r1, r2, r3, *np.moveaxis(t12, -1, 0), *np.moveaxis(t13, -1, 0))
    if e is None:
        return _solve_scaled(R12, t12, R13, t13, r1, r2, r3, ap1, ap2, ap3, None)
    down = [np.ldexp(x, -e) for x in (r1, r2, r3)]
    return _solve_scaled(R12, np.ldexp(t12, -e[..., None]), R13, np.ldexp(t13, -e[..., None]),
                         *down, ap1, ap2, ap3, (e, t12, t13))


def _solve_scaled(R12, t12, R13, t13, r1, r2, r3, ap1, ap2, ap3, unscaled) -> dict:
    """:func:`_solve` for lengths scaled by ``2**-e``; ``unscaled`` is ``(e, t12, t13)`` with
    the translations in metres (None if not scaled)."""
    u2, c2 = _plane(R12, t12, r1, r2)
    u3, c3 = _plane(R13, t13, r1, r3)
    n2 = np.linalg.norm(u2, axis=-1)  # = |t12|
    n3 = np.linalg.norm(u3, axis=-1)
    coincident_origin = ((n2 <= COINCIDENT_ORIGINS_RTOL * (r1 + r2))
                         | (n3 <= COINCIDENT_ORIGINS_RTOL * (r1 + r3)))
    s2, s3 = np.where(coincident_origin, 1.0, n2), np.where(coincident_origin, 1.0, n3)
    w = np.cross(u2, u3)
    wn = np.linalg.norm(w, axis=-1)
    sin_angle = wn / (s2 * s3)
    cos_angle = np.sum(u2 * u3, axis=-1) / (s2 * s3)
    angle = np.degrees(np.arctan2(sin_angle, np.abs(cos_angle)))
    parallel = ~coincident_origin & (sin_angle <= PARALLEL_PLANES_SIN_TOL)
    # offsets of the planes from sensor 1 along n2 (n3 = sign * n2 when parallel)
    same = np.abs(c2 / s2 - np.sign(cos_angle) * c3 / s3) <= COINCIDENT_PLANES_RTOL * r1
    coincident_planes = parallel & same
    has_line = ~coincident_origin & ~parallel
    ws = np.where(has_line, wn, 1.0)
    p0 = (c2[..., None] * np.cross(u3, w) + c3[..., None] * np.cross(w, u2)) / (ws * ws)[..., None]
    p0 = np.where(has_line[..., None], p0, 0.0)
    d = np.where(has_line[..., None], w / ws[..., None], 0.0)
    dist = np.linalg.norm(p0, axis=-1)
    h2 = (r1 - dist) * (r1 + dist)
    tangent = has_line & (np.abs(h2) <= LINE_TANGENT_RTOL * r1 * r1)
    two = has_line & ~tangent & (h2 > 0.0)
    h = np.where(two, np.sqrt(np.maximum(h2, 0.0)), 0.0)
    cand = p0[..., None, :] + np.stack([h, -h], axis=-1)[..., None] * d[..., None, :]
    exists = np.stack([two | tangent, two], axis=-1)
    cand = np.where(exists[..., None], cand, 0.0)
    ratio = np.where(has_line, dist / r1, np.inf)
    if unscaled is not None:  # lengths back to metres, exactly
        e, t12, t13 = unscaled
        cand, p0, h = np.ldexp(cand, e[..., None, None]), np.ldexp(p0, e[..., None]), np.ldexp(h, e)

    valid = (exists & ap1.contains(cand) & ap2.contains(_transform(R12, t12, cand))
             & ap3.contains(_transform(R13, t13, cand)))
    status = np.full(r1.shape, ThreeViewStatus.TWO_POINTS, dtype=np.int8)
    status[tangent] = ThreeViewStatus.ONE_POINT
    status[has_line & ~tangent & ~two] = ThreeViewStatus.NO_POINT
    status[parallel & ~coincident_planes] = ThreeViewStatus.PARALLEL_PLANES
    status[coincident_planes] = ThreeViewStatus.COINCIDENT_PLANES
    status[coincident_origin] = ThreeViewStatus.COINCIDENT_ORIGINS
    return dict(
        candidates=cand, valid=valid, n_valid=valid.sum(axis=-1).astype(np.int64), status=status,
        line_point=p0, line_direction=d,
        plane_angle_deg=np.where(coincident_origin, 0.0, angle),
        line_distance_ratio=ratio,
        half_separation=h,
    )


def three_view_points(R12, t12, R13, t13, r1, r2, r3, aperture1: Aperture, aperture2: Aperture,
                      aperture3: Aperture) -> ThreeViewResult:
    """Candidate 3-D positions of a feature ranged by three sidescan sensors with known poses.

    Parameters
    ----------
    R12, R13 : array_like, shape (..., 3, 3), or scipy.spatial.transform.Rotation
        Rotations from sensor-1 coordinates to sensor 2's (3's): ``p2 = R12 p1 + t12``,
        ``p3 = R13 p1 + t13``.
    t12, t13 : array_like, shape (..., 3)
        Translations (m): sensor 1's origin in frame 2 (frame 3).
    r1, r2, r3 : array_like, shape (...)
        Measured ranges (m) to the feature; > 0. Any finite magnitude: configurations far from
        1 m are solved at a power-of-two scale (exact), so no square overflows or underflows.
    aperture1, aperture2, aperture3 : Aperture
        Fields of view of the three sensors, each in its own frame.

    The batch shapes broadcast together to ``S`` (which may be empty, e.g. ``(0,)`` or
    ``(2, 0)``). Numeric arguments must be real numbers: Python or NumPy ints and floats, or
    arrays of them.

    Returns
    -------
    ThreeViewResult
        Candidates ``S + (2, 3)`` in frame 1 (never NaN), their validity, status and the
        conditioning measures ``plane_angle_deg``, ``line_distance_ratio`` and
        ``half_separation``.

    Raises
    ------
    TypeError
        (:class:`~sss_locus.geometry.validation.InputTypeError`, also a ``ValueError``) naming
        the argument: booleans, complex numbers, strings, dates, datetimes or timedeltas,
        ``None`` or object arrays for a numeric argument; an aperture that is not an
        :class:`Aperture`.
    ValueError
        Naming the argument: a rotation that is not proper, a non-finite value, a wrong
        trailing shape, a range that is not positive, or batch shapes that do not broadcast.

    Notes
    -----
    Degenerate geometry has defined results (see :class:`ThreeViewStatus`): parallel planes give
    no point, coincident planes leave the two-view circle (no point returned), coincident
    origins give no point. The order of the two candidates follows ``d = u2 x u3``: slot 0 is
    ``p0 + h d``. Swapping views 2 and 3 reverses ``d`` and so swaps the slots.

    Examples
    --------
    >>> import numpy as np
    >>> from sss_locus import Aperture
    >>> ap = Aperture(360.0, 180.0, 1e3)
    >>> p = np.array([30.0, 5.0, -10.0])
    >>> t12, t13 = np.array([0.0, 20.0, 0.0]), np.array([15.0, 0.0, 3.0])
    >>> res = three_view_points(np.eye(3), t12, np.eye(3), t13, np.linalg.norm(p),
    ...                         np.linalg.norm(p + t12), np.linalg.norm(p + t13), ap, ap, ap)
    >>> bool(np.isclose(res.candidates, p).all(axis=-1).any())
    True
    """
    for name, ap in (("aperture1", aperture1), ("aperture2", aperture2), ("aperture3", aperture3)):
        check_aperture(ap, name, Aperture)
    R12 = as_rotation_matrices(R12, "R12")
    R13 = as_rotation_matrices(R13, "R13")
    t12 = as_float_array(t12, "t12", tail=(3,))
    t13 = as_float_array(t13, "t13", tail=(3,))
    r1, r2, r3 = (as_positive_array(v, n) for v, n in ((r1, "r1"), (r2, "r2"), (r3, "r3")))
    shape = broadcast_leading({"R12": R12.shape[:-2], "t12": t12.shape[:-1], "R13": R13.shape[:-2],
                               "t13": t13.shape[:-1], "r1": r1.shape, "r2": r2.shape, "r3": r3.shape})
    args = [np.broadcast_to(a, shape + a.shape[a.ndim - k:] if k else shape)
            for a, k in ((R12, 2), (t12, 1), (R13, 2), (t13, 1), (r1, 0), (r2, 0), (r3, 0))]
    return ThreeViewResult(**_solve(*args, aperture1, aperture2, aperture3))
