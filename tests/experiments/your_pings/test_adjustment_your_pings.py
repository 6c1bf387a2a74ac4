"""The joint adjustment on a user's own sightings CSV: a survey of the independent simulation
(tests/adjustment_sim.py: per-pass offsets of metres and a heading bias, 4 m relief), written as
a user would write it (vehicle reference point in local metres, grid heading, altitude, slant
range), run through the your-pings chapter's reader and :func:`joint_estimate`."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from adjustment_sim import simulate
from sss_locus.experiments.adjustment import map_errors
from sss_locus.experiments.passes.pass_noise import load_pass_noise
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.your_pings.study import run
from sss_locus.experiments.your_pings.files import against_truth
from sss_locus.experiments.your_pings.joint import infer_passes, joint_estimate, with_joint
from sss_locus.report.common.text import fmt_sig
from sss_locus.report.your_pings.joint import joint_sentence


def user_csv(sv, platform, path):
    """The simulated survey as a sightings CSV of ``platform`` (its transducer at the simulated
    sensor): reference point = navigated sensor origin minus the transducer's lever arm."""
    fwd = sv.W_nav[:, :2, 2]
    yaw = np.degrees(np.arctan2(fwd[:, 1], fwd[:, 0]))  # the navigated heading (ccw from east)
    side = np.where(sv.side > 0, "port", "starboard")
    ref = np.empty_like(sv.origin_nav)
    for name, tr in platform.transducers.items():
        rows = side == name
        _, o0 = tr.world_pose(np.zeros((rows.sum(), 3)), yaw[rows], 0.0, 0.0)
        ref[rows] = sv.origin_nav[rows] - o0
    lever_up = sv.origin_nav[:, 2] - ref[:, 2]
    t = 10_000.0 * sv.pass_index + 0.5 * sv.along_m  # 2 m/s along each line, lines 10,000 s apart
    table = pd.DataFrame({"feature": [f"T{i:03d}" for i in sv.feature], "platform": platform.key, "side": side,
                          "east_m": ref[:, 0], "north_m": ref[:, 1], "depth_m": -ref[:, 2],
                          "altitude_m": sv.altimeter_m - lever_up, "heading_deg": np.mod(90.0 - yaw, 360.0),
                          "pitch_deg": 0.0, "roll_deg": 0.0, "slant_range_m": sv.range_m,
                          "range_sigma_m": np.hypot(0.05, 0.05), "time_s": t})
    table.sort_values("time_s").to_csv(path, index=False)
    return table


@pytest.fixture(scope="module")
def survey(tmp_path_factory):
    platform = load_platform("auv")
    sv = simulate(71, n_features=150, sensor_z=-6.0, tilt_deg=25.5)
    path = tmp_path_factory.mktemp("yp") / "my_survey.csv"
    user_csv(sv, platform, path)
    res = run(path, platform)
    joint = joint_estimate(res, platform, load_pass_noise("auv"), ping_position_sigma_m=0.05,
                           ping_attitude_sigma_deg=0.05)
    return sv, res, joint, platform


def test_passes_are_the_survey_lines(survey):
    sv, res, _, _ = survey
    got = infer_passes(res.sightings)
    line = np.floor(res.sightings["time_s"].to_numpy() / 10_000.0 + 0.5).astype(int)  # the simulated pass
    pairs = set(zip(got.tolist(), line.tolist()))  # one inferred pass per simulated line, and back
    assert len(pairs) == len(set(got.tolist())) == len(set(line.tolist())) == len(sv.reference)


def test_joint_estimate_of_a_users_csv_beats_the_mosaic_shape_and_says_so(survey):
    sv, res, joint, _ = survey
    truth = pd.DataFrame({"feature": [f"T{i:03d}" for i in range(len(sv.truth))], "east_m": sv.truth[:, 0],
                          "north_m": sv.truth[:, 1], "up_m": sv.truth[:, 2]})
    f = joint.features.merge(res.features, on="feature").merge(truth, on="feature")
    ok = (f["joint_status"] == "adjusted").to_numpy()
    assert ok.sum() >= 0.9 * (f["n_passes"] >= 2).sum()
    t = f[["east_m", "north_m", "up_m"]].to_numpy()
    j = map_errors(f[["joint_east_m", "joint_north_m", "joint_up_m"]].to_numpy(), t, ok)
    m = map_errors(f[["flat_east_m", "flat_north_m", "flat_up_m"]].to_numpy(), t, ok)
    assert np.median(j["shape_m"][ok]) <= 0.25 * np.median(m["shape_m"][ok])
    assert np.median(np.abs(j["vertical_m"][ok])) <= 0.15 * np.median(np.abs(m["vertical_m"][ok]))
    assert np.all(np.isfinite(f.loc[ok, "joint_ellipse_major_m"]))
    # the page's sentence: the shape is clearly better, and the common shift is stated
    s = joint.summary
    assert s["shape_ratio"] >= 1.5 and np.isfinite(s["common_shift_sigma_m"])
    text = joint_sentence(s)
    assert "unobservable" in text and "times less" not in text  # a ratio said as a division, not "N times less"
    ratio = s["mosaic_disagreement_m"] / s["joint_misfit_m"]  # the two medians the sentence prints, divided here
    assert f"the mosaic's disagreement divided by {fmt_sig(ratio)}." in text
    assert "different measures" in text and "optimistic" in text  # what the ratio compares, and its bias
    # the pass table: one row per pass, heading biases (clockwise) recovered within 3 sigma
    p = joint.passes
    assert len(p) == len(sv.reference)
    first = res.sightings.groupby(infer_passes(res.sightings))["time_s"].first().to_numpy()
    line = np.floor(first / 10_000.0 + 0.5).astype(int)
    err = p["heading_bias_deg"].to_numpy() + np.degrees(sv.heading_bias[line])  # the simulation's is counter-clockwise
    assert np.all(np.abs(err) <= 3 * p["heading_bias_sigma_deg"].to_numpy())


def test_the_chapter_tables_carry_the_joint_estimate(survey):
    sv, res, joint, _ = survey
    both = with_joint(res, joint)
    assert {"joint_east_m", "joint_ellipse_major_m", "n_passes"} <= set(both.features.columns)
    assert len(both.sightings) == len(res.sightings) and "pass" in both.sightings
    truth = pd.DataFrame({"feature": [f"T{i:03d}" for i in range(len(sv.truth))], "east_m": sv.truth[:, 0],
                          "north_m": sv.truth[:, 1], "up_m": sv.truth[:, 2]})
    assert "joint" in set(against_truth(both, truth)["estimator"])
