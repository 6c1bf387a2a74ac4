"""One straight survey pass: the vehicle pose along its track and the ping that sees a feature.

Shared by the samplers (:mod:`sss_locus.experiments.pose_space.study`,
:mod:`sss_locus.experiments.survey_passes.study`, :mod:`sss_locus.experiments.passes.view_sets`).

Geometry (frames as in :mod:`sss_locus.experiments.datamodel.platforms`)
--------------------------------------------------
World frame: origin at the feature, ``x`` along pass 1's heading, ``y`` to its port, ``z`` up.
Pass ``k`` is a straight, horizontal track at heading ``h_k`` (pass 1: 0; pass 2: the crossing
angle ``gamma``, positive toward port), with unit direction ``e = (cos h, sin h, 0)`` and port
normal ``n = (-sin h, cos h, 0)``. The vehicle holds a constant pitch (positive nose-up) and
zero roll, its body axis turned by the pitch about ``n`` while it moves along ``e`` (a trimmed
vehicle at constant altitude). At along-track position ``s`` its reference point is
``P(s) = s e - y n + a z``, where ``a`` is the altitude of the reference point above the feature
and ``y`` is the signed across-track ground offset of the feature (positive to port).

The observing transducer (rotation ``M`` and position ``m`` in the vehicle frame) has axes
``W = R_v M`` and origin ``o(s) = P(s) + R_v m`` in the world, so the feature in the transducer
frame is **linear in s**::

    p(s) = W^T (0 - o(s)) = a_vec - s b,   a_vec = W^T (y n - a z - R_v m),   b = W^T e,

with ``|b| = 1``. The ping that sees the feature at in-beam elevation ``phi`` satisfies
``p_z = sin(phi) |p|``. Squaring gives ``A s^2 + B s + C = 0`` with ``A = b_z^2 - sin^2 phi``,
``B = -2 (a_z b_z - sin^2 phi (a.b))``, ``C = a_z^2 - sin^2 phi |a|^2``. Its discriminant is
``B^2 - 4AC = 4 sin^2 phi D`` with ``D = b_z^2 |a|^2 + a_z^2 - 2 a_z b_z (a.b)
- sin^2 phi (|a|^2 - (a.b)^2)``, so the roots are ``s = (a_z b_z - sin^2 phi (a.b)
± |sin phi| sqrt(D)) / A`` without cancellation. For ``phi = 0`` the condition is linear,
``s = a_z / b_z``. When ``A > 0`` (the track crosses the beam plane more steeply than the beam's
half-width, ``|b_z| > |sin phi|``; ``|b_z| = cos(pitch)`` here) the elevation along the line runs
from ``-asin(b_z)`` to ``+asin(b_z)``, so the line meets the ``+phi`` and ``-phi`` cones exactly
once each: the root kept is the one whose ``p_z`` has the sign of ``phi``
(:func:`solve_in_beam`). ``A <= 0`` (pitch within the beam half-width of 90 deg) has no unique
ping and is reported as the rejection ``"no_solution"``.
"""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy.spatial.transform import Rotation

from sss_locus.experiments.datamodel.platforms import SIDES, Platform

REJECTION_REASONS = ("outside_swath", "no_solution", "outside_azimuth", "out_of_range")
"""Why a draw is rejected: pass 2's matched offset falls outside its swath; no unique ping
(``A <= 0``); the feature is outside the observing transducer's azimuth aperture, or outside
its range limits, at the ping."""


