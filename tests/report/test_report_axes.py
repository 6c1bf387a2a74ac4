"""Every one-panel plot function of the report layer draws on the axes it is given (``ax=``) or
on the current axes, and returns them (the pattern of xarray's ``plot.utils.get_axis``)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from sss_locus.experiments.pose_space.stats import binned_median  # noqa: E402
from sss_locus.report.noise import figures as noise
from sss_locus.report.pose_space import figures as pose_space
from sss_locus.report.survey_passes import figures as survey_passes
from sss_locus.report.three_views import figures as three_views
from sss_locus.report.water import figures as water  # noqa: E402
from sss_locus.report.common.style import get_axis  # noqa: E402

RNG = np.random.default_rng(3)
PF = [SimpleNamespace(key="auv", name="AUV"), SimpleNamespace(key="boat", name="Boat")]
G = np.arange(0, 181, 10.0)


def _curve(s: float) -> pd.DataFrame:
    d = {"crossing_angle_deg": G}
    for v in ("locus_length_m", "elevation_misalignment_deg", "extent_m", "empty_fraction", "band_width_m"):
        base = s * (1 + np.sin(np.radians(G)))
        d[f"{v}_median"], d[f"{v}_q25"], d[f"{v}_q75"] = base, 0.8 * base, 1.2 * base
    return pd.DataFrame(d)


def _binned():
    df = pd.DataFrame({"r1_m": RNG.uniform(0, 100, 2000), "r2_m": RNG.uniform(0, 100, 2000)})
    df["locus_length_m"] = 0.01 * df.r1_m
    return binned_median(df, "r1_m", "r2_m", x_edges=np.linspace(0, 100, 5), y_edges=np.linspace(0, 100, 4),
                         min_count=1)


def _patterns():
    return {name: pd.DataFrame({"n_valid": RNG.choice([0, 1, 2], 40), "plane_angle_deg": RNG.lognormal(2, 1, 40),
                                "point_error_q95_m": RNG.lognormal(-1, 1, 40)})
            for name in ("repeat + reciprocal", "two lines + cross line")}


def _sweep():
    h = np.arange(0.0, 181.0, 45.0)
    h2, h3 = np.meshgrid(h, h, indexing="ij")
    keep = h2 <= h3
    s = pd.DataFrame({"heading2_deg": h2[keep], "heading3_deg": h3[keep]})
    s["plane_angle_median_deg"] = 1 + 0.1 * s.heading2_deg
    return s


def _effects():
    rows = [dict(label=lab, statistic=stat, estimate=0.3, ci_low=0.2, ci_high=0.4, subset="all", crop="surface")
            for lab in ("a", "b") for stat in ("multi_arc_share_uncropped", "multi_arc_share_cropped", "length_ratio")]
    return pd.DataFrame(rows)


def _check():
    return pd.DataFrame([dict(platform=p.key, kind="two", scale=1.0, monte_carlo_m=a, first_order_m=1.1 * a)
                         for p in PF for a in RNG.lognormal(0, 1, 10)])


RHO = pd.DataFrame({"target": ["locus_length_m", "locus_length_normalized"], "quantity": ["r1_m"] * 2,
                    "rho": [0.5, -0.2], "ci_low": [0.4, -0.3], "ci_high": [0.6, -0.1]})
SUBSET = pd.DataFrame({"elevation_misalignment_deg": RNG.uniform(0, 80, 50),
                       "locus_length_normalized": RNG.lognormal(-5, 1, 50), "n_arcs": np.arange(50) % 5 + 1})
LABELS = {noise.level_label(1.0): _curve(1), "range only": _curve(2), "attitude only": _curve(3),
          "position only": _curve(4)}
PANELS = {
    "pose_space.plot_rho_bars": lambda ax: pose_space.plot_rho_bars(RHO, ax=ax),
    "pose_space.plot_length_scatter": lambda ax: pose_space.plot_length_scatter(SUBSET, ax=ax),
    "pose_space.plot_heatmap": lambda ax: pose_space.plot_heatmap(_binned(), title="(a) r vs r", ax=ax),
    "survey_passes.plot_crossing_curves": lambda ax: survey_passes.plot_crossing_curves(
        {p.key: SimpleNamespace(platform=p, curve=_curve(1)) for p in PF}, colors={"auv": "r", "boat": "b"}, ax=ax),
    "three_views.plot_outcome_shares": lambda ax: three_views.plot_outcome_shares(_patterns(), ax=ax),
    "three_views.plot_pattern_boxes": lambda ax: three_views.plot_pattern_boxes(_patterns(), "plane_angle_deg", ax=ax),
    "three_views.plot_sweep_heatmap": lambda ax: three_views.plot_sweep_heatmap(_sweep(), "plane_angle_median_deg",
                                                                                ax=ax),
    "water.plot_crop_bars": lambda ax: water.plot_crop_bars(_effects(), [("length_ratio", None, "b")], ax=ax),
    "noise.plot_noise_extent": lambda ax: noise.plot_noise_extent(LABELS, [1.0], ax=ax),
    "noise.plot_empty_share": lambda ax: noise.plot_empty_share(LABELS, [1.0], ax=ax),
    "noise.plot_band_widths": lambda ax: noise.plot_band_widths(LABELS, noise.level_label(1.0), ax=ax),
    "noise.plot_check_panel": lambda ax: noise.plot_check_panel(_check(), PF, "two", 1.0,
                                                                colors={"auv": "r", "boat": "b"}, ax=ax),
}


def _drawn(ax) -> int:
    return len(ax.lines) + len(ax.patches) + len(ax.collections)


@pytest.mark.parametrize("name", sorted(PANELS))
def test_panel_draws_on_the_axes_given_and_returns_them(name):
    fig, (left, right) = plt.subplots(1, 2)
    assert PANELS[name](right) is right
    assert _drawn(right) > 0 and _drawn(left) == 0  # nothing on the other panel
    plt.close(fig)


@pytest.mark.parametrize("name", sorted(PANELS))
def test_panel_without_ax_draws_on_the_current_axes(name):
    fig, (left, right) = plt.subplots(1, 2)
    plt.sca(left)
    assert PANELS[name](None) is left
    assert _drawn(left) > 0 and _drawn(right) == 0
    plt.close(fig)


def test_get_axis_given_current_or_new():
    fig, ax = plt.subplots()
    assert get_axis(ax) is ax and get_axis() is ax
    new = get_axis(figsize=(3.0, 2.0))
    assert new is not ax and tuple(new.figure.get_size_inches()) == (3.0, 2.0)
    with pytest.raises(ValueError, match="ax or figsize"):
        get_axis(ax, figsize=(3.0, 2.0))
    plt.close("all")


def test_locus_concept_draws_into_given_3d_axes():
    from scipy.spatial.transform import Rotation

    from sss_locus import Aperture, two_view_locus
    from sss_locus.report.concept import figures as concept

    aperture, feature, origin2 = Aperture(130.0, 20.0, 150.0), np.array([9.0, 3.0, 0.0]), np.array([-1.0, -2.0, 5.0])
    axes2 = Rotation.from_euler("ZYX", [-10, 25, 0], degrees=True)
    R = axes2.inv().as_matrix()
    t = -R @ origin2
    r1, r2 = np.linalg.norm(feature), np.linalg.norm(R @ feature + t)
    locus = two_view_locus(R, t, r1, r2, aperture, aperture)
    data = concept.concept_data(locus, axes2.as_matrix(), origin2, r1, r2, n_per_arc=20)
    fig = plt.figure()
    other, ax = fig.add_subplot(1, 2, 1, projection="3d"), fig.add_subplot(1, 2, 2, projection="3d")
    assert concept.plot_locus_concept(data, aperture, feature, locus_length_m=float(locus.length), ax=ax) is fig
    assert _drawn(ax) > 0 and _drawn(other) == 0 and ax.get_legend() is not None and not fig.legends
    plt.close(fig)
