"""The three-view line–sphere derivation (sss_locus.geometry.symbolic.three_view_points) against itself and the
kernel (sss_locus.geometry.three_view_points), as tests/geometry/test_symbolic.py does for the two-view locus."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from scipy.spatial.transform import Rotation

from sss_locus import Aperture
from sss_locus.geometry import symbolic as S
from sss_locus.geometry.symbolic import three_view_points as T3
from sss_locus.geometry.three_view_points import ThreeViewStatus, three_view_points


@pytest.fixture(scope="module")
def g():
    return T3.numeric_three_view()


def test_line_derivation_steps_are_exact():
    _, steps = T3.derive_line()
    assert steps["closed_form_residual"] == sp.zeros(3, 1)
    for key in ("on_plane2_residual", "on_plane3_residual", "orthogonal_residual"):
        assert steps[key] == 0, key
    assert steps["direction_in_planes"] == (0, 0)


def test_line_check_can_fail():
    """A wrong closed form (c2 and c3 swapped) is not the solved point."""
    s = T3.three_view_symbols()
    line, steps = T3.derive_line()
    w = line["w"]
    wrong = (s["c3"] * s["u3"].cross(w) + s["c2"] * w.cross(s["u2"])) / (w.T * w)[0]
    diff = (wrong - steps["solved"]).applyfunc(lambda e: sp.simplify(sp.cancel(e)))
    assert diff != sp.zeros(3, 1)


def test_line_sphere_roots():
    res, steps = T3.derive_line_sphere()
    assert steps["linear_coefficient_on_line"] == 0
    assert steps["root_residuals"] == (0, 0)
    assert steps["h_residual"] == 0
    # two real roots exactly when r1^2 > |p0|^2: the discriminant is 4 |w|^2 h^2
    line, _ = T3.derive_line()
    w = line["w"]
    assert sp.simplify(sp.cancel(res["discriminant"] - 4 * (w.T * w)[0] * res["h_sq"])) == 0


def _configs(rng, n):
    R12 = Rotation.random(n, random_state=rng).as_matrix()
    R13 = Rotation.random(n, random_state=rng).as_matrix()
    t12, t13 = rng.normal(scale=20.0, size=(2, n, 3))
    p = rng.normal(scale=40.0, size=(n, 3))
    r1 = np.linalg.norm(p, axis=1)
    r2 = np.linalg.norm(np.einsum("nij,nj->ni", R12, p) + t12, axis=1)
    r3 = np.linalg.norm(np.einsum("nij,nj->ni", R13, p) + t13, axis=1)
    r3[: n // 2] *= rng.uniform(0.5, 1.5, n // 2)  # half inconsistent: some lines miss sphere 1
    return R12, t12, R13, t13, r1, r2, r3


def test_derived_line_and_points_match_the_kernel(g):
    f = S.numeric_functions()  # the two-view plane, lambdified from derive_plane
    rng = np.random.default_rng(71)
    R12, t12, R13, t13, r1, r2, r3 = _configs(rng, 600)
    ap = Aperture(360.0, 180.0, 1e9)
    res = three_view_points(R12, t12, R13, t13, r1, r2, r3, ap, ap, ap)
    u2, u3 = f["u"](R12, t12), f["u"](R13, t13)
    c2, c3 = 0.5 * f["C"](t12, r1, r2), 0.5 * f["C"](t13, r1, r3)
    p0 = g["p0"](u2, u3, c2, c3)
    np.testing.assert_allclose(res.line_point, p0, rtol=1e-9, atol=1e-9 * np.abs(p0).max())
    h_sq = g["h_sq"](u2, u3, c2, c3, r1)
    two = h_sq > 1e-6 * r1**2
    none = h_sq < -1e-6 * r1**2
    assert 50 < none.sum() and 300 < two.sum()  # both outcomes exercised
    assert np.all(res.status[two] == ThreeViewStatus.TWO_POINTS)
    assert np.all(res.status[none] == ThreeViewStatus.NO_POINT)
    np.testing.assert_allclose(res.half_separation[two], np.sqrt(h_sq[two]), rtol=1e-8)
    with np.errstate(invalid="ignore"):
        pts = g["points"](u2, u3, c2, c3, r1)  # (n, 2, 3), sympy's root order (minus first)
    # as sets of two points
    k = res.candidates[two]
    s = pts[two]
    d_same = np.maximum(np.linalg.norm(k - s, axis=-1).max(1), 0)
    d_swap = np.linalg.norm(k - s[:, ::-1], axis=-1).max(1)
    assert np.max(np.minimum(d_same, d_swap)) < 1e-8 * r1.max()
    assert np.all(np.isnan(pts[none]))
