"""Generated prose says what the run holds (a new user's trial on their own ROV, rov9): which
platforms "this run" includes follows the run's own platforms, an interval that cannot be computed
is said in words (never "nan" or "n/a–n/a"), and counts of one read in the singular. The sentence
functions are rendered with a count of 1 and with NaN inputs; expected words are written here,
not copied from the functions."""

from __future__ import annotations

import itertools
import json
import math
import re

import pytest

from sss_locus.paths import REPO_ROOT
from sss_locus.report.common import text as tx
from sss_locus.report.pose_space import findings as ps
from sss_locus.report.pose_space.figures import check_row
from sss_locus.report.survey_design import prose as sdp
from sss_locus.report.your_pings import joint as ypj

NAN = float("nan")
LEAKS = re.compile(r"\bnan\b|n/a|\binf\b", re.IGNORECASE)
PLURAL_ONE = re.compile(r"\b1 (features|seeds|platforms|passes|sightings|pings|samples)\b")


def _clean(text: str) -> None:
    assert not LEAKS.search(text), text
    assert not PLURAL_ONE.search(text), text


@pytest.mark.parametrize("keys", [list(c) for n in (1, 2, 3) for c in itertools.combinations(["auv", "boat", "rov9"], n)])
def test_run_platforms_phrase_names_what_the_run_holds(keys):
    paper = ["auv", "boat"]
    text = tx.run_platforms_md(keys, paper)
    for k in keys:
        assert f"`{k}`" in text
    missing = [k for k in paper if k not in keys]
    for k in missing:  # named as missing, after the semicolon
        assert f"`{k}`" in text.split(";", 1)[1] and "not in this run" in text
    if not missing:
        assert "not in" not in text and text.startswith("the paper's")
    assert ("is not" in text) == (len(missing) == 1) and ("are not" in text) == (len(missing) == 2)


def test_no_chapter_claims_the_papers_platforms_are_included_in_any_run():
    """The trial's rov9 run read "(the paper's AUV and boat included)": typed text that was false
    for any run without them. The words must come from the run's platforms (a glued phrase)."""
    said = re.compile(r"paper's (?:AUV|boat|platforms|AUV and boat|boat and AUV)?\s*included|\(the paper's\s+included",
                      re.IGNORECASE)
    for path in sorted((REPO_ROOT / "notebooks").glob("*.ipynb")):
        for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
            if cell["cell_type"] == "markdown":
                assert not said.search(" ".join("".join(cell["source"]).split())), (path.name, cell.get("id"))


def test_every_run_platforms_key_a_chapter_shows_is_glued_in_it():
    for path in sorted((REPO_ROOT / "notebooks").glob("*.ipynb")):
        cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
        shown = {k for c in cells if c["cell_type"] == "markdown"
                 for k in re.findall(r"\{glue:md\}`([a-z]+-run-[a-z]+):myst`", "".join(c["source"]))}
        code = "".join("".join(c["source"]) for c in cells if c["cell_type"] == "code")
        for k in shown:
            assert f'ch.glue("{k}", ch.Markdown(ch.run_platforms_md(' in code, (path.name, k)


def test_an_interval_that_cannot_be_computed_is_said_in_words():
    assert tx.fmt_ci(0.46, NAN, NAN) == f"0.46 ({tx.NO_CI})"
    assert tx.fmt_ci(0.46, 0.1, NAN, no_ci=tx.NO_BATCH_CI) == f"0.46 ({tx.NO_BATCH_CI})"
    assert tx.fmt_ci(NAN, NAN, NAN) == tx.NO_VALUE
    assert tx.fmt_ci(0.02, NAN, NAN, percent=True).startswith("2.0 % (no 95 % CI")
    assert tx.fmt_interval({"median": 3.1, "ci_low": NAN, "ci_high": NAN}, "m") == f"3.1 m ({tx.NO_CI})"
    assert tx.fmt_interval({"median": NAN, "ci_low": 1.0, "ci_high": 2.0}, "°") == tx.NO_VALUE
    for text in (tx.fmt_ci(0.46, NAN, NAN), tx.fmt_ci(NAN, 0.0, 1.0), tx.fmt_interval({"median": 2.0, "ci_low": NAN,
                                                                                       "ci_high": 1.0}, "m")):
        _clean(text)
        assert "95 % CI" not in text or "no 95 % CI" in text


def _metrics(ci_low: float, ci_high: float) -> dict:
    return {"top_raw": "mean_range_m", "top_norm": "elevation_misalignment_deg",
            "norm_elevation_misalignment_deg_rho": 0.55, "norm_azimuth1_deg_rho": -0.17,
            "azimuth_peak_theta1_deg": -19.0, "azimuth_peak_theta2_deg": -19.0,
            "azimuth_region_theta1_lo_deg": -19.0, "azimuth_region_theta1_hi_deg": -19.0,
            "azimuth_region_theta2_lo_deg": -19.0, "azimuth_region_theta2_hi_deg": -19.0,
            "azimuth_region_equal": 1.0, "yaw_near0_over_peak_ratio": 0.46,
            "yaw_near0_over_peak_ratio_ci_low": ci_low, "yaw_near0_over_peak_ratio_ci_high": ci_high,
            "multi_arc_fraction": 0.004}