def vehicle_attitude(yaw_deg, pitch_deg, roll_deg) -> Rotation:
    """``R_world_vehicle = Rz(yaw) Ry(-pitch) Rx(roll)``: yaw toward port, pitch nose-up positive.

    Parameters
    ----------
    yaw_deg, pitch_deg, roll_deg : float or array_like
        Vehicle heading (toward port positive), pitch (nose-up positive) and roll, degrees;
        broadcast against each other.

    Returns
    -------
    scipy.spatial.transform.Rotation
        ``Rotation.from_euler("ZYX", [yaw, -pitch, roll], degrees=True)``: one rotation per
        broadcast element (a single one for scalars).
    """
    angles = np.stack(np.broadcast_arrays(np.asarray(yaw_deg, float), -np.asarray(pitch_deg, float),
                                          np.asarray(roll_deg, float)), axis=-1)
    return Rotation.from_euler("ZYX", angles, degrees=True)


def level_attitude_matrices(yaw_deg, pitch_deg) -> np.ndarray:
    """:func:`vehicle_attitude` with zero roll as matrices, one rotation computed per distinct
    ``(yaw, pitch)`` when the rows repeat a few attitudes (a survey line's every ping, a layout's
    few headings), so the result equals ``vehicle_attitude(yaw, pitch, 0).as_matrix()`` exactly.

    Parameters
    ----------
    yaw_deg, pitch_deg : array_like, shape (n,)
        Vehicle heading (toward port positive) and pitch (nose-up positive), degrees.

    Returns
    -------
    numpy.ndarray, shape (n, 3, 3)
        ``R_world_vehicle`` per row.
    """
    yaw, pitch = (np.ravel(a).astype(float) for a in np.broadcast_arrays(yaw_deg, pitch_deg))
    if yaw.size > 64 and np.all(pitch == pitch[0]):
        u, inv = np.unique(yaw, return_inverse=True)
        if 4 * u.size <= yaw.size:
            one = vehicle_attitude(u, np.full(u.size, pitch[0]), np.zeros(u.size)).as_matrix().reshape(-1, 3, 3)
            return one[inv.ravel()]
    return vehicle_attitude(yaw, pitch, np.zeros(yaw.size)).as_matrix().reshape(-1, 3, 3)


def attitude_angles(rot: Rotation) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Inverse of :func:`vehicle_attitude`: (yaw, pitch, roll) in degrees.

    Parameters
    ----------
    rot : scipy.spatial.transform.Rotation
        Vehicle attitudes ``R_world_vehicle``.

    Returns
    -------
    yaw_deg, pitch_deg, roll_deg : numpy.ndarray
        One per rotation, degrees (pitch nose-up positive).
    """
    e = np.atleast_2d(rot.as_euler("ZYX", degrees=True))
    return e[:, 0], -e[:, 1], e[:, 2]


@functools.lru_cache(maxsize=64)
def mount(transducer) -> tuple[np.ndarray, np.ndarray]:
    """A transducer's rotation matrix and position (read-only; computed once per transducer)."""
    out = transducer.rotation.as_matrix(), transducer.position_m
    for a in out:
        a.setflags(write=False)
    return out


def transducer_stack(platform, is_port):
    """Stacked transducer rotations (matrices) and positions for a boolean port mask: row ``i``
    is a copy of the port transducer's where ``is_port[i]``, else of the starboard one's.

    Parameters
    ----------
    platform : Platform
        The platform.
    is_port : numpy.ndarray of bool, shape (n,)
        Whether row ``i`` observes with the port transducer.

    Returns
    -------
    rotations : numpy.ndarray, shape (n, 3, 3)
        Transducer-to-vehicle rotation matrices.
    positions : numpy.ndarray, shape (n, 3)
        Transducer positions in the vehicle frame, metres.
    """
    mats, pos = _mount_pair(platform.transducers["starboard"], platform.transducers["port"])  # index 0, 1
    pick = np.asarray(is_port, bool).astype(np.intp)
    return np.take(mats, pick, axis=0), np.take(pos, pick, axis=0)


@functools.lru_cache(maxsize=64)
def _mount_pair(starboard, port) -> tuple[np.ndarray, np.ndarray]:
    """The two transducers' rotation matrices and positions stacked (starboard, port)."""
    out = tuple(np.stack([mount(starboard)[i], mount(port)[i]]) for i in (0, 1))
    for a in out:
        a.setflags(write=False)
    return out


