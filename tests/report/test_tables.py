"""Tables a reader can read (sss_locus.report.common.tables.readable_table)."""

from __future__ import annotations

import re

import numpy as np
import pandas as pd
import pytest

from sss_locus.report.common.tables import NOT_APPLICABLE, cell, header, readable_table


def _cells(html: str, tag: str) -> list[str]:
    return [re.sub(r"<[^>]+>", "", c).strip() for c in re.findall(rf"<{tag}[^>]*>(.*?)</{tag}>", html, re.S)]


def test_no_index_units_in_headers_and_a_mark_for_missing_values():
    frame = pd.DataFrame({"median_length_m": [0.0123456, np.nan], "stable": [True, None], "note": ["a b", "c"]},
                         index=pd.Index(["auv", "boat"], name="platform"))
    html = readable_table(frame, caption="Two platforms.").to_html()
    assert _cells(html, "th") == ["platform", "median length (m)", "stable", "note"]  # the index is a column
    body = _cells(html, "td")
    assert body == ["auv", "0.0123", "yes", "a b", "boat", NOT_APPLICABLE, NOT_APPLICABLE, "c"]
    assert "NaN" not in html and "None" not in html and "nan" not in body
    assert re.search(rf"<caption>Two platforms\. {NOT_APPLICABLE}: no value for this row\.</caption>", html)
    assert "white-space: nowrap" in html and "overflow-wrap: normal" in html  # numbers never wrap, words whole


def test_a_range_index_is_not_shown_and_a_full_table_has_no_note():
    html = readable_table(pd.DataFrame({"n": [1200, 3]})).to_html()
    assert _cells(html, "td") == ["1,200", "3"] and "<caption>" not in html and 'class="row_heading' not in html


def test_the_same_table_gets_the_same_html_and_another_table_other_ids():
    frame = pd.DataFrame({"x_deg": [1.0, 2.5]})
    assert readable_table(frame).to_html() == readable_table(frame).to_html()  # executed copies are reproducible
    other = readable_table(frame.assign(x_deg=[1.0, 3.5])).to_html()
    assert re.search(r'id="(T_\w+)"', other).group(1) != re.search(r'id="(T_\w+)"', readable_table(frame).to_html()).group(1)


@pytest.mark.parametrize("value, text", [(0.000123456, "1.23e-04"), (0.00123456, "0.00123"), (98765.4, "98,765"), (2.0, "2.00"),
                                         (np.float32(0.5), "0.500"), (np.int64(12345), "12,345"),
                                         (float("inf"), "inf"), (pd.NA, NOT_APPLICABLE), (np.bool_(False), "no")])
def test_cells(value, text):
    assert cell(value) == text


def test_headers_name_units_and_join_levels():
    assert header("range_sigma_m") == "range sigma (m)" and header("plane_angle_q10_deg") == "plane angle q10 (deg)"
    assert header("median locus length (m)") == "median locus length (m)"  # already words
    assert header(("ratio", "ci_low")) == "ratio ci low"


def test_not_a_frame_is_refused():
    with pytest.raises(ValueError, match="frame must be a pandas DataFrame"):
        readable_table([[1, 2]])


def test_row_numbers_are_dropped_and_labels_kept():
    rows = pd.DataFrame({"x_m": [1.0, 2.0, 3.0]}, index=[5, 7, 9])  # a filtered frame: row numbers
    assert _cells(readable_table(rows).to_html(), "th") == ["x (m)"]
    near = pd.concat({"boat": pd.DataFrame({"x_m": [1.0, 2.0]})}, names=["curve"])  # named keys, unnamed rows
    assert _cells(readable_table(near).to_html(), "th") == ["curve", "x (m)"]
    labels = pd.DataFrame({"auv": {"a_m": 1.0}}).T  # unnamed labels: kept, without a header
    assert _cells(readable_table(labels).to_html(), "td")[0] == "auv"


def test_long_names_may_break_after_an_underscore():
    assert cell("elevation_misalignment_deg").replace("\u200b", "") == "elevation_misalignment_deg"
    assert "_\u200bmisalignment" in cell("elevation_misalignment_deg")


