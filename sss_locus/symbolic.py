"""Symbolic (SymPy) derivation of the two-view sidescan locus.

This module re-derives, as exact symbolic identities, every formula the
numeric kernel (:mod:`sss_locus.locus`, :mod:`sss_locus.arcs`) evaluates:

* :func:`derive_plane` -- the plane ``2 (R^T t)^T p1 = r2^2 - r1^2 - |t|^2``
  from the two range spheres (paper, Sec. III, eq. (plane));
* :func:`derive_circle` -- centre ``C u / (2 |u|^2)``, radius
  ``sqrt(r1^2 - C^2 / (4 |u|^2))``, the existence condition
  ``C^2 <= 4 |u|^2 r1^2`` and ``|u| = |t|``;
* :func:`derive_one_angle` -- the paper's one-angle form (eq. (onelocus)) and
  its closed-form solutions for ``phi1`` given ``theta1`` and vice versa;
* :func:`derive_scaling` -- the scaling law ``(r1, r2, t) -> k (r1, r2, t)``;
* :func:`derive_crop` -- an affine half-space ``a . p + b >= 0`` restricted to
  the circle becomes ``A cos(alpha) + B sin(alpha) + D >= 0``, with boundary
  angles ``alpha0 +- arccos(-D / hypot(A, B))``, ``alpha0 = atan2(B, A)``;
  :func:`elevation_halfspaces`, :func:`azimuth_halfspaces` and
  :func:`halfspace_in_frame1` give the aperture bounds in that form.

Each ``derive_*`` function returns ``(result, steps)``: ``result`` is a dict
of the final SymPy expressions, ``steps`` an ordered dict of intermediate
expressions (for display in ``notebooks/derivation.ipynb``), including
``residual`` entries that :func:`sympy.simplify` reduces to exactly 0 when
the derivation holds.  Rotations are treated generally in two ways: as a
3x3 matrix of free symbols with the orthonormality ``R^T R = I`` applied as
an explicit substitution (the paper's route), and as the rotation of a
non-zero quaternion ``q``, ``R(q) = M(q) / |q|^2``, which is a proper
rotation for every ``q != 0`` and reaches every rotation, so identities in
``q`` hold over all of SO(3) with no side condition.

Frames and units follow the package: sensor frame x boresight, y left,
z up; ``p2 = R p1 + t``; lengths in metres, angles in radians.

SymPy is imported here only; ``sss_locus/__init__.py`` does not import this
module (SymPy is an optional ``book`` dependency).
"""
from __future__ import annotations

import sympy as sp

__all__ = [
    "symbols",
    "quaternion_rotation",
    "derive_plane",
    "derive_circle",
    "derive_one_angle",
    "derive_scaling",
    "derive_crop",
    "elevation_halfspaces",
    "azimuth_halfspaces",
    "halfspace_in_frame1",
    "numeric_functions",
]


def _vec(name: str, **assumptions) -> sp.Matrix:
    """A 3x1 column of real symbols ``name_x, name_y, name_z``."""
    return sp.Matrix(sp.symbols(f"{name}_x {name}_y {name}_z", real=True, **assumptions))


def symbols() -> dict:
    """The shared symbols of the derivation.

    Returns
    -------
    dict
        ``p`` (feature in frame 1), ``t`` (translation), ``u`` (free vector
        standing for ``R^T t``), ``R`` (general 3x3 symbolic matrix), ``q``
        (quaternion ``(q_w, q_x, q_y, q_z)``), scalars ``r1``, ``r2``
        (positive ranges), ``C``, ``k`` (positive scale), ``alpha``,
        ``theta1``, ``phi1``.
    """
    R = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"R_{i + 1}{j + 1}", real=True))
    return {
        "p": _vec("p"),
        "t": _vec("t"),
        "u": _vec("u"),
        "R": R,
        "q": sp.symbols("q_w q_x q_y q_z", real=True),
        "r1": sp.Symbol("r_1", positive=True),
        "r2": sp.Symbol("r_2", positive=True),
        "C": sp.Symbol("C", real=True),
        "k": sp.Symbol("k", positive=True),
        "alpha": sp.Symbol("alpha", real=True),
        "theta1": sp.Symbol("theta_1", real=True),
        "phi1": sp.Symbol("phi_1", real=True),
    }


