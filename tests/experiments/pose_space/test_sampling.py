"""The pose-space sampler honours every constraint it claims, reproducibly.

Constraint checks rebuild the geometry from the kernel inputs ``(R, t)`` and the platform's
mounting, not from the sampler's own intermediate positions.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from sss_locus import two_view_locus
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.pose_space.study import (
    BLOCK_SIZE,
    COLUMNS,
    PoseSpaceSpec,
    sample_geometry,
    sample_pose_space,
    spherical_to_cartesian,
)

N = 3 * BLOCK_SIZE + 123  # several blocks and a partial one


@pytest.fixture(scope="module", params=["boat", "auv"])
def platform_run(request):
    spec = PoseSpaceSpec(load_platform(request.param))
    return spec, sample_geometry(spec, N, seed=11), sample_pose_space(spec, N, seed=11)


def _frames(spec, g):
    """World poses rebuilt from R, t and the mounting: (R1, o1, Rv2, v2, o2)."""
    pf = spec.platform
    port1 = g["port1"]
    R1 = np.where(port1[:, None, None], pf.transducers["port"].rotation.as_matrix(),
                  pf.transducers["starboard"].rotation.as_matrix())
    o1 = np.where(port1[:, None], pf.transducers["port"].position_m,
                  pf.transducers["starboard"].position_m)
    R, t = g["R"], g["t"]
    R2 = np.einsum("nij,nkj->nik", R1, R)  # R1 R^T: sensor 2 -> world
    o2 = np.einsum("nij,nj->ni", R1, -np.einsum("nji,nj->ni", R, t)) + o1
    port2 = g["port2"]
    M2 = np.where(port2[:, None, None], pf.transducers["port"].rotation.as_matrix(),
                  pf.transducers["starboard"].rotation.as_matrix())
    m2 = np.where(port2[:, None], pf.transducers["port"].position_m,
                  pf.transducers["starboard"].position_m)
    Rv2 = np.einsum("nij,nkj->nik", R2, M2)
    v2 = o2 - np.einsum("nij,nj->ni", Rv2, m2)
    return R1, o1, R2, o2, Rv2, v2


def test_table_columns_and_rows(platform_run):
    spec, g, df = platform_run
    assert list(df.columns) == list(COLUMNS) and len(df) == N
    assert not df.drop(columns=["side1", "side2"]).isna().any().any()
    assert np.allclose(df["locus_length_normalized"], df["locus_length_m"] / df["mean_range_m"])
    assert np.allclose(df["mean_range_m"], (df["r1_m"] + df["r2_m"]) / 2)


def test_feature_inside_both_apertures(platform_run):
    spec, g, df = platform_run
    ap = spec.platform.sonar.aperture()
    p1 = spherical_to_cartesian(g["r1"], g["th1"], g["ph1"])
    p2 = np.einsum("nij,nj->ni", g["R"], p1) + g["t"]  # the kernel's transform
    assert np.allclose(np.linalg.norm(p2, axis=1), g["r2"], rtol=1e-9, atol=1e-9)
    # the boundary is allowed a rounding-level slack: shrink nothing, grow the aperture by 1e-9 deg
    from sss_locus import Aperture

    loose = Aperture(ap.azimuth_deg + 1e-7, ap.elevation_deg + 1e-7, ap.max_range + 1e-6)
    assert loose.contains(p1).all() and loose.contains(p2).all()
    assert np.abs(df["azimuth2_deg"]).max() <= ap.azimuth_deg / 2 + 1e-9
    # the true feature lies on the locus, so the visible locus is never empty
    assert (df["locus_length_m"] > 0).mean() > 0.999


def test_feature_below_both_sensors(platform_run):
    spec, g, df = platform_run
    R1, o1, R2, o2, Rv2, v2 = _frames(spec, g)
    f = np.einsum("nij,nj->ni", R1, spherical_to_cartesian(g["r1"], g["th1"], g["ph1"])) + o1
    assert (f[:, 2] < o1[:, 2]).all() and (f[:, 2] < o2[:, 2]).all()


def test_attitude_limits(platform_run):
    spec, g, df = platform_run
    pf = spec.platform
    *_, Rv2, _ = _frames(spec, g)
    pitch = np.degrees(np.arcsin(Rv2[:, 2, 0]))  # nose-up positive: z of the forward axis
    roll_z = Rv2[:, 2, 1]  # z of the port axis: 0 when roll = 0
    assert np.abs(pitch).max() <= pf.pitch_max_deg + 1e-9
    assert np.allclose(pitch, df["pitch2_deg"], atol=1e-9)
    assert np.abs(roll_z).max() < 1e-12
    if pf.pitch_max_deg > 0:  # the envelope is used, not just respected
        assert np.abs(pitch).max() > 0.99 * pf.pitch_max_deg
        assert stats.kstest(pitch / pf.pitch_max_deg, stats.uniform(-1, 2).cdf).pvalue > 1e-3
    yaw = np.degrees(np.arctan2(Rv2[:, 1, 0], Rv2[:, 0, 0]))
    assert np.allclose(np.cos(np.radians(yaw - df["yaw2_deg"])), 1.0)
    assert yaw.min() < -179 and yaw.max() > 179


def test_depth_constraints(platform_run):
    spec, g, df = platform_run
    pf = spec.platform
    *_, v2 = _frames(spec, g)
    if pf.fixed_depth:  # equal draft, exactly (rounding only)
        assert np.abs(v2[:, 2]).max() < 1e-9
    else:
        assert np.abs(v2[:, 2]).max() <= pf.depth_max_m - pf.depth_min_m
        assert np.abs(v2[:, 2]).max() > 0.5 * (pf.depth_max_m - pf.depth_min_m)
    assert np.allclose(-v2[:, 2], df["depth2_minus_depth1_m"], atol=1e-9)


def test_sides(platform_run):
    spec, g, df = platform_run
    assert (df["side1"] == "port").all()
    share = (df["side2"] == "port").mean()
    assert 0.3 < share < 0.7


@pytest.mark.parametrize("key", ["boat", "auv"])
def test_same_seed_same_table_whatever_the_chunk(key):
    spec = PoseSpaceSpec(load_platform(key))
    n = BLOCK_SIZE + 500
    ref = sample_pose_space(spec, n, seed=5, chunk_size=65536)
    for chunk in (1000, BLOCK_SIZE, BLOCK_SIZE + 1):
        pd.testing.assert_frame_equal(sample_pose_space(spec, n, seed=5, chunk_size=chunk), ref)
    pd.testing.assert_frame_equal(sample_pose_space(spec, 700, seed=5), ref.iloc[:700])
    other = sample_pose_space(spec, 700, seed=6)
    assert not np.allclose(other["r1_m"], ref["r1_m"].iloc[:700])


@pytest.mark.parametrize("key", ["boat", "auv"])
def test_scaling_law_on_sampled_configurations(key):
    spec = PoseSpaceSpec(load_platform(key))
    g = sample_geometry(spec, 2000, seed=3)
    ap = spec.platform.sonar.aperture()
    base = two_view_locus(g["R"], g["t"], g["r1"], g["r2"], ap, ap).length
    assert (base > 0).all()
    for k in (0.01, 0.37, 1.0 / 3.0):  # ranges stay inside max_range when shrunk
        scaled = two_view_locus(g["R"], k * g["t"], k * g["r1"], k * g["r2"], ap, ap).length
        np.testing.assert_allclose(scaled, k * base, rtol=1e-7, atol=1e-9 * k)


def test_feature_distribution_parameter():
    pf = load_platform("auv")
    ap = pf.sonar.aperture()
    angles = sample_geometry(PoseSpaceSpec(pf, profile="unconstrained"), 20000, seed=2)
    volume = sample_geometry(PoseSpaceSpec(pf, profile="unconstrained", feature_distribution="volume"),
                             20000, seed=2)
    rmax = ap.max_range
    assert stats.kstest(angles["r1"] / rmax, "uniform").pvalue > 1e-3
    assert stats.kstest((volume["r1"] / rmax) ** 3, "uniform").pvalue > 1e-3
    assert stats.kstest(volume["r1"] / rmax, "uniform").pvalue < 1e-6  # they really differ
    half = ap.half_azimuth_rad
    assert stats.kstest(angles["th1"], stats.uniform(-half, 2 * half).cdf).pvalue > 1e-3


def test_unconstrained_profile_is_any_orientation():
    pf = load_platform("auv")
    spec = PoseSpaceSpec(pf, profile="unconstrained")
    g = sample_geometry(spec, 20000, seed=4)
    *_, R2, o2, Rv2, v2 = _frames(spec, g)
    # uniform rotations: each rotated axis's z-component is uniform on [-1, 1]
    assert stats.kstest(R2[:, 2, 0], stats.uniform(-1, 2).cdf).pvalue > 1e-3
    f = o2 + np.einsum("nij,nj->ni", R2, spherical_to_cartesian(g["r2"], g["th2"], g["ph2"]))
    assert (f[:, 2] > o2[:, 2]).mean() > 0.2  # features above sensor 2 are not excluded


def test_pitch_override_and_bad_input():
    pf = load_platform("auv")
    df = sample_pose_space(PoseSpaceSpec(pf, pitch_max_deg=15.0), 3000, seed=1)
    assert df["pitch2_deg"].abs().max() <= 15.0 + 1e-9
    with pytest.raises(ValueError, match="profile"):
        PoseSpaceSpec(pf, profile="sideways")
    with pytest.raises(ValueError, match="side2"):
        PoseSpaceSpec(pf, side2="up")
    with pytest.raises(ValueError, match="n_samples"):
        sample_pose_space(PoseSpaceSpec(pf), 0, seed=1)
    with pytest.raises(ValueError, match="seed"):
        sample_pose_space(PoseSpaceSpec(pf), 10, seed=-1)
    with pytest.raises(ValueError, match="chunk_size"):
        sample_pose_space(PoseSpaceSpec(pf), 10, seed=1, chunk_size=0)


def test_tilt_override_moves_the_fan():
    """With the boat's transducers tilted to 45 deg, features up to 70 deg below the horizontal
    are seen; with 25 deg (half the fan), none above it."""
    pf = load_platform("boat")
    for tilt in (25.0, 45.0):
        spec = PoseSpaceSpec(pf, tilt_deg=tilt)
        assert spec.platform.transducers["port"].tilt_deg == tilt
        df = sample_pose_space(spec, 3000, seed=2)
        depression = tilt + df["azimuth1_deg"]  # level vehicle, elevation ~ 0
        assert depression.min() >= -1e-9 and depression.max() <= tilt + 25.0 + 1e-9
        assert depression.max() > tilt + 24.0


def test_vehicle_depths_keep_vehicle_2_in_the_water():
    pf = load_platform("auv")
    span = pf.depth_max_m - pf.depth_min_m
    fixed = sample_pose_space(PoseSpaceSpec(pf, vehicle1_depth_m=pf.depth_min_m), N, seed=5)
    depth2 = pf.depth_min_m + fixed["depth2_minus_depth1_m"]  # vehicle 1 at its shallowest depth
    assert depth2.min() >= pf.depth_min_m - 1e-9 and depth2.max() <= pf.depth_max_m + 1e-9
    old = sample_pose_space(PoseSpaceSpec(pf, vehicle_depths="difference"), N, seed=5)
    assert (pf.depth_min_m + old["depth2_minus_depth1_m"] < 0).mean() > 0.2  # above the surface, often
    assert np.abs(old["depth2_minus_depth1_m"]).max() <= span
    # vehicle 1's depth drawn uniformly in the range: a sample of the "difference" rule is kept
    # with probability (span - |d|) / span, so its weighted mean of |d| predicts the new rule's
    drawn = sample_pose_space(PoseSpaceSpec(pf), 4 * N, seed=6)
    d_old = np.abs(sample_pose_space(PoseSpaceSpec(pf, vehicle_depths="difference"), 4 * N, seed=6)
                   ["depth2_minus_depth1_m"].to_numpy())
    w = (span - d_old) / span
    predicted = float((d_old * w).sum() / w.sum())
    assert abs(np.abs(drawn["depth2_minus_depth1_m"]).mean() / predicted - 1) < 0.03
    boat = load_platform("boat")  # fixed depth: the rule does not apply, the table is unchanged
    assert sample_pose_space(PoseSpaceSpec(boat), 500, seed=1).equals(
        sample_pose_space(PoseSpaceSpec(boat, vehicle_depths="difference"), 500, seed=1))
    with pytest.raises(ValueError, match="vehicle1_depth_m must lie in platform 'auv'"):
        PoseSpaceSpec(pf, vehicle1_depth_m=-1.0)
    with pytest.raises(ValueError, match="vehicle_depths must be one of"):
        PoseSpaceSpec(pf, vehicle_depths="surface")
