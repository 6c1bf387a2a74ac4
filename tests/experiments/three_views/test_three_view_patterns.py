"""Three passes over one feature (sss_locus.experiments.passes.view_sets.three_view_table / heading_sweep): the kernel
recovers the true feature on survey-pattern geometry, and the sweep covers its grid."""

from __future__ import annotations

import numpy as np
import pytest

from sss_locus.experiments.datamodel.noise_model import NoiseModel
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.datamodel.envelopes import load_envelope
from sss_locus.geometry.three_view_points import ThreeViewStatus
from sss_locus.experiments.three_views.patterns import PATTERNS, heading_sweep, three_view_table
from sss_locus.experiments.passes.view_sets import draw_pattern


@pytest.mark.parametrize("key", ["auv", "boat"])
@pytest.mark.parametrize("pattern", list(PATTERNS))
def test_pattern_feature_is_recovered(key, pattern):
    pf = load_platform(key)
    views, _ = draw_pattern(pf, load_envelope(key), PATTERNS[pattern], 200, seed=11)
    tab = three_view_table(views, pf.sonar.aperture())
    # the feature is inside all three apertures, so a valid candidate exists and it is the feature
    assert np.all(tab.n_valid >= 1)
    assert np.all(tab.feature_error_m <= 1e-6 * tab.r1_m)
    assert np.all(np.isin(tab.status, [ThreeViewStatus.TWO_POINTS, ThreeViewStatus.ONE_POINT]))
    # lifting a bound can only keep more candidates
    assert np.all(tab.n_valid_no_elevation >= tab.n_valid) and np.all(tab.n_valid_no_azimuth >= tab.n_valid)


def test_conditioning_column_scales_with_the_range_error():
    pf = load_platform("auv")
    views, _ = draw_pattern(pf, load_envelope("auv"), PATTERNS["two lines + cross line"], 30, seed=12)
    a = three_view_table(views, pf.sonar.aperture(), NoiseModel(0.01))
    b = three_view_table(views, pf.sonar.aperture(), NoiseModel(0.03))
    np.testing.assert_allclose(b.point_error_q95_m, 3 * a.point_error_q95_m, rtol=1e-3)


def test_heading_sweep_grid_and_bad_input():
    pf = load_platform("boat")
    sw = heading_sweep(pf, load_envelope("boat"), [0.0, 90.0], [0.0, 90.0, 180.0], 20, seed=1)
    assert list(zip(sw.heading2_deg, sw.heading3_deg)) == [(0, 0), (0, 90), (0, 180), (90, 90), (90, 180)]
    assert np.all((sw.resolved_fraction + sw.ambiguous_fraction) <= 1.0)
    views, _ = draw_pattern(pf, load_envelope("boat"), (0.0, 90.0), 5, seed=1)
    with pytest.raises(ValueError, match="3 views"):
        three_view_table(views, pf.sonar.aperture())
    with pytest.raises(ValueError, match="headings_deg"):
        draw_pattern(pf, load_envelope("boat"), [[0.0, 1.0]], 5, seed=1)
    with pytest.raises(ValueError, match="n must"):
        draw_pattern(pf, load_envelope("boat"), (0.0,), 0, seed=1)


@pytest.mark.parametrize("count, n", [(0, 4000), (4, 4000), (24, 4000), (3, 10), (10, 10)])
def test_share_upper_bound_is_the_one_sided_clopper_pearson_bound(count, n):
    from scipy.stats import binomtest

    from sss_locus.experiments.three_views.patterns import share_upper_bound

    upper = share_upper_bound(count, n, 0.95)
    ref = binomtest(count, n, alternative="less").proportion_ci(0.95, method="exact").high
    assert upper == pytest.approx(ref, rel=1e-9, abs=1e-12)
    if count < n:  # the defining property: seeing <= count is just 5 % likely at the bound
        from scipy.stats import binom
        assert binom.cdf(count, n, upper) == pytest.approx(0.05, rel=1e-6)
    if count == 0:
        assert upper == pytest.approx(1 - 0.05 ** (1 / n), rel=1e-9)  # the "rule of three" form


@pytest.mark.parametrize("count, n, level", [(-1, 10, 0.95), (11, 10, 0.95), (1, 0, 0.95), (1, 10, 1.0),
                                             (1.5, 10, 0.95), (True, 10, 0.95)])
def test_share_upper_bound_refuses_bad_input(count, n, level):
    from sss_locus.experiments.three_views.patterns import share_upper_bound

    with pytest.raises(ValueError):
        share_upper_bound(count, n, level)
