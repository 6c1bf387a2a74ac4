"""Symbolic (SymPy) derivation of the three-view point: two planes, their line, sphere 1.

The planes of views 1–2 and 1–3 are ``u2 . p = c2`` and ``u3 . p = c3`` (``c = C / 2`` of
:func:`sss_locus.geometry.symbolic.derive_plane`). :func:`derive_line` derives their line
``p0 + s w``, ``w = u2 x u3``, and its point ``p0`` nearest the origin;
:func:`derive_line_sphere` substitutes the line into ``|p|^2 = r1^2`` and solves the quadratic
for ``s``. Every ``residual`` step simplifies to exactly 0 when the derivation holds; the
lambdified results are compared with :func:`sss_locus.geometry.three_view_points.three_view_points` in
``tests/geometry/test_three_view_symbolic.py``.
"""
from __future__ import annotations

import functools

import sympy as sp

from .derivation import vector


def _dot(a: sp.Matrix, b: sp.Matrix):
    return (a.T * b)[0]


def three_view_symbols() -> dict:
    """``u2``, ``u3`` (plane normals, free vectors), ``c2``, ``c3`` (offsets), ``r1``, ``s``.

    Returns
    -------
    dict
        ``u2``, ``u3`` (sympy.Matrix (3, 1) of real symbols: normals of the planes ``u . p = c``
        in frame 1), ``c2``, ``c3`` (real symbols), ``r1`` (positive symbol: range of view 1)
        and ``s`` (real symbol: the parameter along the line of the two planes).
    """
    return {"u2": vector("u2"), "u3": vector("u3"), "c2": sp.Symbol("c_2", real=True),
            "c3": sp.Symbol("c_3", real=True), "r1": sp.Symbol("r_1", positive=True),
            "s": sp.Symbol("s", real=True)}


@functools.lru_cache(maxsize=1)
def derive_line():
    """The line in which ``u2 . p = c2`` and ``u3 . p = c3`` meet.

    ``p0`` is found by solving the 3x3 linear system ``u2 . p = c2``, ``u3 . p = c3``,
    ``w . p = 0`` (the point of the line nearest the origin: ``p0`` is orthogonal to the
    direction ``w = u2 x u3``), not by quoting the closed form; the closed form
    ``(c2 (u3 x w) + c3 (w x u2)) / |w|^2`` is then checked against it.

    Returns
    -------
    result : dict
        ``w`` (direction, ``u2 x u3``) and ``p0``.
    steps : dict
        ``solved`` (``p0`` from the linear solve), ``closed_form_residual``,
        ``on_plane2_residual``, ``on_plane3_residual``, ``orthogonal_residual``,
        ``direction_in_planes`` (``(u2 . w, u3 . w)``); all exactly 0.
    """
    s = three_view_symbols()
    u2, u3, c2, c3 = s["u2"], s["u3"], s["c2"], s["c3"]
    w = u2.cross(u3)
    p = vector("p")
    A = sp.Matrix.vstack(u2.T, u3.T, w.T)
    sol = sp.solve(list(A * p - sp.Matrix([c2, c3, 0])), list(p), dict=True)[0]
    solved = sp.Matrix([sp.factor(sp.cancel(sol[x])) for x in p])
    w2 = _dot(w, w)
    closed = (c2 * u3.cross(w) + c3 * w.cross(u2)) / w2

    def zero(e):
        return sp.simplify(sp.cancel(sp.expand(e)))

    steps = {
        "solved": solved,
        "closed_form_residual": (closed - solved).applyfunc(zero),
        "on_plane2_residual": zero(_dot(u2, closed) - c2),
        "on_plane3_residual": zero(_dot(u3, closed) - c3),
        "orthogonal_residual": zero(_dot(w, closed)),
        "direction_in_planes": (zero(_dot(u2, w)), zero(_dot(u3, w))),
    }
    return {"w": w, "p0": closed}, steps


