"""N sidescan views of one feature: least squares on the range residuals, batched over features.

Each view ``k`` of a feature has a sensor origin ``o_k`` (world frame, metres) and a measured
range ``rho_k`` with standard deviation ``sigma_k``. The feature ``p`` minimises

    cost(p) = sum_k ((|p - o_k| - rho_k) / sigma_k)^2

over the views that saw it (``mask``). The residual of view ``k`` is
``e_k(p) = (|p - o_k| - rho_k) / sigma_k`` and its gradient, the row of the Jacobian, is
``(p - o_k)^T / (sigma_k |p - o_k|)``: the unit line of sight over ``sigma_k`` (derived
symbolically in :mod:`sss_locus.geometry.symbolic.range_residuals`). At the optimum the
first-order covariance of ``p`` is ``(J^T J)^-1`` (weighted Jacobian), i.e.
``sigma^2 (J^T J)^-1`` for equal ``sigma``.

:func:`solve_ranges` runs Levenberg-Marquardt (Marquardt's diagonal scaling; a step is taken
only if it lowers the cost; the damping follows Nielsen's gain-ratio rule, as in Madsen, Nielsen
& Tingleff, *Methods for non-linear least squares problems*, 2004, Sec. 3.2) on every feature at once: each iteration is a handful of array operations on
the features still running (no per-feature Python loop). Rows are solved relative to the mean
of their sensor origins, so a scene far from the world origin loses no digits.

A feature is ranged by at most three sensors whose origins lie on one line (collinear passes)
only up to a rotation about that line: ``J^T J`` is singular (rank 2). Such rows are reported
as ``degenerate`` (the smallest eigenvalue of ``J^T J`` below :data:`~sss_locus.geometry.
tolerances.RANGE_JACOBIAN_RANK_RTOL` times the largest), with their last iterate and an
infinite covariance, never NaN.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .tolerances import RANGE_JACOBIAN_RANK_RTOL
from .validation import as_float_array

XTOL_REL = 1e-10
"""A row has converged when its step is shorter than ``XTOL_REL`` times its largest range ..."""
FTOL_REL = 1e-12
"""... or when an accepted step lowers its cost by at most ``FTOL_REL`` of the cost ..."""
GTOL = 1e-10
"""... or when the gradient is orthogonal to the residuals to ``GTOL``: ``max_i |(J^T e)_i| /
(|J_i| |e|) <= GTOL`` (MINPACK's test; ``J_i`` the i-th column)."""


@dataclass(frozen=True)
class RangeSolution:
    """What :func:`solve_ranges` returns, for ``n`` features (world frame, metres).

    Attributes
    ----------
    point : ndarray, shape (n, 3)
        The last accepted iterate (the optimum where ``converged``).
    cost : ndarray, shape (n,)
        ``sum_k e_k^2`` at ``point`` (dimensionless: residuals in units of ``sigma``).
    converged : ndarray of bool, shape (n,)
        The step fell below ``XTOL_REL`` (relative), the cost stopped decreasing
        (``FTOL_REL``) or the gradient vanished (``GTOL``) within ``max_iter`` iterations.
    degenerate : ndarray of bool, shape (n,)
        ``J^T J`` at ``point`` is rank-deficient (e.g. collinear sensor origins, fewer than
        three views).
    covariance : ndarray, shape (n, 3, 3)
        ``(J^T J)^-1`` at ``point`` (m^2); ``inf`` where ``degenerate``.
    n_iter : ndarray of int, shape (n,)
        Iterations run.
    """

    point: np.ndarray
    cost: np.ndarray
    converged: np.ndarray
    degenerate: np.ndarray
    covariance: np.ndarray
    n_iter: np.ndarray


def range_residuals(points, origins, ranges, sigmas, mask) -> tuple[np.ndarray, np.ndarray]:
    """Weighted range residuals and their Jacobian.

    Parameters
    ----------
    points : array_like, shape (n, 3)
        Feature positions, metres.
    origins : array_like, shape (n, k, 3)
        Sensor origins, same frame, metres.
    ranges, sigmas : array_like, shape (n, k)
        Measured ranges and their standard deviations (> 0 where ``mask``), metres.
    mask : array_like of bool, shape (n, k)
        Views that saw the feature; the others give zero residuals and rows.

    Returns
    -------
    e : ndarray, shape (n, k)
        ``(|p - o_k| - rho_k) / sigma_k``.
    J : ndarray, shape (n, k, 3)
        ``de_k / dp = (p - o_k) / (sigma_k |p - o_k|)``; zero where ``p = o_k``.
    """
    d = np.asarray(points, float)[:, None, :] - np.asarray(origins, float)
    dist = np.sqrt(np.einsum("nki,nki->nk", d, d))
    w = np.where(mask, 1.0 / np.where(mask, sigmas, 1.0), 0.0)
    e = (dist - ranges) * w
    J = d * (w / np.where(dist > 0, dist, 1.0))[..., None]
    return e, J


def check_views(mask, ranges, sigmas, shape: tuple[int, int]):
    """``mask`` (bool), ``ranges`` and ``sigmas`` (float) of shape ``shape`` = (n, k), ranges
    and sigmas finite and > 0 wherever ``mask``; a ``ValueError`` naming the argument otherwise.

    Parameters
    ----------
    mask : array_like of bool, shape (n, k)
        Views that saw each feature (``n`` features, ``k`` views).
    ranges : array_like, shape (n, k)
        Measured slant ranges, metres (finite everywhere, > 0 where ``mask``).
    sigmas : array_like, shape (n, k)
        Standard deviations of the ranges, metres (finite everywhere, > 0 where ``mask``).
    shape : tuple of int
        The expected ``(n, k)``.

    Returns
    -------
    mask : ndarray of bool, shape (n, k)
    ranges, sigmas : ndarray of float64, shape (n, k)

    Raises
    ------
    ValueError
        Wrong dtype or shape, non-finite values, or a value <= 0 in a masked view.
    """
    mask = np.asarray(mask)
    if mask.dtype != bool or mask.shape != shape:
        raise ValueError(f"mask must be a boolean array of shape {shape}; got {mask.dtype} {mask.shape}")
    out = []
    for name, value in (("ranges", ranges), ("sigmas", sigmas)):
        a = as_float_array(value, name)
        if a.shape != shape:
            raise ValueError(f"{name} must have shape {shape}; got {a.shape}")
        if np.any(mask & ~(a > 0)):
            raise ValueError(f"{name} must be > 0 for every view in mask")
        out.append(a)
    return mask, out[0], out[1]


def _residuals_cm(p, o, rho, w):
    """Component-major residuals: ``p`` (3, n), ``o`` (3, n, k), ``rho``, ``w`` (n, k) (``w`` = 1/sigma,
    0 outside the mask). Returns ``e`` (n, k), ``J`` (3, n, k) and the cost (n,)."""
    d = p[:, :, None] - o
    dist = np.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
    e = (dist - rho) * w
    J = d * (w / np.where(dist > 0, dist, 1.0))
    return e, J, np.sum(e * e, axis=1)


def _normal_cm(J, e):
    """``J^T J`` as its six entries (xx, yy, zz, xy, xz, yz), each (n,), and ``J^T e`` (3, n)."""
    A = np.stack([np.sum(J[i] * J[j], axis=1) for i, j in ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))])
    return A, np.sum(J * e, axis=2)


