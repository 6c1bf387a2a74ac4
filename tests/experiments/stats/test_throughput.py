"""The faster paths of the studies give the same numbers, bit for bit, as the plain ones.

References: rotation matrices written out by hand for the vehicle attitude; average ranks
counted by brute force; one block at a time (the documented stream definition) for the
samplers that draw many blocks together.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from sss_locus.experiments.passes.straight_pass import vehicle_attitude


def _elementary(axis: int, deg: np.ndarray) -> np.ndarray:
    """Right-handed rotation matrices about one axis, written out by hand (the reference)."""
    c, s = np.cos(np.radians(deg)), np.sin(np.radians(deg))
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m = np.zeros(deg.shape + (3, 3))
    m[..., axis, axis] = 1.0
    m[..., i, i], m[..., j, j], m[..., i, j], m[..., j, i] = c, c, -s, s
    return m


@pytest.mark.parametrize("shape", [(), (9,), (4, 5)])
def test_vehicle_attitude_is_yaw_then_pitch_nose_up_then_roll(shape):
    rng = np.random.default_rng(len(shape) * 7 + sum(shape))
    yaw, pitch, roll = (rng.uniform(-180, 180, shape), rng.uniform(-90, 90, shape),
                        rng.uniform(-180, 180, shape))
    ref = _elementary(2, yaw) @ _elementary(1, -pitch) @ _elementary(0, roll)
    ours = vehicle_attitude(yaw, pitch, roll)
    assert ours.single == (shape == ())
    np.testing.assert_allclose(ours.as_matrix(), ref, atol=1e-14)
    nose = vehicle_attitude(0.0, 30.0, 0.0).apply([1.0, 0.0, 0.0])  # pitch nose-up: x rises
    np.testing.assert_allclose(nose, [np.cos(np.radians(30)), 0.0, np.sin(np.radians(30))], atol=1e-15)


@pytest.mark.parametrize("platform_key, model", [("auv", "independent"), ("boat", "independent"),
                                                  ("auv", "matched:2:same")])
def test_survey_blocks_drawn_together_equal_blocks_drawn_alone(platform_key, model):
    from sss_locus.experiments.datamodel.envelopes import OffsetModel, load_envelope
    from sss_locus.experiments.datamodel.platforms import load_platform
    from sss_locus.experiments.survey_passes.study import draw_block, draw_blocks

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
    from sss_locus.experiments.survey_passes.planning import bootstrap_median

    x = np.random.default_rng(n).normal(size=n)
    if ties:
        x = np.round(x, 1) + 5.0  # many equal values (no zeros: see the signed-zero test)
    ref_rng, ours = np.random.default_rng(4), bootstrap_median(x, 150, np.random.default_rng(4), batch=64)
    ref = np.concatenate([np.median(x[ref_rng.integers(0, n, (k, n))], axis=1) for k in (64, 64, 22)])
    assert ours.tobytes() == ref.tobytes()


@pytest.mark.parametrize("x", [[1.0, np.nan, 3.0, 4.0], [0.0, -0.0, 0.0, -0.0, 1.0, -1.0, -0.0]])
def test_bootstrap_median_nan_and_signed_zeros_like_numpy(x):
    from sss_locus.experiments.survey_passes.planning import bootstrap_median

    x = np.array(x)
    ref_rng, ours = np.random.default_rng(2), bootstrap_median(x, 30, np.random.default_rng(2))
    ref = np.median(x[ref_rng.integers(0, x.size, (30, x.size))], axis=1)
    assert ours.tobytes() == ref.tobytes()


@pytest.mark.parametrize("values", [
    np.array([3.0, 1.0, 2.0, 1.0, 3.0, 3.0, -0.0, 0.0]),  # ties, signed zeros
    np.random.default_rng(3).integers(0, 50, 2000).astype(float),  # many ties
    np.random.default_rng(4).standard_normal(1001),
    np.array([1.0, np.nan, 2.0]), np.array([5.0]), np.array([], float),
    np.random.default_rng(5).integers(-5, 5, 300),  # integers
    np.array([np.inf, -np.inf, 0.0, -0.0, 5e-324, -5e-324, 1e308, -1e308, -0.0, np.inf, -2.5]),
    np.random.default_rng(6).standard_normal(300) * 10.0 ** np.random.default_rng(7).integers(-300, 300, 300),
    np.array([-0.0, -0.0, 0.0]), np.array([2.0, 1.0]), np.array([-1.0, -1.0]),
    np.random.default_rng(8).standard_normal(500).astype(np.float32),  # float32: plain argsort
])
def test_average_ranks_are_the_brute_force_average_ranks(values):
    from sss_locus.experiments.stats.rowstats import average_ranks

    v = np.asarray(values, float)
    if np.isnan(v).any():
        ref = np.full(v.size, np.nan)
    else:  # rank of x: values below it, plus the mean position among those equal to it
        below, equal = (v[None, :] < v[:, None]).sum(1), (v[None, :] == v[:, None]).sum(1)
        ref = below + (equal + 1) / 2.0
    np.testing.assert_array_equal(average_ranks(values), ref)


def test_gaussian_norm_quantile_of_a_batch_equals_one_at_a_time():
    from sss_locus.experiments.stats.gaussian_norm import gaussian_norm_quantile

    A = np.random.default_rng(6).standard_normal((300, 3, 3))
    cov = A @ A.transpose(0, 2, 1)
    batch = gaussian_norm_quantile(cov, 0.95)
    alone = np.array([gaussian_norm_quantile(c, 0.95) for c in cov[::37]])
    assert batch[::37].tobytes() == alone.tobytes()


def test_column_ranks_remembered_are_the_ranks(monkeypatch):
    from sss_locus.experiments.pose_space import stats as pose_stats
    from sss_locus.experiments.stats.rowstats import average_ranks

    monkeypatch.setattr(pose_stats, "_rank_memo", type(pose_stats._rank_memo)())
    monkeypatch.setattr(pose_stats, "_memo_bytes", [0])
    monkeypatch.setattr(pose_stats, "_RANK_MEMO_BYTES", 3 * 4 * 1000)  # three columns of 1000
    rng = np.random.default_rng(12)
    cols = [rng.standard_normal(1000), np.round(rng.standard_normal(1000), 1),
            rng.integers(0, 9, 1000), rng.standard_normal(1000), rng.standard_normal(1000) > 0]
    for _ in range(2):  # computed, then remembered (or recomputed after eviction)
        for c in cols:
            assert pose_stats.column_ranks(c).tobytes() == average_ranks(c).tobytes()
            assert pose_stats.column_ranks(c.copy()).tobytes() == average_ranks(c).tobytes()
    assert sum(a.nbytes for a in pose_stats._rank_memo.values()) <= 3 * 4 * 1000
    changed = cols[0].copy()
    changed[[3, 700]] = changed[[700, 3]]  # same values, another order: other ranks
    assert pose_stats.column_ranks(changed).tobytes() == average_ranks(changed).tobytes()
    with_nan = cols[3].copy()
    with_nan[5] = np.nan
    assert np.isnan(pose_stats.column_ranks(with_nan)).all()
    assert pose_stats.column_ranks(np.array(["b", "a", "b"], object)).tolist() == [2.5, 1.0, 2.5]


@pytest.mark.parametrize("key, options", [
    ("auv", {}), ("boat", {}), ("auv", {"profile": "unconstrained"}), ("boat", {"feature_below": False}),
    ("boat", {"tilt_deg": 35.0, "side2": "port"}), ("auv", {"side1": "either", "feature_distribution": "volume"}),
    ("boat", {"azimuth1_window_deg": (-10.0, -5.0), "azimuth2_window_deg": (0.0, 4.0)}),
    ("auv", {"vehicle_depths": "difference"}), ("auv", {"vehicle_depths": "free", "side2": "starboard"}),
    ("auv", {"feature_below": False, "vehicle1_depth_m": 5.0}),
    ("auv", {"azimuth1_window_deg": (-10.0, -5.0), "azimuth2_window_deg": (0.0, 4.0), "pitch_max_deg": 60.0}),
    ("auv", {"roll_max_deg": 30.0, "side1": "either"}),
])
@pytest.mark.parametrize("margin", [None, 0.05])
def test_pose_space_block_is_the_plain_rejection_sampler(key, options, margin, monkeypatch):
    # reference: every candidate's arrays filtered by the acceptance mask, round by round,
    # concatenated and cut to the block (the sampler's definition, without shortcuts); with a
    # wide decision margin most rows are decided by the plain computation, also the same rows
    from sss_locus.experiments.pose_space import draw as pose_draw
    from sss_locus.experiments.datamodel.platforms import load_platform
    from sss_locus.experiments.pose_space.study import BLOCK_SIZE, PoseSpaceSpec, draw_block
    from sss_locus.geometry import relative_pose

    if margin is not None:
        monkeypatch.setattr(pose_draw, "DECISION_MARGIN", margin)
    spec = PoseSpaceSpec(load_platform(key), **options)
    for block in (0, 3):
        rng = np.random.default_rng(np.random.SeedSequence(5, spawn_key=(block,)))
        parts, have = [], 0
        while have < BLOCK_SIZE:
            cand = pose_draw.draw_candidates(spec, rng, max(BLOCK_SIZE, 2 * (BLOCK_SIZE - have)))
            keep = cand.pop("accept")
            parts.append({k: v[keep] for k, v in cand.items()})
            have += int(keep.sum())
        ref = {k: np.concatenate([p[k] for p in parts])[:BLOCK_SIZE] for k in parts[0]}
        ref["R"], ref["t"] = relative_pose(ref.pop("R1"), ref["o1"], ref.pop("R2"), ref["o2"])
        ours = draw_block(spec, 5, block)
        assert ours.keys() == ref.keys()
        for k in ref:
            assert ours[k].dtype == ref[k].dtype and ours[k].tobytes() == ref[k].tobytes(), k


@pytest.mark.parametrize("key, options", [("auv", {}), ("auv", {"side1": "either", "feature_distribution": "volume",
                                                                 "pitch_max_deg": 80.0, "roll_max_deg": 80.0})])
def test_short_acceptance_heights_are_the_plain_ones_within_a_millionth_of_the_margin(key, options):
    # the short closed form decides a candidate only where its margin exceeds DECISION_MARGIN
    # times the length scale: its heights must agree with the plain computation far closer
    from sss_locus.experiments.pose_space import draw as pose_draw
    from sss_locus.experiments.datamodel.platforms import load_platform
    from sss_locus.experiments.pose_space.study import PoseSpaceSpec

    spec = PoseSpaceSpec(load_platform(key), **options)
    d = pose_draw.draw_numbers(spec, np.random.default_rng(8), 200_000)
    plain = pose_draw.candidates(spec, d)
    short = dict(zip(("f_z", "o1_z", "o2_z", "v2_z"), pose_draw._heights(spec, d)))
    ref = dict(f_z=plain["f"][:, 2], o1_z=plain["o1"][:, 2], o2_z=plain["o2"][:, 2], v2_z=plain["v2_z"])
    tol = 1e-6 * pose_draw.DECISION_MARGIN * pose_draw.length_scale(spec.platform)
    for name in ref:
        assert np.max(np.abs(short[name] - ref[name])) < tol, name
    accept, sure = pose_draw._constraints(spec, *short.values(), d.get("d1"), strict=False, tol=0.0)
    assert np.array_equal(accept, plain["accept"])  # at these draws no margin is within rounding


@pytest.mark.parametrize("key", ["auv", "boat"])
def test_transducer_stack_rows_are_the_mountings(key):
    from sss_locus.experiments.datamodel.platforms import load_platform
    from sss_locus.experiments.passes.straight_pass import transducer_stack

    pf = load_platform(key)
    is_port = np.random.default_rng(1).random(50) < 0.5
    mats, pos = transducer_stack(pf, is_port)
    for i, port in enumerate(is_port):
        tr = pf.transducers["port" if port else "starboard"]
        assert mats[i].tobytes() == tr.rotation.as_matrix().tobytes()
        assert pos[i].tobytes() == np.asarray(tr.position_m, float).tobytes()
    assert mats.shape == (50, 3, 3) and pos.shape == (50, 3) and mats.flags.writeable


@pytest.mark.parametrize("repeats", [1, 3, 400])
def test_level_attitude_matrices_equal_vehicle_attitude_bit_for_bit(repeats):
    from sss_locus.experiments.passes.straight_pass import level_attitude_matrices

    rng = np.random.default_rng(repeats)
    yaw = np.repeat(rng.uniform(-180, 180, 7), repeats)  # a few headings, each on many pings (a survey)
    rng.shuffle(yaw)
    for pitch in (np.full(yaw.size, 4.0), rng.uniform(-10, 10, yaw.size)):
        ref = _elementary(2, yaw) @ _elementary(1, -pitch) @ _elementary(0, np.zeros(yaw.size))
        ours = level_attitude_matrices(yaw, pitch)
        assert ours.shape == (yaw.size, 3, 3)
        np.testing.assert_allclose(ours, ref, atol=1e-14)
        assert ours.tobytes() == vehicle_attitude(yaw, pitch, np.zeros(yaw.size)).as_matrix().tobytes()
