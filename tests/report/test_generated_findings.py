"""Findings generated for any platform (sss_locus.report.pose_space.findings, three_views.findings) say what
the numbers they come from say: orders, extremes and flags are recomputed here by hand from
tables built for the test, not copied from the functions' output."""

from __future__ import annotations

import re
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from sss_locus.report.survey_passes import curve_findings as sp
from sss_locus.report.three_views import findings as pf
from sss_locus.report.pose_space import findings as ps
from sss_locus.report.common.text import fmt_percent, plain_label
from sss_locus.report.three_views.figures import share_text

QUANTITIES = ["mean_range_m", "baseline_m", "elevation_misalignment_deg", "azimuth1_deg", "abs_yaw2_deg"]


def _rho_table(raw, norm, width=0.02):
    rows = [{"target": t, "quantity": q, "rho": r, "ci_low": r - width, "ci_high": r + width}
            for t, values in ((ps.RAW, raw), (ps.NORM, norm)) for q, r in zip(QUANTITIES, values)]
    return pd.DataFrame(rows)


def _positions(text, names):
    return [text.index(plain_label(n)) for n in names]


@pytest.mark.parametrize("seed", range(5))
def test_drivers_are_named_in_order_of_absolute_rank_correlation(seed):
    rng = np.random.default_rng(seed)
    raw, norm = rng.uniform(-0.9, 0.9, 5), rng.uniform(-0.9, 0.9, 5)
    text = ps.drivers_finding(_rho_table(raw, norm, width=0.0), top=3)
    first, second = text.split("Divided by the mean of the two ranges")
    for values, part in ((raw, first), (norm, second)):
        order = [QUANTITIES[i] for i in np.argsort(-np.abs(values))]
        head = part.split("; the weakest")[0]
        assert _positions(head, order[:3]) == sorted(_positions(head, order[:3]))  # ranked by |rho|
        assert plain_label(order[-1]) in part.split("; the weakest")[1]  # the smallest |rho|
        top = values[np.argmax(np.abs(values))]
        assert f"ρ = {top:.2f}" in head and (("longer loci" in head) == (top > 0))


def test_drivers_say_whether_the_first_two_intervals_overlap():
    raw = [0.6, 0.3, 0.1, 0.05, 0.0]
    assert "is clear of the runner-up's" in ps.drivers_finding(_rho_table(raw, raw, width=0.05)).split("Divided")[0]
    close = [0.6, 0.58, 0.1, 0.05, 0.0]
    assert "not settled" in ps.drivers_finding(_rho_table(close, raw, width=0.05)).split("Divided")[0]
    assert ps.fmt_rho(-0.004) == "0.00"


def _curve(angles, medians):
    m = np.asarray(medians, float)
    return pd.DataFrame({"crossing_angle_deg": angles, "locus_length_m_median": m,
                         "elevation_misalignment_deg_median": m})


def test_curve_shape_of_an_oblique_peak_with_short_ends():
    g = np.arange(0.0, 181.0, 5.0)
    m = np.exp(-((g - 20.0) / 10.0) ** 2) + 0.01  # the paper's shape: sharp peak at 20 degrees
    s = sp.curve_shape(_curve(g, m), 20.0, 0.25, 0.5)
    assert s["where"] == "oblique" and s["ends_preferred"]
    assert s["ends_ratio"] == pytest.approx(m[-1] / m[0])
    avoid = s["bands"][s["bands"]["kind"] == "avoid"]
    hi = g[(m - m.min()) / (m.max() - m.min()) >= 0.5]  # by hand: the upper half of the range
    assert (avoid["lo_deg"].min(), avoid["hi_deg"].max()) == (hi.min(), hi.max())


def test_curve_shape_of_a_cross_line_peak_with_a_long_reciprocal():
    g = np.arange(0.0, 181.0, 5.0)
    m = np.sin(np.radians(g)) + np.where(g > 170, 2.0, 0.1)  # the 180 degree end is long
    s = sp.curve_shape(_curve(g, m), 90.0, 0.25, 0.5)
    assert s["where"] == "cross" and not s["ends_preferred"]