def _sym3_extreme_eigenvalues(A):
    """Smallest and largest eigenvalues of symmetric 3x3 matrices given as six entries (6, n),
    in closed form (the trigonometric solution of the characteristic cubic; absolute error of
    order ``eps`` times the largest eigenvalue, enough for the rank test)."""
    xx, yy, zz, xy, xz, yz = A
    q = (xx + yy + zz) / 3.0
    p1 = xy * xy + xz * xz + yz * yz
    p2 = (xx - q) ** 2 + (yy - q) ** 2 + (zz - q) ** 2 + 2.0 * p1
    p = np.sqrt(p2 / 6.0)
    safe = np.where(p > 0, p, 1.0)
    b00, b11, b22 = (xx - q) / safe, (yy - q) / safe, (zz - q) / safe
    b01, b02, b12 = xy / safe, xz / safe, yz / safe
    r = 0.5 * (b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) + b02 * (b01 * b12 - b11 * b02))
    phi = np.arccos(np.clip(r, -1.0, 1.0)) / 3.0
    hi = q + 2.0 * p * np.cos(phi)
    lo = q + 2.0 * p * np.cos(phi + 2.0 * np.pi / 3.0)
    return np.where(p > 0, lo, q), np.where(p > 0, hi, q)


def _sym3_inverse(A):
    """Inverses (n, 3, 3) of symmetric 3x3 matrices given as six entries (6, n), by cofactors."""
    xx, yy, zz, xy, xz, yz = A
    c = [yy * zz - yz * yz, xz * yz - xy * zz, xy * yz - xz * yy, xx * zz - xz * xz,
         xy * xz - xx * yz, xx * yy - xy * xy]
    det = xx * c[0] + xy * c[1] + xz * c[2]
    inv = np.stack([c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5]], axis=-1) / det[:, None]
    return inv.reshape(-1, 3, 3)


