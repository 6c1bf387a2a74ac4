"""The joint adjustment against an independent survey simulation (tests/adjustment_sim.py), finite
differences, a dense least_squares written here on residuals written here, and a dense inverse.

Thresholds are the issue's (#39, "Done when"): on a survey with per-pass biases of metres and a
heading bias over non-flat terrain, the joint estimate covers >= 90 % of the features seen on two
passes, its map-shape error is at most a quarter of the flat mosaic's, its vertical error at most
0.15 times the mosaic's, its absolute horizontal error no worse; the pass corrections are
recovered within their stated sigmas.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import least_squares

from adjustment_sim import flat_mosaic, rotz, simulate
from sss_locus.experiments.adjustment import NavigationPriors, Sightings, adjust, beam_plane_points, map_errors
from sss_locus.experiments.adjustment.covariance import marginal_covariances
from sss_locus.experiments.adjustment.residuals import JointProblem
from sss_locus.geometry.beam_plane import beam_plane_angle, beam_plane_sigma_rad

RANGE_SIGMA = np.hypot(0.05, 0.05)  # range error and per-ping position jitter of the simulation


def problem(sv, *, drift_sigma=0.0, heading_moves_track=False):
    sig_phi = beam_plane_sigma_rad(0.5, 0.05, 0.0, 20.0)
    s = Sightings(feature=sv.feature, pass_index=sv.pass_index, origin_m=sv.origin_nav, W=sv.W_nav,
                  range_m=sv.range_m, range_sigma_m=np.full(sv.range_m.size, RANGE_SIGMA),
                  beam_plane_sigma_rad=np.full(sv.range_m.size, sig_phi), along_track_m=sv.along_m)
    p = NavigationPriors(offset_sigma_m=2.0, heading_sigma_deg=1.0, drift_sigma=drift_sigma, reference_m=sv.reference,
                         heading_moves_track=heading_moves_track)
    return s, p


def seen_twice(sv):
    n = sv.truth.shape[0]
    pairs = np.unique(sv.feature * 1000 + sv.pass_index)
    return np.bincount(pairs // 1000, minlength=n) >= 2


def test_beam_plane_angle_is_the_elevation_in_the_sensor_frame_and_its_gradient_matches_differences():
    rng = np.random.default_rng(3)
    W = rotz(rng.uniform(-3, 3, 50)) @ np.linalg.qr(rng.normal(size=(50, 3, 3)))[0]
    W[:, :, 2] *= np.sign(np.linalg.det(W))[:, None]
    o, p = rng.normal(size=(50, 3)) * 10, rng.normal(size=(50, 3)) * 30
    q = np.einsum("nji,nj->ni", W, p - o)  # the point in the sensor frame
    phi, grad = beam_plane_angle(p, o, W)
    assert np.allclose(phi, np.arctan2(q[:, 2], np.hypot(q[:, 0], q[:, 1])), atol=1e-12)
    h = 1e-6
    num = np.stack([(beam_plane_angle(p + h * np.eye(3)[a], o, W)[0] - beam_plane_angle(p - h * np.eye(3)[a], o, W)[0])
                    / (2 * h) for a in range(3)], -1)
    assert np.allclose(grad, num, atol=1e-7)


def test_beam_plane_sigma_is_the_uniform_beam_and_the_tilting_attitude_errors():
    assert beam_plane_sigma_rad(0.5) == pytest.approx(np.radians(0.5) / np.sqrt(12))
    # looking straight across (no depression) only heading tilts the plane's trace; straight down only pitch
    assert beam_plane_sigma_rad(0.5, 1.0, 7.0, 0.0) == pytest.approx(np.radians(np.hypot(0.5 / np.sqrt(12), 1.0)))
    assert beam_plane_sigma_rad(0.5, 7.0, 1.0, 90.0) == pytest.approx(np.radians(np.hypot(0.5 / np.sqrt(12), 1.0)))
    with pytest.raises(ValueError, match="elevation_deg"):
        beam_plane_sigma_rad(0.0)


@pytest.mark.parametrize("moves", [False, True])
def test_jacobian_matches_central_differences(moves):
    sv = simulate(5, n_features=60, area=200.0, spacing=70.0, n_cross=2, drift_sigma=1e-3)
    s, pr = problem(sv, drift_sigma=1e-3, heading_moves_track=moves)
    prob = JointProblem(s, pr, np.flatnonzero(seen_twice(sv)), height_prior_m=np.full(seen_twice(sv).sum(), -30.0),
                        height_sigma_m=np.full(seen_twice(sv).sum(), 2.0))
    rng = np.random.default_rng(0)
    x = prob.pack(sv.truth[prob.features] + rng.normal(0, 0.5, (prob.features.size, 3)),
                  rng.normal(0, 1, (pr.n_passes, 5)) * pr.sigmas())
    J = prob.jacobian(x).toarray()
    h = 1e-6 * np.maximum(1.0, np.abs(x))
    num = np.empty_like(J)
    for i in range(x.size):
        d = np.zeros_like(x)
        d[i] = h[i]
        num[:, i] = (prob.residuals(x + d) - prob.residuals(x - d)) / (2 * h[i])
    assert np.max(np.abs(J - num)) <= 1e-5 * max(1.0, np.max(np.abs(num)))


@pytest.mark.parametrize("seed", [11, 12, 13])
def test_joint_estimate_meets_the_issue_thresholds_against_the_flat_mosaic(seed):
    sv = simulate(seed)
    s, pr = problem(sv)
    mosaic = flat_mosaic(sv)
    res = adjust(s, pr, mosaic)
    twice = seen_twice(sv)
    covered = res.adjusted & twice & np.all(np.isfinite(res.covariance_m2), axis=(1, 2))
    assert res.success
    assert covered.sum() >= 0.9 * twice.sum()
    j, m = map_errors(res.point_m, sv.truth, covered), map_errors(mosaic, sv.truth, covered)
    med = lambda a: float(np.median(np.abs(a[covered])))  # noqa: E731
    assert med(j["shape_m"]) <= 0.25 * med(m["shape_m"])
    assert med(j["vertical_m"]) <= 0.15 * med(m["vertical_m"])
    assert med(j["horizontal_m"]) <= med(m["horizontal_m"])


@pytest.mark.parametrize("seed", [21, 22])
def test_pass_corrections_are_recovered_within_their_stated_sigma(seed):
    sv = simulate(seed, drift_sigma=2e-3)
    s, pr = problem(sv, drift_sigma=2e-3)
    res = adjust(s, pr, flat_mosaic(sv))
    true = np.column_stack([sv.offsets, sv.heading_bias, sv.drift])
    z = (res.corrections - true) / res.correction_sigma
    assert np.all(res.correction_sigma > 0)
    assert np.all(np.abs(z) <= 3.5), np.abs(z).max()
    assert np.sqrt(np.mean(z ** 2)) <= 1.5
    # and far better than the prior: the stated sigma of the heading is a fraction of the prior's
    assert np.all(res.correction_sigma[:, 2] < 0.5 * np.radians(1.0))


def independent_residuals(sv, feats, pr_sigmas):
    """The same measurement model written again, densely, from the simulation's conventions."""
    fidx = {f: i for i, f in enumerate(feats)}
    use = np.array([f in fidx for f in sv.feature])
    f_of = np.array([fidx.get(f, -1) for f in sv.feature])[use]
    p_of, o, W, r, s = sv.pass_index[use], sv.origin_nav[use], sv.W_nav[use], sv.range_m[use], sv.along_m[use]
    P = sv.reference.shape[0]
    sig_phi = beam_plane_sigma_rad(0.5, 0.05, 0.0, 20.0)

    def fun(x):
        pts, c = x[:3 * len(feats)].reshape(-1, 3), x[3 * len(feats):].reshape(P, 3)
        ot = o + np.column_stack([c[p_of, :2], np.zeros(p_of.size)])
        Wt = rotz(c[p_of, 2]) @ W
        q = np.einsum("nji,nj->ni", Wt, pts[f_of] - ot)
        rng = np.linalg.norm(q, axis=1)
        phi = np.arctan2(q[:, 2], np.hypot(q[:, 0], q[:, 1]))
        return np.concatenate([(rng - r) / RANGE_SIGMA, phi / sig_phi, (c / pr_sigmas[:, :3]).ravel()])

    return fun