def _cur(g, m, peak_deg, side="random", mis_peak_deg=None, tried=(100, 100), accepted=(90, 100)):
    curve = _curve(g, m)
    for v in ("locus_length_m", "elevation_misalignment_deg"):
        for k in ("ci_low", "ci_high", "q25", "q75"):
            curve[f"{v}_{k}"] = curve[f"{v}_median"]
    peak = {"angle_deg": peak_deg, "ci_low_deg": peak_deg - 5, "ci_high_deg": peak_deg + 5}
    mis = peak if mis_peak_deg is None else {"angle_deg": mis_peak_deg, "ci_low_deg": mis_peak_deg - 5,
                                             "ci_high_deg": mis_peak_deg + 5}

    def at(gamma, value="locus_length_m"):
        r = curve[np.isclose(curve["crossing_angle_deg"], gamma)].iloc[0]
        return {"median": float(r[f"{value}_median"]), "ci_low": 0.9 * float(r[f"{value}_median"]),
                "ci_high": 1.1 * float(r[f"{value}_median"])}
    acceptance = pd.DataFrame({"n_tried": tried, "n_accepted": accepted,
                               "acceptance": np.divide(accepted, tried)})
    return SimpleNamespace(curve=curve, peak={"locus_length_m": peak, "elevation_misalignment_deg": mis}, at=at,
                           acceptance=acceptance, offset_model=SimpleNamespace(side_rule=side))


def test_curve_finding_quotes_the_curve_and_its_bands():
    g = np.arange(0.0, 181.0, 10.0)
    m = 1.0 + 9.0 * np.sin(np.radians(g))  # 1 m at both ends, 10 m at 90 degrees
    text = sp.curve_finding(_cur(g, m, 90.0), 0.25, 0.5)
    assert "is 1.0 m (95 % CI 0.90–1.1 m) at a repeat pass" in text and "is 10 m (95 % CI 9.0–11 m) at 90°" in text
    assert "near a cross-line" in text
    assert "both fall in the preferred bands" in text and "about equally short" in text
    level = (m - 1.0) / 9.0  # by hand: prefer where the level is at most 0.25
    lo_end = g[np.flatnonzero(level > 0.25)[0] - 1]
    assert f"Prefer γ in 0–{lo_end:.0f}°" in text


def test_curve_finding_quotes_the_misalignment_and_the_rejected_draws():
    g = np.arange(0.0, 181.0, 10.0)
    m = 1.0 + 9.0 * np.sin(np.radians(g))
    text = sp.curve_finding(_cur(g, m, 90.0, mis_peak_deg=80.0, tried=(100, 100), accepted=(90, 100)), 0.25, 0.5)
    assert "rank correlation with the median length over the grid is 1.00" in text  # the same curve
    assert "largest median is at 80° (interval 75–85°)" in text
    assert "5 % were rejected" in text and "at most 10 % at any one angle" in text  # 10 of 200; 10 of 100
    long_end = _cur(g, np.where(g == 180, 2.0, m), 90.0)  # 180 degrees twice as long as 0 degrees
    assert "though not equally short" in sp.curve_finding(long_end, 0.25, 0.5)


def test_shorter_finding_counts_the_angles_where_a_platform_is_shorter():
    g = np.arange(0.0, 181.0, 10.0)
    a, b = 1.0 + np.sin(np.radians(g)), 2.0 + np.sin(np.radians(g))
    curves = {"boat": _cur(g, b, 90.0), "auv": _cur(g, a, 90.0)}
    titles = {"boat": "the boat", "auv": "the AUV"}
    assert sp.shorter_finding(curves, titles) == "the AUV's median locus is shorter than the boat's at every crossing angle."
    b2 = b.copy()
    b2[:3] = 0.5  # the boat shorter at the first three angles only
    assert "at 16 of 19 crossing angles" in sp.shorter_finding({"boat": _cur(g, b2, 90.0), "auv": _cur(g, a, 90.0)},
                                                                titles)
    assert sp.shorter_finding({"auv": _cur(g, a, 90.0)}, titles) == ""


