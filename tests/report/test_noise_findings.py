"""The noise chapter's findings (sss_locus.report.noise.findings) say what their numbers say: curves
and tables are built here by hand so that each verdict, order and word is known in advance, and
each word is flipped by changing the numbers that decide it."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd

from sss_locus.report.noise import findings as nf

GRID = [0.0, 10.0, 20.0, 30.0, 40.0, 90.0, 180.0]
HEAD = "×1"


def _curve(**medians):
    """A curve with each value's medians over GRID and intervals ±10 % around them."""
    out = {"crossing_angle_deg": GRID}
    for value, m in medians.items():
        m = np.asarray(m, float)
        out |= {f"{value}_median": m, f"{value}_ci_low": 0.9 * m, f"{value}_ci_high": 1.1 * m}
    return pd.DataFrame(out)


LENGTH = [1.0, 2.0, 3.0, 3.0, 2.0, 1.5, 1.0]


def _curves(extent, band, range_extent=None):
    return {HEAD: _curve(locus_length_m=LENGTH, band_width_m=band, extent_m=extent),
            "range only": _curve(extent_m=range_extent or extent, band_width_m=band),
            "×0.1": _curve(extent_m=[e / 10 for e in extent])}


def _table(ratio, empty=0.5, attitude=0.4):
    return pd.DataFrame({"noise": [HEAD, HEAD, "attitude only", "×0.1"],
                         "band_width_m": [ratio, ratio, 0.0, 0.0], "locus_length_m": [1.0, 1.0, 1.0, 1.0],
                         "empty_fraction": [empty, empty, attitude, empty / 2]})


def _boot(curve, value="extent_m"):
    return {value: np.tile(curve[f"{value}_median"].to_numpy(), (20, 1))}


def test_the_verdict_follows_the_ends_against_the_oblique_band_and_90_degrees():
    holds = _curves(extent=[5, 9, 9, 9, 9, 8, 6], band=[20, 15, 12, 11, 10, 5, 30])
    text = nf.answer_finding(holds, _boot(holds[HEAD]), _table(10.0), HEAD)
    assert "advice survives noise ×1" in text and "worse end (0° or 180°) 6.0 m against 9.0 m" in text
    fails = _curves(extent=[30, 9, 9, 9, 9, 8, 6], band=[20, 15, 12, 11, 10, 5, 30])
    text = nf.answer_finding(fails, _boot(fails[HEAD]), _table(10.0), HEAD)
    assert "does not survive" in text and "worse end (0° or 180°) 30 m" in text
    # the smallest and largest median extent, read off the hand-built curve
    assert "smallest at 180°" in text and "largest at 0°" in text


def test_band_or_length_sets_the_size_and_the_stereo_shape_is_read_from_the_band():
    c = _curves(extent=[5, 9, 9, 9, 9, 8, 6], band=[20, 15, 12, 11, 10, 5, 30])
    text = nf.answer_finding(c, _boot(c[HEAD]), _table(48.0), HEAD)
    assert "48 times as wide" in text and "the band, not the locus length, sets" in text
    assert "Like classical stereo" in text and "intervals apart from 90° at 0° and 180°" in text
    text = nf.answer_finding(c, _boot(c[HEAD]), _table(0.5), HEAD)
    assert "the locus length, not the band, sets" in text
    one = _curves(extent=[5, 9, 9, 9, 9, 8, 6], band=[5.2, 15, 12, 11, 10, 5, 30])  # 5.2 ± 10 % meets 5 ± 10 %
    assert "intervals apart from 90° at 180°)" in nf.answer_finding(one, _boot(one[HEAD]), _table(2.0), HEAD)
    near = _curves(extent=[5, 9, 9, 9, 9, 8, 6], band=[5.2, 15, 12, 11, 10, 5, 5.3])
    assert "the intervals overlap" in nf.answer_finding(near, _boot(near[HEAD]), _table(2.0), HEAD)
    flat = _curves(extent=[5, 9, 9, 9, 9, 8, 6], band=[5, 15, 12, 11, 10, 8, 30])
    assert "Unlike classical stereo" in nf.answer_finding(flat, _boot(flat[HEAD]), _table(2.0), HEAD)