def test_sparse_solver_agrees_with_a_dense_least_squares_on_independently_written_residuals():
    sv = simulate(31, n_features=40, area=160.0, spacing=60.0, n_cross=1)
    s, pr = problem(sv)
    start = flat_mosaic(sv)
    res = adjust(s, pr, start, loss="linear")
    feats = np.flatnonzero(res.adjusted)
    fun = independent_residuals(sv, feats, pr.sigmas())
    x0 = np.concatenate([start[feats].ravel(), np.zeros(3 * pr.n_passes)])
    dense = least_squares(fun, x0, method="lm", xtol=1e-14, ftol=1e-14, gtol=1e-14)
    pts = dense.x[:3 * feats.size].reshape(-1, 3)
    assert np.max(np.abs(res.point_m[feats] - pts)) < 1e-4
    assert np.max(np.abs(res.corrections[:, :3] - dense.x[3 * feats.size:].reshape(-1, 3))) < 1e-5
    assert 2 * res.cost == pytest.approx(np.sum(dense.fun ** 2), rel=1e-6)


def test_schur_covariances_equal_the_dense_inverse():
    sv = simulate(41, n_features=50, area=160.0, spacing=60.0, n_cross=1)
    s, pr = problem(sv, drift_sigma=1e-3)
    feats = np.flatnonzero(seen_twice(sv))
    prob = JointProblem(s, pr, feats)
    J = prob.jacobian(prob.pack(sv.truth[feats], np.zeros((pr.n_passes, 5))))
    fcov, pcov = marginal_covariances(J, feats.size)
    full = np.linalg.inv((J.T @ J).toarray())
    for i in range(feats.size):
        block = full[3 * i:3 * i + 3, 3 * i:3 * i + 3]
        assert np.allclose(fcov[i], block, rtol=1e-6, atol=1e-6 * np.max(np.diag(block)))
    tail = full[3 * feats.size:, 3 * feats.size:]
    scale = np.sqrt(np.outer(np.diag(tail), np.diag(tail)))
    assert np.all(np.abs(pcov - tail) <= 1e-6 * scale)


