"""A feature from three or more sidescan views: closed-form start, least-squares refinement,
a status for every feature.

For each feature (batched, no per-feature loop):

1. the first three views that saw it (in view order) give at most two candidates in closed form
   (:func:`~sss_locus.geometry.three_view_points.three_view_points`; with noise the line may
   miss sphere 1, and the point of the line nearest it, pushed onto the sphere, is used; where
   the three origins are collinear or coincide there is no candidate and ``prior`` is used);
2. each candidate is refined by Levenberg-Marquardt on the range residuals of *all* its views
   (:func:`~sss_locus.geometry.multiview.solve_ranges`) (the second only where it starts
   inside the widened apertures), and where neither becomes admissible (3.), ``prior`` is
   refined too;
3. a refined candidate is *admissible* if it converged, is determined (``J^T J`` non-singular),
   has a cost (sum of squared residuals in units of sigma) at most ``cost_limit``, lies no
   higher than ``ceiling_m`` (optional), and lies inside every view's aperture widened by
   ``aperture_margin_deg`` (in azimuth and elevation;
   the margin absorbs attitude errors: with an attitude error larger than the beam, the true
   feature lies outside the *estimated* beam).

Statuses (:class:`MultiViewStatus`): one admissible point (two within ``1e-6`` of the range of
each other count as one) resolves the feature; two distinct admissible points leave it
ambiguous (the estimate is the one with the lower cost); fewer than three views, a singular
``J^T J`` (collinear passes) and no admissible point are reported as such. ``point`` is never
NaN: where the status is not ``RESOLVED`` or ``AMBIGUOUS`` it is the best iterate (or the
prior, or zeros), not an estimate.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np

from .aperture import Aperture
from .multiview import check_views, solve_ranges
from .poses import relative_pose
from .three_view_points import ThreeViewStatus, three_view_points
from .validation import as_float_array, check_aperture

DISTINCT_RTOL = 1e-6
"""Two admissible refined candidates closer than ``DISTINCT_RTOL`` times the feature's largest
range are one solution (both starts reached the same minimum)."""
_OPEN = Aperture(360.0, 180.0, 1e300)


class MultiViewStatus(enum.IntEnum):
    """What N views give for one feature."""

    RESOLVED = 0
    """Exactly one admissible point."""
    AMBIGUOUS = 1
    """Two distinct admissible points (e.g. the three-view mirror pair, both inside the
    widened apertures, with three views); ``point`` is the one with the lower cost."""
    TOO_FEW_VIEWS = 2
    """Fewer than three views saw the feature (none: outside every aperture)."""
    DEGENERATE = 3
    """``J^T J`` is singular at the refined point (e.g. collinear sensor origins): the feature
    may turn about the line of the origins without changing a range."""
    DIVERGED = 4
    """No refined candidate is admissible (not converged, cost above ``cost_limit`` or outside
    the widened apertures)."""


@dataclass(frozen=True)
class MultiViewResult:
    """Estimates for ``n`` features (world frame, metres).

    Attributes
    ----------
    point : ndarray, shape (n, 3)
    status : ndarray of int8, shape (n,)
        :class:`MultiViewStatus` codes.
    covariance : ndarray, shape (n, 3, 3)
        First-order covariance ``(J^T J)^-1`` of ``point`` (weighted Jacobian, m^2); ``inf``
        where degenerate.
    cost : ndarray, shape (n,)
        Sum of squared weighted residuals at ``point``.
    n_views : ndarray of int, shape (n,)
    n_admissible : ndarray of int, shape (n,)
    three_view_status : ndarray of int8, shape (n,)
        :class:`~sss_locus.geometry.three_view_points.ThreeViewStatus` of the start (-1 where
        fewer than three views).
    plane_angle_deg : ndarray, shape (n,)
        Angle between the two planes of the start's three views (0 where none).
    n_iter : ndarray of int, shape (n,)
        Largest number of iterations over the candidates.
    """

    point: np.ndarray
    status: np.ndarray
    covariance: np.ndarray
    cost: np.ndarray
    n_views: np.ndarray
    n_admissible: np.ndarray
    three_view_status: np.ndarray
    plane_angle_deg: np.ndarray
    n_iter: np.ndarray

    @property
    def estimated(self) -> np.ndarray:
        """True where ``point`` is an estimate (``RESOLVED`` or ``AMBIGUOUS``)."""
        return self.status <= MultiViewStatus.AMBIGUOUS


def inside_apertures(W, origin, mask, points, aperture: Aperture, margin_deg=0.0) -> np.ndarray:
    """Whether ``points`` (n, 3) lie inside the aperture of every masked view, each widened by
    ``margin_deg`` (scalar or (n, k)) in azimuth and elevation (``W`` (n, k, 3, 3), ``origin``
    (n, k, 3), ``mask`` (n, k)); range limits as given. Returns (n,) bool.

    Parameters
    ----------
    W : ndarray, shape (n, k, 3, 3)
        Sensor axes of each view in the world frame (sensor-to-world rotations).
    origin : ndarray, shape (n, k, 3)
        Sensor origins, world frame, metres.
    mask : ndarray of bool, shape (n, k)
        Views to test; unmasked views are ignored.
    points : ndarray, shape (n, 3)
        Feature positions, world frame, metres.
    aperture : Aperture
        Every view's aperture (one sonar model).
    margin_deg : float or ndarray, shape (n, k)
        Widening of the half-angles in azimuth and elevation, degrees (>= 0); the range limits
        are not widened.

    Returns
    -------
    ndarray of bool, shape (n,)
        True where the point is inside every masked view (also for a row with no masked view).
        A point at a sensor's origin has elevation 0 and azimuth 0 there.
    """
    p = np.einsum("nkji,nkj->nki", W, points[:, None, :] - origin)
    r = np.linalg.norm(p, axis=-1)
    m = np.radians(margin_deg)
    theta = np.abs(np.arctan2(p[..., 1], p[..., 0]))
    phi = np.abs(np.arcsin(np.clip(p[..., 2] / np.where(r > 0, r, 1.0), -1.0, 1.0)))
    ok = ((theta <= aperture.half_azimuth_rad + m) & (phi <= aperture.half_elevation_rad + m)
          & aperture.range_ok(r))
    return np.all(ok | ~mask, axis=1)


def _gather(a, idx):
    return np.take_along_axis(a, idx.reshape(idx.shape + (1,) * (a.ndim - 2)), axis=1)


def _starts(W, o, r, mask, prior):
    """Two start points per feature from its first three views; also the three-view status
    and plane angle."""
    order = np.argsort(~mask, axis=1, kind="stable")[:, :3]
    Wf, of, rf = _gather(W, order), _gather(o, order), _gather(r, order)
    rf = np.where(_gather(mask, order), rf, 1.0)
    R12, t12 = relative_pose(Wf[:, 0], of[:, 0], Wf[:, 1], of[:, 1])
    R13, t13 = relative_pose(Wf[:, 0], of[:, 0], Wf[:, 2], of[:, 2])
    res = three_view_points(R12, t12, R13, t13, rf[:, 0], rf[:, 1], rf[:, 2], _OPEN, _OPEN, _OPEN)
    cand = res.candidates.copy()
    miss = res.status == ThreeViewStatus.NO_POINT  # noise: the line misses sphere 1
    p0n = np.linalg.norm(res.line_point, axis=-1)
    cand[miss, 0] = res.line_point[miss] * (rf[miss, 0] / np.where(p0n[miss] > 0, p0n[miss], 1.0))[:, None]
    world = np.einsum("nij,nkj->nki", Wf[:, 0], cand) + of[:, 0, None, :]
    has0 = (res.status == ThreeViewStatus.TWO_POINTS) | (res.status == ThreeViewStatus.ONE_POINT) | miss
    has1 = res.status == ThreeViewStatus.TWO_POINTS
    start0 = np.where(has0[:, None], world[:, 0], prior)
    start1 = np.where(has1[:, None], world[:, 1], start0)
    return start0, start1, has1, res.status.astype(np.int8), res.plane_angle_deg


def _too_few_views(prior, counts) -> MultiViewResult:
    """The result when no feature has three views: each at its ``prior``, status TOO_FEW_VIEWS."""
    n = len(counts)
    return MultiViewResult(point=np.array(prior, float), status=np.full(n, MultiViewStatus.TOO_FEW_VIEWS, np.int8),
                           covariance=np.full((n, 3, 3), np.inf), cost=np.zeros(n), n_views=counts,
                           n_admissible=np.zeros(n, np.int64), three_view_status=np.full(n, -1, np.int8),
                           plane_angle_deg=np.zeros(n), n_iter=np.zeros(n, np.int64))


def multiview_points(W, origin, ranges, sigmas, mask, aperture: Aperture, *, prior=None,
                     cost_limit=np.inf, aperture_margin_deg=0.0, ceiling_m=np.inf,
                     max_iter: int = 100) -> MultiViewResult:
    """Position of each feature from all its views (see the module docstring).

    Parameters
    ----------
    W : array_like, shape (n, k, 3, 3)
        Sensor axes of each view in the world frame (estimated poses).
    origin : array_like, shape (n, k, 3)
        Sensor origins, metres.
    ranges, sigmas : array_like, shape (n, k)
        Measured ranges and their standard deviations, metres (> 0 where ``mask``).
    mask : array_like of bool, shape (n, k)
        Views that saw the feature.
    aperture : Aperture
        Every view's aperture (one sonar model).
    prior : array_like, shape (n, 3), optional
        Start where the three-view start has no candidate, and ``point`` where there are
        fewer than three views (default: straight below the mean origin at the mean range).
    cost_limit : float or array_like, shape (n,)
        Largest admissible cost (e.g. a chi-square quantile with ``n_views - 3`` degrees of
        freedom); default no limit.
    aperture_margin_deg : float or array_like, shape (n, k), >= 0
        Widening of the apertures (per view) in the admissibility test, degrees.
    ceiling_m : float or array_like, shape (n,)
        Largest admissible world ``z`` of the feature, metres (e.g. the height of the lowest
        sensor that saw it, when features are known to lie below the sensors); default none.
    max_iter : int
        Levenberg-Marquardt iterations.

    Returns
    -------
    MultiViewResult
        Per feature (leading shape (n,)): ``point`` (world frame, m), ``status``, ``covariance``
        ((n, 3, 3), m^2), ``cost``, view counts and the three-view start's status and plane angle
        (deg). Features with fewer than three views keep ``prior`` with status
        ``TOO_FEW_VIEWS`` and an infinite covariance.
    """
    check_aperture(aperture, "aperture", Aperture)
    W = as_float_array(W, "W", tail=(3, 3))
    o = as_float_array(origin, "origin", tail=(3,))
    if W.ndim != 4 or o.shape != W.shape[:2] + (3,):
        raise ValueError(f"W must have shape (n, k, 3, 3) and origin (n, k, 3); got {W.shape}, {o.shape}")
    n, k = o.shape[:2]
    mask, r, s = check_views(mask, ranges, sigmas, (n, k))
    margin = np.asarray(aperture_margin_deg, float)
    if not (np.all(np.isfinite(margin)) and np.all(margin >= 0)):
        raise ValueError(f"aperture_margin_deg must be finite numbers >= 0; got {aperture_margin_deg!r}")
    try:
        margin = np.broadcast_to(margin, (n, k))
    except ValueError:
        raise ValueError(f"aperture_margin_deg must be a number or broadcast to {(n, k)}; "
                         f"got shape {margin.shape}") from None
    limit = np.broadcast_to(np.asarray(cost_limit, float), (n,))
    ceiling = np.broadcast_to(np.asarray(ceiling_m, float), (n,))
    if np.any(np.isnan(ceiling)) or np.any(np.isnan(limit)):
        raise ValueError("cost_limit and ceiling_m must not be NaN")
    counts = mask.sum(axis=1)
    if prior is None:
        c = np.einsum("nki,nk->ni", o, mask) / np.maximum(counts, 1)[:, None]
        mean_r = np.sum(np.where(mask, r, 0.0), axis=1) / np.maximum(counts, 1)
        prior = c - mean_r[:, None] * np.array([0.0, 0.0, 1.0])
    prior = as_float_array(prior, "prior", tail=(3,))
    if prior.shape != (n, 3):
        raise ValueError(f"prior must have shape {(n, 3)}; got {prior.shape}")

    ok3 = counts >= 3
    idx = np.flatnonzero(ok3)
    if idx.size == 0:  # no feature has three views (e.g. fewer than three view slots): every one
        return _too_few_views(prior, counts)  # is TOO_FEW_VIEWS at its prior, as documented
    m = idx.size
    Wi, oi, ri, mi = W[idx], o[idx], r[idx], mask[idx]
    si = np.where(mi, s[idx], 1.0)
    s0, s1, has1, tv_status, angle = _starts(Wi, oi, ri, mi, prior[idx])
    mg, lim, ceil = margin[idx], limit[idx], ceiling[idx]
    P = np.zeros((m, 3, 3))
    C = np.full((m, 3), np.inf)
    A = np.zeros((m, 3), bool)
    D = np.ones((m, 3), bool)
    S = np.full((m, 3, 3, 3), np.inf)
    it = np.zeros((m, 3), np.int64)

    def refine(slot, rows, start):
        sol = solve_ranges(oi[rows], ri[rows], si[rows], mi[rows], start, max_iter=max_iter)
        P[rows, slot], C[rows, slot], D[rows, slot] = sol.point, sol.cost, sol.degenerate
        S[rows, slot], it[rows, slot] = sol.covariance, sol.n_iter
        A[rows, slot] = (sol.converged & ~sol.degenerate & (sol.cost <= lim[rows])
                         & (sol.point[:, 2] <= ceil[rows])
                         & inside_apertures(Wi[rows], oi[rows], mi[rows], sol.point, aperture, mg[rows]))

    refine(0, np.arange(m), s0)
    # the second candidate is refined only where it starts inside the widened apertures (a
    # mirror image outside them is rejected by the apertures before any refinement)
    two = np.flatnonzero(has1 & inside_apertures(Wi, oi, mi, s1, aperture, mg))
    refine(1, two, s1[two])
    # fallback: from the prior, where neither closed-form candidate became admissible
    rest = np.flatnonzero(~A[:, 0] & ~A[:, 1])
    refine(2, rest, prior[idx][rest])
    # the reported candidate: the admissible one with the lowest cost, else the lowest cost
    best = np.argmin(np.where(A, C, np.inf), axis=1)
    best = np.where(A.any(axis=1), best, np.argmin(np.where(np.isfinite(C), C, np.inf), axis=1))
    take = lambda a: np.take_along_axis(a, best.reshape((m, 1) + (1,) * (a.ndim - 2)), axis=1)[:, 0]  # noqa: E731
    pb = take(P)
    scale = np.max(np.where(mi, ri, 0.0), axis=1)
    distinct = np.linalg.norm(P - pb[:, None, :], axis=-1) > DISTINCT_RTOL * scale[:, None]
    n_adm = A.any(axis=1).astype(np.int64) + np.any(A & distinct, axis=1)
    st = np.where(n_adm == 2, MultiViewStatus.AMBIGUOUS,
                  np.where(n_adm == 1, MultiViewStatus.RESOLVED,
                           np.where(take(D), MultiViewStatus.DEGENERATE, MultiViewStatus.DIVERGED)))

    point = prior.copy()
    point[idx] = pb
    status = np.full(n, MultiViewStatus.TOO_FEW_VIEWS, np.int8)
    status[idx] = st
    cov = np.full((n, 3, 3), np.inf)
    cov[idx] = take(S)
    cost = np.zeros(n)
    cost[idx] = take(C)
    out_tv = np.full(n, -1, np.int8)
    out_tv[idx] = tv_status
    out_angle = np.zeros(n)
    out_angle[idx] = angle
    n_adm_all = np.zeros(n, np.int64)
    n_adm_all[idx] = n_adm
    iters = np.zeros(n, np.int64)
    iters[idx] = it.max(axis=1)
    return MultiViewResult(point=point, status=status, covariance=cov, cost=cost, n_views=counts,
                           n_admissible=n_adm_all, three_view_status=out_tv, plane_angle_deg=out_angle,
                           n_iter=iters)
