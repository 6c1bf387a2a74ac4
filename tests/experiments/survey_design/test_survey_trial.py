"""A new user's trial (a 900 kHz ROV over a 3 km L-shaped block of Bedford Basin with an island
hole; their files, unchanged, in ``tests/data/trial/rov9.toml`` and ``bedford.toml``): on
seed 3 the standard plan saw every feature on two or more passes, yet its joint estimate had
none, because the solve stopped on the reconstruction chapter's evaluation limit (400) while
one feature still moved along a narrow valley between its two minima (it converges at 624)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from sss_locus.experiments.datamodel import userdata
from sss_locus.experiments.datamodel.noise_model import load_noise_model
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.passes.pass_noise import load_pass_noise
from sss_locus.experiments.survey_design.area import load_area
from sss_locus.experiments.survey_design.front import make_setting
from sss_locus.experiments.survey_design.joint import plan_joint_errors
from sss_locus.experiments.survey_design.plans import standard_plan

DATA = Path(__file__).parents[2] / "data" / "trial"


@pytest.fixture
def rov9():
    userdata.use([str(DATA / "rov9.toml")], [])
    try:
        yield load_platform("rov9"), load_noise_model("rov9"), load_pass_noise("rov9")
    finally:
        userdata.use()  # leave the process with the shipped data only


def test_the_standard_plan_estimates_every_feature_it_saw_twice_on_the_trial_seed(rov9):
    """Seed 3 of the user's quick run (60 features): the quadratic joint solve of a simulation
    with known association converges, so every feature seen on two or more passes is estimated
    (an invariant of the estimator), and its horizontal error is of the order of the USBL's
    2 m per-pass offset, not a lost seed (old code: 0 features, NaN errors)."""
    pf, noise, pn = rov9
    area = load_area(DATA / "bedford.toml")
    s = make_setting(pf, area, "flat", n_features=60, seed=3, grid_m=40.0)
    plan = standard_plan(pf, area, s.terrain, s.settings, s.heights_m)
    ev = plan_joint_errors(s, plan, noise, pn, seed=3)
    assert ev["n_passes"] > 100 and ev["n_seen_twice"] == 60
    assert ev["n_joint"] == ev["n_seen_twice"]
    assert 0.0 < ev["horizontal_median_m"] < 2.0 * pn.pass_offset_sigma_m
    assert np.isfinite(ev["shape_median_m"])