def test_range_floor_is_compared_with_the_noise_free_length_at_each_angle():
    c = _curves(extent=[5, 9, 9, 9, 9, 8, 6], band=[1] * 7, range_extent=[2, 1, 1, 1, 1, 0.75, 3])
    text = nf.range_floor_finding(c, HEAD, ["×0.1"])
    # range extent over length: 2/1, 0.75/1.5, 3/1
    assert "0.50–3.0 times the noise-free locus length" in text and "larger at 2 of the 3 angles" in text
    assert "With every standard deviation ×0.1 the extent is 0.50 m" in text
    assert "extent at the other" not in nf.range_floor_finding(c, HEAD, [])


def test_crop_failure_and_the_beam_thickness_against_the_attitude_errors():
    model = SimpleNamespace(roll_sigma_deg=0.1, pitch_sigma_deg=0.1, heading_sigma_deg=1.0)
    text = nf.crop_finding(_table(1.0, empty=0.92, attitude=0.83), HEAD, ["×0.1"], 0.27, model)
    assert "92 % of the noisy draws" in text and "(46 % at ×0.1)" in text and "alone empty 83 %" in text
    assert "0.27° thick along-track" in text and "the largest 3.7 times that thickness" in text  # 1.0 / 0.27
    assert "widen the beams" in text
    assert "never empty the locus" in nf.crop_finding(_table(1.0, attitude=0.0), HEAD, [], 0.27, model)


def test_the_dominant_error_group_is_counted_angle_by_angle():
    pos, rng = [9, 8, 7, 7, 7, 6, 9], [2, 1, 1, 1, 1, 0.5, 2]
    curves = {HEAD: _curve(band_width_m=[10] * 7), "position only": _curve(band_width_m=pos),
              "range only": _curve(band_width_m=rng)}
    text = nf.breakdown_finding(curves, HEAD)
    assert text.startswith("sensor-position errors dominate") and "at 7 of 7 crossing angles" in text
    assert "a floor of 0.50–2.0 m" in text and "Both grow toward" in text
    curves["position only"], curves["range only"] = _curve(band_width_m=rng), _curve(band_width_m=[1, 1, 1, 1, 1, 3, 1])
    text = nf.breakdown_finding(curves, HEAD)
    assert text.startswith("range errors dominate") and "Only the position-only band" in text
    assert nf.summary_finding({**curves, HEAD: _curve(locus_length_m=LENGTH, band_width_m=[1] * 7,
                                                      extent_m=[5, 9, 9, 9, 9, 8, 6])},
                              _table(2.0), HEAD).count("range errors dominate the band") == 1


def _check(two, three):
    rows = [dict(platform=p, kind=k, scale=s, monte_carlo_m=10.0, rel_diff=r)
            for p in ("a", "b") for k, rels in (("two", two), ("three", three)) for s in (0.001, 1.0)
            for r in (rels if s == 1.0 else [0.01, -0.02])]
    return pd.DataFrame(rows)


def test_first_order_is_a_fair_guide_only_where_its_median_difference_is_small():
    check = _check(two=[0.05, -0.05, 0.3], three=[0.6, 0.7, -0.9])
    assert nf.guide_sentence(check, 1.0) == "first order is a fair guide for the band but not for the three-view point"
    text = nf.check_finding(check, {"a": 1.0, "b": 0.25}, {"a": "AUV", "b": "boat"}, 0.001, 1.0)
    assert "agree to within 2.0 % for the band" in text and "median relative difference is 5 % for the band" in text
    assert "67 % of the pass pairs within 10 %" in text and "indications of conditioning" in text
    assert "no candidate in 100 % of the draws" in text and "no candidate in 25 %" in text
    good = _check(two=[0.05, -0.05, 0.3], three=[0.05, 0.1, 0.5])
    assert nf.guide_sentence(good, 1.0).endswith("for both the band and the three-view point")
    assert "indications of conditioning" not in nf.check_finding(good, {"a": 0, "b": 0}, {"a": "A", "b": "B"}, 0.001, 1.0)


def test_other_offset_models_each_get_their_verdict_at_every_level():
    v = {("a", "independent", 1.0): dict(holds=True, ends=1, oblique=2, perpendicular=3),
         ("a", "matched:10:same", 1.0): dict(holds=False, ends=120, oblique=20, perpendicular=8.8),
         ("a", "matched:10:same", 0.1): dict(holds=True, ends=1, oblique=2.9, perpendicular=1.5)}
    text = nf.offset_models_finding(v, "a", {"matched:10:same": "matched ±10 m"})
    assert "independent" not in text and "at ×1 the advice fails (median extent: worse end 120 m" in text
    assert "at ×0.1 the advice holds" in text
    assert "no other offset model" in nf.offset_models_finding({k: x for k, x in v.items() if k[1] == "independent"},
                                                               "a", {})
