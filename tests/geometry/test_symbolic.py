"""The book's algebra (sss_locus.geometry.symbolic) against itself and against the numeric kernel.

Two kinds of check:

* symbolic: every derivation step reduces to an exact 0 in SymPy, for a general rotation
  (a free 3x3 matrix reduced modulo R^T R = I, and a free quaternion), and a deliberately
  wrong formula does NOT reduce to 0 (so the checks can fail);
* numeric: the derived expressions, lambdified, reproduce the kernel's u, C, centre, radius,
  existence and arcs on random configurations. The arcs are rebuilt here from the derived
  crop coefficients A, B, D and boundary angles alpha0 +- arccos(-D / hypot(A, B)) with an
  interval arithmetic written for this test (no code shared with sss_locus.geometry.arcs).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from scipy.spatial.transform import Rotation

from sss_locus import Aperture, LocusStatus, two_view_locus
from sss_locus.geometry import symbolic as S

TWO_PI = 2.0 * math.pi


@pytest.fixture(scope="module")
def f():
    return S.numeric_functions()


# ---------------------------------------------------------------- symbolic identities


def test_quaternion_rotation_is_a_rotation_identically():
    R = S.quaternion_rotation()
    assert (R.T * R - sp.eye(3)).applyfunc(lambda e: sp.simplify(sp.cancel(e))) == sp.zeros(3)
    assert sp.simplify(sp.cancel(R.det())) == 1


@pytest.mark.parametrize("rotation", ["general", "quaternion"])
def test_plane_from_two_spheres(rotation):
    R = None if rotation == "general" else S.quaternion_rotation()
    res, steps = S.derive_plane(R)
    assert steps["residual"] == 0
    if rotation == "quaternion":  # no side condition left
        assert steps["orthonormality_term"] == 0
    else:  # the orthonormality term is genuinely needed: it is not 0 for a free matrix
        assert steps["orthonormality_term"] != 0
        assert sp.expand(steps["difference"] - steps["reduced"]) != 0


def test_plane_check_can_fail():
    """A wrong sign on |t|^2 in C leaves a non-zero residual after the same reduction."""
    s = S.symbols()
    _, steps = S.derive_plane()
    u = s["R"].T * s["t"]
    wrong_C = s["r2"] ** 2 - s["r1"] ** 2 + (s["t"].T * s["t"])[0]
    assert sp.simplify(steps["reduced"] - (2 * (u.T * s["p"])[0] - wrong_C)) != 0


def test_circle_center_radius_existence():
    res, steps = S.derive_circle()
    for key in ("u_dot_center_minus_half_C", "pythagoras_residual", "radius_sq_residual",
                "norm_u_minus_norm_t_general", "norm_u_minus_norm_t_quaternion"):
        assert steps[key] == 0, key
    s = S.symbols()
    u2 = (s["u"].T * s["u"])[0]
    # existence <=> radius^2 >= 0 (multiply by 4|u|^2 > 0)
    assert sp.simplify(4 * u2 * res["radius_sq"] - (4 * u2 * s["r1"] ** 2 - s["C"] ** 2)) == 0
    assert sp.simplify(steps["center_norm_sq"] - s["C"] ** 2 / (4 * u2)) == 0


def test_one_angle_form_and_its_solutions():
    res, steps = S.derive_one_angle()
    for key in ("phi_residual_plus", "phi_residual_minus", "theta_residual_plus", "theta_residual_minus"):
        assert steps[key] == 0, key
    s = S.symbols()
    ux, uy, uz = s["u"]
    th, ph = s["theta1"], s["phi1"]
    paper = 2 * s["r1"] * (ux * sp.cos(th) * sp.cos(ph) + uy * sp.sin(th) * sp.cos(ph) + uz * sp.sin(ph))
    assert sp.simplify(res["equation"].lhs - paper) == 0
    # a wrong solution (sin and cos swapped in a) fails the equation: one rational point where
    # the residual is non-zero proves it is not an identity
    wrong = sp.atan2(uz, ux * sp.sin(th) + uy * sp.cos(th)) + sp.acos(s["C"] / (2 * s["r1"] * sp.sqrt(
        (ux * sp.sin(th) + uy * sp.cos(th)) ** 2 + uz**2)))
    point = {ux: 3, uy: -2, uz: 1, s["C"]: 5, s["r1"]: 4, th: sp.Rational(1, 3)}
    value = (res["equation"].lhs.subs(ph, wrong) - s["C"]).subs(point)
    assert abs(float(value.evalf(30))) > 1e-3


def test_crop_form_and_boundary_angles():
    res, steps = S.derive_crop()
    assert steps["residual"] == 0
    assert steps["boundary_residual_plus"] == 0
    assert steps["boundary_residual_minus"] == 0
    A, B, D = sp.symbols("A B D", real=True)
    assert sp.simplify(steps["value_at_alpha0"] - (sp.sqrt(A**2 + B**2) + D)) == 0


def test_frame2_halfspace_in_frame1():
    s = S.symbols()
    R, t, p = S.quaternion_rotation(), s["t"], s["p"]
    a2, b2 = sp.Matrix(sp.symbols("a2_x a2_y a2_z", real=True)), sp.Symbol("b2", real=True)
    a1, b1 = S.halfspace_in_frame1(a2, b2, R, t)
    assert sp.simplify(sp.cancel((a2.T * (R * p + t))[0] + b2 - ((a1.T * p)[0] + b1))) == 0


def test_halfspaces_describe_the_angles():
    """Angular form of the half-spaces: sin(theta_max -+ theta) >= 0 and z = r sin(phi)."""
    r, th, ph, tm, pm = sp.symbols("r theta phi theta_m phi_m", real=True)
    p = r * sp.Matrix([sp.cos(th) * sp.cos(ph), sp.sin(th) * sp.cos(ph), sp.sin(ph)])
    (a_hi, _), (a_lo, _) = S.azimuth_halfspaces(tm)
    assert sp.simplify((a_hi.T * p)[0] - r * sp.cos(ph) * sp.sin(tm - th)) == 0
    assert sp.simplify((a_lo.T * p)[0] - r * sp.cos(ph) * sp.sin(tm + th)) == 0
    (a_up, b_up), (a_dn, b_dn) = S.elevation_halfspaces(r, pm)
    assert sp.simplify((a_up.T * p)[0] + b_up - r * (sp.sin(pm) - sp.sin(ph))) == 0
    assert sp.simplify((a_dn.T * p)[0] + b_dn - r * (sp.sin(pm) + sp.sin(ph))) == 0


def test_scaling_law():
    res, steps = S.derive_scaling()
    k = S.symbols()["k"]
    assert res["center_ratio"] == sp.zeros(3, 1)
    assert res["normal_change"] == sp.zeros(3, 1)
    assert res["radius_ratio"] == k
    assert res["plane_offset_ratio"] == k
    assert steps["crop_coefficients_scaled_over_original"] == (k, k, k)


# ---------------------------------------------------------------- against the kernel


def _random_configs(rng, n, *, exists=True):
    R = Rotation.random(n, random_state=rng).as_matrix()
    t = rng.normal(scale=20.0, size=(n, 3))
    p1 = rng.normal(scale=40.0, size=(n, 3))
    r1 = np.linalg.norm(p1, axis=1)
    r2 = np.linalg.norm(np.einsum("nij,nj->ni", R, p1) + t, axis=1)
    if not exists:  # independent ranges: a mix of meeting and non-meeting spheres
        r2 = rng.uniform(1.0, 120.0, size=n)
    return R, t, r1, r2


def _inside(rng, n, ap, scale):
    th = rng.uniform(-1, 1, n) * min(ap.half_azimuth_rad, math.pi)
    ph = rng.uniform(-1, 1, n) * ap.half_elevation_rad
    r = rng.uniform(0.3, 1.0, n) * scale
    return r[:, None] * np.stack([np.cos(th) * np.cos(ph), np.sin(th) * np.cos(ph), np.sin(ph)], axis=1)


def _configs_with_feature(rng, n, ap1, ap2):
    """Half random configurations, half with a feature placed inside both apertures (so the
    locus is non-empty): p1 inside aperture 1, p2 inside aperture 2, t = p2 - R p1."""
    R, t, r1, r2 = _random_configs(rng, n)
    m = n // 2
    p1, p2 = _inside(rng, m, ap1, 60.0), _inside(rng, m, ap2, 60.0)
    t[:m] = p2 - np.einsum("nij,nj->ni", R[:m], p1)
    r1[:m], r2[:m] = np.linalg.norm(p1, axis=1), np.linalg.norm(p2, axis=1)
    return R, t, r1, r2


@pytest.mark.parametrize("exists", [True, False])
def test_circle_matches_kernel(f, exists):
    rng = np.random.default_rng(20261121 + exists)
    R, t, r1, r2 = _random_configs(rng, 400, exists=exists)
    ap = Aperture(360.0, 180.0, 1e6)
    res = two_view_locus(R, t, r1, r2, ap, ap)
    u = f["u"](R, t)
    C = f["C"](t, r1, r2)
    np.testing.assert_allclose(res.u, u, rtol=1e-12, atol=1e-12 * np.abs(u).max())
    np.testing.assert_allclose(res.C, C, rtol=1e-12, atol=1e-12 * np.abs(C).max())
    ex = f["exists"](u, C, r1)
    circle = res.status == LocusStatus.CIRCLE
    # away from tangency the existence condition decides exactly
    clear = np.abs(C**2 - 4 * np.sum(u * u, axis=1) * r1**2) > 1e-8 * C**2
    assert np.array_equal(res.exists[clear], ex[clear])
    if not exists:
        assert 20 < ex.sum() < 380  # both outcomes are exercised
    np.testing.assert_allclose(res.center[circle], f["center"](u, C)[circle], rtol=1e-10, atol=1e-9)
    np.testing.assert_allclose(res.radius[circle], f["radius"](u, C, r1)[circle], rtol=1e-9, atol=1e-9)
    assert np.all(np.isnan(f["radius"](u, C, r1)[~ex]))


# --- an independent interval arithmetic on the circle, [0, 2 pi)


def _halfspace_set(A, B, D):
    """Intervals (list of (lo, hi) in [0, 2 pi)) where A cos + B sin + D >= 0, via the derived
    boundary angles alpha0 +- arccos(-D / hypot(A, B))."""
    H = math.hypot(A, B)
    if H == 0.0 or -D / H <= -1.0:
        return [(0.0, TWO_PI)] if (H > 0.0 or D >= 0.0) else []
    if -D / H >= 1.0:
        return []
    a0, d = math.atan2(B, A), math.acos(-D / H)
    lo = (a0 - d) % TWO_PI
    hi = lo + 2.0 * d
    return [(lo, hi)] if hi <= TWO_PI else [(lo, TWO_PI), (0.0, hi - TWO_PI)]


MERGE_TOL = 1e-11  # rad: boundaries computed twice (e.g. y >= 0 and y <= 0) differ by rounding


def _normalise(iv):
    iv = sorted((lo, hi) for lo, hi in iv if hi > lo)
    out = []
    for lo, hi in iv:
        if out and lo <= out[-1][1] + MERGE_TOL:
            out[-1] = (out[-1][0], max(out[-1][1], hi))
        else:
            out.append((lo, hi))
    return out


def _intersect(a, b):
    return _normalise([(max(x0, y0), min(x1, y1)) for x0, x1 in a for y0, y1 in b])


def _union(a, b):
    return _normalise(a + b)


def _measure(iv):
    return sum(hi - lo for lo, hi in iv)


def _endpoints(iv):
    """Boundary angles of a cyclic interval set (the artificial cut at 0 = 2 pi removed)."""
    iv = _normalise(iv)
    pts = [x for lo, hi in iv for x in (lo, hi)]
    if len(iv) > 1 and iv[0][0] <= MERGE_TOL and iv[-1][1] >= TWO_PI - MERGE_TOL:
        pts = pts[1:-1]
    elif len(iv) == 1 and iv[0][1] - iv[0][0] >= TWO_PI - MERGE_TOL:
        pts = []
    return np.sort(np.mod(pts, TWO_PI))


def _kernel_set(start, end):
    iv = []
    for s0, e0 in zip(start, end):
        if np.isnan(s0):
            continue
        lo = s0 % TWO_PI
        hi = lo + (e0 - s0)
        iv += [(lo, min(hi, TWO_PI))] + ([(0.0, hi - TWO_PI)] if hi > TWO_PI else [])
    return _normalise(iv)


def _aperture_set(f, ap, c, rho, e1, e2, r, R=None, t=None):
    """Allowed set of one aperture on the circle, from the symbolic half-spaces."""
    sets = []
    halves = [S.elevation_halfspaces(sp.Float(r), sp.Float(ap.half_elevation_rad)),
              S.azimuth_halfspaces(sp.pi if ap.azimuth_deg == 360.0 else sp.Float(ap.half_azimuth_rad))]
    for pair in halves:
        one = []
        for a, b in pair:
            if R is not None:
                a, b = S.halfspace_in_frame1(a, b, sp.Matrix(R), sp.Matrix(t))
            a = np.array([float(x) for x in a])
            A, B, D = (float(x) for x in f["crop"](c, rho, e1, e2, a, float(b)))
            one.append(_halfspace_set(A, B, D))
        sets.append(one)
    elev = _intersect(*sets[0])
    az = _union(*sets[1]) if ap.azimuth_deg > 180.0 else _intersect(*sets[1])
    return _intersect(elev, az)


def _circ_dist(a, b):
    d = np.abs(np.subtract.outer(a, b)) % TWO_PI
    return np.minimum(d, TWO_PI - d)


@pytest.mark.parametrize(
    "ap1, ap2",
    [
        (Aperture(360.0, 12.0, 1e6), Aperture(360.0, 180.0, 1e6)),  # sensor 1's elevation band only
        (Aperture(130.0, 20.0, 1e6), Aperture(50.0, 30.0, 1e6)),
        (Aperture(270.0, 25.0, 1e6), Aperture(200.0, 40.0, 1e6)),  # non-convex azimuth wedges
        (Aperture(360.0, 180.0, 1e6), Aperture(360.0, 180.0, 1e6)),  # every bound full: whole circle
        (Aperture(130.0, 0.27, 1e6), Aperture(50.0, 0.5, 1e6)),  # the paper's real beams
    ],
)
def test_crop_matches_kernel_arcs(f, ap1, ap2):
    rng = np.random.default_rng(7)
    R, t, r1, r2 = _configs_with_feature(rng, 150, ap1, ap2)
    res = two_view_locus(R, t, r1, r2, ap1, ap2)
    u, C = f["u"](R, t), f["C"](t, r1, r2)
    centers, radii = f["center"](u, C), f["radius"](u, C, r1)
    compared = 0
    for i in range(len(r1)):
        if res.status[i] != LocusStatus.CIRCLE:
            continue
        e1, e2 = res.basis1[i], res.basis2[i]
        # the crop formula needs an orthonormal in-plane basis: check the kernel's
        basis = np.array([e1, e2, u[i] / np.linalg.norm(u[i])])
        np.testing.assert_allclose(basis @ basis.T, np.eye(3), atol=1e-12)
        ref = _intersect(_aperture_set(f, ap1, centers[i], radii[i], e1, e2, r1[i]),
                         _aperture_set(f, ap2, centers[i], radii[i], e1, e2, r2[i], R[i], t[i]))
        ker = _kernel_set(res.arc_start[i], res.arc_end[i])
        assert _measure(ref) * radii[i] == pytest.approx(res.length[i], rel=1e-9, abs=1e-9)
        sym_diff = _measure(ref) + _measure(ker) - 2 * _measure(_intersect(ref, ker))
        assert sym_diff < 1e-9
        pr, pk = _endpoints(ref), _endpoints(ker)
        assert len(pr) == len(pk) == 2 * res.n_arcs[i] or (res.n_arcs[i] == 1 and len(pr) == len(pk) == 0)
        if len(pr):
            assert _circ_dist(pr, pk).min(axis=1).max() < 1e-9
        compared += int(res.n_arcs[i] > 0)
    assert compared >= 75  # at least the constructed half
    if ap1.azimuth_deg == ap2.azimuth_deg == 360.0 and ap1.elevation_deg == ap2.elevation_deg == 180.0:
        circle = res.status == LocusStatus.CIRCLE
        assert np.all(res.n_arcs[circle] == 1)
        np.testing.assert_allclose(res.length[circle], TWO_PI * radii[circle], rtol=1e-12)


def test_elevation_band_only_boundary_angles(f):
    """Sensor 1's elevation band alone bounds the locus: kernel arc ends = alpha0 +- delta."""
    ap1, ap2 = Aperture(360.0, 10.0, 1e6), Aperture(360.0, 180.0, 1e6)
    R = Rotation.from_euler("xyz", [20.0, -35.0, 60.0], degrees=True).as_matrix()
    t = R @ np.array([2.0, 20.0, 1.5])  # u = R^T t nearly horizontal: a steep circle crossing the band
    p1 = np.array([30.0, 10.0, 1.0])
    r1, r2 = np.linalg.norm(p1), np.linalg.norm(R @ p1 + t)
    res = two_view_locus(R, t, r1, r2, ap1, ap2)
    u, C = f["u"](R, t), f["C"](t, r1, r2)
    c, rho = f["center"](u, C), f["radius"](u, C, r1)
    angles = []
    for a, b in S.elevation_halfspaces(sp.Float(r1), sp.Float(ap1.half_elevation_rad)):
        A, B, D = (float(x) for x in f["crop"](c, rho, res.basis1, res.basis2,
                                                np.array([float(x) for x in a]), float(b)))
        H = math.hypot(A, B)
        assert abs(D / H) < 1.0  # each bound cuts the circle
        a0, d = math.atan2(B, A), math.acos(-D / H)
        angles += [a0 - d, a0 + d]
    assert res.n_arcs == 2
    ends = np.concatenate([res.arc_start[:2], res.arc_end[:2]])
    assert _circ_dist(np.sort(np.mod(angles, TWO_PI)), ends).min(axis=1).max() < 1e-10
    assert _circ_dist(ends, np.mod(angles, TWO_PI)).min(axis=1).max() < 1e-10