def test_the_choices_table_and_sentence_say_why_the_yaw_interval_is_missing():
    """The rov9 quick run's smaller check runs had a near-0 yaw bin with no sample in some of the
    20 replicate batches: the table read "(nan, nan)" and the sentence "95 % CI n/a–n/a"."""
    import pandas as pd

    bad, good = check_row("rov9, unconstrained sweep", _metrics(NAN, NAN)), check_row("rov9, x", _metrics(0.3, 0.6))
    assert isinstance(bad["yaw 0 / peak CI"], str) and "too few samples" in bad["yaw 0 / peak CI"]
    assert good["yaw 0 / peak CI"] == (0.3, 0.6)
    csv = pd.DataFrame([bad, good]).to_csv(index=False)
    _clean(csv)
    text = ps.choices_finding(_metrics(0.3, 0.6), pd.DataFrame([bad, good]), "rov9")
    _clean(text)
    assert "median near yaw 0 0.46 (no 95 % CI: too few samples" in text
    assert "median near yaw 0 0.46 (95 % CI 0.30–0.60)" in text


def test_counts_of_one_read_in_the_singular():
    assert [tx.count_noun(n, "pass", "passes") for n in (0, 1, 2)] == ["0 passes", "1 pass", "2 passes"]
    assert tx.count_noun(1, "feature") == "1 feature" and tx.count_noun(1200, "feature") == "1,200 features"
    one = ypj.passes_caption(1, "a.csv", "My ROV", synthetic=False)
    _clean(one)
    assert "Each of the" not in one and one.startswith("The one pass of a.csv (My ROV)")
    assert "common shift" in one  # one pass: its offsets are the survey's common shift, held by the priors
    assert ypj.passes_caption(3, "a.csv", "My ROV", synthetic=False).startswith("Each of the 3 passes")
    none = ypj.joint_sentence({"n_adjusted": 0, "n_passes": 1})
    _clean(none)
    assert none.startswith("The sightings form one pass")


class _Area:
    source, sha256 = "data/examples/survey_area.toml", "0123456789abcdef"


def test_survey_design_sentences_with_one_feature_and_one_seed():
    _clean(sdp.area_note(_Area(), "flat", 1, 1))
    assert "1 feature," in sdp.area_note(_Area(), "flat", 1, 1)
    assert "200 features" in sdp.area_note(_Area(), "flat", 200, 1)
    from sss_locus.report.survey_design.prose import _counts

    row = type("Row", (), {"n_seeds": 1, "min_features": 1})()
    assert _counts(row) == "1 seed, at least 1 feature each"


def test_the_example_area_shows_holes_lonlat_and_its_lonlat_lines_are_the_same_area(tmp_path):
    """data/examples/survey_area.toml shows the outline and hole in WGS 84 degrees as commented
    lines; uncommented in place of the metre lines they must give the same area (pyproj's
    inverse of the shipped metres, 6 decimals: within 0.2 m)."""
    pytest.importorskip("shapely")
    pytest.importorskip("pyproj")
    from sss_locus.experiments.survey_design.area import load_area

    src = (REPO_ROOT / "data/examples/survey_area.toml").read_text(encoding="utf-8")
    assert re.search(r"^# holes_lonlat = \[\[\[", src, re.MULTILINE)
    readme = (REPO_ROOT / "data/README.md").read_text(encoding="utf-8")
    assert "`area.holes_m`" in readme and "`area.holes_lonlat`" in readme
    lonlat = re.sub(r"^vertices_m = .*$", "", src, flags=re.MULTILINE)
    lonlat = re.sub(r"^# (vertices_lonlat|holes_lonlat) = ", r"\1 = ", lonlat, flags=re.MULTILINE)
    metres = re.sub(r"^# holes_m = ", "holes_m = ", src, flags=re.MULTILINE)
    (tmp_path / "ll.toml").write_text(lonlat, encoding="utf-8")
    (tmp_path / "m.toml").write_text(metres, encoding="utf-8")
    a, b = load_area(tmp_path / "ll.toml"), load_area(tmp_path / "m.toml")
    assert len(a.polygon.interiors) == len(b.polygon.interiors) == 1
    assert a.polygon.symmetric_difference(b.polygon).area < 0.2 * b.polygon.length
    outline = 0.5 * (900 * 380 + (900 * 560 - 520 * 380) + 520 * 450)  # shoelace of the shipped vertices_m, m^2
    assert math.isclose(a.polygon.area, outline - 100 * 80, rel_tol=1e-3)  # less the 100 m x 80 m hole
