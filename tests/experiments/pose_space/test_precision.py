"""What the book prints is what the sampling supports: intervals of the claim metrics, peak
regions, the two-seed check at the printed digits, the heading sweep's cells.

References are brute force (batches dealt by hand, Student's t from scipy.stats) and synthetic
tables with a known structure."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from sss_locus.experiments.pose_space.claims import batch_medians, batches, claim_metrics, peak_region
from sss_locus.experiments.pose_space.stats import binned_profile, heatmaps, spearman_table
from sss_locus.experiments.three_views.patterns import cells_within
from sss_locus.report.pose_space.figures import agree_at_print, printed_metric, seed_stability_table


def _t_interval(full: float, per_batch) -> tuple[float, float]:
    b = np.asarray(per_batch, float)
    half = stats.t.ppf(0.975, len(b) - 1) * b.std(ddof=1) / math.sqrt(len(b))
    return full - half, full + half


def _table(n: int, seed: int, yaw_peaks=(60.0,), hotspot: bool = False):
    """A pose-space-like table of the AUV's apertures whose length grows with both ranges and
    peaks at |yaw| in ``yaw_peaks`` (equal heights); with ``hotspot`` also at (theta1, theta2) =
    (10, -20) and at zero elevation. Returns the table and the platform."""
    from sss_locus.experiments.datamodel.platforms import load_platform

    pf = load_platform("auv")
    rng = np.random.default_rng(seed)
    half_az, half_el = pf.sonar.azimuth_deg / 2, pf.sonar.elevation_deg / 2
    df = pd.DataFrame({
        "r1_m": rng.uniform(0, 150, n), "r2_m": rng.uniform(0, 150, n),
        "azimuth1_deg": rng.uniform(-half_az, half_az, n), "azimuth2_deg": rng.uniform(-half_az, half_az, n),
        "elevation1_deg": rng.uniform(-half_el, half_el, n), "elevation2_deg": rng.uniform(-half_el, half_el, n),
        "yaw2_deg": rng.uniform(-180, 180, n), "pitch2_deg": rng.uniform(-45, 45, n),
        "n_arcs": np.where(rng.random(n) < 0.01, 2, 1),
    })
    bump = np.minimum(sum(np.exp(-((np.abs(df.yaw2_deg) - p) / 25.0) ** 2) for p in yaw_peaks), 1.0)
    if hotspot:
        az_bump = np.exp(-(((df.azimuth1_deg - 10) / 8) ** 2 + ((df.azimuth2_deg + 20) / 8) ** 2))
        el_bump = np.exp(-((df.elevation1_deg / half_el) ** 2 + (df.elevation2_deg / half_el) ** 2))
        df["locus_length_m"] = (df.r1_m + df.r2_m) * (0.2 + bump + 3 * az_bump) * el_bump
    else:
        df["locus_length_m"] = (df.r1_m + df.r2_m) * (0.2 + bump) * rng.lognormal(0, 0.3, n)
    df["locus_length_normalized"] = df.locus_length_m / (df.r1_m + df.r2_m) * 2
    return df, pf


def test_claim_metrics_on_synthetic_structure():
    """A table built with known structure: length grows with both ranges, peaks at yaw = +-60
    and at (theta1, theta2) = (10, -20), is larger at zero elevation; the metrics find it, and
    each located peak's region holds the true peak."""
    from sss_locus.experiments.pose_space.stats import HEATMAP_PANELS

    df, pf = _table(200_000, 0, hotspot=True)
    rho = spearman_table(df, ["r1_m", "yaw2_deg"])
    maps = heatmaps(df, pf, n_bins=26, min_count=30)
    assert set(maps) == {p for p, _, _ in HEATMAP_PANELS}
    m = claim_metrics(df, rho, maps)
    assert m["range_far_over_near_ratio"] > 2.5 and m["range_r1_rho"] > 0.3
    assert abs(m["azimuth_peak_theta1_deg"] - 10) <= 5 and abs(m["azimuth_peak_theta2_deg"] + 20) <= 5
    assert m["elevation_centre_over_corner_ratio"] > 1.5
    assert abs(m["yaw_peak_neg_deg"] + 60) <= 10 and abs(m["yaw_peak_pos_deg"] - 60) <= 10
    assert m["yaw_peak_neg_lo_deg"] - 5 <= -60 <= m["yaw_peak_neg_hi_deg"] + 5
    assert m["yaw_peak_pos_lo_deg"] - 5 <= 60 <= m["yaw_peak_pos_hi_deg"] + 5
    assert m["yaw_near0_over_peak_ratio"] < 0.5 and m["yaw_near180_over_peak_ratio"] < 0.5
    assert m["multi_arc_fraction"] == pytest.approx(0.01, abs=0.002)
    assert m["multi_arc_fraction_ci_low"] < 0.01 < m["multi_arc_fraction_ci_high"]
    assert m["top_raw"] == "r1_m"