def test_offset_models_finding_names_the_models_with_an_oblique_peak():
    g = np.arange(0.0, 181.0, 10.0)
    curves = {"independent": _cur(g, g, 90.0), "matched same": _cur(g, g, 20.0, side="same", mis_peak_deg=10.0)}
    text = sp.offset_models_finding(curves)
    assert "independent: 90° (85–95°; misalignment 90°); matched same: 20° (15–25°; misalignment 10°)" in text
    assert "appears with matched same (matched same: an interval that holds the paper's ≈20°)" in text
    assert "points to passes planned around the feature on the same side" in text
    curves["matched random"] = _cur(g, g, 30.0, side="random")  # an oblique peak with random sides
    text = sp.offset_models_finding(curves)
    assert "appears with matched same and matched random" in text and "same side" not in text
    assert "interval that holds" in text and "matched random: an interval" not in text  # 25-35 misses 20
    assert "no offset model puts the peak" in sp.offset_models_finding({"independent": _cur(g, g, 90.0)})


def _ratio_rows(ratios, lo, hi):
    return pd.DataFrame({"ratio": ratios, "ratio_ci_low": lo, "ratio_ci_high": hi})


def _depth(ratio, lo, hi, norm=(0.9, 0.8, 1.0)):
    return _ratio_rows([1.0, ratio], [1.0, lo], [1.0, hi]).assign(
        **{"altitude (m)": [7.5, 30.0], "norm_ratio": [1.0, norm[0]], "norm_ratio_ci_low": [1.0, norm[1]],
           "norm_ratio_ci_high": [1.0, norm[2]]})


def test_pitch_depth_finding_judges_effects_by_their_intervals():
    pitch = _ratio_rows([1.0, 1.02, 0.99, 1.5, 0.6], [0.95, 0.97, 0.9, 1.3, 0.5], [1.05, 1.08, 1.1, 1.7, 0.7])
    text = sp.pitch_depth_finding(pitch, _depth(0.7, 0.6, 0.8), [5.0, 10.0, 15.0], (30.0, 80.0))
    assert "no clear effect at any level, as the mirror symmetry requires" in text and "0 % (95 % CI -5 % to +5 %) at ±5°" in text
    assert "+50 %" in text and "-40 %" in text and "opposite sign, set by the turn direction" in text
    assert "at 30 m instead of 7.5 m" in text and "-30 %" in text and "flying higher shortens the locus" in text
    assert "per unit range no clear change, so it is the change of range" in text  # norm interval holds 1
    assert "not merely" in sp.pitch_depth_finding(pitch, _depth(0.7, 0.6, 0.8, (0.8, 0.7, 0.9)), [5, 10, 15], (30, 80))
    assert "flying higher lengthens" in sp.pitch_depth_finding(pitch, _depth(1.3, 1.2, 1.4), [5, 10, 15], (30, 80))
    assert ": no clear effect." in sp.pitch_depth_finding(pitch, _depth(1.0, 0.9, 1.1), [5, 10, 15], (30, 80))
    pitch.loc[0, ["ratio", "ratio_ci_low", "ratio_ci_high"]] = [1.2, 1.1, 1.3]
    pitch.loc[4, ["ratio", "ratio_ci_low", "ratio_ci_high"]] = [1.2, 1.1, 1.3]
    text = sp.pitch_depth_finding(pitch, None, [5.0, 10.0, 15.0], (30.0, 80.0))
    assert "at 1 of 3 levels the interval excludes 0 %, though the mirror symmetry allows no effect" in text
    assert "clear effects of the same sign either way" in text and "altitude" not in text
    pitch.loc[4, ["ratio", "ratio_ci_low", "ratio_ci_high"]] = [1.0, 0.9, 1.1]
    assert "no clear effect turning toward starboard" in sp.pitch_depth_finding(pitch, None, [5, 10, 15], (30, 80))


