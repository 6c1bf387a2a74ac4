"""The water-column option of the studies (off by default) and its paired comparison.

Independent checks: with the crop off nothing changes (keys and samples); with it on, the
samples are the same and lengths only shrink; for the level boat at its documented 25 deg tilt
the crop removes nothing, because the whole fan lies at or below the horizontal through a
transducer 0.10 m under the waterline (an argument from the geometry, not the code).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from sss_locus.experiments.datamodel.envelopes import OffsetModel, load_envelope
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.pose_space.study import PoseSpaceSpec, sample_pose_space
from sss_locus.experiments.survey_passes.study import simulate_passes
from sss_locus.experiments.datamodel.water_column import WaterColumn, deepest_feature_m
from sss_locus.experiments.water.study import crop_effect, crop_effects, default_conditions, pass2_above_surface_share


def test_off_by_default_keeps_the_spec_key():
    spec = PoseSpaceSpec(load_platform("boat"))
    assert spec.water is None and "water" not in spec.key()
    assert PoseSpaceSpec(load_platform("boat"), water=WaterColumn()).key()["water"] == {
        "vehicle_depth_m": None, "max_water_depth_m": None}


def test_submerged_platform_needs_a_depth_in_its_range():
    with pytest.raises(ValueError, match="vehicle_depth_m is required"):
        PoseSpaceSpec(load_platform("auv"), water=WaterColumn())
    with pytest.raises(ValueError, match="vehicle_depth_m must lie in"):
        PoseSpaceSpec(load_platform("auv"), water=WaterColumn(500.0))
    with pytest.raises(ValueError, match="water must be a WaterColumn"):
        PoseSpaceSpec(load_platform("auv"), water=3.0)


@pytest.mark.parametrize("key, opts, water, changes", [
    ("boat", {}, WaterColumn(), False),
    ("boat", {"tilt_deg": 15.0}, WaterColumn(), True),
    ("auv", {}, WaterColumn(2.0), True),
])
def test_pose_space_crop_keeps_samples_and_only_shortens(key, opts, water, changes):
    a = sample_pose_space(PoseSpaceSpec(load_platform(key), **opts), 8192, 3)
    b = sample_pose_space(PoseSpaceSpec(load_platform(key), water=water, **opts), 8192, 3)
    cols = [c for c in a.columns if c not in ("locus_length_m", "locus_length_normalized", "n_arcs")]
    pd.testing.assert_frame_equal(a[cols], b[cols])
    assert np.all(b.locus_length_m <= a.locus_length_m * (1 + 1e-12))
    if changes:
        assert (b.locus_length_m < a.locus_length_m * (1 - 1e-9)).any()
    else:  # level boat, fan top at the horizontal: nothing lies above the water
        np.testing.assert_allclose(b.locus_length_m, a.locus_length_m, rtol=1e-12)
        np.testing.assert_array_equal(b.n_arcs, a.n_arcs)


def test_survey_crop_keeps_samples_and_acceptance():
    pf, env, m = load_platform("auv"), load_envelope("auv"), OffsetModel.parse("independent")
    a, acc_a = simulate_passes(pf, env, m, [0.0, 90.0], 300, 2)
    b, acc_b = simulate_passes(pf, env, m, [0.0, 90.0], 300, 2, water=WaterColumn(2.0))
    pd.testing.assert_frame_equal(acc_a, acc_b)
    np.testing.assert_array_equal(a.r1_m, b.r1_m)
    assert np.all(b.locus_length_m <= a.locus_length_m * (1 + 1e-12))
    with pytest.raises(ValueError, match="vehicle_depth_m is required"):
        simulate_passes(pf, env, m, [0.0], 10, 2, water=WaterColumn())


def test_crop_effect_statistics_and_errors():
    a = pd.DataFrame({"locus_length_m": [2.0, 2.0, 1.0, 0.0], "n_arcs": [2, 1, 2, 0]})
    b = pd.DataFrame({"locus_length_m": [1.0, 2.0, 0.0, 0.0], "n_arcs": [1, 1, 0, 0]})
    e = crop_effect(a, b, n_batches=3).set_index("statistic")["estimate"]
    assert e["length_ratio"] == pytest.approx(3.0 / 5.0)
    assert e["shortened_share"] == pytest.approx(0.5)
    assert e["emptied_share"] == pytest.approx(1.0 / 3.0)
    assert e["multi_arc_share_uncropped"] == pytest.approx(0.5)
    assert e["multi_arc_share_cropped"] == 0.0 and e["extra_arcs_share"] == pytest.approx(0.5)
    with pytest.raises(ValueError, match="same non-empty samples"):
        crop_effect(a, b.iloc[:2])
    with pytest.raises(ValueError, match="not the same samples"):
        crop_effect(b, a)
    with pytest.raises(ValueError, match="n_batches"):
        crop_effect(a, b, n_batches=2)


def test_crop_effects_table_covers_conditions_and_subsets():
    pfs = [load_platform("boat"), load_platform("auv")]
    conds = default_conditions(pfs, surface_tilts_deg=[15.0], submerged_depths_m=[2.0, 500.0])
    assert [c.slug for c in conds] == ["boat-pose", "boat-pose-tilt15", "auv-pose-depth2m"]
    out = crop_effects(conds[:1], n_samples=4096, n_per_angle=10, crossing_angles_deg=[0.0], seed=1,
                       n_batches=5)
    assert set(out["subset"]) == {"all", "port-port"} and (out["n"] > 0).all()
    with pytest.raises(ValueError, match="none of submerged_depths_m"):
        default_conditions(pfs, submerged_depths_m=[500.0])


# --- the seafloor (a known water depth) ---------------------------------------------------------
def test_seafloor_options_are_exclusive_and_need_the_feature():
    with pytest.raises(ValueError, match="not both"):
        WaterColumn(max_water_depth_m=50.0, seafloor_below_feature_m=1.0)
    with pytest.raises(ValueError, match="seafloor_below_feature_m"):
        WaterColumn(seafloor_below_feature_m=-1.0)
    with pytest.raises(ValueError, match="needs feature_z"):
        WaterColumn(seafloor_below_feature_m=1.0).half_spaces(np.eye(3)[None], np.zeros(1), 0.0)
    assert "seafloor_below_feature_m" not in WaterColumn().key()  # earlier keys unchanged
    assert WaterColumn(seafloor_below_feature_m=1.0).key()["seafloor_below_feature_m"] == 1.0


def test_fixed_water_depth_above_sampled_features_is_refused():
    # the boat's fan reaches deepest_feature_m below the surface; a 5 m deep floor is above most features
    spec = PoseSpaceSpec(load_platform("boat"), water=WaterColumn(max_water_depth_m=5.0))
    with pytest.raises(ValueError, match="sampled features lie below WaterColumn.max_water_depth_m"):
        sample_pose_space(spec, 4096, 1)


def test_deepest_feature_is_the_fan_edge_at_full_range():
    pf = load_platform("boat")  # 25 deg tilt + 25 deg half fan: 50 deg down at 150 m, transducer 0.10 m deep
    assert deepest_feature_m(pf) == pytest.approx(0.10 + 150.0 * np.sin(np.radians(50.0)))
    assert deepest_feature_m(load_platform("auv")) == pytest.approx(2.0 + 150.0)  # fan reaches nadir


@pytest.mark.parametrize("key, depth", [("boat", None), ("auv", 2.0)])
def test_seafloor_crop_is_monotone_and_keeps_the_feature(key, depth):
    """Invariants, not values: the same samples; a floor further below the feature keeps at least
    as much (each crop contains the tighter one); a floor far below changes nothing beyond the
    surface crop; with a positive margin the feature lies strictly inside the water column, so
    no non-empty locus is emptied."""
    pf = load_platform(key)
    run = lambda **w: sample_pose_space(PoseSpaceSpec(pf, water=WaterColumn(depth, **w)), 4096, 5)
    paper = sample_pose_space(PoseSpaceSpec(pf), 4096, 5)
    surface, near, far, huge = run(), run(seafloor_below_feature_m=1.0), run(seafloor_below_feature_m=10.0), \
        run(seafloor_below_feature_m=5000.0)
    tol = 1e-9 * paper.locus_length_m.max()
    assert np.all(near.locus_length_m <= far.locus_length_m + tol)
    assert np.all(far.locus_length_m <= surface.locus_length_m + tol)
    np.testing.assert_allclose(huge.locus_length_m, surface.locus_length_m, rtol=1e-12, atol=tol)
    assert (near.locus_length_m < surface.locus_length_m - 1e-6).any()  # the floor does crop
    assert not ((paper.locus_length_m > 0) & (near.locus_length_m == 0)).any()
    np.testing.assert_array_equal(near.r1_m, paper.r1_m)


def test_survey_seafloor_and_pass2_above_surface():
    pf, env, m = load_platform("auv"), load_envelope("auv"), OffsetModel.parse("independent")
    a, _ = simulate_passes(pf, env, m, [0.0, 90.0], 300, 2, water=WaterColumn(2.0))
    b, _ = simulate_passes(pf, env, m, [0.0, 90.0], 300, 2, water=WaterColumn(2.0, seafloor_below_feature_m=1.0))
    assert np.all(b.locus_length_m <= a.locus_length_m * (1 + 1e-12))
    assert not ((a.locus_length_m > 0) & (b.locus_length_m == 0)).any()
    # brute force: count pass pairs whose pass 2 flies more than 2 m above pass 1
    expected = sum(r.altitude2_m - r.altitude1_m > 2.0 for r in a.itertuples()) / len(a)
    assert pass2_above_surface_share(a, pf, WaterColumn(2.0)) == pytest.approx(expected)


def test_crop_effect_interval_of_a_rare_share_stays_in_zero_one():
    # one shortened locus in 1000: the symmetric replicate interval would reach below 0
    a = pd.DataFrame({"locus_length_m": np.ones(1000), "n_arcs": np.ones(1000, int)})
    b = a.copy()
    b.loc[7, "locus_length_m"] = 0.5
    e = crop_effect(a, b).set_index("statistic")
    assert e.loc["shortened_share", "estimate"] == pytest.approx(0.001)
    assert e.loc["shortened_share", "ci_low"] == 0.0 < e.loc["shortened_share", "ci_high"] < 0.01
    assert e.loc["length_ratio", "ci_high"] == 1.0
