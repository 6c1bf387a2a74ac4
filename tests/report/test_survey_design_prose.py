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