def test_survey_summary_names_the_shape_the_models_and_the_study():
    g = np.arange(0.0, 181.0, 10.0)
    m = 1.0 + 9.0 * np.sin(np.radians(g))
    models = {"matched same": _cur(g, m, 20.0, side="same"), "matched opposite": _cur(g, m, 100.0)}
    text = sp.survey_summary(_cur(g, m, 90.0), models, 0.25, 0.5)
    assert "peaks at 90° (near a cross-line" in text and "repeat and anti-parallel passes give the shortest loci" in text
    assert "appears with matched same, so the shape of the curve is set by an offset model" in text
    assert "pitch" not in text
    text = sp.survey_summary(_cur(g, m, 20.0), {"matched opposite": models["matched opposite"]}, 0.25, 0.5)
    assert "(at a moderate oblique angle" in text and "No other offset model shown" in text
    pitch = _ratio_rows([1.0, 1.0, 1.5, 0.6], [0.9, 0.9, 1.3, 0.5], [1.1, 1.1, 1.7, 0.7])
    text = sp.survey_summary(_cur(g, m, 90.0), models, 0.25, 0.5, (pitch, _depth(0.7, 0.6, 0.8)))
    assert "the sign of its pitch changes nothing" in text and "flying higher above the feature shortens the locus (-30 %" in text
    pitch.loc[1, ["ratio_ci_low", "ratio_ci_high"]] = [1.05, 1.2]
    assert "changes the median at some levels" in sp.survey_summary(_cur(g, m, 90.0), models, 0.25, 0.5,
                                                                      (pitch, _depth(0.7, 0.6, 0.8)))


def _summary():
    return pd.DataFrame({"pattern": ["repeat + reciprocal", "two lines + cross line", "60° apart"], "n": 1000,
                         "resolved": [0.97, 0.999, 1.0], "ambiguous": [0.03, 0.001, 0.0], "none": [0.0, 0.0, 0.0],
                         "ambiguous_no_elevation": [0.5, 0.4, 0.3], "ambiguous_no_azimuth": [0.03, 0.001, 0.0],
                         "plane_angle_median_deg": [1.5, 60.0, 40.0], "error_per_cm_median_m": [3.0, 0.05, 0.08],
                         "error_full_median_m": [9.0, 2.0, 2.5]})


def _intervals(s):
    return {r.pattern: {"plane_angle_deg": {"median": r.plane_angle_median_deg, "ci_low": 0.9 * r.plane_angle_median_deg,
                                            "ci_high": 1.1 * r.plane_angle_median_deg},
                        "point_error_q95_m": {"median": r.error_per_cm_median_m, "ci_low": 0.9 * r.error_per_cm_median_m,
                                              "ci_high": 1.1 * r.error_per_cm_median_m},
                        "r1_m": {"median": 20.0, "ci_low": 19.0, "ci_high": 21.0}} for r in s.itertuples()}


