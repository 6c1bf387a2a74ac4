"""The survey-design front figure's legend lists only what is drawn: a Pareto front of one plan
draws no line (so no "Pareto front" entry), and no kind of plan absent from every panel is listed."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

from sss_locus.experiments.datamodel.platforms import load_platform  # noqa: E402
from sss_locus.report.survey_design.figures import plot_front  # noqa: E402


def _plans(n_front: int, all_eligible: bool) -> pd.DataFrame:
    """Five searched plans, the first ``n_front`` on the front, and a standard plan."""
    return pd.DataFrame({"kind": ["search"] * 5 + ["standard"], "total_m": [5e3, 6e3, 7e3, 8e3, 9e3, 8e3],
                         "locus_median_m": [5.0, 4.0, 3.0, 4.5, 4.2, 6.0],
                         "eligible": [True] * 5 + [True] if all_eligible else [True, True, True, False, False, True],
                         "front": [i < n_front for i in range(5)] + [False],
                         "recommended": [True] + [False] * 5})


def _legend(fig) -> list[str]:
    return [t.get_text() for t in fig.legends[0].get_texts()]


def test_a_front_of_one_plan_has_no_pareto_front_entry():
    platforms = {"boat": load_platform("boat"), "auv": load_platform("auv")}
    fig = plot_front({"boat": _plans(1, True), "auv": _plans(1, True)}, "locus", platforms)
    labels = _legend(fig)
    assert "Pareto front" not in labels and "less seen twice than standard" not in labels
    assert {"searched plan", "recommended"} <= set(labels) and len(labels) == len(set(labels))
    plt.close(fig)


def test_a_front_of_several_plans_in_any_panel_is_listed():
    platforms = {"boat": load_platform("boat"), "auv": load_platform("auv")}
    fig = plot_front({"boat": _plans(1, True), "auv": _plans(3, False)}, "locus", platforms)
    labels = _legend(fig)
    assert "Pareto front" in labels and "less seen twice than standard" in labels  # drawn in the second panel only
    plt.close(fig)
