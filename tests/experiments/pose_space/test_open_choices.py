"""The open-choice measurements and verdict tests (experiments.pose_space.choices, experiments.survey_passes.verdicts),
against independent references: closed forms, brute force and hand-built curves."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from sss_locus.experiments.pose_space.choices import fan_share_removed, hotspot_check, in_bin
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.pose_space.study import PoseSpaceSpec, sample_pose_space
from sss_locus.experiments.pose_space.stats import binned_median, with_derived
from sss_locus.experiments.survey_passes.verdicts import advice_verdict, near_end_check, peak_agreement


@pytest.mark.parametrize("key", ["auv", "boat"])
def test_fan_share_matches_closed_form(key):
    # at phi = 0 a direction is below the sensor iff its depression tilt + theta > 0 (module
    # docstring of platforms); the elevation aperture is sub-degree, so the share of the fan
    # removed is (half_az - tilt) / (2 half_az), clipped at 0, to a small fraction of a percent
    pf = load_platform(key)
    half, tilt = pf.sonar.azimuth_deg / 2, pf.transducers["port"].tilt_deg
    expected = max(0.0, (half - tilt) / (2 * half))
    got = fan_share_removed(pf, n_grid=1001)
    assert got["share"] == pytest.approx(expected, abs=2e-3)
    assert got["theta_min_deg"] == pytest.approx(max(-tilt, -half), abs=0.2)
    assert fan_share_removed(pf, "starboard", n_grid=1001)["share"] == pytest.approx(got["share"], abs=1e-12)


def test_fan_share_brute_force_with_pitch():
    # Monte Carlo of random directions in the aperture, world z from scipy's own Euler rotation
    from scipy.spatial.transform import Rotation
    pf = load_platform("auv").with_tilt(5.0)
    ap = pf.sonar.aperture()
    rng = np.random.default_rng(0)
    th = rng.uniform(-ap.half_azimuth_rad, ap.half_azimuth_rad, 200_000)
    ph = rng.uniform(-ap.half_elevation_rad, ap.half_elevation_rad, 200_000)
    d = np.stack([np.cos(th) * np.cos(ph), np.sin(th) * np.cos(ph), np.sin(ph)], axis=-1)
    world = Rotation.from_euler("ZYX", [0.0, -30.0, 0.0], degrees=True).as_matrix() @ \
        pf.transducers["port"].rotation.as_matrix()
    mc = float(np.mean(d @ world[2] >= 0))
    assert fan_share_removed(pf, pitch_deg=30.0)["share"] == pytest.approx(mc, abs=5e-3)


def test_fan_share_bad_input():
    pf = load_platform("boat")
    with pytest.raises(ValueError, match="side"):
        fan_share_removed(pf, "up")
    with pytest.raises(ValueError, match="n_grid"):
        fan_share_removed(pf, n_grid=1)


def test_feature_below_rule_limits_azimuth_and_can_be_lifted():
    pf = load_platform("auv")
    tilt = pf.transducers["port"].tilt_deg
    kept = sample_pose_space(PoseSpaceSpec(pf), 4096, 3)
    lifted = sample_pose_space(PoseSpaceSpec(pf, feature_below=False), 4096, 3)
    assert kept["azimuth1_deg"].min() > -tilt - 0.2  # the closed-form edge of the rule
    assert lifted["azimuth1_deg"].min() < -tilt - 10


def test_misalignment_readings_against_definitions():
    df = pd.DataFrame({"psi1_deg": [10.0, -30.0, 5.0], "psi2_deg": [-20.0, 5.0, 7.0]})
    mag = with_derived(df)["elevation_misalignment_deg"].to_numpy()
    sig = with_derived(df, misalignment="signed")["elevation_misalignment_deg"].to_numpy()
    np.testing.assert_array_equal(mag, [20.0, 30.0, 7.0])
    np.testing.assert_array_equal(sig, [10.0, 5.0, 7.0])
    with pytest.raises(ValueError, match="misalignment"):
        with_derived(df, misalignment="abs")


def test_magnitude_reading_reproduces_kernel_column():
    tab = sample_pose_space(PoseSpaceSpec(load_platform("auv")), 2000, 1)
    np.testing.assert_allclose(with_derived(tab)["elevation_misalignment_deg"], tab["elevation_misalignment_deg"])


def test_azimuth_window_is_the_conditional_distribution():
    # a window on theta1 gives the default sampler's rows with theta1 in the window: compare the
    # medians of locus length (independent streams) within a few standard errors
    pf = load_platform("auv")
    window = (0.0, 20.0)
    full = sample_pose_space(PoseSpaceSpec(pf), 60_000, 5)
    sub = full[full["azimuth1_deg"].between(*window)]["locus_length_m"].to_numpy()
    tgt = sample_pose_space(PoseSpaceSpec(pf, azimuth1_window_deg=window), 20_000, 6)
    assert tgt["azimuth1_deg"].between(*window).all()
    x = tgt["locus_length_m"].to_numpy()
    se = 1.2533 * np.hypot(sub.std() / math.sqrt(sub.size), x.std() / math.sqrt(x.size))
    assert abs(np.median(sub) - np.median(x)) < 5 * se
    with pytest.raises(ValueError, match="azimuth1_window_deg"):
        PoseSpaceSpec(pf, azimuth1_window_deg=(10.0, 90.0))


def test_hotspot_check_on_hand_built_bins():
    rng = np.random.default_rng(1)
    df = pd.DataFrame({"a": rng.uniform(0, 2, 4000), "b": rng.uniform(0, 2, 4000)})
    df["locus_length_m"] = np.where((df.a >= 1) & (df.b >= 1), 5.0, 1.0) + rng.normal(0, 0.1, len(df))
    binned = binned_median(df, "a", "b", x_edges=[0, 1, 2], y_edges=[0, 1, 2], min_count=1)
    targeted = df.assign(a=rng.uniform(1, 2, len(df)), b=rng.uniform(1, 2, len(df)),
                         locus_length_m=5.0 + rng.normal(0, 0.1, len(df)))
    out = hotspot_check(binned, targeted)
    assert (out["x_mid"], out["y_mid"]) == (1.5, 1.5)
    assert out["target_count"] == len(in_bin(targeted, "a", "b", (1, 2), (1, 2)))
    assert out["target_ci_low"] <= 5.0 <= out["target_ci_high"] + 0.02
    assert out["still_peak"] is True and out["runner_up_median"] == pytest.approx(1.0, abs=0.05)


def _curve(g, m):
    return pd.DataFrame({"crossing_angle_deg": np.asarray(g, float), "locus_length_m_median": np.asarray(m, float)})


def test_near_end_check_finds_a_spike_next_to_an_end():
    g = [0, 5, 10, 20, 90, 170, 175, 180]
    m = [1.0, 16.0, 2.0, 30.0, 20.0, 9.0, 1.5, 1.0]
    out = near_end_check(_curve(g, m), window_deg=10).set_index("end_deg")
    assert out.loc[0.0, "worst_angle_deg"] == 5 and out.loc[0.0, "ratio"] == 16.0
    assert out.loc[180.0, "worst_angle_deg"] == 170 and out.loc[180.0, "worst_median"] == 9.0
    # range 1..30: prefer <= 1 + 0.25 * 29 = 8.25 -> 5 deg (16) and 170 deg (9) are not preferred
    assert not out.loc[0.0, "all_preferred"] and not out.loc[180.0, "all_preferred"]
    flat = near_end_check(_curve(g, [1, 1, 1, 30, 20, 1, 1, 1]), window_deg=10)
    assert flat["all_preferred"].all()
    with pytest.raises(ValueError, match="window_deg"):
        near_end_check(_curve(g, m), window_deg=0)
    coarse = near_end_check(_curve([0, 45, 90, 135, 180], [1, 5, 4, 3, 1]), window_deg=10)
    assert (coarse["n_angles"] == 0).all() and coarse["worst_median"].isna().all()


def test_peak_agreement_and_advice_verdict():
    a = {"angle_deg": 20.0, "ci_low_deg": 15.0, "ci_high_deg": 25.0}
    b = {"angle_deg": 28.0, "ci_low_deg": 26.0, "ci_high_deg": 30.0}
    out = peak_agreement(a, b)
    assert out["gap_deg"] == 8.0 and not out["intervals_overlap"]
    assert peak_agreement(a, dict(b, ci_low_deg=25.0))["intervals_overlap"]
    g = [0, 10, 20, 30, 40, 90, 180]
    v = advice_verdict(_curve(g, [1, 5, 7, 6, 4, 3, 2]))
    assert v == {"ends": 2.0, "oblique": 5.5, "perpendicular": 3.0, "holds": True}
    assert not advice_verdict(_curve(g, [4, 5, 7, 6, 4, 3, 2]))["holds"]  # 90 deg beats the ends