def test_one_angle_solutions_recover_kernel_points(f):
    rng = np.random.default_rng(11)
    R, t, r1, r2 = _random_configs(rng, 200)
    ap = Aperture(130.0, 30.0, 1e6)
    res = two_view_locus(R, t, r1, r2, ap, ap)
    pts = res.points(n_per_arc=5)[:, 0]  # first arc, (n, 5, 3)
    ok = ~np.isnan(pts[..., 0])
    assert ok.sum() > 100
    p = pts[ok]
    idx = np.nonzero(ok)[0]
    u, C = f["u"](R, t)[idx], f["C"](t, r1, r2)[idx]
    rr = r1[idx]
    theta = np.arctan2(p[:, 1], p[:, 0])
    phi = np.arcsin(np.clip(p[:, 2] / rr, -1, 1))
    with np.errstate(invalid="ignore"):  # arccos of 1 + rounding -> NaN, counted below
        ph_p, ph_m = f["phi1"](u, C, rr, theta)
        th_p, th_m = f["theta1"](u, C, rr, phi)
    err_phi = np.minimum(_circ_dist_pair(ph_p, phi), _circ_dist_pair(ph_m, phi))
    err_th = np.minimum(_circ_dist_pair(th_p, theta), _circ_dist_pair(th_m, theta))
    assert np.nanmax(err_phi) < 1e-6 and np.nanmax(err_th) < 1e-6
    assert np.mean(np.isfinite(err_phi)) > 0.99 and np.mean(np.isfinite(err_th)) > 0.99