def quaternion_rotation(q=None) -> sp.Matrix:
    """Rotation matrix of a non-zero (not necessarily unit) quaternion.

    ``R(q) = M(q) / |q|^2`` with ``M`` the usual homogeneous quadratic form;
    ``R(q)^T R(q) = I`` and ``det R(q) = 1`` hold identically in ``q``.
    """
    w, x, y, z = symbols()["q"] if q is None else q
    n2 = w**2 + x**2 + y**2 + z**2
    M = sp.Matrix([
        [w**2 + x**2 - y**2 - z**2, 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), w**2 - x**2 + y**2 - z**2, 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), w**2 - x**2 - y**2 + z**2],
    ])
    return M / n2


def _zero(expr) -> bool:
    """True when ``expr`` (scalar or matrix) simplifies to exactly zero."""
    if isinstance(expr, sp.MatrixBase):
        return all(_zero(e) for e in expr)
    return sp.simplify(sp.cancel(sp.expand(expr))) == 0


def _orthonormality_reduce(expr, R: sp.Matrix):
    """Normal form of polynomial ``expr`` modulo the ideal of ``R^T R = I``.

    Uses a Groebner basis (grevlex) of the six entries of ``R^T R - I`` in the
    nine entries of ``R``: the remainder is what is left of ``expr`` after
    every consequence of orthonormality has been substituted.
    """
    gram = R.T * R - sp.eye(3)
    gens = list(R)
    basis = sp.groebner([gram[i, j] for i in range(3) for j in range(i, 3)], *gens, order="grevlex")
    return sp.expand(sp.reduced(sp.expand(expr), list(basis.exprs), *gens, order="grevlex")[1])


def derive_plane(R: sp.Matrix | None = None):
    """Derive the plane ``2 u^T p1 = C`` from ``|p1| = r1`` and ``|R p1 + t| = r2``.

    Parameters
    ----------
    R : sympy.Matrix, optional
        Rotation to use. Default: the general symbolic 3x3 matrix; the
        difference of the sphere constraints is then reduced modulo the
        polynomial ideal generated by the entries of ``R^T R - I`` (a
        Groebner-basis normal form, i.e. orthonormality used as an exact
        substitution). Pass :func:`quaternion_rotation` for a parametrised
        rotation, for which the identity holds with no side condition.

    Returns
    -------
    result : dict
        ``plane`` (``Eq(2 u.p, C)``), ``u`` (``R^T t``), ``C``.
    steps : dict
        ``sphere1``, ``sphere2`` (constraints as ``expr = 0``),
        ``difference`` (``sphere2 - sphere1``, expanded),
        ``orthonormality_term`` (``p^T (R^T R - I) p``),
        ``gram_minus_identity`` (``R^T R - I``; identically 0 for
        :func:`quaternion_rotation`), ``reduced`` (the difference after
        using orthonormality) and ``residual`` (``reduced - (2 u.p - C)``,
        identically 0).
    """
    s = symbols()
    p, t, r1, r2 = s["p"], s["t"], s["r1"], s["r2"]
    general = R is None
    R = s["R"] if general else R
    p2 = R * p + t
    sphere1 = (p.T * p)[0] - r1**2
    sphere2 = (p2.T * p2)[0] - r2**2
    difference = sp.expand(sphere2 - sphere1)
    gram = (R.T * R - sp.eye(3)).applyfunc(lambda e: sp.simplify(sp.cancel(e)))
    orth_term = sp.cancel(sp.expand((p.T * gram * p)[0]))
    u = R.T * t
    C = r2**2 - r1**2 - (t.T * t)[0]
    if general:
        reduced = _orthonormality_reduce(difference, R)
    else:
        reduced = sp.expand(sp.cancel(difference))
    residual = sp.simplify(sp.cancel(reduced - (2 * (u.T * p)[0] - C)))
    steps = {
        "sphere1": sphere1,
        "sphere2": sphere2,
        "difference": difference,
        "orthonormality_term": orth_term,
        "gram_minus_identity": gram,
        "reduced": reduced,
        "residual": residual,
    }
    return {"plane": sp.Eq(2 * (u.T * p)[0], C), "u": u, "C": C}, steps