def test_ratio_and_share_intervals_match_batches_dealt_by_hand():
    df, pf = _table(40_000, 1)
    m = claim_metrics(df, spearman_table(df, ["r1_m", "yaw2_deg"]), heatmaps(df, pf, n_bins=8), n_batches=20)
    half_r = 75.0
    parts = [df.iloc[j::20] for j in range(20)]

    def far_near(d):
        return (d[(d.r1_m > half_r) & (d.r2_m > half_r)].locus_length_m.median()
                / d[(d.r1_m <= half_r) & (d.r2_m <= half_r)].locus_length_m.median())

    lo, hi = _t_interval(far_near(df), [far_near(p) for p in parts])
    assert m["range_far_over_near_ratio"] == pytest.approx(far_near(df))
    assert (m["range_far_over_near_ratio_ci_low"], m["range_far_over_near_ratio_ci_high"]) == pytest.approx((lo, hi))
    share = [(p.n_arcs > 1).mean() for p in parts]
    lo, hi = _t_interval((df.n_arcs > 1).mean(), share)
    assert (m["multi_arc_fraction_ci_low"], m["multi_arc_fraction_ci_high"]) == pytest.approx((max(lo, 0), hi))
    assert m["range_far_over_near_ratio_ci_low"] < m["range_far_over_near_ratio"] < m["range_far_over_near_ratio_ci_high"]


def test_peak_region_brute_force_and_flat_top():
    df, _ = _table(60_000, 2, yaw_peaks=(50.0, 70.0, 90.0))  # a flat top over |yaw| 50-90
    prof = binned_profile(df, "yaw2_deg", edges=np.arange(-180.0, 190.0, 10.0), min_count=30)
    meds = batch_medians(batches(df, 20), prof)
    for j, part in enumerate(batches(df, 20)):  # each batch's medians, bin by bin
        sel = (part.yaw2_deg >= -180) & (part.yaw2_deg < -170)
        assert meds[j, 0] == pytest.approx(part.locus_length_m[sel].median())
    pos = prof["mid"].to_numpy() > 0
    region, lo, hi = peak_region(prof, meds, pos)
    i = int(np.flatnonzero(pos)[np.argmax(prof["median"].to_numpy()[pos])])
    assert (lo, hi) == pytest.approx(_t_interval(prof["median"].iloc[i], meds[:, i]))
    reach = [_t_interval(prof["median"].iloc[j], meds[:, j])[1] for j in range(len(prof))]
    expected = prof[pos & (np.array(reach) >= lo) & ~prof["masked"]]
    assert list(region.index) == list(expected.index)
    assert region["mid"].min() <= 55 and region["mid"].max() >= 85  # the flat top, not one bin
    sharp, _ = _table(60_000, 3, yaw_peaks=(60.0,))
    prof = binned_profile(sharp, "yaw2_deg", edges=np.arange(-180.0, 190.0, 10.0), min_count=30)
    region, _, _ = peak_region(prof, batch_medians(batches(sharp, 20), prof), prof["mid"] > 0)
    assert region["mid"].max() - region["mid"].min() <= 20  # a sharp peak: a bin or two


def _run(rho_norm_az: float, ratio: tuple[float, float, float], peak: tuple[float, float, float],
         theta1: float) -> dict:
    rho = pd.DataFrame({"target": ["locus_length_normalized"], "quantity": ["azimuth1_deg"], "rho": [rho_norm_az]})
    metrics = {"top_norm": "azimuth1_deg", "x_ratio": ratio[0], "x_ratio_ci_low": ratio[1], "x_ratio_ci_high": ratio[2],
               "yaw_peak_neg_deg": peak[0], "yaw_peak_neg_lo_deg": peak[1], "yaw_peak_neg_hi_deg": peak[2],
               "azimuth_peak_theta1_deg": theta1, "azimuth_peak_count": 80.0}
    return {"rho": rho, "metrics": metrics, "maps": {}}


def test_two_seed_check_compares_at_the_printed_digits():
    """The old blanket two-significant-figure check flagged a rho of -0.0569 against -0.0582
    (printed to two decimals, -0.06 both) and a ratio of 2.13 against 2.06 with overlapping
    intervals; the check at the printed digits passes them and flags what differs as printed."""
    a = _run(-0.0569, (2.13, 2.07, 2.19), (-75.0, -85.0, -75.0), -28.4375)
    b = _run(-0.0582, (2.06, 2.01, 2.12), (-85.0, -85.0, -85.0), -28.4375)
    tab = seed_stability_table({"auv": (a, b)}, (1, 2)).set_index("quantity")
    assert tab["stable"].all() and len(tab) == 5  # rho, top_norm, ratio, peak span, theta1 (count left out)
    c = _run(-0.0660, (2.40, 2.35, 2.46), (-55.0, -65.0, -55.0), -20.3125)
    tab = seed_stability_table({"auv": (a, c)}, (1, 2)).set_index("quantity")
    assert tab.loc["top_norm", "stable"]
    assert not tab["stable"].drop("top_norm").any()  # -0.06 vs -0.07, disjoint intervals and spans, another bin
    assert tab.loc["x_ratio", "seed 2"] == "2.4 (95 % CI 2.4–2.5)" and tab.loc["yaw_peak_neg_deg", "seed 1"] == "-85° to -75°"
    # the unit of the last printed digit decides, not a fixed number of digits
    assert printed_metric("r_ratio", {"r_ratio": 0.0412})[:3:2] == ("0.041", pytest.approx(0.001))
    assert printed_metric("x_rho", {"x_rho": 0.0412})[:3:2] == ("0.04", pytest.approx(0.01))
    assert agree_at_print("unit", (0.0410, 1e-3), (0.0414, 1e-3))
    assert not agree_at_print("unit", (0.0410, 1e-3), (0.0416, 1e-3))
    assert not agree_at_print("text", "abs_psi1_deg", "abs_psi2_deg")