def test_a_wide_table_of_few_rows_is_turned_a_quarter():
    wide = pd.DataFrame({"platform": ["auv", "boat"], **{f"q{i}_m": [float(i), 2.0 * i] for i in range(8)}})
    html = readable_table(wide).to_html()
    assert _cells(html, "th") == ["quantity", "auv", "boat"]
    assert _cells(html, "td")[:6] == ["q0 (m)", "0", "0", "q1 (m)", "1.00", "2.00"]
    narrow = wide.iloc[:, :4]
    assert _cells(readable_table(narrow).to_html(), "th") == ["platform", "q0 (m)", "q1 (m)", "q2 (m)"]


def test_a_turned_table_keeps_whole_numbers_whole():
    """A count beside measured values stays a count once the table is turned (a plain transpose
    made it a float and printed 1.00 plans)."""
    wide = pd.DataFrame({"kind": ["standard", "search"], "plan_index": [0, 3], "n_features": [60, 60],
                         **{f"q{i}_m": [0.5 + i, 1.25 * i] for i in range(6)}})
    cells = _cells(readable_table(wide).to_html(), "td")
    assert cells[:6] == ["plan index", "0", "3", "n features", "60", "60"]
    assert cells[6:9] == ["q0 (m)", "0.500", "0"]


def test_numbers_held_as_objects_are_not_taken_for_row_labels():
    """A frame built by transposing a dict of mixed results (numbers and a yes/no) holds every
    column as objects; its first number column must not join the headers (it did: "auv, -24.375")."""
    checks = {"auv": {"x_mid_deg": -24.375, "count": 178, "still_peak": True, **{f"q{i}_m": 1.0 for i in range(6)}},
              "boat": {"x_mid_deg": -21.875, "count": 1282, "still_peak": False, **{f"q{i}_m": 2.0 for i in range(6)}}}
    frame = pd.DataFrame(checks).T.rename_axis("platform")
    assert (frame.dtypes == object).all()  # the case guarded
    html = readable_table(frame).to_html()
    assert _cells(html, "th") == ["quantity", "auv", "boat"]
    assert _cells(html, "td")[:9] == ["x mid (deg)", "-24.4", "-21.9", "count", "178", "1,282", "still peak", "yes", "no"]


def test_a_turned_table_is_headed_by_its_row_labels_as_they_are():
    """The platform key my_auv heads its column as the key (not "my auv"); a text column of results
    next to the label (the top quantity of a run) joins the headers only when no labels are named."""
    runs = pd.DataFrame({"run": ["my_auv, tilt 15 deg"], "top_raw": ["mean range"],
                         **{f"q{i}_m": [float(i)] for i in range(8)}})
    assert _cells(readable_table(runs).to_html(), "th") == ["quantity", "my_auv, tilt 15 deg, mean range"]
    html = readable_table(runs, row_labels=["run"]).to_html()
    assert _cells(html, "th") == ["quantity", "my_auv, tilt 15 deg"]
    assert _cells(html, "td")[:2] == ["top raw", "mean range"]
    with pytest.raises(ValueError, match="row_labels must be columns"):
        readable_table(runs, row_labels=["platform"])


def test_caption_markdown_is_markup_and_names_are_text():
    """A caption's **bold** and `code` become HTML (a Styler shows its caption raw), and a user's
    name holding <, > or & in a caption, a cell or a header stays text."""
    frame = pd.DataFrame({"feature": ["rock<1m> & co"], "n": [3]})
    out = readable_table(frame, caption="**Real data**: picks of `a<b>.csv` & more").to_html()
    caption = out[out.index("<caption"):out.index("</caption>")]
    assert "<strong>Real data</strong>" in caption and "<code>a&lt;b&gt;.csv</code>" in caption
    assert "**" not in caption and "`" not in caption and "&amp; more" in caption
    assert "rock&lt;1m&gt; &amp; co" in out and "rock<1m>" not in out
    wide = pd.DataFrame({"feature": ["<b>x</b>"], **{f"c{i}": [i] for i in range(12)}})
    assert "&lt;b&gt;x&lt;/b&gt;" in readable_table(wide).to_html()  # turned: the name is a header