def derive_circle():
    """Derive the circle in which the plane ``2 u.p = C`` cuts ``|p| = r1``.

    Returns
    -------
    result : dict
        ``center`` (``C u / (2 |u|^2)``), ``radius_sq``
        (``r1^2 - C^2 / (4 |u|^2)``), ``radius``, ``exists``
        (``C^2 <= 4 |u|^2 r1^2``), ``tangent`` (equality: a single point).
    steps : dict
        ``u_dot_center_minus_half_C`` (0: the centre is on the plane),
        ``pythagoras_residual`` (``|c + w|^2 - |c|^2 - |w|^2 - 2 (C/(2|u|^2)) u.w``,
        identically 0, so for ``w`` in the plane (``u.w = 0``) ``|w|^2 =
        r1^2 - |c|^2``), ``center_norm_sq`` and ``radius_sq_residual``,
        ``norm_u_minus_norm_t_general`` (``|R^T t|^2 - |t|^2`` reduced
        modulo ``R^T R = I``: 0) and ``norm_u_minus_norm_t_quaternion``
        (identically 0).
    """
    s = symbols()
    u, C, r1, t = s["u"], s["C"], s["r1"], s["t"]
    u2 = (u.T * u)[0]
    center = C / (2 * u2) * u
    w = _vec("w")
    radius_sq = r1**2 - C**2 / (4 * u2)
    center_norm_sq = sp.simplify((center.T * center)[0])
    pyth = sp.simplify(
        ((center + w).T * (center + w))[0] - center_norm_sq - (w.T * w)[0]
        - 2 * C / (2 * u2) * (u.T * w)[0]
    )
    R = s["R"]
    uR = R.T * t
    general = _orthonormality_reduce((uR.T * uR)[0] - (t.T * t)[0], R)
    uq = quaternion_rotation().T * t
    quat = sp.simplify(sp.cancel((uq.T * uq)[0] - (t.T * t)[0]))
    steps = {
        "u_dot_center_minus_half_C": sp.simplify((u.T * center)[0] - C / 2),
        "pythagoras_residual": pyth,
        "center_norm_sq": center_norm_sq,
        "radius_sq_residual": sp.simplify(radius_sq - (r1**2 - center_norm_sq)),
        "norm_u_minus_norm_t_general": general,
        "norm_u_minus_norm_t_quaternion": quat,
    }
    result = {
        "center": center,
        "radius_sq": radius_sq,
        "radius": sp.sqrt(radius_sq),
        "exists": sp.Le(C**2, 4 * u2 * r1**2),
        "tangent": sp.Eq(C**2, 4 * u2 * r1**2),
    }
    return result, steps


def derive_one_angle():
    """The paper's one-angle form (eq. (onelocus)) and its closed-form solutions.

    Substituting ``p1 = r1 (cos th cos ph, sin th cos ph, sin ph)`` into
    ``2 u.p1 = C`` gives ``2 r1 (u_x cos th cos ph + u_y sin th cos ph +
    u_z sin ph) = C``. Writing ``a = u_x cos th + u_y sin th``:
    ``phi1 = atan2(u_z, a) +- arccos(C / (2 r1 hypot(a, u_z)))``; and
    ``theta1 = atan2(u_y, u_x) +- arccos((C/(2 r1) - u_z sin ph) /
    (cos ph hypot(u_x, u_y)))``. Real solutions need the arccos argument in
    ``[-1, 1]``; elevations are then wrapped to ``[-pi/2, pi/2]`` by the
    caller (a solution with ``cos(phi1) < 0`` is the same point as
    ``(theta1 + pi, pi - phi1)``).

    Returns
    -------
    result : dict
        ``equation`` (``Eq``), ``phi1_plus``, ``phi1_minus``, ``theta1_plus``,
        ``theta1_minus``.
    steps : dict
        ``spherical_point``, ``phi_residual_plus/minus`` and
        ``theta_residual_plus/minus`` (the equation's left side minus its
        right side at each solution: identically 0).
    """
    s = symbols()
    u, C, r1, th, ph = s["u"], s["C"], s["r1"], s["theta1"], s["phi1"]
    ux, uy, uz = u
    p = r1 * sp.Matrix([sp.cos(th) * sp.cos(ph), sp.sin(th) * sp.cos(ph), sp.sin(ph)])
    lhs = sp.factor_terms(2 * (u.T * p)[0])
    a = ux * sp.cos(th) + uy * sp.sin(th)
    kk = C / (2 * r1)
    phi_sol = [sp.atan2(uz, a) + sgn * sp.acos(kk / sp.sqrt(a**2 + uz**2)) for sgn in (1, -1)]
    th_sol = [sp.atan2(uy, ux) + sgn * sp.acos((kk - uz * sp.sin(ph)) / (sp.cos(ph) * sp.sqrt(ux**2 + uy**2)))
              for sgn in (1, -1)]

    def res(expr):
        return sp.simplify(sp.expand_trig(sp.expand(expr)))

    steps = {
        "spherical_point": p,
        "phi_residual_plus": res(lhs.subs(ph, phi_sol[0]) - C),
        "phi_residual_minus": res(lhs.subs(ph, phi_sol[1]) - C),
        "theta_residual_plus": res(lhs.subs(th, th_sol[0]) - C),
        "theta_residual_minus": res(lhs.subs(th, th_sol[1]) - C),
    }
    result = {"equation": sp.Eq(lhs, C), "phi1_plus": phi_sol[0], "phi1_minus": phi_sol[1],
              "theta1_plus": th_sol[0], "theta1_minus": th_sol[1]}
    return result, steps


