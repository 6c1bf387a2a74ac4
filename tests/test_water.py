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

from sss_locus.experiments.envelopes import OffsetModel, load_envelope
from sss_locus.experiments.platforms import load_platform
from sss_locus.experiments.pose_space import PoseSpaceSpec, sample_pose_space
from sss_locus.experiments.survey_passes import simulate_passes
from sss_locus.experiments.water import WaterColumn, crop_effect
from sss_locus.experiments.water_study import crop_effects, default_conditions


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
    e = crop_effect(a, b, n_resamples=50).set_index("statistic")["estimate"]
    assert e["length_ratio"] == pytest.approx(3.0 / 5.0)
    assert e["shortened_share"] == pytest.approx(0.5)
    assert e["emptied_share"] == pytest.approx(1.0 / 3.0)
    assert e["multi_arc_share_uncropped"] == pytest.approx(0.5)
    assert e["multi_arc_share_cropped"] == 0.0 and e["extra_arcs_share"] == pytest.approx(0.5)
    with pytest.raises(ValueError, match="same non-empty samples"):
        crop_effect(a, b.iloc[:2])
    with pytest.raises(ValueError, match="not the same samples"):
        crop_effect(b, a)
    with pytest.raises(ValueError, match="n_resamples"):
        crop_effect(a, b, n_resamples=0)


def test_crop_effects_table_covers_conditions_and_subsets():
    pfs = [load_platform("boat"), load_platform("auv")]
    conds = default_conditions(pfs, surface_tilts_deg=[15.0], submerged_depths_m=[2.0, 500.0])
    assert [c.slug for c in conds] == ["boat-pose", "boat-pose-tilt15", "auv-pose-depth2m"]
    out = crop_effects(conds[:1], n_samples=4096, n_per_angle=10, crossing_angles_deg=[0.0], seed=1,
                       n_resamples=5)
    assert set(out["subset"]) == {"all", "port-port"} and (out["n"] > 0).all()
    with pytest.raises(ValueError, match="none of submerged_depths_m"):
        default_conditions(pfs, submerged_depths_m=[500.0])
