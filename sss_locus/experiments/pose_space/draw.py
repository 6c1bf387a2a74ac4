"""The candidate configurations of the pose-space sampler: its random draws and their geometry.

The method is that of :mod:`sss_locus.experiments.pose_space.study` (its module docstring, steps 1-4).
A round of ``m`` candidates is drawn in two stages: :func:`draw_numbers` takes every random
number the round uses from the block's generator, in a fixed order and amount that depend only
on the spec and ``m``; :func:`candidates` turns them into configurations and the acceptance
mask, row by row (numpy's elementwise arithmetic: a row's numbers do not depend on the other
rows). :func:`draw_candidates` is the two together, the plain sampler.

:func:`draw_round` gives the same rows, bit for bit, at a fraction of the cost where most
candidates are rejected (about 70 % for the AUV): for a platform whose depth is not fixed it
decides acceptance from a short closed form of the constrained heights (:func:`_heights`: the
world ``z`` row of each rotation from the angles directly, instead of the quaternion route
that gives the whole rotation), and runs :func:`candidates` only on the rows kept. A decision
is taken from the short form only where its margin exceeds :data:`DECISION_MARGIN` (relative),
about a million times its rounding error; the few rows nearer a boundary are decided by
:func:`candidates` itself. ``tests/experiments/stats/test_throughput.py`` checks both the rows and the margins.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.spatial.transform import Rotation

from sss_locus.experiments.passes.straight_pass import attitude_angles, mount, transducer_stack, vehicle_attitude

DECISION_MARGIN = 1e-9
"""Acceptance decided from the short closed form only where every constraint holds or fails by
more than this times the platform's length scale (ranges, mounting and depths, in metres);
nearer rows go through the plain computation. Its rounding error is below 1e-15 of the scale."""


def spherical_to_cartesian(r, theta, phi) -> np.ndarray:
    """The paper's eq. (1): ``(r cos t cos p, r sin t cos p, r sin p)``; shape ``(..., 3)``.

    Parameters
    ----------
    r : array_like
        Ranges, metres.
    theta, phi : array_like
        Azimuth and elevation, radians; broadcast with ``r``.

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        Points in the sensor frame, metres.
    """
    cp = np.cos(phi)
    return np.stack([r * np.cos(theta) * cp, r * np.sin(theta) * cp, r * np.sin(phi)], axis=-1)


def _range_angles(u, ap, distribution, window_deg=None):
    """Range, azimuth, elevation from ``u`` ``(3, n)`` uniform in (0, 1]."""
    lo, hi = ap.min_range, ap.max_range
    if distribution == "angles":
        r = lo + (hi - lo) * u[0]
        phi = (2.0 * u[2] - 1.0) * ap.half_elevation_rad
    else:
        r = np.cbrt(lo ** 3 + (hi ** 3 - lo ** 3) * u[0])
        phi = np.arcsin((2.0 * u[2] - 1.0) * math.sin(ap.half_elevation_rad))
    if window_deg is None:
        theta = (2.0 * u[1] - 1.0) * ap.half_azimuth_rad
    else:
        a, b = np.radians(window_deg)
        theta = a + (b - a) * (1.0 - u[1])
    return r, theta, phi


def _sides(rng, n, choice):
    if choice == "either":
        return rng.random(n) < 0.5  # True = port
    return np.full(n, choice == "port")


def _solve_azimuth(pick_second, a_row, r2, phi2, depth_target, half_az):
    """Azimuth ``theta`` with ``a . p2(r2, theta, phi2) = depth_target``; NaN where none fits.

    ``a . p2 = A cos(theta) + B sin(theta) + r2 a_z sin(phi2)``, with ``A = r2 cos(phi2) a_x``,
    ``B = r2 cos(phi2) a_y``; the two roots are ``atan2(B, A) ± arccos(D / hypot(A, B))``;
    where both are in the aperture, ``pick_second`` chooses.
    """
    A = r2 * np.cos(phi2) * a_row[:, 0]
    B = r2 * np.cos(phi2) * a_row[:, 1]
    D = depth_target - r2 * np.sin(phi2) * a_row[:, 2]
    rho = np.hypot(A, B)
    with np.errstate(invalid="ignore", divide="ignore"):
        c = D / rho
    ok = (rho > 0) & (np.abs(c) <= 1.0)
    base = np.arctan2(B, A)
    delta = np.arccos(np.clip(c, -1.0, 1.0))
    roots = np.stack([base + delta, base - delta])
    roots = (roots + np.pi) % (2.0 * np.pi) - np.pi
    inside = ok & (np.abs(roots) <= half_az)
    first = np.where(inside[0] & inside[1], np.where(pick_second, roots[1], roots[0]),
                     np.where(inside[0], roots[0], roots[1]))
    return np.where(inside[0] | inside[1], first, np.nan)


def _solved(spec) -> bool:
    return spec.profile == "platform" and spec.platform.fixed_depth


def draw_numbers(spec, rng, m: int) -> dict[str, np.ndarray]:
    """Every random number of a round of ``m`` candidates, drawn from ``rng`` in the sampler's
    order; each array has the candidates along its last axis (``R2``: along its first).

    Parameters
    ----------
    spec : PoseSpaceSpec
        The study.
    rng : numpy.random.Generator
        The stream's generator.
    m : int
        Number of candidates.

    Returns
    -------
    dict of str to numpy.ndarray
        The draws by name (uniform numbers, rotations ``R2`` of shape ``(m, 3, 3)``).
    """
    pf = spec.platform
    d = {"port1": _sides(rng, m, spec.side1)}
    d["u1"] = 1.0 - rng.random((3, m))  # in (0, 1]: r never hits min_range = 0 exactly
    d["port2"] = _sides(rng, m, spec.side2)
    d["u2"] = 1.0 - rng.random((3, m))
    if spec.profile == "unconstrained":
        d["R2"] = Rotation.random(m, rng=rng).as_matrix()
        return d
    d["yaw"] = rng.uniform(-180.0, 180.0, m)
    d["pitch"] = rng.uniform(-1.0, 1.0, m) * pf.pitch_max_deg
    d["roll"] = rng.uniform(-1.0, 1.0, m) * pf.roll_max_deg
    if _solved(spec):
        d["pick_second"] = rng.random(m) < 0.5
    elif spec.vehicle_depths == "in_water":  # drawn last: the draws above stay
        d["d1"] = (rng.uniform(pf.depth_min_m, pf.depth_max_m, m) if spec.vehicle1_depth_m is None
                   else np.full(m, float(spec.vehicle1_depth_m)))
    return d


def rows_of(d: dict[str, np.ndarray], rows) -> dict[str, np.ndarray]:
    """The draws of :func:`draw_numbers` for the candidates ``rows`` only.

    Parameters
    ----------
    d : dict of str to numpy.ndarray
        Draws of :func:`draw_numbers`.
    rows : array_like of int or bool
        Candidates kept (indices or a mask along the candidates' axis).

    Returns
    -------
    dict of str to numpy.ndarray
        The same draws for those candidates only.
    """
    return {k: v[rows] if k == "R2" else v[..., rows] for k, v in d.items()}


def candidates(spec, d: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The candidate configurations of the draws ``d`` and a boolean ``accept`` mask (the
    constraints); the sensors' world rotations ``R1``, ``R2``.

    Parameters
    ----------
    spec : PoseSpaceSpec
        The study.
    d : dict of str to numpy.ndarray
        Draws of :func:`draw_numbers`.

    Returns
    -------
    dict of str to numpy.ndarray
        The configurations (ranges in metres, angles in radians, world positions and rotations)
        and ``accept``, a boolean mask, one entry per candidate.
    """
    pf = spec.platform
    ap = pf.sonar.aperture()
    port1, port2 = d["port1"], d["port2"]
    R1, o1 = transducer_stack(pf, port1)  # vehicle 1 = world
    r1, th1, ph1 = _range_angles(d["u1"], ap, spec.feature_distribution, spec.azimuth1_window_deg)
    f = np.einsum("nij,nj->ni", R1, spherical_to_cartesian(r1, th1, ph1)) + o1
    M2, m2 = transducer_stack(pf, port2)
    solved = _solved(spec)
    r2, th2, ph2 = _range_angles(d["u2"], ap, spec.feature_distribution,
                                 None if solved else spec.azimuth2_window_deg)
    m = port1.size
    if spec.profile == "unconstrained":
        R2 = d["R2"]
        Rv2 = np.einsum("nij,nkj->nik", R2, M2)  # R2 M2^T
        yaw, pitch, roll = attitude_angles(Rotation.from_matrix(Rv2))
    else:
        yaw, pitch, roll = d["yaw"], d["pitch"], d["roll"]
        Rv2 = vehicle_attitude(yaw, pitch, roll).as_matrix()
        R2 = Rv2 @ M2
    mount2 = np.einsum("nij,nj->ni", Rv2, m2)
    accept = np.ones(m, bool)
    if solved:
        # vehicle 2 reference at z = 0 (same depth as vehicle 1): o2_z = mount2_z, so the world
        # z of R2 p2 must equal f_z - mount2_z
        th2 = _solve_azimuth(d["pick_second"], R2[:, 2, :], r2, ph2, f[:, 2] - mount2[:, 2], ap.half_azimuth_rad)
        accept &= np.isfinite(th2)
        th2 = np.where(accept, th2, 0.0)
        if spec.azimuth2_window_deg is not None:
            lo2, hi2 = np.radians(spec.azimuth2_window_deg)
            accept &= (th2 >= lo2) & (th2 <= hi2)
    o2 = f - np.einsum("nij,nj->ni", R2, spherical_to_cartesian(r2, th2, ph2))
    v2_z = o2[:, 2] - mount2[:, 2]
    if spec.profile == "platform":
        accept &= _constraints(spec, f[:, 2], o1[:, 2], o2[:, 2], v2_z, d.get("d1"), strict=True)
    return dict(accept=accept, R1=R1, R2=R2, r1=r1, r2=r2, th1=th1, th2=th2, ph1=ph1, ph2=ph2,
                yaw=yaw, pitch=pitch, roll=roll, port1=port1, port2=port2, v2_z=v2_z,
                f=f, o1=o1, o2=o2)


def _constraints(spec, f_z, o1_z, o2_z, v2_z, d1, strict: bool, tol: float = 0.0):
    """The plausibility rules (``profile="platform"``): with ``strict``, whether each row meets
    them; otherwise ``(accept, sure)``, ``sure`` where every margin exceeds ``tol``."""
    pf = spec.platform
    margins = []  # each rule as a margin, positive where it holds
    if spec.feature_below:
        margins += [o1_z - f_z, o2_z - f_z]
    if not pf.fixed_depth and spec.vehicle_depths == "difference":
        margins.append((pf.depth_max_m - pf.depth_min_m) - np.abs(v2_z))
    elif not pf.fixed_depth and spec.vehicle_depths == "in_water":
        margins += [(d1 - v2_z) - pf.depth_min_m, pf.depth_max_m - (d1 - v2_z)]
    if strict:  # the plain sampler's comparisons, as written there
        accept = np.ones(f_z.shape, bool)
        if spec.feature_below:
            accept &= (f_z < o1_z) & (f_z < o2_z)
        if not pf.fixed_depth and spec.vehicle_depths == "difference":
            accept &= np.abs(v2_z) <= pf.depth_max_m - pf.depth_min_m
        elif not pf.fixed_depth and spec.vehicle_depths == "in_water":
            accept &= (d1 - v2_z >= pf.depth_min_m) & (d1 - v2_z <= pf.depth_max_m)
        return accept
    accept, sure = np.ones(f_z.shape, bool), np.ones(f_z.shape, bool)
    for margin in margins:
        accept &= margin > 0
        sure &= np.abs(margin) > tol
    return accept, sure


def draw_candidates(spec, rng, m: int) -> dict[str, np.ndarray]:
    """``m`` candidate configurations and their ``accept`` mask: the plain sampler's round.

    Parameters
    ----------
    spec : PoseSpaceSpec
        The study.
    rng : numpy.random.Generator
        The stream's generator.
    m : int
        Number of candidates.

    Returns
    -------
    dict of str to numpy.ndarray
        :func:`candidates` of :func:`draw_numbers` (with ``accept``).
    """
    return candidates(spec, draw_numbers(spec, rng, m))


def length_scale(pf) -> float:
    """Metres against which :data:`DECISION_MARGIN` is taken: twice the maximum range, the
    transducers' distances from the reference point and the deepest depth, plus 1.

    Parameters
    ----------
    pf : Platform
        The platform of the study.

    Returns
    -------
    float
        The length scale, metres.
    """
    mounts = max(float(np.linalg.norm(t.position_m)) for t in pf.transducers.values())
    return 2.0 * pf.sonar.max_range_m + 2.0 * mounts + abs(pf.depth_max_m) + abs(pf.depth_min_m) + 1.0


def _heights(spec, d):
    """The world heights the constraints compare (``f_z``, ``o1_z``, ``o2_z``, ``v2_z``) by the
    short closed form: only world ``z`` rows, vehicle 2's ``Rv2[2] = (sin p, cos p sin r,
    cos p cos r)`` (``Rz(yaw) Ry(-pitch) Rx(roll)``: the yaw leaves it alone), each side's
    mounting as scalars and the side picked last."""
    pf = spec.platform
    ap = pf.sonar.aperture()
    mounts = {port: mount(pf.transducers["port" if port else "starboard"]) for port in (False, True)}
    p1 = _cartesian(*_range_angles(d["u1"], ap, spec.feature_distribution, spec.azimuth1_window_deg))
    p2 = _cartesian(*_range_angles(d["u2"], ap, spec.feature_distribution, spec.azimuth2_window_deg))
    pitch, roll = np.radians(d["pitch"]), np.radians(d["roll"])
    cos_p = np.cos(pitch)
    z = (np.sin(pitch), cos_p * np.sin(roll), cos_p * np.cos(roll))
    f_z, o1_z, o2_z, v2_z = {}, {}, {}, {}
    for port, (M, m) in mounts.items():
        o1_z[port] = m[2]
        f_z[port] = M[2, 0] * p1[0] + M[2, 1] * p1[1] + M[2, 2] * p1[2] + m[2]
    f_z = np.where(d["port1"], f_z[True], f_z[False])
    o1_z = np.where(d["port1"], o1_z[True], o1_z[False])
    for port, (M, m) in mounts.items():
        q = [M[i, 0] * p2[0] + M[i, 1] * p2[1] + M[i, 2] * p2[2] for i in range(3)]  # M2 p2
        o2_z[port] = f_z - (z[0] * q[0] + z[1] * q[1] + z[2] * q[2])
        v2_z[port] = o2_z[port] - (z[0] * m[0] + z[1] * m[1] + z[2] * m[2])
    return (f_z, o1_z, np.where(d["port2"], o2_z[True], o2_z[False]),
            np.where(d["port2"], v2_z[True], v2_z[False]))


def _cartesian(r, theta, phi):
    cp = np.cos(phi)
    return r * np.cos(theta) * cp, r * np.sin(theta) * cp, r * np.sin(phi)


def draw_round(spec, rng, m: int, need: int) -> tuple[dict[str, np.ndarray], int]:
    """One round of :func:`draw_candidates`, reduced to its first ``need`` accepted rows:
    ``(rows, n_accepted)``, ``rows`` the arrays of those candidates (without ``accept``) and
    ``n_accepted`` how many of the ``m`` were accepted. The same numbers, bit for bit, as
    filtering :func:`draw_candidates` (module docstring).

    Parameters
    ----------
    spec : PoseSpaceSpec
        The study.
    rng : numpy.random.Generator
        The stream's generator.
    m : int
        Number of candidates drawn.
    need : int
        Accepted rows still needed by the block.

    Returns
    -------
    rows : dict of str to numpy.ndarray
        The first ``min(need, n_accepted)`` accepted candidates.
    n_accepted : int
        Candidates of the ``m`` accepted.
    """
    d = draw_numbers(spec, rng, m)
    if spec.profile != "platform" or spec.platform.fixed_depth:
        cand = candidates(spec, d)
        keep = np.flatnonzero(cand.pop("accept"))
        return {k: v[keep[:need]] for k, v in cand.items()}, keep.size
    accept, sure = _constraints(spec, *_heights(spec, d), d.get("d1"), strict=False,
                                tol=DECISION_MARGIN * length_scale(spec.platform))
    unsure = np.flatnonzero(~sure)
    if unsure.size:  # near a boundary: the plain computation decides
        accept[unsure] = candidates(spec, rows_of(d, unsure))["accept"]
    keep = np.flatnonzero(accept)
    used = keep[:need]
    rows = candidates(spec, rows_of(d, used if used.size else [0]))  # (one row: scipy needs a rotation)
    if not rows.pop("accept")[:used.size].all():
        raise AssertionError("the short form accepted a candidate the plain sampler rejects")
    return {k: v[:used.size] for k, v in rows.items()}, keep.size