def derive_scaling():
    """The scaling law: ``(r1, r2, t) -> (k r1, k r2, k t)``, ``k > 0``.

    ``u -> k u`` and ``C -> k^2 C``: the plane keeps its unit normal and its
    offset from the origin scales by ``k`` (a point ``p`` is on the scaled
    plane iff ``p / k`` is on the original); the centre and the radius scale
    by ``k``; the crop coefficients ``A, B, D`` of an angle-only aperture
    bound (``b`` proportional to the range, as for the elevation band) scale
    by ``k`` so the boundary angles are unchanged, and the locus length
    (radius times the angular measure) scales by ``k``. Range limits
    (``min_range``, ``max_range``) are not scale-invariant: the law holds for
    angle-only apertures.

    Returns
    -------
    result : dict
        ``center_ratio`` (``c_k - k c``, 0), ``radius_ratio`` (``rho_k / rho``),
        ``plane_offset_ratio`` (scaled over original plane offset
        ``C / (2 |u|)``), ``normal_change`` (``n_k - n``, 0).
    steps : dict
        ``u_scaled``, ``C_scaled``, ``center_scaled``, ``radius_sq_scaled``,
        ``crop_coefficients_scaled_over_original`` (``(A_k/A, B_k/B, D_k/D)``
        for the upper elevation bound).
    """
    s = symbols()
    t, r1, r2, k, R = s["t"], s["r1"], s["r2"], s["k"], quaternion_rotation()
    plane, _ = derive_plane(R)
    circ, _ = derive_circle()
    u_sym, C_sym = s["u"], s["C"]

    def at(scale):
        sub = {r1: scale * r1, r2: scale * r2, **{ti: scale * ti for ti in t}}
        u = plane["u"].subs(sub, simultaneous=True)
        C = plane["C"].subs(sub, simultaneous=True)
        rep = {**dict(zip(u_sym, u)), C_sym: C, r1: scale * r1}
        return u, C, circ["center"].subs(rep, simultaneous=True), circ["radius_sq"].subs(rep, simultaneous=True)

    u1, C1, c1, rho2_1 = at(1)
    uk, Ck, ck, rho2_k = at(k)
    norm = lambda v: sp.sqrt((v.T * v)[0])  # noqa: E731
    e1, e2 = _vec("e1"), _vec("e2")
    phi_max = sp.Symbol("phi_max", positive=True)
    crop = []
    for center, rho2, rr in ((c1, rho2_1, r1), (ck, rho2_k, k * r1)):
        (a, b), _ = elevation_halfspaces(rr, phi_max)
        crop.append(derive_crop(center, sp.sqrt(rho2), e1, e2, a, b)[0])
    ratios = tuple(sp.simplify(crop[1][n] / crop[0][n]) for n in ("A", "B", "D"))
    result = {
        "center_ratio": (ck - k * c1).applyfunc(lambda e: sp.simplify(sp.cancel(e))),
        "radius_ratio": sp.simplify(sp.sqrt(sp.factor(sp.cancel(rho2_k / rho2_1)))),
        "plane_offset_ratio": sp.simplify(sp.cancel((Ck / norm(uk)) / (C1 / norm(u1)))),
        "normal_change": (uk / norm(uk) - u1 / norm(u1)).applyfunc(sp.simplify),
    }
    steps = {"u_scaled": sp.simplify(uk), "C_scaled": sp.expand(Ck), "center_scaled": ck,
             "radius_sq_scaled": rho2_k, "crop_coefficients_scaled_over_original": ratios}
    return result, steps