def swath_m(platform: Platform, is_port, altitude_m) -> tuple[np.ndarray, np.ndarray]:
    """Across-track ground offsets a level vehicle images at zero elevation.

    Parameters
    ----------
    platform : Platform
    is_port : array_like of bool
        Observing transducer: port (True) or starboard (False).
    altitude_m : array_like
        Height of the vehicle reference point above the feature, metres (broadcast with
        ``is_port``).

    Returns
    -------
    near, far : ndarray
        Ground offset from the vehicle centreline, toward the observing side, metres: the
        feature is inside the transducer's azimuth fan and range for ``near <= offset <= far``.
        From the depression angles ``tilt ± azimuth/2`` of the fan edges and the range limits;
        ``near`` may be slightly negative when the fan reaches past nadir. (With a minimum range
        above the transducer's height, the sliver past nadir is left out.)

    Raises
    ------
    ValueError
        If some altitude leaves no swath (transducer not above the feature, or higher than
        the maximum range).
    """
    is_port, alt = np.broadcast_arrays(np.asarray(is_port, bool), np.asarray(altitude_m, float))
    son = platform.sonar
    tr = {s: platform.transducers[s] for s in SIDES}
    pick = lambda f: np.where(is_port, f(tr["port"]), f(tr["starboard"]))
    H = alt - pick(lambda t: t.depth_m)
    tilt, lateral = pick(lambda t: t.tilt_deg), pick(lambda t: t.lateral_offset_m)
    bad = ~(H > 0) | ~(H < son.max_range_m)
    if np.any(bad):
        raise ValueError(f"altitude_m must put the transducer above the feature and less than the "
                         f"maximum range ({son.max_range_m} m) above it; got {alt[bad][:3]}")
    reach = np.sqrt(son.max_range_m ** 2 - H ** 2)
    d_max, d_min = tilt + son.azimuth_deg / 2, tilt - son.azimuth_deg / 2
    with np.errstate(divide="ignore", invalid="ignore"):
        near = np.where(d_max >= 180, -reach, np.where(d_max <= 0, np.inf, H / np.tan(np.radians(d_max))))
        far = np.where(d_min > 0, H / np.tan(np.radians(d_min)), np.inf)
    near = np.maximum(near, -reach)
    if son.min_range_m > 0:
        near = np.maximum(near, np.sqrt(np.maximum(son.min_range_m ** 2 - H ** 2, 0.0)))
    far = np.minimum(far, reach)
    if np.any(far <= near):
        raise ValueError(f"no swath: the {platform.key!r} fan sees no seafloor at altitude_m "
                         f"{alt[far <= near][:3]}")
    return lateral + near, lateral + far


def solve_in_beam(a, b, elevation_rad) -> tuple[np.ndarray, np.ndarray]:
    """Along-track position ``s`` at which ``p(s) = a - s b`` has elevation ``elevation_rad``.

    Parameters
    ----------
    a : array_like, shape (..., 3)
        Feature in the transducer frame at ``s = 0``, metres.
    b : array_like, shape (..., 3)
        Unit track direction in the transducer frame.
    elevation_rad : array_like, shape (...)
        In-beam elevation, radians.

    Returns
    -------
    s : ndarray, shape (...)
        Metres along the track (0 where there is no unique solution).
    ok : ndarray of bool
        False where ``b_z**2 <= sin(elevation)**2`` (no unique ping; see the module docstring).
    """
    a, b = np.asarray(a, float), np.asarray(b, float)
    sphi = np.sin(np.asarray(elevation_rad, float))
    sig = sphi ** 2
    az, bz = a[..., 2], b[..., 2]
    ab, aa = np.sum(a * b, axis=-1), np.sum(a * a, axis=-1)
    A = bz ** 2 - sig
    ok = A > 0
    A = np.where(ok, A, 1.0)
    D = np.maximum(bz ** 2 * aa + az ** 2 - 2 * az * bz * ab - sig * (aa - ab ** 2), 0.0)
    mid, half = (az * bz - sig * ab) / A, np.abs(sphi) * np.sqrt(D) / A
    roots = np.stack([mid + half, mid - half])
    pz = az - roots * bz
    s = np.where(np.sign(sphi) * pz[0] >= np.sign(sphi) * pz[1], roots[0], roots[1])
    return np.where(ok, s, 0.0), ok


