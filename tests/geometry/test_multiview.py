"""The N-view range least squares, the flat-seafloor baseline and the two-view prior point,
against independent references (closed forms, scipy.optimize.least_squares, finite differences,
SymPy, rigid-motion invariance, brute-force sampling of the locus)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from sss_locus.geometry import Aperture, relative_pose, two_view_locus
from sss_locus.geometry.multiview import range_residuals, solve_ranges
from sss_locus.geometry.multiview_points import MultiViewStatus, inside_apertures, multiview_points
from sss_locus.geometry.slant_range import TwoViewStatus, flat_seafloor_points, nearest_locus_points

OPEN = Aperture(360.0, 180.0, 1e4)


def scene(n, k, seed, spread=60.0):
    """Features near the origin, k sensor origins at random heights above them (not coplanar)."""
    rng = np.random.default_rng(seed)
    f = rng.normal(size=(n, 3)) * 20.0
    f[:, 2] -= 30.0
    o = f[:, None, :] + rng.normal(size=(n, k, 3)) * spread
    o[..., 2] = f[:, None, 2] + 15.0 + 20.0 * rng.random((n, k))
    W = Rotation.random(n * k, random_state=seed).as_matrix().reshape(n, k, 3, 3)
    return f, o, W, np.linalg.norm(f[:, None, :] - o, axis=-1)


def sidescan_frame(heading_deg, pitch_deg, tilt_deg, port=True):
    """Sensor axes (columns x boresight, y fan, z along-track) of a sidescan transducer on a
    vehicle at the given heading and pitch (nose-up positive), built independently of the
    package: boresight to port (or starboard), tilted down by tilt_deg."""
    s = 1.0 if port else -1.0
    t = math.radians(tilt_deg)
    x = np.array([0.0, s * math.cos(t), -math.sin(t)])
    z = np.array([-s, 0.0, 0.0])
    y = np.cross(z, x)
    M = np.stack([x, y, z], axis=1)
    V = Rotation.from_euler("ZY", [heading_deg, -pitch_deg], degrees=True).as_matrix()
    return V @ M


def test_noise_free_well_conditioned_is_exact():
    f, o, W, r = scene(500, 5, seed=1)
    res = multiview_points(W, o, r, np.full(r.shape, 0.01), np.ones(r.shape, bool), OPEN, cost_limit=1e-6)
    assert np.all(res.status == MultiViewStatus.RESOLVED)
    err = np.linalg.norm(res.point - f, axis=-1) / r.max(axis=1)
    assert err.max() <= 1e-9


def test_matches_scipy_least_squares_feature_by_feature():
    f, o, W, r = scene(40, 4, seed=2)
    rng = np.random.default_rng(3)
    sig = 0.05 + 0.1 * rng.random(r.shape)
    meas = r + sig * rng.normal(size=r.shape)
    start = f + rng.normal(size=f.shape)
    mask = np.ones(r.shape, bool)
    sol = solve_ranges(o, meas, sig, mask, start)
    assert sol.converged.all()
    for i in range(len(f)):
        ref = least_squares(lambda p: (np.linalg.norm(p - o[i], axis=-1) - meas[i]) / sig[i], start[i],
                            method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15)
        assert np.linalg.norm(sol.point[i] - ref.x) <= 1e-7 * r[i].max()
        assert sol.cost[i] == pytest.approx(2 * ref.cost, rel=1e-9, abs=1e-12)
        # covariance: (J^T J)^-1 of scipy's Jacobian at its optimum
        cov = np.linalg.inv(ref.jac.T @ ref.jac)
        assert np.allclose(sol.covariance[i], cov, rtol=1e-5, atol=1e-12)


def test_jacobian_against_finite_differences_and_sympy():
    from sss_locus.geometry.symbolic import range_residuals as S

    f, o, W, r = scene(30, 3, seed=4)
    rng = np.random.default_rng(5)
    p = f + rng.normal(size=f.shape)
    sig = 0.1 + rng.random(r.shape)
    mask = np.ones(r.shape, bool)
    e, J = range_residuals(p, o, r, sig, mask)
    h = 1e-6
    for i in range(3):
        dp = np.zeros(3)
        dp[i] = h
        fd = (range_residuals(p + dp, o, r, sig, mask)[0] - range_residuals(p - dp, o, r, sig, mask)[0]) / (2 * h)
        assert np.allclose(J[..., i], fd, rtol=1e-6, atol=1e-9)
    _, steps = S.derive_range_jacobian()
    assert steps["line_of_sight_residual"] == S.sp.zeros(1, 3)
    fn = S.numeric_range_jacobian()
    P = np.broadcast_to(p[:, None, :], o.shape)
    e_s, g_s = fn(*np.moveaxis(P, -1, 0), *np.moveaxis(o, -1, 0), r, sig)
    assert np.allclose(e, e_s, rtol=1e-12, atol=1e-12)
    assert np.allclose(J, np.stack(g_s, axis=-1), rtol=1e-12, atol=1e-15)
    # the derivation chapter's check (unequal sigmas, noisy ranges): rounding-level agreement
    d = S.kernel_jacobian_discrepancy(seed=1, n=200, n_views=5)
    assert d["n_rows"] == 1000
    assert d["residual"] < 1e-10 and d["jacobian_rel"] < 1e-13 and d["finite_difference_rel"] < 1e-6


def test_invariant_under_a_rigid_motion():
    f, o, W, r = scene(200, 4, seed=6)
    rng = np.random.default_rng(7)
    meas = r + 0.02 * rng.normal(size=r.shape)
    sig, mask = np.full(r.shape, 0.02), np.ones(r.shape, bool)
    a = multiview_points(W, o, meas, sig, mask, OPEN, cost_limit=30.0)
    Q = Rotation.from_euler("zyx", [40.0, -25.0, 70.0], degrees=True).as_matrix()
    t = np.array([1234.5, -987.0, 321.0])
    b = multiview_points(Q @ W, o @ Q.T + t, meas, sig, mask, OPEN, cost_limit=30.0)
    assert np.array_equal(a.status, b.status)
    assert np.allclose(a.point @ Q.T + t, b.point, rtol=0, atol=1e-7)
    assert np.allclose(Q @ a.covariance @ Q.T, b.covariance, rtol=1e-5, atol=1e-12)


def test_degenerate_cases_get_their_status():
    f = np.array([[0.0, 40.0, -20.0]] * 4)
    # collinear sensor origins: three or four on one line (passes on one straight track)
    o_line = np.array([[[x, 0.0, 0.0] for x in (-30.0, -5.0, 20.0, 45.0)]] * 4)
    W = np.broadcast_to(np.eye(3), (4, 4, 3, 3))
    r = np.linalg.norm(f[:, None] - o_line, axis=-1)
    mask = np.array([[1, 1, 1, 1], [1, 1, 1, 0], [1, 1, 0, 0], [0, 0, 0, 0]], bool)
    res = multiview_points(W, o_line, r, np.full(r.shape, 0.01), mask, OPEN, prior=f + 1.0)
    assert list(res.status) == [MultiViewStatus.DEGENERATE, MultiViewStatus.DEGENERATE,
                                MultiViewStatus.TOO_FEW_VIEWS, MultiViewStatus.TOO_FEW_VIEWS]
    assert np.all(np.isfinite(res.point)) and np.all(np.isinf(res.covariance[:2]))
    assert np.array_equal(res.point[2:], f[2:] + 1.0)  # fewer than three views: the prior
    # a mirror pair inside both apertures with three views is ambiguous; with the apertures
    # closed around the true point it is resolved
    fs, o, Ws, rs = scene(50, 3, seed=8)
    amb = multiview_points(Ws, o, rs, np.full(rs.shape, 0.01), np.ones(rs.shape, bool), OPEN)
    assert np.all(amb.status == MultiViewStatus.AMBIGUOUS)
    # a start that cannot reach an admissible point (aperture too narrow for anything): diverged
    narrow = Aperture(5.0, 0.1, 1e4)
    none = multiview_points(Ws, o, rs, np.full(rs.shape, 0.01), np.ones(rs.shape, bool), narrow)
    assert np.all(none.status == MultiViewStatus.DIVERGED)


def test_apertures_decide_the_mirror():
    """Sidescan frames on three headings: the true point is inside all apertures, its mirror
    is not; without noise the estimator resolves it exactly."""
    ap = Aperture(130.0, 0.27, 150.0)
    feat = np.array([0.0, 0.0, 0.0])
    W, o = [], []
    for head, g, alt in ((0.0, 40.0, 20.0), (180.0, 70.0, 22.0), (90.0, 55.0, 18.0), (270.0, 30.0, 25.0)):
        Wk = sidescan_frame(head, 0.0, 25.5)
        port = Wk[:, 0]
        horiz = np.array([port[0], port[1], 0.0]) / np.hypot(port[0], port[1])
        o.append(feat - g * horiz + np.array([0.0, 0.0, alt]))
        W.append(Wk)
    W, o = np.array(W)[None], np.array(o)[None]
    r = np.linalg.norm(feat - o, axis=-1)
    assert inside_apertures(W, o, np.ones((1, 4), bool), feat[None], ap)[0]
    for k in (3, 4):
        res = multiview_points(W[:, :k], o[:, :k], r[:, :k], np.full((1, k), 0.01), np.ones((1, k), bool), ap)
        assert res.status[0] == MultiViewStatus.RESOLVED
        assert np.linalg.norm(res.point[0] - feat) <= 1e-9 * r.max()


@pytest.mark.parametrize("pitch", [0.0, 10.0, -12.0])
def test_flat_seafloor_slant_range_correction_is_exact(pitch):
    rng = np.random.default_rng(9)
    n = 100
    heading = rng.uniform(-180, 180, n)
    W = np.stack([sidescan_frame(h, pitch, 25.0, port=bool(i % 2)) for i, h in enumerate(heading)])
    o = np.column_stack([rng.normal(size=(n, 2)) * 50, np.full(n, 0.0)])
    H = 5.0 + 25.0 * rng.random(n)
    # a seafloor point in the zero-elevation plane on the transducer's side
    nz = W[:, :, 2]
    d = np.cross(nz, [0.0, 0.0, 1.0])
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    d *= np.sign(np.sum(d * W[:, :, 0], axis=1))[:, None]
    m = np.cross(nz, d)
    lam = -H / m[:, 2]
    g = 3.0 + 100.0 * rng.random(n)
    feat = o + lam[:, None] * m + g[:, None] * d
    assert np.allclose(feat[:, 2], -H) and np.allclose(np.sum((feat - o) * nz, axis=1), 0, atol=1e-9)
    r = np.linalg.norm(feat - o, axis=1)
    out = flat_seafloor_points(W, o, r, H)
    assert np.allclose(out["point"], feat, rtol=0, atol=1e-9 * r.max())
    if pitch == 0.0:  # level: ground range is sqrt(r^2 - H^2) (the textbook correction)
        assert np.allclose(out["ground_range_m"], np.sqrt(r * r - H * H), rtol=1e-12)
    short = flat_seafloor_points(W, o, 0.5 * H, H)
    assert short["below_altitude"].all() and np.all(np.isfinite(short["point"]))


def test_two_view_prior_point_is_the_nearest_locus_point():
    ap = Aperture(130.0, 0.27, 150.0)
    f, o, W, r = scene(100, 2, seed=10, spread=40.0)
    # orient view 1 so the feature is in its beam: boresight toward the feature
    rng = np.random.default_rng(11)
    R, t = relative_pose(W[:, 0], o[:, 0], W[:, 1], o[:, 1])
    loc = two_view_locus(R, t, r[:, 0], r[:, 1], OPEN, OPEN)
    prior = np.einsum("nji,nj->ni", W[:, 0], f - o[:, 0]) + rng.normal(size=f.shape) * 5
    out = nearest_locus_points(loc, prior, r[:, 0])
    assert np.all(out["status"] == TwoViewStatus.LOCUS)
    pts = loc.points(2000)  # brute force: the nearest of many locus points
    brute = np.nanmin(np.linalg.norm(pts - prior[:, None, None, :], axis=-1), axis=(1, 2))
    got = np.linalg.norm(out["point"] - prior, axis=-1)
    assert np.all(got <= brute + 1e-9) and np.all(got >= brute - 1e-3 * r.max())
    assert np.allclose(np.linalg.norm(out["point"], axis=-1), r[:, 0])
    # spheres that do not meet: the point of sphere 1 nearest the prior, never NaN
    far = two_view_locus(np.eye(3), [500.0, 0.0, 0.0], 10.0, 10.0, ap, ap)
    miss = nearest_locus_points(far, np.array([3.0, 4.0, 0.0]), 10.0)
    assert miss["status"] == TwoViewStatus.SPHERE and np.allclose(miss["point"], [6.0, 8.0, 0.0])


@pytest.mark.parametrize("kwargs, match", [
    (dict(mask=np.ones((2, 3), int)), "mask"),
    (dict(ranges=-np.ones((2, 3))), "ranges"),
    (dict(sigmas=np.zeros((2, 3))), "sigmas"),
    (dict(start=np.full((2, 3), np.nan)), "start"),
    (dict(max_iter=0), "max_iter"),
])
def test_bad_input_is_named(kwargs, match):
    args = dict(origins=np.zeros((2, 3, 3)) + np.arange(3)[:, None], ranges=np.ones((2, 3)),
                sigmas=np.ones((2, 3)), mask=np.ones((2, 3), bool), start=np.ones((2, 3)))
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        solve_ranges(**args)


@pytest.mark.parametrize("k", [0, 1, 2, 4])
def test_fewer_than_three_views_everywhere_is_too_few_views_not_an_index_error(k):
    """Issue 38: a survey too small or narrow for three views of any feature (``k < 3`` view
    slots, or no feature with three) gets the documented result: every feature at its prior,
    status TOO_FEW_VIEWS, infinite covariance."""
    n = 5
    rng = np.random.default_rng(0)
    W = np.broadcast_to(np.eye(3), (n, k, 3, 3)).copy()
    o = rng.normal(0, 50, (n, k, 3))
    mask = np.zeros((n, k), bool)
    mask[:, :min(k, 2)] = True
    prior = rng.normal(0, 10, (n, 3))
    res = multiview_points(W, o, np.full((n, k), 30.0), np.full((n, k), 0.1), mask, OPEN, prior=prior)
    assert np.all(res.status == MultiViewStatus.TOO_FEW_VIEWS)
    np.testing.assert_array_equal(res.point, prior)
    np.testing.assert_array_equal(res.n_views, mask.sum(axis=1))
    assert np.all(np.isinf(res.covariance))