def test_robust_loss_keeps_wrong_matches_from_bending_the_map_and_reports_them():
    share = 0.05
    sv = simulate(51, wrong_share=share)
    clean = simulate(51)
    wrong = sv.feature != clean.feature
    s, pr = problem(sv)
    mosaic = flat_mosaic(sv)
    full = adjust(s, pr, mosaic)  # the gate, then the robust loss
    robust = adjust(s, pr, mosaic, loss="soft_l1", gate_m=np.inf)  # the robust loss alone
    plain = adjust(s, pr, mosaic, loss="linear", gate_m=np.inf)
    ok = full.adjusted & robust.adjusted & plain.adjusted & seen_twice(clean)
    shape = lambda est: float(np.median(map_errors(est, clean.truth, ok)["shape_m"][ok]))  # noqa: E731
    assert shape(full.point_m) <= 0.25 * shape(mosaic)
    assert shape(robust.point_m) <= 0.25 * shape(mosaic)
    assert shape(robust.point_m) < 0.5 * shape(plain.point_m)
    for res in (full, robust):
        used = np.isfinite(res.weight)
        # the wrong sightings of adjusted features are flagged (down-weighted or gated); few right ones are
        assert res.downweighted[wrong & used].mean() >= 0.8
        assert res.downweighted[~wrong & used].mean() <= 0.03
    assert full.gated.any() and not full.gated[~wrong].any()


