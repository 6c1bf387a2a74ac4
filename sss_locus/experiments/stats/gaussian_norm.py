"""Quantiles of the length of a zero-mean Gaussian vector in up to three dimensions.

For ``x ~ N(0, C)`` with ``C`` (d, d), d <= 3, and eigenvalues ``l_max >= l_mid >= l_min >= 0``,
``|x|^2 = l_max (z1^2 + a z2^2 + b z3^2)`` with independent standard normal ``z`` and the
ratios ``a = l_mid / l_max``, ``b = l_min / l_max`` in ``[0, 1]``. The ``q`` quantile of
``|x|`` is therefore ``sqrt(l_max) g_q(a, b)``, where ``g_q(a, b)^2`` is the ``q`` quantile of
``z1^2 + a z2^2 + b z3^2``.

``g_q`` is computed exactly (to about 1e-10) on a grid of ratios and interpolated:

* CDF. Write ``z = R u`` with ``u`` uniform on the unit sphere and ``R^2 ~ chi^2_3``
  independent of it; then ``P(z1^2 + a z2^2 + b z3^2 <= t) = E_u[F_3(t / c(u))]`` with
  ``c(u) = u1^2 + a u2^2 + b u3^2`` and ``F_3`` the chi-square CDF with 3 degrees of freedom.
  On the sphere ``u1 = s`` is uniform on ``[0, 1]`` (by symmetry) and ``(u2, u3) =
  sqrt(1 - s^2) (cos p, sin p)`` with ``p`` uniform on ``[0, pi/2]``: Gauss-Legendre in ``s``
  and the midpoint rule in ``p`` (periodic and even: spectrally accurate). The integrand is
  smooth, even where ``c`` reaches 0 (there ``F_3(t / c) -> 1`` with every derivative);
  converged (doubling the nodes changes the quantile by < 1e-10 for ``q`` >= 0.5).
* Quantile. Newton's method on that CDF (its derivative is ``E_u[f_3(t / c) / c]``), kept
  inside a bracket around the ``chi^2_1`` and ``chi^2_3`` quantiles (which bound it for
  every ``a, b`` in [0, 1]), with bisection where a step would leave it.
* Interpolation. A bicubic spline (:class:`scipy.interpolate.RectBivariateSpline`) through
  the exact values on a :data:`GRID_SIZE` x :data:`GRID_SIZE` grid of ``(sqrt(a), sqrt(b))``
  (``g_q`` is symmetric, so half of it is computed), built once per process and quantile
  (about 0.2 s).

Accuracy (relative, measured by ``tests/experiments/stats/test_gaussian_norm.py`` against the exact value at
random ratios, the closed forms ``a = b = 0``: normal, ``a = 1, b = 0``: Rayleigh, ``a = b =
1``: chi with 3 degrees of freedom, and brute-force Monte Carlo): about 1e-7 for ``q`` = 0.95,
1e-6 for ``q`` = 0.5; it degrades for small quantiles (about 1e-4 at ``q`` = 0.05), whose CDF
rises steeply from 0 where the quadrature is coarse.
"""

from __future__ import annotations

import functools

import numpy as np

from sss_locus.geometry.validation import as_float_array

GRID_SIZE = 33  # nodes per ratio axis of the interpolation table
_S_LEVELS, _S_PER_PANEL, _P_NODES = 6, 8, 24  # quadrature in s (panels, Gauss-Legendre) and p (midpoint)
_NEWTON_STEPS = 60  # at most; stops when every node has converged to 1e-13 relative


def _check_quantile(quantile) -> float:
    if isinstance(quantile, bool) or not isinstance(quantile, (int, float, np.integer, np.floating)) \
            or not 0.0 < float(quantile) < 1.0:
        raise ValueError(f"quantile must be a number in the open interval (0, 1); got {quantile!r}")
    return float(quantile)