def test_closure_finding_names_best_and_worst_pattern_by_error():
    s = _summary()
    text = pf.closure_finding(s, _intervals(s))
    best, worst = s.loc[s.error_per_cm_median_m.idxmin()], s.loc[s.error_per_cm_median_m.idxmax()]
    assert f"best-conditioned pattern is {best.pattern}, the worst {worst.pattern}" in text
    assert "(median point error 60 times the best's)" in text  # 3.0 / 0.05
    assert text.startswith(f"resolved to one point in {share_text(0.97, 1000)} (repeat + reciprocal), "
                           f"{share_text(0.999, 1000)} (two lines + cross line) and {share_text(1.0, 1000)} (60° apart)")
    assert f"would be left ambiguous; with the azimuth and range bounds lifted instead, {share_text(0.03, 1000)}" in text
    assert ": the elevation bound rejects the mirror candidate" in text  # lifting it leaves far more ambiguous
    assert "1.5° (95 % CI 1.4–1.6°)" in text and "none left" not in text
    s2 = s.assign(ambiguous_no_azimuth=[0.6, 0.5, 0.4], none=[0.0, 0.01, 0.0])
    text = pf.closure_finding(s2, _intervals(s2))
    assert ": the azimuth and range bounds reject the mirror candidate" in text and "none left in" in text
    ranking = pf.pattern_ranking(s)
    order = [s.pattern[i] for i in np.argsort(s.error_full_median_m.to_numpy())]
    assert [ranking.index(p) for p in order] == sorted(ranking.index(p) for p in order)
    assert f": {order[0]} is the best-conditioned choice and {order[-1]} the worst" in ranking
    assert f"at least {share_text(0.97, 1000)} of the configurations" in ranking


def test_sweep_finding_finds_the_extreme_cells():
    h = np.arange(0.0, 181.0, 30.0)
    h2, h3 = (a.ravel() for a in np.meshgrid(h, h))
    err = 0.1 + np.cos(np.radians(h2)) ** 2 * np.cos(np.radians(h3)) ** 2
    sweep = pd.DataFrame({"heading2_deg": h2, "heading3_deg": h3, "point_error_q95_median_m": err,
                          "point_error_q95_median_ci_low_m": err - 0.01, "point_error_q95_median_ci_high_m": err + 0.01,
                          "resolved_fraction": np.where(np.arange(len(h2)) == 3, 0.9, 1.0), "n": 100})
    text = pf.sweep_finding(sweep)
    # the worst cells: the four corners, all at 1.1 (equal or reciprocal headings); the best: every
    # cell with a heading of 90° (0.1), within 0.01 of each other
    assert text.startswith("The worst cells are the corners, where all three headings are equal or reciprocal: "
                           "4 cells with h₂ 0° to 180° and h₃ 0° to 180° (median up to 1.10 m (95 % CI 1.09–1.11 m))")
    assert "The best cells, read the same way, are 13 cells" in text and "down to 0.10 m (95 % CI 0.090–0.11 m)" in text
    assert "a flat optimum, not one best pair of headings" in text
    # the diagonal away from the corners: (30°, 30°) and (150°, 150°) at 0.1 + 0.75² = 0.6625, the
    # largest, far below the corners' interval (1.09): not degenerate
    assert "is not degenerate: its largest median error is 0.66 m" in text
    # spread out (h2 >= 45, h3 <= 135, h3 - h2 >= 45): (60°, 120°) at 0.1 + 0.25 * 0.25 = 0.1625
    assert "the largest median error is 0.16 m" in text
    n_all, unresolved = 100 * len(h2), 10  # one cell at 90 %
    assert f"Over all cells {fmt_percent(1 - unresolved / n_all)} of the configurations are resolved" in text


def test_sweep_finding_says_when_the_worst_cells_are_not_the_corners_and_the_diagonal_is_degenerate():
    h = np.arange(0.0, 181.0, 30.0)
    h2, h3 = (a.ravel() for a in np.meshgrid(h, h))
    err = np.where(np.isclose(h2, h3), 1.0, 0.2) + np.where((h2 == 60) & (h3 == 90), -0.1, 0.0)  # the whole diagonal worst
    sweep = pd.DataFrame({"heading2_deg": h2, "heading3_deg": h3, "point_error_q95_median_m": err,
                          "point_error_q95_median_ci_low_m": err - 0.01, "point_error_q95_median_ci_high_m": err + 0.01,
                          "resolved_fraction": 1.0, "n": 100})
    text = pf.sweep_finding(sweep)
    assert "equal or reciprocal" not in text and text.startswith("The worst cells are 7 cells")
    assert "is as degenerate as the worst cells" in text
    assert ": one best pair of headings." in text  # (60°, 90°) alone at 0.1, the others at 0.2


