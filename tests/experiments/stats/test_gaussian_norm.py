"""gaussian_norm_quantile (the quantile of |x| for x ~ N(0, C)) against independent references:
closed forms, brute-force Monte Carlo, the exact quadrature it interpolates, and invariants."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation
from scipy.stats import chi, norm

from sss_locus.experiments.stats.gaussian_norm import exact_quantile_squared, gaussian_norm_quantile


@pytest.mark.parametrize("q", [0.5, 0.95, 0.999])
def test_closed_forms(q):
    # one non-zero eigenvalue: |N(0, s^2)| (half-normal); two equal: Rayleigh = chi with 2 dof;
    # three equal: chi with 3 dof; the zero covariance: 0
    assert gaussian_norm_quantile(np.array([[4.0]]), q) == pytest.approx(2 * norm.ppf((1 + q) / 2), rel=1e-9)
    assert gaussian_norm_quantile(np.diag([0.0, 9.0, 0.0]), q) == pytest.approx(3 * norm.ppf((1 + q) / 2), rel=1e-9)
    assert gaussian_norm_quantile(np.eye(2) * 4.0, q) == pytest.approx(2 * chi.ppf(q, 2), rel=1e-9)
    assert gaussian_norm_quantile(np.diag([0.0, 4.0, 4.0]), q) == pytest.approx(2 * chi.ppf(q, 2), rel=1e-9)
    assert gaussian_norm_quantile(np.eye(3) * 9.0, q) == pytest.approx(3 * chi.ppf(q, 3), rel=1e-9)
    assert gaussian_norm_quantile(np.zeros((3, 3)), q) == 0.0
    assert gaussian_norm_quantile(np.diag([-1e-12, 1.0, 1.0]), q) == pytest.approx(chi.ppf(q, 2), rel=1e-9)


def test_small_quantiles_are_less_accurate_as_documented():
    for lam, ref in [((4.0,), 2 * norm.ppf(0.525)), ((4.0, 4.0), 2 * chi.ppf(0.05, 2)),
                     ((4.0, 4.0, 4.0), 2 * chi.ppf(0.05, 3))]:
        assert gaussian_norm_quantile(np.diag(lam), 0.05) == pytest.approx(ref, rel=1e-4)


@pytest.mark.parametrize("lam", [(1.0, 0.3, 0.1), (1.0, 0.8, 0.05), (2.0, 1.0, 1.0), (1.0, 1e-3, 0.0)])
def test_brute_force_monte_carlo(lam):
    z = np.random.default_rng(11).standard_normal((2_000_000, 3))
    for q in (0.5, 0.95):
        mc = np.quantile(np.sqrt(z ** 2 @ np.asarray(lam)), q)
        assert gaussian_norm_quantile(np.diag(lam), q) == pytest.approx(mc, rel=1.5e-3)  # MC: ~3e-4


def test_the_table_matches_the_exact_quadrature_at_random_ratios():
    rng = np.random.default_rng(3)
    a = rng.random(400)
    b = a * rng.random(400)
    a[:20], b[:20] = rng.random(20) * 1e-3, 0.0  # near the a = b = 0 corner
    for q, rtol in ((0.95, 3e-7), (0.5, 3e-6)):
        exact = np.sqrt(exact_quantile_squared(a, b, q))
        got = gaussian_norm_quantile(np.stack([np.diag([1.0, ai, bi]) for ai, bi in zip(a, b)]), q)
        np.testing.assert_allclose(got, exact, rtol=rtol)


def test_quadrature_converged_and_symmetric():
    import sss_locus.experiments.stats.gaussian_norm as gn

    a, b = np.array([0.7, 0.2, 0.01]), np.array([0.3, 0.2, 0.0])
    base = exact_quantile_squared(a, b, 0.95)
    np.testing.assert_allclose(exact_quantile_squared(b, a, 0.95), base, rtol=1e-12)  # g(a, b) = g(b, a)
    saved = gn._S_LEVELS, gn._S_PER_PANEL, gn._P_NODES
    try:
        gn._S_LEVELS, gn._S_PER_PANEL, gn._P_NODES = saved[0] + 2, 2 * saved[1], 2 * saved[2]
        gn._sphere_nodes.cache_clear()
        for q in (0.5, 0.95):
            finer = exact_quantile_squared(a, b, q)
            gn._S_LEVELS, gn._S_PER_PANEL, gn._P_NODES = saved
            gn._sphere_nodes.cache_clear()
            np.testing.assert_allclose(finer, exact_quantile_squared(a, b, q), rtol=1e-9)
            gn._S_LEVELS, gn._S_PER_PANEL, gn._P_NODES = saved[0] + 2, 2 * saved[1], 2 * saved[2]
            gn._sphere_nodes.cache_clear()
    finally:
        gn._S_LEVELS, gn._S_PER_PANEL, gn._P_NODES = saved
        gn._sphere_nodes.cache_clear()


def test_rotation_and_scaling_invariance():
    rng = np.random.default_rng(8)
    A = rng.standard_normal((50, 3, 3))
    cov = A @ A.transpose(0, 2, 1)
    R = Rotation.random(50, rng=rng).as_matrix()
    turned = R @ cov @ R.transpose(0, 2, 1)
    base = gaussian_norm_quantile(cov, 0.9)
    np.testing.assert_allclose(gaussian_norm_quantile(turned, 0.9), base, rtol=1e-9)
    np.testing.assert_allclose(gaussian_norm_quantile(cov * 1e-6, 0.9), base * 1e-3, rtol=1e-9)
    assert gaussian_norm_quantile(cov.reshape(5, 10, 3, 3), 0.9).shape == (5, 10)


@pytest.mark.parametrize("cov, q, match", [
    (np.eye(4), 0.95, "d in 1..3"), (np.ones(3), 0.95, "shape"), (np.eye(3) * np.nan, 0.95, "finite"),
    (np.eye(3), 1.0, "open interval"), (np.eye(3), 0.0, "open interval"), (np.eye(3), True, "open interval"),
    (np.eye(3), "0.9", "open interval"), (np.array([["1"]]), 0.95, "cov"),
    (np.array([[1.0, 2.0], [2.0, 1.0]]), 0.95, "positive semi-definite")])
def test_bad_input_is_refused(cov, q, match):
    with pytest.raises((ValueError, TypeError), match=match):
        gaussian_norm_quantile(cov, q)
