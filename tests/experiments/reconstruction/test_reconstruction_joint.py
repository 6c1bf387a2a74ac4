"""The beam-plane and joint estimators as chapter estimators: exact without noise where the ranges
determine the feature, on the same views as the others; the joint one refuses per-view errors."""

from __future__ import annotations

import numpy as np
import pytest

from sss_locus.experiments.datamodel.envelopes import load_envelope
from sss_locus.experiments.datamodel.noise_model import load_noise_model
from sss_locus.experiments.passes.pass_noise import load_pass_noise
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.reconstruction.estimators import reconstruct
from sss_locus.experiments.reconstruction.joint import adjustment_estimators
from sss_locus.experiments.datamodel.terrain import place_features, random_terrain
from sss_locus.experiments.reconstruction.terrain_survey import SurveyLayout, observe_features

LAYOUT = SurveyLayout(area_m=200.0, line_spacing_m=60.0, cross_line_spacing_m=100.0, margin_m=50.0)


def _survey(key="auv"):
    pf, env = load_platform(key), load_envelope(key)
    ter = random_terrain(2.0, 25.0, 800.0, 2.5, seed=1)
    f = place_features(ter, 60, LAYOUT.area_m, seed=2)
    views, seen, info = observe_features(pf, ter, f, LAYOUT, 15.0, env.same_altitude, seed=3)
    return pf, views, seen, info


def test_noise_free_beam_and_joint_recover_features_seen_three_times():
    pf, views, seen, info = _survey()
    tab = reconstruct(views, seen, info["sensor_height_m"], load_noise_model("auv").scaled(0.0), pf.sonar.aperture(),
                      seed=4, navigation="per_pass", pass_noise=load_pass_noise("auv").scaled(0.0),
                      along_m=info["along_m"], extra=adjustment_estimators(pf.sonar.elevation_deg))
    for est in ("beam", "joint"):
        t = tab[(tab.estimator == est) & (tab.n_seen >= 3)]
        assert len(t) > 30 and t.estimated.all()
        # the ranges are exact (sigma 1e-6 m); the beam-plane angle's 0 is off by the in-beam elevation
        assert t.error_3d_m.max() < 1e-3, est
    flat = tab[(tab.estimator == "flat") & (tab.n_seen >= 3)]
    assert flat.error_3d_m.median() > 0.5  # 2 m RMS relief: the baseline is not exact, so the test can fail


def test_joint_needs_the_per_pass_model():
    pf, views, seen, info = _survey()
    with pytest.raises(ValueError, match="per_pass"):
        reconstruct(views, seen, info["sensor_height_m"], load_noise_model("auv"), pf.sonar.aperture(), seed=4,
                    pass_noise=load_pass_noise("auv"), along_m=info["along_m"],
                    extra=adjustment_estimators(pf.sonar.elevation_deg, ["joint"]))
    with pytest.raises(ValueError, match="names must be among"):
        adjustment_estimators(0.5, ["bundle"])
