"""Symbolic (SymPy) derivation of the range residual of one view and its Jacobian, used by the
N-view least squares (:mod:`sss_locus.geometry.multiview`).

The weighted residual of a feature ``p`` seen from a sensor at ``o`` with measured range
``rho`` and standard deviation ``sigma`` is ``e = (|p - o| - rho) / sigma``.
:func:`derive_range_jacobian` differentiates it with respect to ``p`` (SymPy's ``diff``, not a
quoted formula) and checks that the result is the unit line of sight over ``sigma``,
``(p - o)^T / (sigma |p - o|)``; :func:`numeric_range_jacobian` lambdifies the derived
gradient for comparison with :func:`sss_locus.geometry.multiview.range_residuals` in
``tests/test_multiview.py``.
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
    from the derived expressions (numpy, vectorised over array arguments)."""
    r, _ = derive_range_jacobian()
    args = list(r["p"]) + list(r["o"]) + [r["rho"], r["sigma"]]
    return sp.lambdify(args, (r["residual"], list(r["gradient"])), "numpy")
