"""Lambdified (NumPy) forms of the derived expressions and a cross-check against the kernel."""
from __future__ import annotations

import functools

import sympy as sp

from .derivation import (
    vector,
    derive_circle,
    derive_crop,
    derive_one_angle,
    derive_plane,
    elevation_halfspaces,
    symbols,
)


@functools.lru_cache(maxsize=1)
def numeric_functions() -> dict:
    """NumPy functions lambdified from the derived expressions (for tests and the book).

    The result is cached (the derivations take a few seconds); do not mutate it.

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
    c, e1, e2, a = vector("c"), vector("e1"), vector("e2"), vector("a")
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


def kernel_discrepancy(seed: int = 0, n: int = 2000, elevation_deg: float = 10.0) -> dict:
    """Largest differences between the derived formulas and the kernel on random configurations.

    ``n`` configurations: a uniformly random rotation, ``t ~ N(0, 20 m)``, a feature
    ``p1 ~ N(0, 40 m)`` and the ranges it implies (so the spheres meet). Sensor 1 sees
    ``elevation_deg`` in elevation and 360 deg in azimuth, sensor 2 everything, so the locus is
    bounded by sensor 1's elevation band only and every kernel arc end must be one of the four
    derived boundary angles ``alpha0 +- arccos(-D / hypot(A, B))``.

    Parameters
    ----------
    seed : int
        Seed of ``numpy.random.default_rng`` for the configurations.
    n : int
        Number of random configurations.
    elevation_deg : float
        Full elevation aperture of sensor 1, degrees (its half is the band's bound).

    Returns
    -------
    dict
        ``u``, ``C``, ``center`` (m, m^2, m; max abs difference), ``radius_rel`` (max relative),
        ``exists_mismatch`` (count), ``boundary_rad`` (max distance of a kernel arc end to the
        nearest derived boundary angle, rad), ``n_ends`` (arc ends compared).
    """
    import numpy as np
    from scipy.spatial.transform import Rotation

    from ..aperture import Aperture
    from ..locus import LocusStatus, two_view_locus

    f = numeric_functions()
    rng = np.random.default_rng(seed)
    R = Rotation.random(n, random_state=rng).as_matrix()
    t = rng.normal(scale=20.0, size=(n, 3))
    p1 = rng.normal(scale=40.0, size=(n, 3))
    r1 = np.linalg.norm(p1, axis=1)
    r2 = np.linalg.norm(np.einsum("nij,nj->ni", R, p1) + t, axis=1)
    ap1 = Aperture(360.0, elevation_deg, 1e9)
    res = two_view_locus(R, t, r1, r2, ap1, Aperture(360.0, 180.0, 1e9))
    u, C = f["u"](R, t), f["C"](t, r1, r2)
    c, rho = f["center"](u, C), f["radius"](u, C, r1)
    ok = res.status == LocusStatus.CIRCLE
    bounds = []
    for a, b in elevation_halfspaces(sp.Symbol("r"), sp.Float(ap1.half_elevation_rad)):
        b_of_r = sp.lambdify(sp.Symbol("r"), b)(r1)
        A, B, D = f["crop"](c, rho, res.basis1, res.basis2, np.array(a, dtype=float).ravel(), b_of_r)
        H = np.hypot(A, B)
        with np.errstate(invalid="ignore", divide="ignore"):
            delta = np.arccos(-D / H)  # NaN where the bound does not cut the circle
        bounds += [np.arctan2(B, A) - delta, np.arctan2(B, A) + delta]
    bounds = np.stack(bounds, axis=1)[:, None, :]  # (n, 1, 4)
    ends = np.concatenate([res.arc_start, res.arc_end], axis=1)[:, :, None]  # (n, 2 MAX_ARCS, 1)
    full = (res.arc_end - res.arc_start)[:, 0] >= 2 * np.pi - 1e-12
    d = np.abs(ends - bounds) % (2 * np.pi)
    d = np.nanmin(np.minimum(d, 2 * np.pi - d), axis=2, initial=np.inf)
    use = ok[:, None] & ~full[:, None] & ~np.isnan(ends[..., 0])
    return {
        "u": float(np.max(np.abs(res.u - u))),
        "C": float(np.max(np.abs(res.C - C))),
        "center": float(np.max(np.abs(res.center - c)[ok])),
        "radius_rel": float(np.max(np.abs(res.radius - rho)[ok] / rho[ok])),
        "exists_mismatch": int(np.sum(res.exists != f["exists"](u, C, r1))),
        "boundary_rad": float(np.max(d[use])) if use.any() else float("nan"),
        "n_ends": int(use.sum()),
    }