@functools.lru_cache(maxsize=1)
def _sphere_nodes() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Quadrature on the octant of the sphere, flattened product grid: ``s^2``, ``cos^2 p``
    and weights (summing to 1). ``s``: Gauss-Legendre on the panels ``[0, 2^-L], [2^-L,
    2^(1-L)], ..., [1/2, 1]`` (small quantiles put the CDF's transition at small ``s``);
    ``p``: midpoint rule."""
    edges = np.concatenate([[0.0], 2.0 ** -np.arange(_S_LEVELS, -1, -1)])
    x, w = np.polynomial.legendre.leggauss(_S_PER_PANEL)
    half = 0.5 * np.diff(edges)[:, None]
    s = (edges[:-1, None] + half * (x + 1.0)).ravel()
    ws = (half * w).ravel()
    p = (np.arange(_P_NODES) + 0.5) * (0.5 * np.pi / _P_NODES)
    return np.repeat(s * s, _P_NODES), np.tile(np.cos(p) ** 2, s.size), np.repeat(ws, _P_NODES) / _P_NODES


def exact_quantile_squared(a, b, quantile: float) -> np.ndarray:
    """``q`` quantile of ``z1^2 + a z2^2 + b z3^2`` (independent standard normal ``z``), by
    quadrature over the sphere and Newton's method (module docstring); ``a``, ``b`` broadcast,
    values in ``[0, 1]``. About 2,000 CDF evaluations per Newton step and point: for tables and
    tests, not for millions of rows (use :func:`gaussian_norm_quantile`).

    Parameters
    ----------
    a, b : array_like
        Variances of the second and third terms relative to the first, in [0, 1].
    quantile : float
        Quantile, in (0, 1).

    Returns
    -------
    numpy.ndarray
        The quantile of the squared norm, one per broadcast element.
    """
    from scipy.special import chdtri, erf  # chdtri(k, 1 - q) = chi2(k).ppf(q), without scipy.stats

    q = _check_quantile(quantile)
    a, b = np.broadcast_arrays(np.asarray(a, float), np.asarray(b, float))
    if a.size and not (np.all((a >= 0) & (a <= 1)) and np.all((b >= 0) & (b <= 1))):
        raise ValueError("the eigenvalue ratios a and b must lie in [0, 1]")
    s2, cos2, w = _sphere_nodes()
    c = s2 + (1.0 - s2) * (a.reshape(-1, 1) * cos2 + b.reshape(-1, 1) * (1.0 - cos2))  # (m, N)
    lo = np.full(a.size, 0.99 * chdtri(1, 1.0 - q))  # widened: the root may sit on a bound (a = b = 0
    hi = np.full(a.size, 1.01 * chdtri(3, 1.0 - q))  # or 1), where a Newton step may land just past it
    t = 0.5 * (lo + hi)
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        for _ in range(_NEWTON_STEPS):
            y = np.sqrt(0.5 * t[:, None] / c)  # inf where c == 0: F_3 = 1, f_3 = 0 there
            density = np.where(np.isinf(y), 0.0, y * np.exp(-y * y))  # f_3(x) x sqrt(pi) / 2
            # F_3(x) = erf(y) - 2 y exp(-y^2) / sqrt(pi), y = sqrt(x / 2); f_3(x) = y exp(-y^2) / sqrt(pi)
            cdf = (erf(y) - (2.0 / np.sqrt(np.pi)) * density) @ w
            pdf = (density / c) @ w / np.sqrt(np.pi)
            lo, hi = np.where(cdf < q, t, lo), np.where(cdf < q, hi, t)
            step = t - (cdf - q) / pdf
            new = np.where((step >= lo) & (step <= hi), step, 0.5 * (lo + hi))
            done = np.abs(new - t) <= 1e-13 * t
            t = new
            if done.all():
                break
    return t.reshape(a.shape)


@functools.lru_cache(maxsize=8)
def _table(quantile: float):
    """Bicubic spline of ``g_q`` over ``(sqrt(a), sqrt(b))`` (the ratios of the standard
    deviations: smoother near 0 than ``a``, ``b``) on the :data:`GRID_SIZE` grid, built once per
    quantile."""
    from scipy.interpolate import RectBivariateSpline

    grid = np.linspace(0.0, 1.0, GRID_SIZE)  # of sqrt(a), sqrt(b)
    i, j = np.triu_indices(GRID_SIZE)  # a >= b half (g is symmetric in a, b)
    g = np.empty((GRID_SIZE, GRID_SIZE))
    g[j, i] = g[i, j] = np.sqrt(exact_quantile_squared(grid[j] ** 2, grid[i] ** 2, quantile))
    return RectBivariateSpline(grid, grid, g, kx=3, ky=3, s=0)


def gaussian_norm_quantile(cov, quantile: float = 0.95) -> np.ndarray:
    """Quantile of ``|x|`` for ``x ~ N(0, cov)``.

    Parameters
    ----------
    cov : array_like, shape (..., d, d), d in {1, 2, 3}
        Covariance matrices (symmetric positive semi-definite, finite; units squared, e.g.
        m^2). Negative eigenvalues from rounding (within 1e-9 of the largest) count as 0; larger
        ones are refused.
    quantile : float
        In the open interval (0, 1).

    Returns
    -------
    numpy.ndarray, shape (...)
        The quantile, in the units of ``sqrt(cov)``; 0 for a zero covariance. Relative accuracy
        about 1e-7 at ``q`` = 0.95 (the module docstring says how it is made and measured).
    """
    cov = as_float_array(cov, "cov")  # real numbers, finite
    if cov.ndim < 2 or cov.shape[-1] != cov.shape[-2] or not 1 <= cov.shape[-1] <= 3:
        raise ValueError(f"cov must have shape (..., d, d) with d in 1..3; got {cov.shape}")
    q = _check_quantile(quantile)
    asym = np.abs(cov - np.swapaxes(cov, -1, -2)).max(initial=0.0)
    if asym > 1e-9 * np.abs(cov).max(initial=0.0):
        raise ValueError(f"cov must be symmetric (a covariance); found |cov - cov^T| up to {asym:.3g}")
    lam = np.linalg.eigvalsh(cov)  # ascending
    if lam.size and np.any(lam[..., 0] < -1e-9 * np.abs(lam).max(axis=-1)):
        raise ValueError("cov must be positive semi-definite (a covariance); found a negative eigenvalue "
                         "beyond rounding (< -1e-9 of the largest)")
    lam = np.clip(lam, 0.0, None)
    lam = np.concatenate([np.zeros(lam.shape[:-1] + (3 - lam.shape[-1],)), lam], axis=-1)
    top = lam[..., 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        a = np.where(top > 0, lam[..., 1] / top, 0.0)
        b = np.where(top > 0, lam[..., 0] / top, 0.0)
    sa, sb = (np.sqrt(np.clip(r, 0.0, 1.0)).ravel() for r in (a, b))
    g = _table(q).ev(sa, sb).reshape(top.shape)
    return np.sqrt(top) * g
