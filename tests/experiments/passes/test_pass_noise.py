"""Navigation errors shared per pass (sss_locus.experiments.passes.pass_noise) against invariants and
sample statistics, and their use by the reconstruction estimators."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sss_locus.experiments.datamodel.envelopes import load_envelope
from sss_locus.experiments.datamodel.noise_model import NoiseModel, load_noise_model, parse_noise_model
from sss_locus.experiments.passes.pass_noise import load_pass_noise
from sss_locus.experiments.passes.pass_noise import PASS_FIELDS, PassNoise, parse_pass_noise, view_errors
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.reconstruction.estimators import reconstruct
from sss_locus.experiments.datamodel.terrain import place_features, random_terrain
from sss_locus.experiments.reconstruction.terrain_survey import SurveyLayout, observe_features

LAYOUT = SurveyLayout(area_m=200.0, line_spacing_m=60.0, cross_line_spacing_m=100.0, margin_m=50.0)


def test_pass_errors_are_shared_by_every_ping_of_a_pass():
    n, L = 50, 6
    sig = np.ones((n, L, 7))
    along = np.random.default_rng(1).random((n, L)) * 400
    p = PassNoise(pass_offset_sigma_m=2.0, pass_heading_bias_sigma_deg=1.0, drift_sigma_fraction=0.01)
    d = view_errors(sig, np.random.default_rng(2).standard_normal((n, L, 7)), model="per_pass", pass_noise=p,
                    along_m=along, rng=np.random.default_rng(3))
    # no jitter: the heading error is one number per pass, the position error affine in the distance travelled
    assert np.all(d[..., 6] == d[:1, :, 6])
    for l in range(L):
        A = np.stack([np.ones(n), along[:, l]], axis=1)
        coef, *_ = np.linalg.lstsq(A, d[:, l, 1:3], rcond=None)
        assert np.allclose(A @ coef, d[:, l, 1:3], atol=1e-12)
    # range, vertical, roll and pitch stay per view: standard * sigma
    z = np.random.default_rng(2).standard_normal((n, L, 7))
    assert np.array_equal(d[..., [0, 3, 4, 5]], z[..., [0, 3, 4, 5]])
    # per view: everything standard * sigma
    assert np.array_equal(view_errors(2 * sig, z, model="per_view"), 2 * z)


def test_pass_error_sigmas_match_sample_statistics():
    n, L = 3, 20_000
    sig = np.zeros((n, L, 7))
    p = PassNoise(pass_offset_sigma_m=2.0, pass_heading_bias_sigma_deg=1.5, drift_sigma_fraction=0.005,
                  ping_horizontal_sigma_m=0.3, ping_heading_sigma_deg=0.2)
    along = np.tile(np.array([[0.0], [100.0], [400.0]]), (1, L))
    d = view_errors(sig, np.random.default_rng(4).standard_normal((n, L, 7)), model="per_pass", pass_noise=p,
                    along_m=along, rng=np.random.default_rng(5))
    for i, s in enumerate(along[:, 0]):
        want = math.hypot(math.hypot(2.0, 0.005 * s), 0.3)
        assert np.std(d[i, :, 1]) == pytest.approx(want, rel=0.03) and np.std(d[i, :, 2]) == pytest.approx(want, rel=0.03)
    assert np.std(d[0, :, 6]) == pytest.approx(math.radians(math.hypot(1.5, 0.2)), rel=0.03)
    # two pings of one pass share the offset: their difference is jitter and drift only
    diff = d[2, :, 1] - d[1, :, 1]
    assert np.std(diff) == pytest.approx(math.hypot(0.005 * 300, 0.3 * math.sqrt(2)), rel=0.03)


def test_reconstruct_moves_every_sensor_of_a_pass_alike():
    """Through the estimators: the navigated sensor origins of one pass are the true ones moved by
    one vector (no jitter, no drift), and their axes turned by one heading bias."""
    pf, env = load_platform("auv"), load_envelope("auv")
    ter = random_terrain(1.0, 25.0, 800.0, 2.5, seed=1)
    f = place_features(ter, 80, LAYOUT.area_m, seed=2)
    views, seen, info = observe_features(pf, ter, f, LAYOUT, 15.0, env.same_altitude, seed=3)
    got = {}

    def capture(inputs):
        got.update(inputs)
        return np.zeros((len(f), 3)), np.zeros(len(f), bool)

    p = PassNoise(pass_offset_sigma_m=2.0, pass_heading_bias_sigma_deg=1.0)
    reconstruct(views, seen, info["sensor_height_m"], load_noise_model("auv"), pf.sonar.aperture(), seed=4,
                navigation="per_pass", pass_noise=p, along_m=info["along_m"], extra={"capture": capture})
    for l in range(seen.shape[1]):
        i = np.flatnonzero(seen[:, l])
        shift = got["origin"][i, l, :2] - views.origin[i, l, :2]
        assert np.allclose(shift, shift[0], atol=1e-9)
        rot = got["W"][i, l] @ np.transpose(views.W[i, l], (0, 2, 1))  # the attitude error of each ping
        yaw = np.arctan2(rot[:, 1, 0], rot[:, 0, 0])
        assert np.std(yaw) < 0.5 * math.radians(0.1)  # roll and pitch noise of 0.1 deg only
    shifts = [got["origin"][np.flatnonzero(seen[:, l])[0], l, :2] - views.origin[np.flatnonzero(seen[:, l])[0], l, :2]
              for l in range(seen.shape[1]) if seen[:, l].any()]
    assert np.std(np.array(shifts)[:, 0]) > 0.3  # passes differ


def test_noise_file_and_fallback():
    auv = load_pass_noise("auv")
    assert auv.drift_sigma_fraction > 0 and auv.pass_offset_sigma_m > 0
    doc = {"noise": {"mine": {k: {"value": v, "assumption": "test"} for k, v in
                              NoiseModel(0.01, horizontal_sigma_m=1.5, heading_sigma_deg=0.7).key().items()}}}
    t = doc["noise"]["mine"]
    fallback = parse_pass_noise(t, "noise.mine", parse_noise_model(doc, "mine"))
    assert fallback == PassNoise(pass_offset_sigma_m=1.5, pass_heading_bias_sigma_deg=0.7)
    t[PASS_FIELDS[0]] = {"value": 1.0, "assumption": "test"}
    parse_noise_model(doc, "mine")  # the per-pass keys are allowed in the table
    with pytest.raises(ValueError, match="per-pass navigation keys but not"):
        parse_pass_noise(t, "noise.mine", parse_noise_model(doc, "mine"))
    with pytest.raises(ValueError, match="model must be one of"):
        view_errors(np.ones((1, 1, 7)), np.ones((1, 1, 7)), model="per_feature")
    with pytest.raises(ValueError, match="needs pass_noise"):
        view_errors(np.ones((1, 1, 7)), np.ones((1, 1, 7)), model="per_pass")