def test_bad_input_is_refused_naming_the_argument():
    sv = simulate(61, n_features=30, area=150.0, spacing=60.0, n_cross=1)
    s, pr = problem(sv)
    start = flat_mosaic(sv)
    with pytest.raises(ValueError, match="loss"):
        adjust(s, pr, start, loss="l2")
    with pytest.raises(ValueError, match="start_m"):
        adjust(s, pr, start[:5])
    with pytest.raises(ValueError, match="pass_index"):
        adjust(s, NavigationPriors(2.0, 1.0, 0.0, sv.reference[:2]), start)
    with pytest.raises(ValueError, match="range_sigma_m"):
        Sightings(feature=sv.feature, pass_index=sv.pass_index, origin_m=sv.origin_nav, W=sv.W_nav,
                  range_m=sv.range_m, range_sigma_m=0.0, beam_plane_sigma_rad=1e-3, along_track_m=sv.along_m)
    with pytest.raises(ValueError, match="gate_m"):
        adjust(s, pr, start, gate_m=-1.0)
    with pytest.raises(ValueError, match="offset_sigma_m"):
        NavigationPriors(0.0, 1.0, 0.0, sv.reference)
    # a feature seen on one pass is not adjusted, and says so (no NaN position)
    one = adjust(s, pr, start, min_passes=50)
    assert not one.adjusted.any() and np.all(np.isfinite(one.point_m))


def views_layout(sv):
    """The simulation's sightings in the (n, k) layout of the N-view estimators."""
    n, L = sv.truth.shape[0], sv.reference.shape[0]
    mask = np.zeros((n, L), bool)
    mask[sv.feature, sv.pass_index] = True
    W = np.broadcast_to(np.eye(3), (n, L, 3, 3)).copy()
    o, r = np.zeros((n, L, 3)), np.ones((n, L))
    W[sv.feature, sv.pass_index], o[sv.feature, sv.pass_index], r[sv.feature, sv.pass_index] = sv.W_nav, sv.origin_nav, sv.range_m
    return W, o, r, mask


def test_beam_plane_points_recover_features_seen_twice_exactly_without_noise():
    # a sparse survey (many features seen twice), no noise, the feature in the plane of its ping
    sv = simulate(81, spacing=110.0, n_cross=1, offset_sigma=0.0, heading_sigma_deg=0.0, range_sigma=0.0, jitter_m=0.0,
                  jitter_deg=0.0, beam_deg=1e-7)
    W, o, r, mask = views_layout(sv)
    two = mask.sum(axis=1) == 2
    assert two.sum() >= 20  # features a range-only estimate cannot place (two spheres: a circle)
    res = beam_plane_points(W, o, r, 0.05, 1e-3, mask, flat_mosaic(sv))
    assert res.estimated[mask.sum(axis=1) >= 2].all()
    assert np.max(np.linalg.norm(res.point[two] - sv.truth[two], axis=1)) < 1e-5
    assert np.max(np.linalg.norm(res.point[mask.sum(axis=1) >= 2] - sv.truth[mask.sum(axis=1) >= 2], axis=1)) < 1e-5


def test_beam_plane_points_errors_match_their_covariance():
    sv = simulate(82, offset_sigma=0.0, heading_sigma_deg=0.0)
    W, o, r, mask = views_layout(sv)
    sig_phi = beam_plane_sigma_rad(0.5, 0.05, 0.0, 20.0)
    res = beam_plane_points(W, o, r, RANGE_SIGMA, sig_phi, mask, flat_mosaic(sv))
    ok = res.estimated
    d = res.point[ok] - sv.truth[ok]
    m2 = np.einsum("ni,nij,nj->n", d, np.linalg.inv(res.covariance[ok]), d)
    # squared Mahalanobis distances of a calibrated 3-D estimate: chi-square with 3 degrees of freedom
    assert 0.6 * 2.366 <= np.median(m2) <= 1.6 * 2.366
