"""Single- and two-view positions of a feature: slant-range correction and the locus point
nearest a prior.

Flat-seafloor baseline (:func:`flat_seafloor_points`)
-----------------------------------------------------
Everyday sidescan processing assumes a flat seafloor at the sensor's altitude ``H`` (measured at
nadir, e.g. by an altimeter): a return at slant range ``r`` lies at ground range
``sqrt(r^2 - H^2)``. In 3-D, the return is placed in the sonar's zero-elevation plane (the plane
of the wide fan, normal the sensor's ``z`` axis ``n``) on the horizontal plane ``H`` below the
sensor: that plane pair meets in the line ``o + lambda m + s d`` with ``d = n x z_up / |n x z_up|``
(horizontal, across-track), ``m = n x d`` and ``lambda = -H / m_z``, so ``|lambda| = H`` for a
level sensor, and the point at range ``r`` has ``s = +-sqrt(r^2 - lambda^2)``: the ground range.
The sign puts it on the side the transducer looks to (``s d . x_sensor >= 0``). A range shorter
than ``|lambda|`` is placed at ``s = 0`` (flag ``below_altitude``); a zero-elevation plane within
1e-9 of horizontal has no such line (flag ``degenerate``, the point is the sensor origin).

Two views and a prior (:func:`nearest_locus_points`)
----------------------------------------------------
Two views leave the feature on the ambiguity locus (:func:`~sss_locus.geometry.locus.
two_view_locus`). A point estimate needs a prior; :func:`nearest_locus_points` returns the point
of the cropped locus nearest a given prior point (the projection onto the circle when it falls
inside an arc, else the nearest arc end). Where noise empties the cropped locus it falls back to
the nearest point of the uncropped circle, and where the spheres do not meet, to the point of
sphere 1 nearest the prior (:class:`TwoViewStatus`).
"""

from __future__ import annotations

import enum

import numpy as np

from .locus_result import LocusResult, LocusStatus
from .validation import as_float_array, broadcast_leading


class TwoViewStatus(enum.IntEnum):
    """Where the two-view estimate comes from."""

    LOCUS = 0
    """The point of the cropped locus nearest the prior."""
    CIRCLE = 1
    """The cropped locus is empty (noise moved the circle out of an aperture): the point of the
    uncropped circle nearest the prior."""
    SPHERE = 2
    """The spheres do not meet (or the origins coincide): the point of range sphere 1 nearest
    the prior."""


def flat_seafloor_points(W, origin, ranges, altitude_m) -> dict:
    """Slant-range correction: the feature on a flat seafloor ``altitude_m`` below the sensor.

    Parameters
    ----------
    W : array_like, shape S + (3, 3)
        Sensor axes in the world frame (columns: boresight ``x``, fan ``y``, elevation ``z``);
        world ``z`` is up.
    origin : array_like, shape S + (3,)
        Sensor origins, metres.
    ranges : array_like, shape S
        Slant ranges, metres (>= 0).
    altitude_m : array_like, shape S
        Height of the sensor above the (assumed flat) seafloor, metres.

    Returns
    -------
    dict
        ``point`` S + (3,) (world, metres), ``ground_range_m`` S, ``below_altitude`` S (bool),
        ``degenerate`` S (bool).
    """
    W = as_float_array(W, "W", tail=(3, 3))
    o = as_float_array(origin, "origin", tail=(3,))
    r = as_float_array(ranges, "ranges")
    H = as_float_array(altitude_m, "altitude_m")
    if np.any(r < 0):
        raise ValueError("ranges must be >= 0 m")
    shape = broadcast_leading({"W": W.shape[:-2], "origin": o.shape[:-1], "ranges": r.shape,
                               "altitude_m": H.shape})
    nz = W[..., :, 2]
    d = np.stack([nz[..., 1], -nz[..., 0], np.zeros_like(nz[..., 0])], axis=-1)  # n x z_up
    dn = np.linalg.norm(d, axis=-1)
    degenerate = np.broadcast_to(dn <= 1e-9, shape)
    d = d / np.where(dn > 1e-9, dn, 1.0)[..., None]
    m = np.cross(nz, d)
    mz = np.where(np.abs(m[..., 2]) > 0, m[..., 2], 1.0)
    lam = -H / mz
    g2 = r * r - lam * lam
    below = np.broadcast_to(g2 < 0, shape) & ~degenerate
    side = np.where(np.einsum("...i,...i->...", d, W[..., :, 0]) >= 0, 1.0, -1.0)
    s = side * np.sqrt(np.maximum(g2, 0.0))
    point = o + lam[..., None] * m + s[..., None] * d
    point = np.where(degenerate[..., None], np.broadcast_to(o, shape + (3,)), point)
    return dict(point=np.broadcast_to(point, shape + (3,)).copy(),
                ground_range_m=np.broadcast_to(np.where(degenerate, 0.0, np.abs(s)), shape).copy(),
                below_altitude=below.copy(), degenerate=degenerate.copy())