def test_tilt_markdown_is_explicit_when_no_platform_is_a_surface_vessel():
    empty = pd.DataFrame(columns=["platform", "tilt_deg", "pattern", "n", "resolved", "ambiguous"])
    assert "No platform of this run is a surface vessel" in pf.tilt_markdown(empty, {}, {})


def _tilt_rows(resolved_15, resolved_35, n=1000):
    return pd.DataFrame({"platform": "boat", "tilt_deg": [15.0, 15.0, 35.0, 35.0], "pattern": ["x", "y", "x", "y"],
                         "n": n, "resolved": [resolved_15, 0.9, resolved_35, 0.9],
                         "ambiguous": [1 - resolved_15, 0.1, 1 - resolved_35, 0.1]})


def test_tilt_finding_is_the_papers_paragraph_for_the_shipped_boat():
    """One source for the paper's boat and a user's vessel: the fan's top edge from the fan and
    the tilt (50° fan: 25° - 15° = 10° above the horizontal), the shares as the chapter glues them
    (share_text), and the conclusion only where a resolved share changes beyond both intervals;
    "an assumed value" because data/platforms.toml marks the boat's tilt as an assumption."""
    from sss_locus.experiments.datamodel.platforms import load_platform
    from sss_locus.report.three_views.figures import share_text

    boat = load_platform("boat")
    text = pf.tilt_markdown(_tilt_rows(0.5, 1.0), {"boat": boat}, {"boat": "Boat (`boat`)"})
    assert text.startswith("- **Boat (`boat`)**: With its transducers tilted 15° the fan reaches 10° above "
                           "the horizontal: the feature is resolved in ")
    assert f"{share_text(0.5, 1000)} (x) and {share_text(0.9, 1000)} (y) of the configurations" in text
    assert f"a two-fold ambiguity remaining in {share_text(0.5, 1000)} and {share_text(0.1, 1000)}" in text
    assert f"; at 35° the shares resolved are {share_text(1.0, 1000)} and {share_text(0.9, 1000)}." in text
    assert text.rstrip().endswith("Its resolution at 25° therefore rests on where the top of its fan lies, "
                                  "an assumed value.")
    # 50.0 % vs 50.5 % of 1000: the exact intervals overlap, so no dependence on the tilt is claimed
    same = pf.tilt_markdown(_tilt_rows(0.5, 0.505), {"boat": boat}, {"boat": "Boat (`boat`)"})
    assert "rests on" not in same and same.rstrip().endswith(".")


def test_drivers_say_what_normalising_moves_the_azimuths_and_a_constant_pitch():
    raw = [0.7, 0.3, 0.2, 0.05, 0.0]  # mean range first raw
    norm = [0.1, 0.2, 0.6, 0.05, 0.0]  # misalignment first normalised
    rho = _rho_table(raw, norm)
    text = ps.drivers_finding(rho)
    assert "Normalising moves mean range from ρ = 0.70 to 0.10" in text
    assert f"The azimuths' normalised ρ: {plain_label('azimuth1_deg')} 0.05." in text and "pitch" not in text
    rho.attrs["dropped"] = ["pitch2_deg", "abs_pitch2_deg"]
    assert "Vehicle 2's pitch is constant here" in ps.drivers_finding(rho)
    assert "Normalising" not in ps.drivers_finding(_rho_table(raw, raw))  # the same first


def test_fan_finding_says_the_heatmap_edge_only_when_the_rule_removes_part():
    level = {"share": 0.2, "theta_min_deg": -11.6}
    text = ps.fan_finding(level, [{"share": 0.3}])
    assert "removes 20 % of the fan" in text and "at most 30 % for a pitched" in text
    assert "no samples left of θ₁ ≈ -12°" in text
    flat = ps.fan_finding({"share": 0.0, "theta_min_deg": float("nan")}, [])
    assert "does not reach above the horizontal" in flat and "no samples left" not in flat


