"""Which sightings the your-pings estimates use: the best pair of the two-view locus (against a
brute force over every pair, each locus computed on its own) and empty loci shown as what they
are (not as locus points)."""

from __future__ import annotations

import matplotlib
import numpy as np
import pytest

from sss_locus.experiments.your_pings import study as yp
from sss_locus.paths import DATA_DIR

matplotlib.use("Agg")
EXAMPLE = DATA_DIR / "examples" / "your_pings" / "example_sightings.csv"


@pytest.fixture(scope="module")
def example():
    return yp.run(EXAMPLE, aperture_margin_deg=10.0)


def test_the_best_pair_is_the_shortest_non_empty_locus(example):
    """Brute force: every pair of each feature's sightings through two_view_locus on its own."""
    from sss_locus.experiments.datamodel.platforms import load_platform
    from sss_locus.geometry import sea_surface_half_space
    from sss_locus.geometry.locus import two_view_locus
    from sss_locus.geometry.poses import relative_pose

    platform = load_platform("auv")
    ap = platform.sonar.aperture()
    s = example.sightings
    pose = yp.sensor_poses(s, platform)
    checked = 0
    for _, f in example.features.iterrows():
        rows = np.flatnonzero(s["feature"].to_numpy() == f["feature"])
        lengths = {}
        for a in range(len(rows)):
            for b in range(a + 1, len(rows)):
                i, j = rows[a], rows[b]
                R, t = relative_pose(pose["W"][i], pose["origin"][i], pose["W"][j], pose["origin"][j])
                n, off = sea_surface_half_space(max(-pose["origin"][i][2], 0.0), pose["W"][i])
                loc = two_view_locus(R, t, pose["ranges"][i], pose["ranges"][j], ap, ap,
                                     half_space_normals=n, half_space_offsets=off)
                lengths[f"{a + 1}+{b + 1}"] = float(loc.length)
        nonempty = {k: v for k, v in lengths.items() if v > 0}
        if nonempty:
            best = min(nonempty, key=nonempty.get)
            assert f["two_view_pair"] == best and f["locus_length_m"] == pytest.approx(nonempty[best], rel=1e-9)
            checked += 1
        else:
            assert f["two_view_status"].startswith("empty locus") and f["locus_length_m"] == 0
    assert checked >= 3  # the comparison is not vacuous


def test_empty_loci_are_not_drawn_counted_or_compared_as_locus_points(example):
    from sss_locus.experiments.your_pings.files import against_truth, read_truth
    from sss_locus.experiments.datamodel.platforms import load_platform
    from sss_locus.report.your_pings.figures import ESTIMATES, feature_panels, plan_view, summary_sentence

    f = example.features
    empty = f["two_view_status"] != "locus"
    assert empty.any() and (~empty).any() and np.isfinite(f.loc[empty, "two_view_east_m"]).all()  # fallbacks exist
    fig, _ = plan_view(example, load_platform("auv"))
    label = ESTIMATES["two_view"][0]
    drawn = [c for c in fig.axes[0].collections if c.get_label() == label][0].get_offsets()
    assert len(drawn) == (~empty).sum()
    assert np.allclose(np.sort(drawn[:, 0]), np.sort(f.loc[~empty, "two_view_east_m"]))
    truth = read_truth(DATA_DIR / "examples" / "your_pings" / "example_truth.csv", EXAMPLE)
    errors = against_truth(example, truth)
    assert set(errors.loc[errors["estimator"] == "two_view", "feature"]) == set(f.loc[~empty, "feature"])
    text = summary_sentence(example)
    assert f"{(~empty).sum()} of {len(f)} two-view loci (best pair) non-empty" in text
    med = f.loc[~empty, "locus_length_m"].median()
    assert "median length of those" in text and f"{med:.2g}" in text
    fig, _ = feature_panels(example)
    titles = [ax.get_title() for ax in fig.axes if ax.get_visible() and ax.get_title()]
    assert sum("empty locus" in t for t in titles) == empty.sum()
    assert all("N views:" in t for t in titles)


def test_geojson_does_not_call_a_fallback_a_locus_point(example):
    import json

    from sss_locus.experiments.your_pings.files import geojson_text

    doc = json.loads(geojson_text(example))
    kinds = {f["properties"]["feature"]: f["properties"]["kind"] for f in doc["features"]
             if f["properties"]["kind"].startswith("two_view")}
    status = example.features.set_index("feature")["two_view_status"]
    assert kinds and all((k == "two_view") == (status[f] == "locus") for f, k in kinds.items())
    assert "two_view_empty_locus" in kinds.values()


