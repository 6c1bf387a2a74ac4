"""Noise model (sss_locus.experiments.datamodel.noise_model), its propagation
(sss_locus.experiments.passes.propagation), the noise chapter's study (sss_locus.experiments.noise.study)
and the pass geometry it uses (sss_locus.experiments.passes.view_sets).

* the Monte Carlo percentile and the first-order (Jacobian) estimate agree for small noise, for
  the band of the two-view locus and for the three-view point;
* the closed-form nearest / farthest distances to a cropped locus agree with a dense walk along
  the kernel's arcs;
* without noise nothing moves; each error group perturbs what it should and nothing else;
* the pass geometry reproduces the survey simulation's ranges and puts the feature inside every
  sensor's aperture;
* bad input is rejected with the argument named.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from sss_locus import Aperture, two_view_locus
from sss_locus.experiments.datamodel.noise_model import NoiseModel, load_noise_model
from sss_locus.experiments.passes.propagation import first_order, monte_carlo, noise_sigmas, perturb, two_view_offsets
from sss_locus.experiments.stats.gaussian_norm import gaussian_norm_quantile
from sss_locus.experiments.noise.study import survey_noise_table
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.datamodel.envelopes import OffsetModel, load_envelope
from sss_locus.experiments.survey_passes.study import simulate_passes
from sss_locus.experiments.three_views.patterns import PATTERNS
from sss_locus.experiments.passes.view_sets import draw_pattern, views_from_survey

FULL = Aperture(360.0, 180.0, 1e4)


@pytest.fixture(scope="module")
def auv():
    return load_platform("auv")


@pytest.fixture(scope="module")
def pattern(auv):
    views, _ = draw_pattern(auv, load_envelope("auv"), PATTERNS["three headings 60 deg apart"], 12, seed=3)
    return views


def test_noise_file_has_both_platforms_and_validates(tmp_path):
    for key in ("auv", "boat"):
        m = load_noise_model(key)
        assert m.range_resolution_m > 0 and m.horizontal_sigma_m > 0 and m.heading_sigma_deg > 0
    with pytest.raises(ValueError, match=r"no \[noise.submarine\] table .*\[noise\] has .auv., .boat."):
        load_noise_model("submarine")
    bad = tmp_path / "noise.toml"
    bad.write_text('[noise.auv]\nrange_resolution_m = { value = 0.01 }\n')
    with pytest.raises(ValueError, match="source"):
        load_noise_model("auv", bad)
    with pytest.raises(ValueError, match="heading_sigma_deg"):
        NoiseModel(0.01, heading_sigma_deg=-1.0)
    with pytest.raises(ValueError, match="k must"):
        NoiseModel(0.01).scaled(np.nan)


@pytest.mark.parametrize("kind, key, q", [("two", "circle_miss_q", 0.95), ("three", "point_error_q", 0.95),
                                          ("two", "circle_miss_q", 0.5)])
def test_monte_carlo_agrees_with_first_order_for_small_noise(auv, pattern, kind, key, q):
    views = pattern if kind == "three" else pattern.select(0, 2)
    noise = load_noise_model("auv").scaled(1e-3)
    mc = monte_carlo(views, noise, FULL, kind=kind, n_draws=4000, seed=5, quantile=q)
    lin = gaussian_norm_quantile(first_order(views, noise, FULL, kind=kind), q)
    np.testing.assert_allclose(mc[key].to_numpy(), lin, rtol=0.06)
    # and at 200 times the noise the linear estimate is 200 times larger (exactly, by design),
    # while the Monte Carlo one need not be: only the small-noise agreement is claimed
    lin2 = gaussian_norm_quantile(first_order(views, noise.scaled(200.0), FULL, kind=kind), q)
    np.testing.assert_allclose(lin2, 200 * lin, rtol=1e-3)


def test_without_noise_nothing_moves(pattern):
    views = pattern.select(0, 1)
    mc = monte_carlo(views, load_noise_model("auv").scaled(0.0), Aperture(130.0, 0.27, 150.0),
                     n_draws=3, seed=1)
    R, t = views.relative(0, 1)
    r = views.ranges
    ref = two_view_locus(R, t, r[:, 0], r[:, 1], Aperture(130.0, 0.27, 150.0), Aperture(130.0, 0.27, 150.0))
    np.testing.assert_allclose(mc["length0_m"], ref.length, rtol=1e-12)
    np.testing.assert_allclose(mc["length_median_m"], ref.length, rtol=1e-12)
    assert np.all(mc["circle_miss_q"] < 1e-9) and np.all(mc["near_q"] < 1e-6)
    assert np.all(mc["far0_m"] <= mc["length0_m"] + 1e-9) and np.all(mc["empty_fraction"] == 0)


def test_each_error_group_perturbs_only_its_part(pattern):
    views = pattern.select(0, 1)
    base = load_noise_model("auv")
    e = np.random.default_rng(2).standard_normal((len(views.feature), 1, 2, 7))
    W0, o0, r0 = views.W[:, None], views.origin[:, None], views.ranges[:, None]
    W, o, r = perturb(views, noise_sigmas(views, base.only("range")), e)
    assert np.array_equal(np.broadcast_to(W0, W.shape), W) and np.array_equal(np.broadcast_to(o0, o.shape), o)
    np.testing.assert_allclose(r - r0, e[..., 0] * base.range_sigma_m(r0), rtol=1e-9, atol=1e-12)
    W, o, r = perturb(views, noise_sigmas(views, base.only("position")), e)
    np.testing.assert_allclose((o - o0)[..., :2], e[..., 1:3] * base.horizontal_sigma_m, rtol=1e-12)
    np.testing.assert_allclose((o - o0)[..., 2], e[..., 3] * base.vertical_sigma_m, rtol=1e-9, atol=1e-12)
    assert np.allclose(W, W0) and np.allclose(r, r0)
    # heading only: a rotation about the vehicle's up axis (pitched vehicles: not world z)
    only_h = NoiseModel(0.0, heading_sigma_deg=1.0)
    W, o, r = perturb(views, noise_sigmas(views, only_h), e)
    up = views.vehicle[:, None, :, :, 2]  # vehicle z axes in the world, (n, 1, 2, 3)
    for i in range(3):
        np.testing.assert_allclose(np.sum(W[..., :, i] * up, -1), np.sum(W0[..., :, i] * up, -1), atol=1e-12)
    ang = Rotation.from_matrix((W @ np.swapaxes(W0, -1, -2)).reshape(-1, 3, 3)).magnitude()
    np.testing.assert_allclose(ang, np.abs(np.radians(1.0) * e[..., 6]).ravel(), rtol=1e-9)


def test_near_and_far_match_a_dense_walk_along_the_arcs(pattern):
    views = pattern.select(0, 1)
    ap = Aperture(130.0, 20.0, 150.0)  # wide enough that perturbed loci are rarely empty
    e = np.random.default_rng(4).standard_normal((len(views.feature), 6, 2, 7))
    W, o, r = perturb(views, noise_sigmas(views, load_noise_model("auv").scaled(0.3)), e)
    f = views.feature[:, None, :]
    out = two_view_offsets(W, o, r, f, ap)
    from sss_locus import relative_pose
    R, t = relative_pose(W[..., 0, :, :], o[..., 0, :], W[..., 1, :, :], o[..., 1, :])
    loc = two_view_locus(R, t, r[..., 0], r[..., 1], ap, ap)
    pts = loc.points(n_per_arc=4000)  # (n, 6, MAX_ARCS, 4000, 3), frame 1
    world = np.einsum("...ij,...abj->...abi", W[..., 0, :, :], pts) + o[..., 0, None, None, :]
    d = np.linalg.norm(world - f[..., None, None, :], axis=-1)
    walk_near = np.nanmin(np.where(np.isnan(d), np.inf, d), axis=(-2, -1))
    walk_far = np.nanmax(np.where(np.isnan(d), -np.inf, d), axis=(-2, -1))
    ok = ~out["empty"]
    assert ok.sum() > 20
    scale = np.max(loc.radius) * 2 * np.pi / 4000  # walk step
    assert np.all(np.abs(out["near_m"][ok] - walk_near[ok]) <= scale)
    assert np.all(out["near_m"][ok] <= walk_near[ok] + 1e-9)
    assert np.all(np.abs(out["far_m"][ok] - walk_far[ok]) <= scale)
    assert np.all(out["far_m"][ok] >= walk_far[ok] - 1e-9)
    assert np.all(np.isnan(out["near_m"][~ok]))


def test_pass_geometry_matches_the_survey_simulation(auv):
    samples, _ = simulate_passes(auv, load_envelope("auv"), OffsetModel("independent"), [0.0, 35.0, 150.0], 40, 7)
    views = views_from_survey(auv, samples)
    np.testing.assert_allclose(views.ranges, samples[["r1_m", "r2_m"]].to_numpy(), rtol=1e-10)


@pytest.mark.parametrize("key", ["auv", "boat"])
def test_pattern_views_see_the_feature(key):
    pf = load_platform(key)
    views, draws = draw_pattern(pf, load_envelope(key), PATTERNS["two lines + cross line"], 50, seed=8)
    ap = pf.sonar.aperture()
    p = np.einsum("nkji,nkj->nki", views.W, views.feature[:, None, :] - views.origin)
    assert np.all(ap.contains(p))
    assert len(draws) == 50 and set(draws["heading3_deg"]) == {90.0}
    if key == "boat":  # level, one altitude
        assert np.allclose(draws["pitch1_deg"], 0.0) and np.allclose(draws["altitude1_m"], draws["altitude3_m"])


def test_bad_input(pattern):
    noise = load_noise_model("auv")
    with pytest.raises(ValueError, match="kind"):
        monte_carlo(pattern, noise, FULL, kind="four")
    with pytest.raises(ValueError, match="views must hold 2"):
        monte_carlo(pattern, noise, FULL, kind="two")
    with pytest.raises(ValueError, match="n_draws"):
        monte_carlo(pattern, noise, FULL, kind="three", n_draws=1)
    with pytest.raises(ValueError, match="aperture"):
        first_order(pattern, noise, (130.0, 0.27, 150.0), kind="three")
    with pytest.raises(ValueError, match="quantile"):
        monte_carlo(pattern, noise, FULL, kind="three", quantile=1.5)
    with pytest.raises(ValueError, match="groups"):
        noise.only("sound")


def test_survey_noise_table_columns_and_definitions(auv):
    samples, _ = simulate_passes(auv, load_envelope("auv"), OffsetModel("independent"), [0.0, 90.0], 10, 3)
    base = load_noise_model("auv")
    tab = survey_noise_table(auv, samples, {"x1": base, "range": base.only("range")}, n_draws=8, seed=2)
    assert list(tab["noise"].unique()) == ["x1", "range"] and len(tab) == 2 * len(samples)
    one = tab[tab.noise == "x1"]
    np.testing.assert_allclose(one.locus_length_m, samples.locus_length_m, rtol=1e-12)
    np.testing.assert_allclose(one.extent_m, np.hypot(one.locus_length_m, one.band_width_m))
    mc = monte_carlo(views_from_survey(auv, samples), base, auv.sonar.aperture(), n_draws=8, seed=2)
    np.testing.assert_allclose(one.band_width_m, 2 * mc.circle_miss_q)
    # range errors alone empty the locus less often than all errors together
    assert tab[tab.noise == "range"].empty_fraction.mean() <= one.empty_fraction.mean()