def derive_crop(center=None, radius=None, e1=None, e2=None, a=None, b=None):
    """Restrict an affine half-space ``a . p + b >= 0`` to the circle.

    On ``p(alpha) = c + rho (cos(alpha) e1 + sin(alpha) e2)`` the condition is
    ``A cos(alpha) + B sin(alpha) + D >= 0`` with ``A = rho a.e1``,
    ``B = rho a.e2``, ``D = a.c + b``. With ``H = hypot(A, B)`` and
    ``alpha0 = atan2(B, A)`` it reads ``H cos(alpha - alpha0) >= -D``:

    * ``H = 0``: whole circle if ``D >= 0``, else empty;
    * ``-D / H <= -1``: whole circle; ``-D / H > 1``: empty;
      ``-D / H = 1``: the single point ``alpha0`` (zero length);
    * otherwise the arc ``[alpha0 - delta, alpha0 + delta]`` with
      ``delta = arccos(-D / H)``.

    Arguments default to free symbols (vectors ``c``, ``e1``, ``e2``, ``a``;
    scalars ``rho``, ``b``).

    Returns
    -------
    result : dict
        ``A``, ``B``, ``D``, ``H``, ``alpha0``, ``delta``, ``inequality``.
    steps : dict
        ``restricted`` (``a.p(alpha) + b``), ``residual`` (``restricted - (A
        cos + B sin + D)``, identically 0), ``boundary_residual_plus/minus``
        (``A cos + B sin + D`` at ``alpha0 +- delta``: identically 0),
        ``value_at_alpha0`` (``H + D``, so the arc between the boundary
        angles is the inside when ``-D/H < 1``).
    """
    alpha = symbols()["alpha"]
    c = _vec("c") if center is None else center
    rho = sp.Symbol("rho", positive=True) if radius is None else radius
    e1 = _vec("e1") if e1 is None else e1
    e2 = _vec("e2") if e2 is None else e2
    a = _vec("a") if a is None else a
    b = sp.Symbol("b", real=True) if b is None else b
    p = c + rho * (sp.cos(alpha) * e1 + sp.sin(alpha) * e2)
    restricted = (a.T * p)[0] + b
    A, B, D = rho * (a.T * e1)[0], rho * (a.T * e2)[0], (a.T * c)[0] + b
    form = A * sp.cos(alpha) + B * sp.sin(alpha) + D
    H = sp.sqrt(A**2 + B**2)
    alpha0 = sp.atan2(B, A)
    delta = sp.acos(-D / H)
    steps = {"restricted": restricted, "residual": sp.simplify(sp.expand(restricted - form))}
    if center is None:  # the boundary proof on free symbols (kept cheap)
        As, Bs, Ds = sp.symbols("A B D", real=True)
        Hs = sp.sqrt(As**2 + Bs**2)
        f = As * sp.cos(alpha) + Bs * sp.sin(alpha) + Ds
        for name, sgn in (("plus", 1), ("minus", -1)):
            at = f.subs(alpha, sp.atan2(Bs, As) + sgn * sp.acos(-Ds / Hs))
            steps[f"boundary_residual_{name}"] = sp.simplify(sp.expand_trig(at))
        steps["value_at_alpha0"] = sp.simplify(f.subs(alpha, sp.atan2(Bs, As)))
    result = {"A": A, "B": B, "D": D, "H": H, "alpha0": alpha0, "delta": delta,
              "inequality": sp.Ge(form, 0)}
    return result, steps


def elevation_halfspaces(r, phi_max):
    """Elevation band ``|phi| <= phi_max`` on a sphere of radius ``r`` as half-spaces.

    On ``|p| = r`` (``r`` constant on the circle), ``|asin(z / r)| <= phi_max``
    with ``phi_max`` in ``(0, pi/2]`` is ``r sin(phi_max) - z >= 0`` and
    ``z + r sin(phi_max) >= 0``, both affine. Returns ``[(a, b), (a, b)]``
    (upper bound first); always intersected.
    """
    sz = r * sp.sin(phi_max)
    return [(sp.Matrix([0, 0, -1]), sz), (sp.Matrix([0, 0, 1]), sz)]


def azimuth_halfspaces(theta_max):
    """Azimuth wedge ``|atan2(y, x)| <= theta_max`` as two half-planes.

    ``x sin(theta_max) - y cos(theta_max) >= 0`` (``theta <= theta_max``) and
    ``x sin(theta_max) + y cos(theta_max) >= 0`` (``theta >= -theta_max``).
    For ``theta_max <= pi/2`` (full azimuth <= 180 deg) the wedge is their
    intersection, for wider wedges their union. Returns ``[(a, b), (a, b)]``.
    """
    s, c = sp.sin(theta_max), sp.cos(theta_max)
    return [(sp.Matrix([s, -c, 0]), sp.S.Zero), (sp.Matrix([s, c, 0]), sp.S.Zero)]


