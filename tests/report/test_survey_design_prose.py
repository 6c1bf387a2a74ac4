"""The survey-design chapter's prose (:mod:`sss_locus.report.survey_design.prose`): each sentence
reads the row it names (the standard plan, the recommended plan) and no other, and the table
captions leave the files sentence to ``show_table``. Expected strings are written by hand (angles to three significant
figures, :func:`~sss_locus.report.common.text.fmt_sig`)."""

from types import SimpleNamespace

import pandas as pd

from sss_locus.report.common.tables import files_note
from sss_locus.report.survey_design import prose


def _plans(twice, angles, recommended):
    """Four plans in the order search, standard, lawn-mower, search; ``recommended``: its position."""
    return pd.DataFrame({"kind": ["search", "standard", "lawnmower", "search"], "covered_twice": twice,
                         "best_pair_angle_median_deg": angles,
                         "recommended": [i == recommended for i in range(4)]})


PLATFORMS = {"auv": SimpleNamespace(name="AUV"), "boat": SimpleNamespace(name="boat")}
PLANS = {"auv": _plans([0.5, 0.25, 0.75, 0.125], [10.0, 2.5, 180.0, 44.0], recommended=3),
         "boat": _plans([0.9, 1.0, 0.2, 0.3], [1.0, 0.5, 170.0, 3.0], recommended=1)}


def test_the_standard_plans_share_seen_twice_is_its_own_row():
    assert prose.standard_twice_text(PLANS["auv"]) == "25.0 %"
    assert prose.standard_twice_sentence(PLANS, PLATFORMS) == (
        "the AUV's standard plan sees 25.0 % of the area twice; "
        "the boat's standard plan sees 100.0 % of the area twice.")


def test_best_pairs_compare_the_recommended_with_the_standard_plan():
    assert prose.best_pairs_sentence(PLANS, PLATFORMS) == (
        "for the AUV, 44.0° apart on the recommended plan and 2.50° on the standard plan; "
        "for the boat, 0.500° apart on the recommended plan and 0.500° on the standard plan.")


def test_table_captions_end_with_the_area_note_and_leave_the_files_sentence_to_show_table():
    area = SimpleNamespace(source="my_area.toml", sha256="0123456789abcdef" * 4)
    note = prose.area_note(area, "flat", 100_000, 7)
    assert note == "Area file my_area.toml (SHA-256 0123456789ab), flat seafloor, 100,000 features, seed 7."
    captions = {"tab-survey-design-plans": prose.plans_caption("Harbour", note),
                "tab-survey-design-noise": prose.noise_caption([1, 2, 3], "shape", note),
                "tab-survey-design-crossing": prose.crossing_caption("three_view", note)}
    for label, caption in captions.items():
        assert caption.endswith(" " + note) and files_note(label) not in caption, label
    assert "seeds 1, 2, 3:" in captions["tab-survey-design-noise"]
    assert "decided on: map-shape)" in captions["tab-survey-design-noise"]
    assert "share of features not resolved by three views" in captions["tab-survey-design-crossing"]


def test_a_verdict_says_when_no_searched_plan_could_be_recommended_and_why_a_heading_cannot_be_forced():
    """A search of north-south lines only over an area whose standard plan runs east-west (heading
    0 deg counter-clockwise from east, compass 090): the searched plans are either not eligible or
    longer than the standard plan, so the rule cannot recommend any; the verdict says so and names
    the headings. Searched at the standard plan's own heading, it says the first part only."""
    from sss_locus.report.survey_design.prose import none_as_short

    plans = pd.DataFrame({"kind": ["standard", "lawnmower", "search", "search", "search"],
                          "heading_deg": [0.0, 0.0, 90.0, 90.0, 90.0], "total_m": [9600.0, 9600.0, 4300.0, 11800.0, 10200.0],
                          "eligible": [True, True, False, True, True], "spacing_m": [240.0, 105.0, 240.0, 105.0, 160.0],
                          "crossing_deg": [0.0, float("nan"), float("nan"), 0.0, 90.0], "cross_spacing_m": [240.0] * 5,
                          "altitude_m": [30.0] * 5, "pitch_deg": [0.0] * 5})
    text = none_as_short(plans)
    assert "None of the 3 searched plans could be recommended: 2 of them see enough of the area twice" in text
    assert "lines at 000°/180°" in text and "`headings_deg` cannot force a heading" in text
    assert "090°/270° lines 240 m apart" in text  # the standard plan, by its own label
    same = plans.assign(heading_deg=0.0)
    assert none_as_short(same).startswith(" None of the 3") and "cannot force" not in none_as_short(same)
    shorter = plans.assign(total_m=[9600.0, 9600.0, 4300.0, 9000.0, 10200.0])  # plan 3: eligible, shorter
    assert none_as_short(shorter) == ""
    verdict = {"standard": 0, "best": 0, "error": "horizontal", "reason": "the standard plan is the best", "holds": False}
    summary = pd.DataFrame({"error_horizontal_m": [1.0], "error_horizontal_lo_m": [0.5], "error_horizontal_hi_m": [1.5],
                            "error_vertical_m": [0.2], "error_vertical_lo_m": [0.1], "error_vertical_hi_m": [0.3],
                            "error_shape_m": [0.4], "error_shape_lo_m": [0.3], "error_shape_hi_m": [0.5],
                            "n_seeds": [5], "min_features": [200], "total_m": [9600.0]}, index=[0])
    from sss_locus.report.survey_design.prose import noise_verdict_sentence

    assert noise_verdict_sentence(summary, verdict, plans, SimpleNamespace(name="AUV")).endswith(text)
