"""The reconstruction chapter's findings (sss_locus.report.reconstruction.findings) say what their
numbers say: summaries over surveys are built here by hand, every comparison word is decided by
where an interval lies against 0, and each is flipped by moving the interval."""

from __future__ import annotations

import numpy as np
import pandas as pd

from sss_locus.experiments.reconstruction.surveys import paired_over_surveys
from sss_locus.report.reconstruction import findings as rf

METRICS = ("horizontal_m", "vertical_m", "shape_m")


def _row(**kw):
    out = {}
    for m in METRICS:
        v = kw.get(m, 1.0)
        out |= {m: v, f"{m}_low": v - 0.5, f"{m}_high": v + 0.5}
    return out


def test_errors_are_quoted_per_error_with_their_interval_at_the_spacing_and_relief_asked():
    rows = [dict(spacing_m=s, value=r, estimator=e, coverage=c, **_row(shape_m=x))
            for s in (60.0, 240.0) for r in (0.0, 4.0)
            for e, c, x in (("flat", 1.0, 0.75 + s + r), ("all", 0.85, 3.0), ("joint", 0.933, 0.33))]
    text = rf.errors_finding(pd.DataFrame(rows), ["flat", "all", "joint"], relief_m=4.0, spacing_m=240.0)
    assert "lines 240 m apart and 4.0 m RMS relief" in text
    assert "**map-shape** error flat-seafloor mosaic 240 (95 % CI 240–250) m" in text  # 0.75 + 240 + 4
    assert "joint adjustment 0.33 (95 % CI -0.17–0.83) m" in text
    assert "N views (ranges) 85.0 %, joint adjustment 93.3 %" in text and "mosaic 100" not in text


def test_slope_says_which_part_is_larger_from_the_signed_medians():
    single = pd.DataFrame({"slope_deg": [0.0, 20.0], "closed_3d_m": [0.0, 39.0], "simulated_3d_m": [0.0, 39.0],
                           "closed_vertical_m": [0.0, -35.0], "closed_across_m": [0.0, -18.0]})
    text = rf.slope_finding(single, 20.0)
    assert "slope of 20°" in text and "vertical part (median -35 m) is larger than its across-track part (-18 m)" in text
    single.loc[1, "closed_vertical_m"] = 6.5
    single.loc[1, "closed_across_m"] = 6.7
    assert "is not larger than" in rf.slope_finding(single, 20.0)


def _models(pv, pp):
    return pd.DataFrame([dict(spacing_m=240.0, estimator=e, navigation=n, **_row(horizontal_m=v))
                         for n, values in (("per_view", pv), ("per_pass", pp)) for e, v in zip(("flat", "all"), values)])


def test_navigation_models_compare_by_their_intervals():
    text = rf.models_finding(_models(pv=[1.4, 1.0], pp=[1.2, 2.2]), 240.0)
    assert "flat-seafloor mosaic 1.4 (95 % CI 0.90–1.9) m per view against 1.2" in text
    assert "N views (ranges) 1.0 (95 % CI 0.50–1.5) m per view against 2.2 (95 % CI 1.7–2.7) m per pass " \
           "(lower with per-view errors (intervals apart))" in text
    assert "mosaic 1.4 (95 % CI 0.90–1.9) m per view against 1.2 (95 % CI 0.70–1.7) m per pass (the intervals overlap)" in text
    assert "higher with per-view errors" in rf.models_finding(_models(pv=[1.0, 3.0], pp=[1.0, 1.0]), 240.0)
    assert rf.models_finding(pd.DataFrame(), 240.0).startswith("not run")


def test_comparison_words_follow_the_paired_intervals_over_the_surveys():
    """Paired differences from per-survey errors made by hand: where the joint adjustment's map
    shape is below the mosaic's in every survey the word is 'closer', above 'farther'."""
    rng = np.random.default_rng(0)
    rows = []
    for seed in range(6):
        for relief in (0.0, 4.0):
            noise = rng.normal(0, 0.01, 3)
            rows.append(dict(seed=seed, spacing_m=240.0, value=relief, estimator="flat",
                             horizontal_m=1.0 + noise[0], vertical_m=0.04, shape_m=1.0 + noise[1]))
            rows.append(dict(seed=seed, spacing_m=240.0, value=relief, estimator="joint", horizontal_m=1.0 + noise[2],
                             vertical_m=0.09 if relief == 0 else 0.01, shape_m=0.3))
    per_survey = pd.DataFrame(rows)
    paired = paired_over_surveys(per_survey, "joint", "flat").rename(columns={"value": "rms_relief_m"})
    text = rf.comparisons_finding(paired, 240.0)
    assert text.startswith("joint adjustment against the mosaic: map-shape error closer at every relief")
    assert "|vertical| error farther at 0 m, closer at 4.0 m" in text
    assert "horizontal error not distinguishable at every relief" in text
