"""The survey-design chapter's tables (report/survey_design/tables.py) on plans built by hand."""

import math

import numpy as np
import pandas as pd
import pytest

from sss_locus.report.survey_design.tables import (NOISE_COLUMNS, PLAN_COLUMNS, all_plans, crossing_table,
                                                   noise_table, plans_table)


def _plans(recommended_at: int) -> pd.DataFrame:
    """Four plans: the standard, a lawn-mower and two searched ones, the one at
    ``recommended_at`` recommended; headings 0° (east) and 90° (north) counter-clockwise."""
    kinds = ["standard", "lawnmower", "search", "search"]
    t = pd.DataFrame({c: np.arange(4, dtype=float) + 1 for c in PLAN_COLUMNS})
    t["kind"] = kinds
    t["heading_deg"] = [0.0, 90.0, 0.0, 90.0]
    t["total_m"] = [4000.0, 4000.0, 3500.0, 3000.0]
    t["eligible"] = True
    t["crossing_deg"] = [math.nan, math.nan, math.nan, 90.0]
    t["locus_median_m"] = [5.0, 6.0, 2.0, 1.0]
    t["best_pair_angle_median_deg"] = [10.0, 12.0, 20.0, 80.0]
    t["recommended"] = [i == recommended_at for i in range(4)]
    return t


def test_plans_table_keeps_baselines_and_the_recommended_search_plan_only():
    table = plans_table({"boat": _plans(3), "auv": _plans(0)})
    assert list(table.index) == [("boat", "standard"), ("boat", "lawnmower"), ("boat", "search = recommended"),
                                 ("auv", "standard = recommended"), ("auv", "lawnmower")]
    # km, and compass headings: 0° from east counter-clockwise is 090°, 90° is 000°
    assert table.loc[("boat", "search = recommended"), "track_km"] == pytest.approx(3.0)
    assert table.loc[("boat", "search = recommended"), "heading_compass_deg"] == pytest.approx(0.0)
    assert table.loc[("boat", "standard"), "heading_compass_deg"] == pytest.approx(90.0)
    assert "total_m" not in table and "heading_deg" not in table and "recommended" not in table


def test_noise_table_marks_the_recommended_plan_by_its_plan_index():
    plans = {"boat": _plans(2)}
    summary = pd.DataFrame({c: [1.0, 2.0, 3.0] for c in NOISE_COLUMNS}, index=[0, 2, 3])
    summary["kind"] = ["standard", "search", "search"]
    table = noise_table({"boat": summary}, plans)
    assert list(table.index) == [("boat", "standard", 0), ("boat", "search = recommended", 2),
                                 ("boat", "search", 3)]
    assert list(table.columns) == NOISE_COLUMNS


def test_crossing_table_groups_searched_plans_by_second_line_set():
    table = crossing_table({"boat": _plans(0)}, "locus")
    assert list(table.index) == [("boat", "none"), ("boat", "cross 90°")]
    assert table.loc[("boat", "cross 90°"), "best"] == pytest.approx(1.0)  # only the searched plans count
    assert table.loc[("boat", "none"), "n_plans"] == 1


def test_all_plans_stacks_platforms_with_compass_headings():
    data = all_plans({"boat": _plans(0), "auv": _plans(1)})
    assert len(data) == 8 and set(data.platform) == {"boat", "auv"}
    assert sorted(data.heading_compass_deg.unique()) == [0.0, 90.0]
    assert all_plans({}).empty