def _circ_dist_pair(a, b):
    d = np.abs(a - b) % TWO_PI
    return np.minimum(d, TWO_PI - d)


def test_scaling_keeps_kernel_boundary_angles(f):
    rng = np.random.default_rng(5)
    R, t, r1, r2 = _random_configs(rng, 100)
    ap = Aperture(130.0, 20.0, 1e6)
    k = 3.7
    a = two_view_locus(R, t, r1, r2, ap, ap)
    b = two_view_locus(R, k * t, k * r1, k * r2, ap, ap)
    assert np.array_equal(a.n_arcs, b.n_arcs)
    np.testing.assert_allclose(b.length, k * a.length, rtol=1e-9, atol=1e-9)
    m = ~np.isnan(a.arc_start)
    assert _circ_dist_pair(b.arc_start[m], a.arc_start[m]).max() < 1e-9
    assert _circ_dist_pair(b.arc_end[m], a.arc_end[m]).max() < 1e-9


def test_kernel_discrepancy_summary_used_by_the_book():
    out = S.kernel_discrepancy(seed=3, n=300, elevation_deg=8.0)
    assert out["n_ends"] > 100
    assert out["exists_mismatch"] == 0
    assert out["radius_rel"] < 1e-10 and out["center"] < 1e-9 and out["boundary_rad"] < 1e-9
