"""Symbolic (SymPy) derivation of the range residual of one view and its Jacobian, used by the
N-view least squares (:mod:`sss_locus.geometry.multiview`).

The weighted residual of a feature ``p`` seen from a sensor at ``o`` with measured range
``rho`` and standard deviation ``sigma`` is ``e = (|p - o| - rho) / sigma``.
:func:`derive_range_jacobian` differentiates it with respect to ``p`` (SymPy's ``diff``, not a
quoted formula) and checks that the result is the unit line of sight over ``sigma``,
``(p - o)^T / (sigma |p - o|)``; :func:`numeric_range_jacobian` lambdifies the derived
gradient and :func:`kernel_jacobian_discrepancy` compares it with
:func:`sss_locus.geometry.multiview.range_residuals` (shown in ``notebooks/derivation.ipynb``,
tested in ``tests/geometry/test_multiview.py``).
"""
from __future__ import annotations

import functools

import sympy as sp

from .derivation import vector


@functools.lru_cache(maxsize=1)
def derive_range_jacobian():
    """``(result, steps)``: ``result`` holds ``residual`` and ``gradient`` (1x3), ``steps`` the
    ``line_of_sight_residual`` (derived gradient minus the closed form, simplifies to zero)."""
    p, o = vector("p"), vector("o")
    rho, sigma = sp.Symbol("rho", positive=True), sp.Symbol("sigma", positive=True)
    d = p - o
    dist = sp.sqrt((d.T * d)[0])
    e = (dist - rho) / sigma
    grad = sp.Matrix([[sp.diff(e, x) for x in p]])
    closed = d.T / (sigma * dist)
    residual = (grad - closed).applyfunc(lambda x: sp.cancel(sp.together(x)))
    return ({"p": p, "o": o, "rho": rho, "sigma": sigma, "residual": e, "gradient": grad},
            {"line_of_sight_residual": residual})


def numeric_range_jacobian():
    """``f(p_x, p_y, p_z, o_x, o_y, o_z, rho, sigma) -> (e, [de/dp_x, de/dp_y, de/dp_z])``
    from the derived expressions (numpy, vectorised over array arguments).

    Returns
    -------
    callable
        ``f`` of eight broadcasting arrays: feature ``p`` and sensor origin ``o`` components
        (m, one frame), measured range ``rho`` and its standard deviation ``sigma`` (m). It
        returns the weighted residual ``e = (|p - o| - rho) / sigma`` (dimensionless) and its
        three derivatives (1/m); at ``p = o`` the derivatives are NaN (0/0).
    """
    r, _ = derive_range_jacobian()
    args = list(r["p"]) + list(r["o"]) + [r["rho"], r["sigma"]]
    return sp.lambdify(args, (r["residual"], list(r["gradient"])), "numpy")


def kernel_jacobian_discrepancy(seed: int = 0, n: int = 2000, n_views: int = 4) -> dict:
    """Largest differences between the derived residual and Jacobian and the kernel's
    (:func:`sss_locus.geometry.multiview.range_residuals`) on random configurations.

    ``n`` features ``p ~ N(0, 40 m)``, each seen from ``n_views`` sensors ``o ~ N(0, 60 m)``,
    with measured ranges ``rho = |p - o| + N(0, 1 m)`` (kept > 0) and ``sigma`` uniform in
    [0.05, 1] m.

    Parameters
    ----------
    seed : int
        Seed of ``numpy.random.default_rng`` for the configurations.
    n : int
        Number of random features.
    n_views : int
        Sensors (views) per feature.

    Returns
    -------
    dict
        ``residual`` (max abs difference of the weighted residuals, in units of sigma),
        ``jacobian`` (max abs difference of the Jacobian entries, 1/m), ``jacobian_rel`` (that
        over the largest Jacobian entry), ``finite_difference_rel`` (the kernel's Jacobian against
        central differences of its own residuals, step 1e-6 m, relative to the largest entry) and
        ``n_rows`` (residuals compared).
    """
    import numpy as np

    from ..multiview import range_residuals

    rng = np.random.default_rng(seed)
    p = rng.normal(scale=40.0, size=(n, 3))
    o = rng.normal(scale=60.0, size=(n, n_views, 3))
    rho = np.abs(np.linalg.norm(p[:, None, :] - o, axis=-1) + rng.normal(size=(n, n_views))) + 0.1
    sigma = rng.uniform(0.05, 1.0, size=(n, n_views))
    mask = np.ones((n, n_views), bool)
    e, J = range_residuals(p, o, rho, sigma, mask)
    P = np.broadcast_to(p[:, None, :], o.shape)
    e_s, g_s = numeric_range_jacobian()(*np.moveaxis(P, -1, 0), *np.moveaxis(o, -1, 0), rho, sigma)
    J_s = np.stack(g_s, axis=-1)
    h, fd = 1e-6, np.empty_like(J)
    for i in range(3):
        step = np.zeros(3)
        step[i] = h
        fd[..., i] = (range_residuals(p + step, o, rho, sigma, mask)[0]
                      - range_residuals(p - step, o, rho, sigma, mask)[0]) / (2 * h)
    scale = float(np.max(np.abs(J)))
    return {
        "residual": float(np.max(np.abs(e - e_s))),
        "jacobian": float(np.max(np.abs(J - J_s))),
        "jacobian_rel": float(np.max(np.abs(J - J_s))) / scale,
        "finite_difference_rel": float(np.max(np.abs(J - fd))) / scale,
        "n_rows": int(mask.sum()),
    }