def observe_pass(platform: Platform, is_port, heading_deg, ground_offset_m, altitude_m,
                 pitch_deg, elevation_rad) -> dict[str, np.ndarray]:
    """The ping of one straight pass that sees the feature (at the origin) at ``elevation_rad``.

    The arguments after ``platform`` are arrays broadcast to one shape ``(n,)``.

    Parameters
    ----------
    platform : Platform
        The vehicle and its transducers.
    is_port : bool
        Observing transducer.
    heading_deg : float
        Track heading, degrees, positive toward port (counter-clockwise from above).
    ground_offset_m : float
        Feature's across-track ground offset from the centreline toward the observing side, m.
    altitude_m : float
        Vehicle reference point above the feature, metres.
    pitch_deg : float
        Vehicle pitch, degrees, positive nose-up.
    elevation_rad : float
        In-beam elevation of the feature, radians.

    Returns
    -------
    dict
        ``W`` (n, 3, 3): transducer axes in the world (``p_world = W p + origin``); ``origin``
        (n, 3): transducer origin at the ping, m; ``p`` (n, 3): feature in the transducer frame;
        ``s`` (n,): along-track position of the vehicle at the ping, m; ``range_m``,
        ``azimuth_rad``, ``elevation_rad``; ``reason`` (n,) int8: -1 if visible, else the index
        in :data:`REJECTION_REASONS`.
    """
    arrays = np.broadcast_arrays(np.asarray(is_port, bool), *(np.asarray(v, float) for v in (
        heading_deg, ground_offset_m, altitude_m, pitch_deg, elevation_rad)))
    port, head, g, alt, pitch, phi = (np.atleast_1d(x) for x in arrays)
    M, m = transducer_stack(platform, port)
    Rv = level_attitude_matrices(head, pitch)
    W = Rv @ M
    h = np.radians(head)
    e = np.stack([np.cos(h), np.sin(h), np.zeros_like(h)], -1)
    n = np.stack([-np.sin(h), np.cos(h), np.zeros_like(h)], -1)
    y = np.where(port, g, -g)
    mount = np.einsum("nij,nj->ni", Rv, m)
    rel0 = y[:, None] * n - alt[:, None] * np.array([0.0, 0.0, 1.0]) - mount  # feature - o(0)
    a = np.einsum("nji,nj->ni", W, rel0)
    b = np.einsum("nji,nj->ni", W, e)
    s, ok = solve_in_beam(a, b, phi)
    p = a - s[:, None] * b
    rng_m = np.linalg.norm(p, axis=-1)
    azim = np.arctan2(p[:, 1], p[:, 0])
    son = platform.sonar
    reason = np.full(port.shape, -1, np.int8)
    out_range = (rng_m > son.max_range_m) | (rng_m < son.min_range_m)
    for code, bad in ((3, out_range), (2, np.abs(azim) > math.radians(son.azimuth_deg / 2)), (1, ~ok)):
        reason = np.where(bad, np.int8(code), reason)
    origin = s[:, None] * e - y[:, None] * n + alt[:, None] * np.array([0.0, 0.0, 1.0]) + mount
    return dict(W=W, origin=origin, p=p, s=s, range_m=rng_m, azimuth_rad=azim,
                elevation_rad=np.arcsin(np.clip(p[:, 2] / np.where(rng_m > 0, rng_m, 1.0), -1, 1)),
                reason=reason)