def _solve_sym3(A, b):
    """Solve the symmetric 3x3 systems ``A x = b`` (``A`` as six entries (6, n), ``b`` (3, n)) by
    cofactors; also return the determinant. Rows with a zero determinant give zeros."""
    xx, yy, zz, xy, xz, yz = A
    c00 = yy * zz - yz * yz
    c01 = xz * yz - xy * zz
    c02 = xy * yz - xz * yy
    c11 = xx * zz - xz * xz
    c12 = xy * xz - xx * yz
    c22 = xx * yy - xy * xy
    det = xx * c00 + xy * c01 + xz * c02
    inv = np.where(det != 0, 1.0 / np.where(det != 0, det, 1.0), 0.0)
    x = np.stack([c00 * b[0] + c01 * b[1] + c02 * b[2], c01 * b[0] + c11 * b[1] + c12 * b[2],
                  c02 * b[0] + c12 * b[1] + c22 * b[2]]) * inv
    return x, det


def solve_ranges(origins, ranges, sigmas, mask, start, *, max_iter: int = 100,
                 damping: float = 1e-3) -> RangeSolution:
    """Batched Levenberg-Marquardt on the range residuals (see the module docstring).

    Parameters
    ----------
    origins : array_like, shape (n, k, 3)
        Sensor origins, metres (finite).
    ranges : array_like, shape (n, k)
        Measured ranges, metres (finite, > 0 where ``mask``).
    sigmas : array_like, shape (n, k)
        Range standard deviations, metres (finite, > 0 where ``mask``).
    mask : array_like of bool, shape (n, k)
        Views that saw each feature.
    start : array_like, shape (n, 3)
        Initial positions, metres (finite).
    max_iter : int, >= 1
    damping : float, > 0
        Initial Marquardt damping (relative to the diagonal of ``J^T J``).

    Returns
    -------
    RangeSolution

    Raises
    ------
    ValueError
        Naming the argument: wrong shapes, non-finite values, a masked range or sigma <= 0,
        ``max_iter`` < 1 or ``damping`` <= 0.
    """
    o = as_float_array(origins, "origins", tail=(3,))
    if o.ndim != 3:
        raise ValueError(f"origins must have shape (n, k, 3); got {o.shape}")
    n, k = o.shape[:2]
    mask, rho, sig = check_views(mask, ranges, sigmas, (n, k))
    p = as_float_array(start, "start", tail=(3,))
    if p.shape != (n, 3):
        raise ValueError(f"start must have shape {(n, 3)}; got {p.shape}")
    if isinstance(max_iter, bool) or not isinstance(max_iter, (int, np.integer)) or max_iter < 1:
        raise ValueError(f"max_iter must be an integer >= 1; got {max_iter!r}")
    if not (isinstance(damping, (int, float)) and np.isfinite(damping) and damping > 0):
        raise ValueError(f"damping must be a finite number > 0; got {damping!r}")

    counts = mask.sum(axis=1)
    centre = np.einsum("nki,nk->ni", o, mask) / np.maximum(counts, 1)[:, None]
    # component-major, about the origins' mean (no digits lost far from the world origin)
    oc = np.ascontiguousarray(np.moveaxis(o - centre[:, None, :], -1, 0))
    pc = np.ascontiguousarray((p - centre).T)
    w = np.where(mask, 1.0 / np.where(mask, sig, 1.0), 0.0)
    rho = np.where(mask, rho, 0.0)
    scale = np.maximum(np.max(rho, axis=1), 1e-300)
    e, J, cost = _residuals_cm(pc, oc, rho, w)
    converged = np.zeros(n, bool)
    n_iter = np.zeros(n, np.int64)
    # the rows still running, compacted (no gather or scatter per iteration, only when rows stop)
    idx = np.flatnonzero(counts > 0)
    P, O, RHO, WT, E, JJ, COST, SC = (pc[:, idx], oc[:, idx], rho[idx], w[idx], e[idx], J[:, idx],
                                       cost[idx], scale[idx])
    LAM, NU, IT = np.full(idx.size, float(damping)), np.full(idx.size, 2.0), np.zeros(idx.size, np.int64)
    for it in range(int(max_iter) + 1):
        if idx.size == 0:
            break
        if it == int(max_iter):  # out of iterations: not converged
            pc[:, idx], e[idx], J[:, idx], cost[idx], n_iter[idx] = P, E, JJ, COST, IT
            break
        A, g = _normal_cm(JJ, E)
        diag = A[:3]
        enorm = np.sqrt(COST)
        flat_gradient = np.max(np.abs(g) / np.maximum(np.sqrt(diag) * enorm, 1e-300), axis=0) <= GTOL
        D = diag + RANGE_JACOBIAN_RANK_RTOL * diag.sum(axis=0) + 1e-300
        M = A.copy()
        M[:3] += LAM * D
        step, _ = _solve_sym3(M, -g)
        trial = P + step
        e_t, J_t, cost_t = _residuals_cm(trial, O, RHO, WT)
        old = COST
        ok = cost_t < old
        small = np.sqrt(np.sum(step * step, axis=0)) <= XTOL_REL * SC
        flat = ok & (old - cost_t <= FTOL_REL * old)
        # gain ratio of the actual to the predicted decrease (Nielsen's damping update)
        xx, yy, zz, xy, xz, yz = A
        sAs = (xx * step[0] ** 2 + yy * step[1] ** 2 + zz * step[2] ** 2
               + 2 * (xy * step[0] * step[1] + xz * step[0] * step[2] + yz * step[1] * step[2]))
        pred = -(2 * np.sum(g * step, axis=0) + sAs)
        gain = (old - cost_t) / np.where(pred > 0, pred, np.inf)
        P = np.where(ok, trial, P)
        E = np.where(ok[:, None], e_t, E)
        JJ = np.where(ok[:, None], J_t, JJ)
        COST = np.where(ok, cost_t, COST)
        LAM = np.where(ok, LAM * np.maximum(1 / 3, 1 - (2 * gain - 1) ** 3), LAM * NU)
        NU = np.where(ok, 2.0, 2.0 * NU)
        IT += 1
        # done: a tiny step (accepted or not), a negligible decrease of the cost, a vanishing
        # gradient, an exact fit; or the damping ran away (not converged)
        good = small | flat | flat_gradient | (COST == 0.0)
        stop = good | (LAM > 1e16)
        if stop.any():
            out = idx[stop]
            pc[:, out], e[out], J[:, out], cost[out], n_iter[out] = P[:, stop], E[stop], JJ[:, stop], COST[stop], IT[stop]
            converged[out] = good[stop]
            keep = ~stop
            idx, P, O, RHO, WT, E, JJ, COST, SC, LAM, NU, IT = (
                idx[keep], P[:, keep], O[:, keep], RHO[keep], WT[keep], E[keep], JJ[:, keep], COST[keep],
                SC[keep], LAM[keep], NU[keep], IT[keep])
    A, _ = _normal_cm(J, e)
    lo, hi = _sym3_extreme_eigenvalues(A)
    degenerate = (counts < 3) | (lo <= RANGE_JACOBIAN_RANK_RTOL * np.maximum(hi, 1e-300))
    cov = _sym3_inverse(np.where(degenerate, 0.0, A) + np.where(degenerate, 1.0, 0.0) * np.array([1, 1, 1, 0, 0, 0.0])[:, None])
    cov = np.where(degenerate[:, None, None], np.inf, cov)
    return RangeSolution(point=pc.T + centre, cost=cost, converged=converged, degenerate=degenerate,
                         covariance=cov, n_iter=n_iter)