@functools.lru_cache(maxsize=1)
def derive_line_sphere():
    """Where the line ``p0 + s w`` meets the sphere ``|p| = r1``.

    For a general point ``q`` and direction ``w`` (free symbols) the substitution gives the
    quadratic ``|w|^2 s^2 + 2 (q . w) s + |q|^2 - r1^2 = 0``. At ``q = p0`` of
    :func:`derive_line` the linear coefficient vanishes (``p0 . w = 0``), so the roots are
    ``s = +- sqrt(r1^2 - |p0|^2) / |w|``: the points ``p0 +- h d`` with ``d = w / |w|`` and
    ``h = sqrt(r1^2 - |p0|^2)``; two points when ``|p0| < r1``, one when ``|p0| = r1``
    (tangent line), none when ``|p0| > r1``. Cached; do not mutate the result.

    Returns
    -------
    result : dict
        ``roots`` (the two ``s``, SymPy's ``solve`` of the reduced quadratic, in its order),
        ``h_sq`` (``r1^2 - |p0|^2``), ``points`` (``p0 + s w`` at each root), ``discriminant``
        (of the reduced quadratic).
    steps : dict
        ``quadratic`` (general, in ``q`` and ``w``), ``linear_coefficient_on_line``
        (``2 p0 . w``: 0), ``root_residuals`` (``|q + s w|^2 - r1^2 - 2 s (q . w)`` at each
        root, i.e. what is left besides the vanishing linear term: 0), ``h_residual``
        (``s^2 |w|^2 - (r1^2 - |q|^2)``: 0).
    """
    s = three_view_symbols()
    r1, sv = s["r1"], s["s"]
    line, _ = derive_line()
    w_line, p0 = line["w"], line["p0"]
    q, w = vector("q"), vector("w")
    p = q + sv * w
    quad = sp.Poly(sp.expand(_dot(p, p) - r1**2), sv)
    a, b, c = quad.all_coeffs()

    def zero(e):
        return sp.simplify(sp.cancel(sp.expand(e)))

    b_on_line = zero(b.subs(dict(zip(list(q) + list(w), list(p0) + list(w_line))), simultaneous=True))
    roots = sp.solve(a * sv**2 + c, sv)  # b = 0 on the line
    on_line = dict(zip(list(q) + list(w), list(p0) + list(w_line)))
    qw = _dot(q, w)
    steps = {
        "quadratic": quad.as_expr(),
        "linear_coefficient_on_line": b_on_line,
        "root_residuals": tuple(zero(_dot(q + rt * w, q + rt * w) - r1**2 - 2 * rt * qw)
                                for rt in roots),
        "h_residual": zero(roots[0] ** 2 * _dot(w, w) - (r1**2 - _dot(q, q))),
    }
    roots_line = [rt.subs(on_line, simultaneous=True) for rt in roots]
    points = [p0 + rt * w_line for rt in roots_line]
    return {"roots": roots_line, "h_sq": r1**2 - _dot(p0, p0), "points": points,
            "discriminant": (-4 * a * c).subs(on_line, simultaneous=True)}, steps


@functools.lru_cache(maxsize=1)
def numeric_three_view():
    """Lambdified ``p0(u2, u3, c2, c3)`` -> (..., 3), ``h_sq(u2, u3, c2, c3, r1)`` and
    ``points(u2, u3, c2, c3, r1)`` -> (..., 2, 3) (NaN where the line misses the sphere)."""
    import numpy as np

    s = three_view_symbols()
    line, _ = derive_line()
    ls, _ = derive_line_sphere()
    args = [list(s["u2"]), list(s["u3"]), s["c2"], s["c3"]]
    f_p0 = sp.lambdify(args, list(line["p0"]), "numpy")
    f_h = sp.lambdify(args + [s["r1"]], ls["h_sq"], "numpy")
    f_pts = sp.lambdify(args + [s["r1"]], [list(q) for q in ls["points"]], "numpy")

    def cols(v):
        v = np.asarray(v, float)
        return [v[..., i] for i in range(3)]

    return {
        "p0": lambda u2, u3, c2, c3: np.stack(np.broadcast_arrays(*f_p0(cols(u2), cols(u3), c2, c3)), -1),
        "h_sq": lambda u2, u3, c2, c3, r1: np.asarray(f_h(cols(u2), cols(u3), c2, c3, r1), float),
        "points": lambda u2, u3, c2, c3, r1: np.stack(
            [np.stack(np.broadcast_arrays(*q), -1) for q in f_pts(cols(u2), cols(u3), c2, c3, r1)], -2),
    }
