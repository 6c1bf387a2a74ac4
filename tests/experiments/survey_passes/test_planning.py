"""Survey planning (sss_locus.experiments.survey_passes.planning): grid, bootstrap, bands from a curve, the curve itself."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from sss_locus.experiments.survey_passes.planning import (bootstrap_median, crossing_angle_curve, crossing_angle_grid,
                                median_ratio, peak_angle, planning_bands, worst_band)
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.datamodel.envelopes import OffsetModel, load_envelope


def test_grid_steps():
    g = crossing_angle_grid()
    assert g[0] == 0 and g[-1] == 180 and 90 in g
    steps = np.diff(g)
    assert steps.max() <= 5 + 1e-12
    assert np.all(steps[g[:-1] < 40] <= 1 + 1e-12)
    with pytest.raises(ValueError, match="fine_step_deg"):
        crossing_angle_grid(fine_step_deg=0)


def _curve(angles, medians):
    return pd.DataFrame({"crossing_angle_deg": np.asarray(angles, float),
                         "locus_length_m_median": np.asarray(medians, float)})


def test_bands_by_hand():
    # range 0..4: prefer <= 1, avoid >= 2
    c = _curve([0, 10, 20, 30, 40, 50, 60], [0.0, 1.0, 3.0, 4.0, 2.0, 1.5, 0.5])
    bands = planning_bands(c)
    assert bands.to_dict("list")["kind"] == ["prefer", "avoid", "prefer"]
    assert bands["lo_deg"].tolist() == [0, 20, 60] and bands["hi_deg"].tolist() == [10, 40, 60]
    assert worst_band(c) == (20.0, 40.0)
    with pytest.raises(ValueError, match="prefer_below"):
        planning_bands(c, prefer_below=0.6, avoid_above=0.5)


def test_flat_curve_prefers_everything():
    bands = planning_bands(_curve([0, 90, 180], [1.0, 1.0, 1.0]))
    assert bands["kind"].tolist() == ["prefer"] and bands["hi_deg"].iloc[0] == 180


def test_bootstrap_median_interval_and_seed():
    rng = np.random.default_rng(0)
    x = rng.exponential(size=2001)
    b1 = bootstrap_median(x, 300, np.random.default_rng(5))
    b2 = bootstrap_median(x, 300, np.random.default_rng(5))
    assert np.array_equal(b1, b2)
    # the bootstrap spread of the median is close to the asymptotic standard error
    se = 1.0 / (2 * np.exp(-np.log(2)) * np.sqrt(x.size))  # 1/(2 f(m) sqrt(n)), f(m) = 1/2
    assert 0.7 * se < b1.std() < 1.4 * se


def test_median_ratio_recovers_a_known_ratio():
    rng = np.random.default_rng(1)
    y = rng.lognormal(size=4000)
    out = median_ratio(1.4 * rng.lognormal(size=4000), y)
    assert out["ratio_ci_low"] < 1.4 < out["ratio_ci_high"]
    same = median_ratio(rng.lognormal(size=4000), y)
    assert same["ratio_ci_low"] < 1.0 < same["ratio_ci_high"]


def test_peak_angle_interval():
    c = _curve([0, 10, 20, 30], [1.0, 2.0, 5.0, 2.0])
    boot = np.array([[1, 2, 5, 2], [1, 6, 5, 2], [1, 2, 5, 7]], float)
    out = peak_angle(c, boot, confidence_level=0.5)
    assert out["angle_deg"] == 20 and out["ci_low_deg"] <= 20 <= out["ci_high_deg"]


def test_crossing_angle_curve_small():
    pf = load_platform("boat")
    cur = crossing_angle_curve(pf, load_envelope("boat"), OffsetModel(), crossing_angles_deg=[0, 30, 90, 180],
                               n_per_angle=300, seed=3, n_resamples=50)
    c = cur.curve
    assert list(c["crossing_angle_deg"]) == [0, 30, 90, 180] and (c["n"] == 300).all()
    for v in ("locus_length_m", "elevation_misalignment_deg"):
        assert (c[f"{v}_q25"] <= c[f"{v}_median"]).all() and (c[f"{v}_median"] <= c[f"{v}_q75"]).all()
        assert (c[f"{v}_ci_low"] <= c[f"{v}_median"] + 1e-12).all()
    assert c["acceptance"].between(0, 1).all()
    assert cur.peak["locus_length_m"]["angle_deg"] in (0, 30, 90, 180)
    assert cur.at(90)["median"] == pytest.approx(c.loc[2, "locus_length_m_median"])
    with pytest.raises(ValueError, match="grid"):
        cur.at(45)


def test_pitch_study_platform_skips_platforms_that_cannot_pitch():
    """Issue 37: a boat-only run fell back to the boat and crashed ("exceeds platform 'boat''s
    limit of ±0.0 deg"); a platform qualifies only when the envelope pitches and its limit covers
    every pitch of the study."""
    from dataclasses import replace

    from sss_locus.experiments.survey_passes.planning import pitch_study_platform

    pfs = {k: load_platform(k) for k in ("boat", "auv")}
    envs = {k: load_envelope(k) for k in pfs}
    assert pfs["boat"].pitch_max_deg == 0 and pfs["auv"].pitch_max_deg >= 15  # the shipped data
    assert pitch_study_platform({"boat": pfs["boat"]}, envs, [5, 10, 15]) is None
    assert pitch_study_platform(pfs, envs, [5, 10, 15]) == "auv"
    low = {"slow": replace(pfs["auv"], pitch_max_deg=10.0)}
    assert pitch_study_platform(low, {"slow": envs["auv"]}, [5, 10, 15]) is None
    assert pitch_study_platform(low, {"slow": envs["auv"]}, [-5, 10]) == "slow"
    flat = {"auv": replace(envs["auv"], pitch_min_deg=0.0, pitch_max_deg=0.0)}
    assert pitch_study_platform({"auv": pfs["auv"]}, flat, [5]) is None
