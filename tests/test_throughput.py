"""The faster paths of the studies give the same numbers, bit for bit, as the plain ones.

References: scipy's ``Rotation.from_euler`` for the vectorised vehicle attitude; one block at a
time (the documented stream definition) for the samplers that draw many blocks together.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from scipy.spatial.transform import Rotation

from sss_locus.experiments.straight_pass import vehicle_attitude


@pytest.mark.parametrize("shape", [(), (1,), (9,), (4, 5), (20_000,)])
def test_vehicle_attitude_is_scipy_from_euler_bit_for_bit(shape):
    rng = np.random.default_rng(len(shape) * 7 + sum(shape))
    yaw, pitch, roll = (rng.uniform(-180, 180, shape), rng.uniform(-90, 90, shape),
                        rng.uniform(-180, 180, shape))
    ours = vehicle_attitude(yaw, pitch, roll)
    ref = Rotation.from_euler("ZYX", np.stack([yaw, -pitch, roll], axis=-1), degrees=True)
    assert ours.single == ref.single
    assert np.array_equal(ours.as_quat(), ref.as_quat())
    assert np.array_equal(ours.as_matrix(), ref.as_matrix())


def test_vehicle_attitude_special_angles_are_scipy_bit_for_bit():
    a = np.array([0.0, -0.0, 90.0, -90.0, 180.0, -180.0, 45.0, 1e-300, 360.0, 720.5])
    for yaw, pitch, roll in ((a, a, a), (a, np.zeros_like(a), -a), (-a, a / 2, np.zeros_like(a))):
        ref = Rotation.from_euler("ZYX", np.stack([yaw, -pitch, roll], axis=-1), degrees=True)
        assert np.array_equal(vehicle_attitude(yaw, pitch, roll).as_matrix(), ref.as_matrix())


@pytest.mark.parametrize("platform_key, model", [("auv", "independent"), ("boat", "independent"),
                                                  ("auv", "matched:2:same")])
def test_survey_blocks_drawn_together_equal_blocks_drawn_alone(platform_key, model):
    from sss_locus.experiments.envelopes import OffsetModel, load_envelope
    from sss_locus.experiments.platforms import load_platform
    from sss_locus.experiments.survey_passes import draw_block, draw_blocks

    pf, env, om = load_platform(platform_key), load_envelope(platform_key), OffsetModel.parse(model)
    together = draw_blocks(pf, env, om, 35.0, 3, [0, 5, 1, 2])
    for k, (rows, rejected, accepted) in zip([0, 5, 1, 2], together):
        alone_rows, alone_rejected, alone_accepted = draw_block(pf, env, om, 35.0, 3, k)
        assert accepted == alone_accepted and np.array_equal(rejected, alone_rejected)
        assert rows.keys() == alone_rows.keys()
        for key in rows:
            assert rows[key].tobytes() == alone_rows[key].tobytes(), key


@pytest.mark.parametrize("n", [1, 2, 3, 10, 11, 1000, 1001])
@pytest.mark.parametrize("ties", [False, True])
def test_bootstrap_median_is_numpy_median_of_the_same_resamples(n, ties):
    from sss_locus.experiments.planning import bootstrap_median

    x = np.random.default_rng(n).normal(size=n)
    if ties:
        x = np.round(x, 1) + 5.0  # many equal values (no zeros: see the signed-zero test)
    ref_rng, ours = np.random.default_rng(4), bootstrap_median(x, 150, np.random.default_rng(4), batch=64)
    ref = np.concatenate([np.median(x[ref_rng.integers(0, n, (k, n))], axis=1) for k in (64, 64, 22)])
    assert ours.tobytes() == ref.tobytes()


@pytest.mark.parametrize("x", [[1.0, np.nan, 3.0, 4.0], [0.0, -0.0, 0.0, -0.0, 1.0, -1.0, -0.0]])
def test_bootstrap_median_nan_and_signed_zeros_like_numpy(x):
    from sss_locus.experiments.planning import bootstrap_median

    x = np.array(x)
    ref_rng, ours = np.random.default_rng(2), bootstrap_median(x, 30, np.random.default_rng(2))
    ref = np.median(x[ref_rng.integers(0, x.size, (30, x.size))], axis=1)
    assert ours.tobytes() == ref.tobytes()


@pytest.mark.parametrize("ties", [False, True])
def test_spearman_interval_is_the_correlation_of_explicitly_resampled_ranks(ties):
    # reference: each resample drawn as rows (rng.integers, the documented draws), the
    # full-sample average ranks of those rows correlated with np.corrcoef
    from scipy import stats

    from sss_locus.experiments.pose_stats import spearman_table

    rng = np.random.default_rng(11)
    n, n_resamples = 700, 150
    x = rng.normal(size=n)
    df = pd.DataFrame({"a": np.round(x, 1) if ties else x, "b": rng.exponential(size=n),
                       "y": x + rng.normal(size=n), "z": rng.normal(size=n)})
    tab = spearman_table(df, ["a", "b"], ["y", "z"], n_resamples=n_resamples, seed=3,
                         confidence_level=0.9)
    ranks = {c: stats.rankdata(df[c]) for c in df}
    draws = np.random.default_rng(3)
    boots = {}
    for _ in range(n_resamples):
        idx = draws.integers(0, n, n)
        for q in ("a", "b"):
            for tg in ("y", "z"):
                boots.setdefault((q, tg), []).append(np.corrcoef(ranks[q][idx], ranks[tg][idx])[0, 1])
    for row in tab.itertuples():
        lo, hi = np.quantile(boots[(row.quantity, row.target)], [0.05, 0.95])
        assert row.rho == pytest.approx(stats.spearmanr(df[row.quantity], df[row.target]).statistic,
                                        abs=1e-13)
        assert (row.ci_low, row.ci_high) == pytest.approx((lo, hi), abs=1e-13)


def test_weighted_correlations_against_repeated_rows():
    from sss_locus.experiments.rowstats import bootstrap_draw_counts, weighted_correlations

    rng = np.random.default_rng(5)
    X, Y = rng.normal(size=(1000, 3)), rng.normal(size=(1000, 2)) + 0.3
    counts = bootstrap_draw_counts(np.random.default_rng(8), 1000, 7)
    ref_rng = np.random.default_rng(8)
    ours = weighted_correlations(X, Y, counts, rows_per_chunk=96)  # chunks not dividing n
    for b in range(7):
        c = np.bincount(ref_rng.integers(0, 1000, 1000), minlength=1000)
        assert np.array_equal(counts[b], c)
        Xr, Yr = np.repeat(X, c, axis=0), np.repeat(Y, c, axis=0)
        ref = np.corrcoef(Xr.T, Yr.T)[:3, 3:]
        np.testing.assert_allclose(ours[b], ref, rtol=0, atol=1e-13)
    with pytest.raises(ValueError, match="share n"):
        weighted_correlations(X, Y, counts[:, :-1])


def test_bootstrap_draw_counts_widen_for_large_counts():
    from sss_locus.experiments.rowstats import bootstrap_draw_counts

    class Skewed:  # draws row 0 every time from the second resample on
        calls = 0

        def integers(self, low, high, size):
            Skewed.calls += 1
            return np.arange(size) % high if Skewed.calls == 1 else np.zeros(size, int)

    counts = bootstrap_draw_counts(Skewed(), 300, 3)
    assert counts.dtype == np.uint16
    assert np.array_equal(counts[0], np.ones(300)) and counts[1, 0] == counts[2, 0] == 300


@pytest.mark.parametrize("values", [
    np.array([3.0, 1.0, 2.0, 1.0, 3.0, 3.0, -0.0, 0.0]),  # ties, signed zeros
    np.random.default_rng(3).integers(0, 50, 2000).astype(float),  # many ties
    np.random.default_rng(4).standard_normal(1001),
    np.array([1.0, np.nan, 2.0]), np.array([5.0]), np.array([], float),
    np.random.default_rng(5).integers(-5, 5, 300),  # integers
])
def test_average_ranks_are_scipy_rankdata_bit_for_bit(values):
    from scipy import stats

    from sss_locus.experiments.rowstats import average_ranks

    ours, ref = average_ranks(values), stats.rankdata(values)
    assert ours.tobytes() == np.asarray(ref, float).tobytes()


def test_weighted_correlation_sets_equal_separate_calls_bit_for_bit():
    from sss_locus.experiments.rowstats import (bootstrap_draw_counts, weighted_correlation_sets,
                                                weighted_correlations)

    rng = np.random.default_rng(9)
    X, Y = rng.standard_normal((5000, 4)), rng.standard_normal((5000, 2))
    sets = [np.ones((1, 5000), np.uint8)] + [bootstrap_draw_counts(rng, 5000, k) for k in (64, 3)]
    together = weighted_correlation_sets(X, Y, sets, rows_per_chunk=700)
    for W, got in zip(sets, together):
        assert got.tobytes() == weighted_correlations(X, Y, W, rows_per_chunk=700).tobytes()


def test_gaussian_norm_quantile_of_a_batch_equals_one_at_a_time():
    from sss_locus.experiments.noise import gaussian_norm_quantile

    A = np.random.default_rng(6).standard_normal((300, 3, 3))
    cov = A @ A.transpose(0, 2, 1)
    batch = gaussian_norm_quantile(cov, 0.95)
    alone = np.array([gaussian_norm_quantile(c, 0.95) for c in cov[::37]])
    assert batch[::37].tobytes() == alone.tobytes()