def test_the_map_does_not_say_every_feature_was_seen_once_when_one_was_seen_twice(tmp_path):
    """Two sightings 300 m apart with 40 m ranges: their spheres do not meet (empty locus), and
    two views give no N-view position, so there is nothing to compare; the map must say why
    without claiming each feature was seen once."""
    from sss_locus.experiments.datamodel.platforms import load_platform
    from sss_locus.report.your_pings.figures import plan_view

    (tmp_path / "s.csv").write_text(
        "feature,platform,side,east_m,north_m,depth_m,altitude_m,heading_deg,pitch_deg,roll_deg,slant_range_m\n"
        "A,auv,port,0,0,5,15,90,0,0,40\nA,auv,port,300,0,5,15,90,0,0,40\n")
    res = yp.run(tmp_path / "s.csv")
    assert res.features["n_sightings"].tolist() == [2] and res.features["two_view_status"].iloc[0] != "locus"
    fig, data = plan_view(res, load_platform("auv"))
    assert not len(data)
    text = " ".join(t.get_text() for t in fig.axes[1].texts)
    assert "no second estimate" in text and "seen once" not in text


def test_one_row_of_feature_panels_keeps_its_axis_label_clear_of_the_legend(tmp_path):
    """The y label and the legend's text must not overlap (measured on the drawn figure)."""
    from sss_locus.report.your_pings.figures import feature_panels

    (tmp_path / "s.csv").write_text(
        "feature,platform,side,east_m,north_m,depth_m,altitude_m,heading_deg,pitch_deg,roll_deg,slant_range_m\n"
        "A,auv,port,0,0,5,15,90,0,0,40\nB,auv,port,300,0,5,15,90,0,0,40\n")
    fig, _ = feature_panels(yp.run(tmp_path / "s.csv"))
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    labels = [t for t in fig.texts if "flat mean" in t.get_text()] + [
        ax.yaxis.label for ax in fig.axes if "flat mean" in ax.get_ylabel()]
    assert len(labels) == 1
    box = labels[0].get_window_extent(r)
    legend = fig.legends[0].get_window_extent(r)
    assert not box.overlaps(legend)


def test_a_users_own_truth_is_not_called_the_synthetic_example(example):
    """A user's sightings with a truth file of their own (no SYNTHETIC marker, so no notice): the
    map, the feature panels and the 3-D view labelled its stars "truth (synthetic example)"."""
    from sss_locus.experiments.datamodel.platforms import load_platform
    from sss_locus.experiments.your_pings.files import read_truth
    from sss_locus.report.your_pings.figures import feature_panels, plan_view, view_3d

    truth = read_truth(DATA_DIR / "examples" / "your_pings" / "example_truth.csv", EXAMPLE)

    def labels(fig):
        return {c.get_label() for ax in fig.axes for c in ax.collections}

    for notice in ("", "synthetic example"):
        drawn = [labels(plan_view(example, load_platform("auv"), truth=truth, notice=notice)[0]),
                 labels(feature_panels(example, truth=truth, notice=notice)[0]),
                 {t.name for t in view_3d(example, truth=truth, notice=notice).data}]
        for names in drawn:
            stars = {n for n in names if n and n.startswith("truth")}
            assert stars == {"truth (synthetic example)" if notice else "truth (known positions)"}, stars


def test_a_users_own_sightings_are_not_called_the_synthetic_example_in_the_pages_prose():
    """The page's introduction said "The page below shows a worked example, synthetic: ... the
    project's own simulator" and the real pass's section "Everything above is synthetic" above a
    user's own sightings: both sentences now follow the run's data."""
    import json
    from pathlib import Path

    from sss_locus.paths import REPO_ROOT
    from sss_locus.report.your_pings.figures import page_data_words

    shown, above = page_data_words(False, [Path("/home/me/survey/my_sightings.csv")])
    assert "`my_sightings.csv`" in shown and "`my_sightings.csv`" in above
    assert not any(w in (shown + above).lower() for w in ("synthetic", "simulator", "/home"))
    shown, above = page_data_words(True, [EXAMPLE])
    assert "**synthetic**" in shown and above == "Everything above is synthetic."
    nb = json.loads((REPO_ROOT / "notebooks" / "your_pings.ipynb").read_text())
    prose = " ".join("".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "markdown")
    assert "{glue:md}`yp-shown`" in prose and "{glue:md}`yp-above`" in prose
    assert "Everything above is synthetic" not in prose and "shows a worked example" not in prose