def test_cells_within_brute_force():
    sweep = pd.DataFrame({"heading2_deg": [0.0, 0.0, 15.0, 30.0, 180.0],
                          "heading3_deg": [0.0, 90.0, 90.0, 90.0, 180.0],
                          "point_error_q95_median_m": [0.9, 0.10, 0.11, 0.13, 0.85],
                          "point_error_q95_median_ci_low_m": [0.8, 0.09, 0.10, 0.12, 0.80],
                          "point_error_q95_median_ci_high_m": [1.0, 0.115, 0.12, 0.14, 0.90]})
    assert list(cells_within(sweep, "min").index) == [1, 2]  # 0.13 > 0.115: out
    assert list(cells_within(sweep, "max").index) == [0, 4]  # 0.85 >= 0.8: in
    with pytest.raises(ValueError, match="best"):
        cells_within(sweep, "median")


def test_quoted_ranks_are_the_ranks_the_book_quotes():
    """The seed table compares only the ranks the book quotes: the list must name every rank
    glued into the pose-space chapter's text or the claims page, and no other."""
    import re
    from pathlib import Path

    from sss_locus.report.pose_space.figures import QUOTED_RANKS

    root = Path(__file__).resolve().parents[3]
    text = (root / "notebooks" / "pose_space.ipynb").read_text() + "".join(
        p.read_text() for p in (root / "book").glob("*.md"))
    quoted = set(re.findall(r"ps-(?:auv|boat)-([a-z0-9_]+_rank)", text))
    assert quoted == set(QUOTED_RANKS)


def test_share_interval_against_scipy_binomtest():
    from sss_locus.experiments.three_views.patterns import share_interval

    for count, n in ((0, 4000), (16, 4000), (3990, 4000), (4000, 4000), (7, 20)):
        ref = stats.binomtest(count, n).proportion_ci(0.95, method="exact")
        assert share_interval(count, n) == pytest.approx((ref.low, ref.high), abs=1e-12)
    with pytest.raises(ValueError, match="count"):
        share_interval(5, 4)


def _seed_tool():
    """tools/compare_seed_outputs.py, imported from its file."""
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[3] / "tools" / "compare_seed_outputs.py"
    spec = importlib.util.spec_from_file_location("compare_seed_outputs", path)
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)
    return tool


def test_seed_comparison_tool_compares_printed_texts():
    """tools/compare_seed_outputs.py: which pairs of glued texts count as agreeing."""
    tool = _seed_tool()
    agree = tool.agree
    assert agree("'0.55'", "'0.54'")[0] and not agree("'0.55'", "'0.53'")[0]  # one unit: a straddle
    assert agree("'2.1 (95 % CI 2.1–2.2)'", "'2.0 (95 % CI 2.0–2.1)'") == (True, "intervals overlap")
    assert not agree("'0.40 m (95 % CI 0.39–0.41 m)'", "'0.37 m (95 % CI 0.36–0.38 m)'")[0]
    assert agree("'[-0.050, -0.044]'", "'[-0.047, -0.042]'")[0] and agree("'-85° to -75°'", "'-75°'")[0]
    assert agree("'5.3e-11'", "'5.4e-11'") == (True, "rounding level")
    assert agree("'-12 % (95 % CI -13 % to -11 %)'", "'-11 % (95 % CI -11 % to -10 %)'")[0]
    assert agree("'5 of 12'", "'6 of 12'") == (False, "texts differ")
    assert ("pose_space", "ps-stable-count") in tool.quoted_keys()


def test_seed_comparison_tool_compares_regions():
    tool = _seed_tool()
    agree = tool.agree
    assert agree("'θ₁ -28° to -20°, θ₂ -28° to -20°'", "'θ₁ -37° to -12°, θ₂ -28°'") == (True, "regions overlap")
    assert not agree("'θ₁ -28° to -20°, θ₂ -28° to -20°'", "'θ₁ -37° to -30°, θ₂ -28°'")[0]
    assert agree("'6 cells with h₂ 45° to 75° and h₃ 105° to 135°'", "'12 cells with h₂ 45° to 90° and h₃ 90° to 150°'")[0]
    assert agree("'(180°, 180°)'", "'(0°, 0°), (0°, 180°), (180°, 180°)'") == (True, "regions overlap")
    assert not agree("'(180°, 180°)'", "'(0°, 0°), (0°, 180°)'")[0]