def test_panels_hotspot_and_choices_follow_their_numbers():
    m = {"range_far_over_near_ratio": 0.5, "azimuth_peak_theta1_deg": 12.4, "azimuth_peak_theta2_deg": -7.6,
         "azimuth_peak_count": 1234.0, "elevation_centre_over_corner_ratio": 2.0, "yaw_peak_neg_deg": -65.0,
         "yaw_peak_pos_deg": 55.0, "yaw_near0_over_peak_ratio": 0.39, "yaw_near180_over_peak_ratio": 0.28,
         "multi_arc_fraction": 0.017, "top_norm": "elevation_misalignment_deg",
         "norm_elevation_misalignment_deg_rho": 0.54, "yaw_peak_neg_lo_deg": -75.0, "yaw_peak_neg_hi_deg": -65.0,
         "yaw_peak_pos_lo_deg": 55.0, "yaw_peak_pos_hi_deg": 55.0,
         **{f"azimuth2_yaw_peak_{h}_{a}_{e}_deg": v for h, a, e, v in (
             ("neg", "yaw", "lo", -90.0), ("neg", "yaw", "hi", -80.0), ("pos", "yaw", "lo", 70.0), ("pos", "yaw", "hi", 70.0),
             ("neg", "theta2", "lo", 5.0), ("neg", "theta2", "hi", 5.0), ("pos", "theta2", "lo", -5.0),
             ("pos", "theta2", "hi", 0.0))}}
    for name in ("range_far_over_near_ratio", "elevation_centre_over_corner_ratio", "yaw_near0_over_peak_ratio",
                 "yaw_near180_over_peak_ratio", "multi_arc_fraction"):
        m[f"{name}_ci_low"], m[f"{name}_ci_high"] = 0.9 * m[name], 1.1 * m[name]
    text = ps.panels_finding(m)
    assert "0.50 (95 % CI 0.45–0.55) times" in text and "shorter far out" in text and "≈ 12°, -8°" in text
    assert "1,234 samples" in text and "peaks at -75° to -65° and 55°" in text and "1.7 % (95 % CI 1.5–1.9 %)" in text
    assert "at yaw -90° to -80° with θ₂ 5° and at yaw 70° with θ₂ -5° to 0°" in text  # panel (e)
    assert "upper edge" not in text  # no heatmap given
    b = pd.DataFrame({"x_mid": [12.4, 12.4, 20.0, 5.0], "y_mid": [-7.6, 3.0, -7.6, -7.6],
                      "masked": [False, False, False, True]})  # the peak at the smallest shown azimuths
    assert "at the upper edge of both fans" in ps.panels_finding(m, b)
    b.loc[3, "masked"] = False  # a shown bin at a smaller azimuth 1
    assert "upper edge" not in ps.panels_finding(m, b)
    check = {"x_mid": 10.0, "y_mid": 20.0, "count": 50, "median": 2.0, "target_count": 2000, "target_median": 1.9,
             "target_ci_low": 1.8, "target_ci_high": 2.0, "runner_up_median": 1.95, "runner_up_x_mid": 5.0,
             "runner_up_y_mid": 20.0, "still_peak": False}
    assert "not settled" in ps.hotspot_finding(check) and "(10°, 20°)" in ps.hotspot_finding(check)
    checks = pd.DataFrame({"run": ["mine, unconstrained sweep", "mine, vehicle 2 may be above the surface",
                                   "mine2, unconstrained sweep"],
                           "top normalised": ["baseline", plain_label("elevation_misalignment_deg"), "range r₁"],
                           "rho misalignment (norm.)": [0.41, 0.5, 0.9],
                           "hotspot region theta1 (deg)": [(4, 10), (0, 0), (0, 0)],
                           "hotspot region theta2 (deg)": [(-26, -26), (0, 0), (0, 0)],
                           "hotspot region at equal azimuths": [False, True, True],
                           "yaw 0 / peak": [0.5, 0.6, 0.7], "yaw 0 / peak CI": [(0.4, 0.6), (0.5, 0.7), (0.6, 0.8)]})
    text = ps.choices_finding(m, checks, "mine")
    assert ("unconstrained sweep: baseline first (misalignment ρ 0.41; hotspot region θ₁ 4° to 10°, θ₂ -26°, without "
            "equal azimuths; median near yaw 0 0.50 (95 % CI 0.40–0.60) of the peak)") in text
    assert "above the surface: " in text and "with equal azimuths" in text
    assert "0.90" not in text and "sea surface" not in text  # another platform's row; no depth share given
    text = ps.choices_finding(m, checks, "mine", (0.23, 5.0))
    assert "above the sea surface in 23 % of the samples with vehicle 1 at its shallowest 5 m" in text
    assert "the top normalised quantity is the same" in text  # elevation misalignment in both
    checks.loc[1, "top normalised"] = "baseline"
    assert "the top normalised quantity differs" in ps.choices_finding(m, checks, "mine", (0.23, 5.0))
    md = ps.findings_markdown({"A (`a`)": text})
    assert re.match(r"- \*\*A \(`a`\)\*\*: main run: ", md)