def nearest_locus_points(locus: LocusResult, prior, r1) -> dict:
    """The point of the two-view locus nearest ``prior`` (see the module docstring).

    Parameters
    ----------
    locus : LocusResult
        From :func:`~sss_locus.geometry.locus.two_view_locus` (``outputs="all"``), batch ``S``.
    prior : array_like, shape S + (3,)
        Prior positions in sensor 1's frame, metres.
    r1 : array_like, shape S
        Range of view 1, metres (for the fallback onto sphere 1).

    Returns
    -------
    dict
        ``point`` S + (3,) in sensor 1's frame, ``status`` S (:class:`TwoViewStatus` codes),
        ``length_m`` S (the locus length).
    """
    q = as_float_array(prior, "prior", tail=(3,))
    d = q - locus.center
    a = np.einsum("...i,...i->...", d, locus.basis1)
    b = np.einsum("...i,...i->...", d, locus.basis2)
    alpha = np.arctan2(b, a)
    start, end = locus.arc_start, locus.arc_end
    with np.errstate(invalid="ignore"):
        inside = np.any((np.mod(alpha[..., None] - start, 2 * np.pi) <= end - start)
                        & ~np.isnan(start), axis=-1)
    ends = np.concatenate([start, end], axis=-1)
    safe_ends = np.where(np.isnan(ends), 0.0, ends)
    pts = locus.point_at(safe_ends)  # S + (2W, 3)
    dist = np.linalg.norm(pts - q[..., None, :], axis=-1)
    dist = np.where(np.isnan(ends), np.inf, dist)
    pick = np.argmin(dist, axis=-1)
    nearest_end = np.take_along_axis(pts, pick[..., None, None], axis=-2)[..., 0, :]
    on_circle = locus.point_at(alpha)
    has_arc = locus.n_arcs > 0
    circle = locus.exists & (locus.status != LocusStatus.COINCIDENT_ORIGINS)
    qn = np.linalg.norm(q, axis=-1)
    r1 = as_float_array(r1, "r1")
    on_sphere = q * (r1 / np.where(qn > 0, qn, 1.0))[..., None]
    point = np.where((has_arc & inside)[..., None], on_circle,
                     np.where(has_arc[..., None], nearest_end,
                              np.where(circle[..., None], on_circle, on_sphere)))
    status = np.where(has_arc, TwoViewStatus.LOCUS,
                      np.where(circle, TwoViewStatus.CIRCLE, TwoViewStatus.SPHERE)).astype(np.int8)
    return dict(point=point, status=status, length_m=locus.length)



def two_view_points(W1, origin1, W2, origin2, r1, r2, prior, aperture1, aperture2, **locus_kw):
    """Two views of each feature and a prior, in the world frame: the locus of the views
    (:func:`~sss_locus.geometry.locus.two_view_locus`, ``outputs="all"``; ``locus_kw`` such as
    half-spaces passed on) and the point of it nearest ``prior`` (:func:`nearest_locus_points`).

    Parameters
    ----------
    W1, W2 : array_like, shape S + (3, 3)
        Sensor-to-world rotations of the two views.
    origin1, origin2 : array_like, shape S + (3,)
        Sensor origins, world frame, metres.
    r1, r2 : array_like, shape S
        Ranges, metres.
    prior : array_like, shape S + (3,)
        Prior positions, world frame, metres.
    aperture1, aperture2 : Aperture
    **locus_kw
        Further keywords of :func:`~sss_locus.geometry.locus.two_view_locus` (e.g. half-spaces).

    Returns
    -------
    locus : LocusResult
        In sensor 1's frame.
    nearest : dict
        :func:`nearest_locus_points`' result (``point`` in sensor 1's frame, ``status``, ``length_m``).
    point : ndarray, shape S + (3,)
        ``nearest["point"]`` in the world frame.
    """
    from .locus import two_view_locus
    from .poses import relative_pose

    W1, o1 = np.asarray(W1, float), np.asarray(origin1, float)
    R, t = relative_pose(W1, o1, W2, origin2)
    locus = two_view_locus(R, t, r1, r2, aperture1, aperture2, **locus_kw)
    prior1 = np.einsum("...ji,...j->...i", W1, np.asarray(prior, float) - o1)
    near = nearest_locus_points(locus, prior1, r1)
    return locus, near, np.einsum("...ij,...j->...i", W1, near["point"]) + o1
