"""The survey over a non-flat seafloor and the estimators on it, against independent checks."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from sss_locus.experiments.datamodel.envelopes import load_envelope
from sss_locus.experiments.datamodel.noise_model import load_noise_model
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.reconstruction.estimators import reconstruct, summarise
from sss_locus.experiments.datamodel.terrain import (flat_terrain, place_features, random_terrain, slope_terrain,
                                                     step_terrain)
from sss_locus.experiments.reconstruction.terrain_survey import SurveyLayout, observe_features, ray_blocked

LAYOUT = SurveyLayout(area_m=200.0, line_spacing_m=60.0, cross_line_spacing_m=100.0, margin_m=50.0)


def test_layout_lines():
    h, c = LAYOUT.lines()
    assert list(h) == [0.0, 180.0, 0.0, 180.0, 90.0, 270.0, 90.0]
    assert np.allclose(c[:4, 1], [-90, -30, 30, 90]) and np.allclose(c[4:, 0], [-100, 0, 100])
    with pytest.raises(ValueError, match="line_spacing_m"):
        SurveyLayout(100.0, 0.0, 10.0)


@pytest.mark.parametrize("key", ["auv", "boat"])
def test_seen_features_are_inside_the_true_aperture(key):
    pf, env = load_platform(key), load_envelope(key)
    ter = random_terrain(2.0, 25.0, 800.0, 2.5, seed=1)
    f = place_features(ter, 300, LAYOUT.area_m, seed=2)
    views, seen, info = observe_features(pf, ter, f, LAYOUT, 15.0, env.same_altitude, seed=3)
    assert seen.any(axis=1).mean() > 0.9
    p = np.einsum("nkji,nkj->nki", views.W, f[:, None, :] - views.origin)
    inside = pf.sonar.aperture().contains(p)
    # the ping's elevation is inside the beam by construction; rounding at the beam edge aside
    assert np.all(inside[seen] | (np.abs(np.arcsin(p[seen][:, 2] / np.linalg.norm(p[seen], axis=1)))
                                  > math.radians(pf.sonar.elevation_deg / 2) * (1 - 1e-9)))
    assert not np.any(pf.sonar.aperture().contains(p)[~seen] & (info["reason"][~seen] == 2))
    # altitude: the transducer above the seafloor under it (terrain following for the AUV)
    h = info["sensor_height_m"][seen]
    if env.same_altitude:
        assert np.allclose(views.origin[..., 2][seen], 15.0 - 0.10, atol=1e-9)  # boat draft 0.10 m
    else:
        assert np.all(np.abs(h - 15.0) < 1.0)  # level vehicle, terrain within a beam's reach


def test_shadowing_by_a_ridge():
    ridge = step_terrain(-40.0, 6.0, 0.0)  # a 40 m high wall along the x axis
    blocked = ray_blocked(ridge, np.array([[0.0, -30.0, 20.0], [0.0, 30.0, 20.0]]),
                          np.array([[0.0, 40.0, 0.0], [0.0, 40.0, 0.0]]))
    assert list(blocked) == [True, False]
    pf, env = load_platform("auv"), load_envelope("auv")
    f = np.array([[0.0, 45.0, 0.0], [0.0, -45.0, 0.0]])
    v_off, s_off, _ = observe_features(pf, ridge, f, LAYOUT, 15.0, True, seed=1, shadowing="off")
    v_on, s_on, info = observe_features(pf, ridge, f, LAYOUT, 15.0, True, seed=1, shadowing="on")
    assert s_on.sum() < s_off.sum() and np.all(s_on <= s_off)
    assert np.array_equal(info["shadowed"], s_off & ~s_on)


@pytest.mark.parametrize("terrain", [flat_terrain(), slope_terrain(4.0), random_terrain(2.0, 25.0, 800.0, 2.5, 5)],
                         ids=["flat", "slope", "rough"])
def test_noise_free_estimates(terrain):
    pf, env, noise = load_platform("auv"), load_envelope("auv"), load_noise_model("auv").scaled(0.0)
    f = place_features(terrain, 300, LAYOUT.area_m, seed=6)
    views, seen, info = observe_features(pf, terrain, f, LAYOUT, 15.0, env.same_altitude, seed=7)
    tab = reconstruct(views, seen, info["sensor_height_m"], noise, pf.sonar.aperture(), seed=8)
    by = {k: t.set_index("feature") for k, t in tab.groupby("estimator")}
    r = np.linalg.norm(f[:, None, :] - views.origin, axis=-1)
    rmax = np.where(seen, r, 0).max(axis=1)
    # N >= 3 views without noise: the true feature, on any terrain
    allv = by["all"]
    est = allv.estimated.to_numpy()
    assert est[allv.n_views >= 3].mean() > 0.95
    assert np.nanmax(allv.error_3d_m[est] / rmax[est]) < 1e-9
    # flat seafloor: slant-range correction is exact up to the in-beam elevation (along-track)
    flat1 = by["flat1"].error_3d_m.to_numpy()
    beam = r.max(axis=1) * math.sin(math.radians(pf.sonar.elevation_deg / 2))
    if terrain.kind == "flat":
        assert np.all(flat1[seen.any(1)] <= beam[seen.any(1)] * 1.01 + 1e-9)
    else:  # a non-flat seafloor moves it by more than the beam, somewhere
        assert np.nanmax(flat1 - beam) > 0.1
    s = summarise(tab)
    assert set(s.estimator) == {"flat", "flat1", "two", "n3", "n4", "n6", "all"}


def test_cases_solved_together_give_each_case_its_own_table(monkeypatch):
    """reconstruct_many: the solver's rows are independent, so the tables of cases solved in one
    call (and split into runs by the row limit or by their number of views) are exactly those of
    one reconstruct per case."""
    import pandas as pd

    from sss_locus.experiments.reconstruction import estimators as rc

    pf, env, noise = load_platform("auv"), load_envelope("auv"), load_noise_model("auv")
    cases = []
    for k, (layout, scale) in enumerate([(LAYOUT, 1.0), (LAYOUT, 0.1), (LAYOUT, 0.0),
                                         (SurveyLayout(200.0, 60.0, 50.0, 50.0), 1.0), (LAYOUT, 2.0)]):
        ter = random_terrain(1.0 + k, 25.0, 800.0, 2.5, seed=k)
        f = place_features(ter, 60, layout.area_m, seed=20 + k)
        views, seen, info = observe_features(pf, ter, f, layout, 15.0, env.same_altitude, seed=30 + k)
        cases.append(dict(views=views, seen=seen, sensor_height_m=info["sensor_height_m"], noise=noise.scaled(scale),
                          seed=40 + k, below_sensors=k != 1))
    assert len({c["seen"].shape[1] for c in cases}) == 2  # two numbers of views: two solver runs at least
    alone = [reconstruct(aperture=pf.sonar.aperture(), **c) for c in cases]
    for limit in (rc.SOLVER_ROWS, 500):  # all in as few calls as the views allow; runs of about two cases
        monkeypatch.setattr(rc, "SOLVER_ROWS", limit)
        for table, reference in zip(rc.reconstruct_many(cases, pf.sonar.aperture()), alone, strict=True):
            pd.testing.assert_frame_equal(table, reference, check_exact=True)


def test_statuses_are_never_silent_nan():
    pf, env, noise = load_platform("boat"), load_envelope("boat"), load_noise_model("boat")
    ter = random_terrain(1.0, 25.0, 800.0, 2.5, seed=9)
    f = np.vstack([place_features(ter, 100, LAYOUT.area_m, seed=10), [[2000.0, 0.0, 0.0]]])
    with pytest.raises(ValueError, match="outside the random terrain"):
        observe_features(pf, ter, f, LAYOUT, 15.0, env.same_altitude, seed=11)
    f = f[:-1]
    f[0] = [0.0, -90.0 + 0.0, ter.height_m(0.0, -90.0)]  # under a line, near nadir of one
    views, seen, info = observe_features(pf, ter, f, LAYOUT, 15.0, env.same_altitude, seed=11)
    seen[1, :] = False  # a feature no pass saw
    tab = reconstruct(views, seen, info["sensor_height_m"], noise, pf.sonar.aperture(), seed=12)
    assert not tab.status.isna().any()
    nan = tab.error_3d_m.isna()
    assert np.array_equal(nan, ~tab.estimated)
    one = tab[tab.feature == 1].set_index("estimator").status
    assert one["flat"] == "unseen" and one["two"] == "too few views" and one["all"] == "too few views"


def test_paired_comparison_against_constructed_tables():
    """The per-feature Wilcoxon comparison of the earlier chapter (kept to reproduce its numbers)."""
    import pandas as pd

    from sss_locus.experiments.reconstruction.study import paired_comparison

    rng = np.random.default_rng(0)
    rows = []
    for relief, shift in ((0.0, 0.5), (2.0, -0.5)):
        base = rng.random(200) + 1.0
        for est, err in (("flat", base), ("all", base + shift + 0.05 * rng.normal(size=200))):
            rows.append(pd.DataFrame(dict(feature=np.arange(200), estimator=est, estimated=True, error_3d_m=err,
                                          noise_scale=1.0, rms_relief_m=relief)))
    c = paired_comparison(pd.concat(rows, ignore_index=True), "all", "flat", by=("noise_scale", "rms_relief_m"))
    assert list(c.n_pairs) == [200, 200]
    assert c.p_value.iloc[0] > 0.5 and c.p_value.iloc[1] < 1e-10 and c.p_value_b_closer.iloc[0] < 1e-10
    assert c.median_difference_m.iloc[1] == pytest.approx(-0.5, abs=0.02)


def _summary(values: dict):
    """A summary in the shape of over_surveys': ``values`` maps (spacing, value, estimator) to
    (mean, low, high), the same for every metric."""
    import pandas as pd

    rows = []
    for (sp, v, est), (m, lo, hi) in values.items():
        row = dict(platform="auv", spacing_m=sp, value=v, estimator=est, n_surveys=20)
        for col in ("horizontal_m", "vertical_m", "shape_m", "coverage"):
            row.update({col: m, f"{col}_low": lo, f"{col}_high": hi})
        rows.append(row)
    return pd.DataFrame(rows)


def test_sweep_points_are_the_summary_means_with_their_intervals():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from sss_locus.report.reconstruction.figures import plot_sweep

    values = {(sp, v, est): (m * (1 + v), m * (1 + v) - 0.1, m * (1 + v) + 0.2)
              for sp in (240.0, 60.0) for v in (0.0, 4.0) for est, m in (("flat", 1.0), ("joint", 0.3))}
    summary = _summary(values).sample(frac=1.0, random_state=1)  # any row order
    fig = plot_sweep([load_platform("auv")], summary, estimators=["flat", "joint"], metrics=["shape_m"],
                     xlabel="relief")
    ax = fig.axes[0]
    labels = ax.get_legend_handles_labels()[1]
    assert len(labels) == 4 and all("m apart" in k and "× range" in k for k in labels)  # spacing in every label
    solid = [ln for ln in ax.lines if ln.get_linestyle() == "-" and len(ln.get_xdata()) == 2]
    ys = sorted(tuple(np.round(ln.get_ydata(), 9)) for ln in solid)
    assert ys == sorted([(1.0, 5.0), (0.3, 1.5)])  # the main spacing (240 m) solid: its means
    bars = [c for c in ax.collections]
    segs = np.concatenate([np.asarray(c.get_segments()) for c in bars])
    assert any(np.allclose(sg[:, 1], [0.9, 1.2]) for sg in segs)  # flat, relief 0: its interval
    plt.close(fig)


def test_verdict_words_follow_the_interval_of_the_paired_difference():
    import pandas as pd

    from sss_locus.report.reconstruction.figures import comparison_word, verdict_sentence

    rows = [dict(spacing_m=240.0, value=v, shape_m=m, shape_m_low=lo, shape_m_high=hi)
            for v, (m, lo, hi) in ((0.0, (-1.0, -1.5, -0.5)), (1.0, (0.1, -0.2, 0.4)), (4.0, (0.6, 0.2, 1.0)))]
    paired = pd.DataFrame(rows)
    assert [comparison_word(r, "shape_m") for r in rows] == ["closer", "not distinguishable", "farther"]
    text = verdict_sentence(load_platform("auv"), paired, "shape_m", a_name="joint", b_name="the mosaic",
                            range_m=150.0)
    assert "map-shape error, joint against the mosaic" in text and "lines 240 m apart (1.6 × range)" in text
    assert "closer at 0 m RMS relief" in text and "farther at 4.0 m RMS relief" in text
    assert "not distinguishable at 1.0 m RMS relief" in text and "0.60 m (95 % CI 0.20 to 1.0)" in text


def test_the_method_says_how_each_platform_of_the_run_flies(tmp_path):
    """Whether a platform holds one height or follows the terrain comes from its envelope
    (``same_altitude``), for any platform: the chapter's method says which, by the platform's name,
    at the altitude the survey uses (the middle of the envelope's range)."""
    import dataclasses

    from sss_locus.experiments.reconstruction.study import survey_altitude_m
    from sss_locus.report.reconstruction.figures import height_sentence

    boat, auv = load_platform("boat"), load_platform("auv")
    eb, ea = load_envelope("boat"), load_envelope("auv")
    assert survey_altitude_m(ea) == pytest.approx(0.5 * (ea.altitude_min_m + ea.altitude_max_m))
    text = height_sentence([boat, auv], [eb, ea])
    assert eb.same_altitude and not ea.same_altitude
    assert f"the {boat.name} holds one height" in text and f"the {auv.name} follows the terrain" in text
    flipped = height_sentence([auv], [dataclasses.replace(ea, same_altitude=True)])
    assert f"the {auv.name} holds one height" in flipped and "follows" not in flipped


@pytest.mark.parametrize("lines", [1, 2])
def test_a_survey_of_one_or_two_lines_gives_too_few_views_not_an_index_error(lines):
    """Issue 38: a narrow area (2000 m x 130 m) is covered by one line: every feature has at
    most one view slot, so every estimator beyond the flat one says "too few views"."""
    from sss_locus.experiments.passes.view_sets import Views

    pf, env, noise = load_platform("boat"), load_envelope("boat"), load_noise_model("boat")
    ter = flat_terrain()
    f = place_features(ter, 40, LAYOUT.area_m, seed=3)
    views, seen, info = observe_features(pf, ter, f, LAYOUT, 15.0, env.same_altitude, seed=4)
    cut = Views(views.W[:, :lines], views.origin[:, :lines], views.vehicle[:, :lines], views.feature)
    seen = seen[:, :lines]
    tab = reconstruct(cut, seen, info["sensor_height_m"][:, :lines], noise, pf.sonar.aperture(), seed=5)
    few = tab[tab.estimator.isin(["n3", "all"])]
    assert (few.status == "too few views").all() and not few.estimated.any()
    two = tab[tab.estimator == "two"]
    assert (two.status == "too few views").all() == (lines == 1)
    flat = tab[tab.estimator == "flat"].set_index("feature")
    assert np.array_equal(flat.estimated.to_numpy(), seen.any(axis=1))