def test_a_table_a_cell_shows_is_its_last_statement():
    """A cell shows only its last expression: a readable_table() earlier in a cell (for example
    before lines gluing generated findings) would silently vanish from the page."""
    import ast
    import json

    from sss_locus.paths import REPO_ROOT

    for path in sorted((REPO_ROOT / "notebooks").glob("*.ipynb")):
        for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
            source = "".join(cell["source"])
            if cell["cell_type"] != "code" or "readable_table(" not in source:
                continue
            body = ast.parse(source.replace("%matplotlib inline", "pass")).body
            shown = [i for i, node in enumerate(body) if isinstance(node, ast.Expr)
                     and "readable_table(" in ast.get_source_segment(source, node).split("\n")[0][:20]]
            assert all(i == len(body) - 1 for i in shown), (path.name, source[:120])


def _bands(rows):
    return pd.DataFrame(rows, columns=["kind", "lo_deg", "hi_deg"])


def test_paper_band_finding_counts_the_paper_band_and_flips_with_the_bands():
    from sss_locus.report.survey_passes.planning import paper_band_finding
    curve = pd.DataFrame({"crossing_angle_deg": np.arange(0.0, 181.0, 5.0)})  # 10..40: 7 grid angles
    bands = _bands([("prefer", 0, 5), ("avoid", 10, 35), ("prefer", 80, 100), ("prefer", 175, 180)])
    text = paper_band_finding(curve, bands)
    assert text.startswith("the first avoided band is 10–35°, ending by the paper's 40°")
    assert "86 % are avoided and 0 % preferred" in text and 'a cross-line (90°) is "prefer"' in text  # 6 of 7
    wide = _bands([("prefer", 0, 15), ("avoid", 40, 120)])
    text = paper_band_finding(curve, wide)
    assert "40–120°, reaching past the paper's 40°" in text and "14 % are avoided and 29 % preferred" in text
    assert 'is "avoid"' in text and "no angle is to be avoided" in paper_band_finding(curve, _bands([]))


def test_cross_line_finding_says_whether_the_offset_model_decides():
    from sss_locus.report.survey_passes.planning import cross_line_finding
    curves = {("b", s): SimpleNamespace(offset_model=SimpleNamespace(label=s)) for s in ("independent", "matched")}
    bands = {("b", "independent"): _bands([("avoid", 60, 120)]), ("b", "matched"): _bands([("prefer", 80, 100)])}
    text = cross_line_finding(curves, bands, "b")
    assert text == ('a cross-line (90°) is "avoid" with independent offsets and "prefer" with matched offsets: '
                    "the offset model decides whether it is a fallback.")
    bands[("b", "matched")] = _bands([("avoid", 80, 100)])
    assert "the same under every offset model shown" in cross_line_finding(curves, bands, "b")
