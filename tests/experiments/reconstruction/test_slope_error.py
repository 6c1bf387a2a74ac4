"""The closed-form flat-seafloor error on a slope against a brute-force construction written for
the test, and against the chapter's simulated survey."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sss_locus.experiments.datamodel.envelopes import load_envelope
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.reconstruction.slope_error import flat_slope_error, slope_views
from sss_locus.experiments.datamodel.terrain import load_terrain_config
from sss_locus.experiments.reconstruction.terrain_survey import SurveyLayout


def _brute_force(y, H, slope_deg, a):
    """Sensor at (0, 0, H) over the point (0, 0, 0) of a plane rising across track; the feature at
    (a, y, y tan(slope)). Slant-range correction by bisection: the point (0, g, 0) of the flat
    seafloor in the vertical across-track plane at the measured range from the sensor."""
    t = math.tan(math.radians(slope_deg))
    f = np.array([a, y, y * t])
    r = np.linalg.norm(f - np.array([0.0, 0.0, H]))
    lo, hi = 0.0, 10 * r
    for _ in range(200):
        g = 0.5 * (lo + hi)
        lo, hi = (g, hi) if math.hypot(g, H) < r else (lo, g)
    est = np.array([0.0, 0.5 * (lo + hi), 0.0])
    return est - f


@pytest.mark.parametrize("y,H,slope,a", [(80.0, 15.0, 10.0, 0.0), (120.0, 20.0, -7.0, 0.6),
                                         (30.0, 40.0, 20.0, -0.3), (145.0, 10.0, 3.0, 0.0)])
def test_closed_form_against_brute_force(y, H, slope, a):
    d = _brute_force(y, H, slope, a)
    c = flat_slope_error(y, H, slope, a)
    assert c["across_m"] == pytest.approx(d[1], abs=1e-9)
    assert c["vertical_m"] == pytest.approx(d[2], abs=1e-12)
    assert c["error_3d_m"] == pytest.approx(np.linalg.norm(d), abs=1e-9)


def test_small_slope_expansion():
    """For a = 0 and small slopes: y_hat - y ~ -H tan(b) + y tan^2(b) / 2 (the docstring's)."""
    y, H, b = 100.0, 15.0, 0.5
    t = math.tan(math.radians(b))
    assert flat_slope_error(y, H, b)["across_m"] == pytest.approx(-H * t + y * t * t / 2, rel=2e-3)


@pytest.mark.parametrize("key", ["auv", "boat"])
def test_closed_form_against_the_simulated_survey(key):
    pf, env = load_platform(key), load_envelope(key)
    config = load_terrain_config()
    layout = SurveyLayout(area_m=300.0, line_spacing_m=240.0, cross_line_spacing_m=120.0, margin_m=60.0)
    t = slope_views(pf, env, config, [0.0, 8.0, 20.0], layout, n_features=80, seed=5)
    assert set(t.slope_deg) == {0.0, 8.0, 20.0} and len(t) > 60
    for what in ("across", "vertical", "3d"):
        assert np.allclose(t[f"simulated_{what}_m"], t[f"closed_{what}_m"], atol=1e-6)
    steep = t[t.slope_deg == 20.0]
    assert steep.simulated_3d_m.median() > 5.0  # not a vacuous match: metres of error on 20 degrees