def halfspace_in_frame1(a2, b2, R, t):
    """A frame-2 half-space ``a2 . p2 + b2 >= 0`` written in frame 1.

    With ``p2 = R p1 + t``: ``(R^T a2) . p1 + (a2 . t + b2) >= 0``.
    Returns ``(a1, b1)``.
    """
    return R.T * a2, (a2.T * t)[0] + b2


def numeric_functions() -> dict:
    """NumPy functions lambdified from the derived expressions (for tests and the book).

    Returns
    -------
    dict of callables (arguments are NumPy arrays, broadcast elementwise)
        ``u(R, t)`` -> (..., 3); ``C(t, r1, r2)``; ``center(u, C)`` -> (..., 3);
        ``radius(u, C, r1)`` (NaN where the spheres do not meet);
        ``exists(u, C, r1)``; ``crop(c, rho, e1, e2, a, b)`` -> ``(A, B, D)``;
        ``phi1(u, C, r1, theta1)`` and ``theta1(u, C, r1, phi1)`` -> the
        ``(+, -)`` solution pairs.
    """
    import numpy as np

    s = symbols()
    plane, _ = derive_plane()
    circ, _ = derive_circle()
    one, _ = derive_one_angle()
    crop, _ = derive_crop()
    R, t, u, C, r1, r2 = s["R"], s["t"], s["u"], s["C"], s["r1"], s["r2"]
    c, e1, e2, a = _vec("c"), _vec("e1"), _vec("e2"), _vec("a")
    rho, b = sp.Symbol("rho", positive=True), sp.Symbol("b", real=True)
    f_u = sp.lambdify([list(R), list(t)], list(plane["u"]), "numpy")
    f_C = sp.lambdify([list(t), r1, r2], plane["C"], "numpy")
    f_c = sp.lambdify([list(u), C], list(circ["center"]), "numpy")
    f_rho2 = sp.lambdify([list(u), C, r1], circ["radius_sq"], "numpy")
    f_ex = sp.lambdify([list(u), C, r1], circ["exists"], "numpy")
    f_crop = sp.lambdify([list(c), rho, list(e1), list(e2), list(a), b],
                         [crop["A"], crop["B"], crop["D"]], "numpy")
    f_phi = sp.lambdify([list(u), C, r1, s["theta1"]], [one["phi1_plus"], one["phi1_minus"]], "numpy")
    f_th = sp.lambdify([list(u), C, r1, s["phi1"]], [one["theta1_plus"], one["theta1_minus"]], "numpy")

    def cols(v):
        v = np.asarray(v, dtype=float)
        return [v[..., i] for i in range(3)]

    def stack(parts):
        return np.stack(np.broadcast_arrays(*parts), axis=-1)

    def radius(u_, C_, r1_):
        rho2 = np.asarray(f_rho2(cols(u_), C_, r1_), dtype=float)
        return np.where(rho2 >= 0, np.sqrt(np.abs(rho2)), np.nan)

    return {
        "u": lambda R_, t_: stack(f_u([np.asarray(R_, float)[..., i, j] for i in range(3) for j in range(3)],
                                      cols(t_))),
        "C": lambda t_, r1_, r2_: np.asarray(f_C(cols(t_), r1_, r2_), dtype=float),
        "center": lambda u_, C_: stack(f_c(cols(u_), C_)),
        "radius": radius,
        "exists": lambda u_, C_, r1_: np.asarray(f_ex(cols(u_), C_, r1_), dtype=bool),
        "crop": lambda c_, rho_, e1_, e2_, a_, b_: tuple(
            np.asarray(x, dtype=float) for x in np.broadcast_arrays(
                *f_crop(cols(c_), rho_, cols(e1_), cols(e2_), cols(a_), b_))),
        "phi1": lambda u_, C_, r1_, th_: tuple(np.asarray(f_phi(cols(u_), C_, r1_, th_), dtype=float)),
        "theta1": lambda u_, C_, r1_, ph_: tuple(np.asarray(f_th(cols(u_), C_, r1_, ph_), dtype=float)),
    }
