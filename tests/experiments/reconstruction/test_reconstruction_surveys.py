"""Errors over independent surveys (sss_locus.experiments.reconstruction.surveys) against
constructed tables and scipy's Student interval, and the chapter's figures drawn from them."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from sss_locus.experiments.reconstruction.surveys import over_surveys, paired_over_surveys, survey_errors


def _table(seed: int, shift, noise: float, n: int = 40, missing=()):
    """Per-feature rows of two estimators: ``flat`` errs by ``shift`` plus noise, ``joint`` by
    noise only; features in ``missing`` are not estimated by ``joint``."""
    rng = np.random.default_rng(seed)
    rows = []
    for est, s in (("flat", np.asarray(shift, float)), ("joint", np.zeros(3))):
        d = s + noise * rng.standard_normal((n, 3))
        ok = ~np.isin(np.arange(n), missing) if est == "joint" else np.ones(n, bool)
        d[~ok] = np.nan
        rows.append(pd.DataFrame(dict(feature=np.arange(n), estimator=est, estimated=ok, n_seen=3, error_x_m=d[:, 0],
                                      error_y_m=d[:, 1], error_v_m=d[:, 2], seed=seed, spacing_m=240.0, value=1.0)))
    return pd.concat(rows, ignore_index=True)


def test_map_shape_removes_a_common_shift_and_the_common_subset_is_shared():
    t = _table(1, [3.0, -4.0, 2.0], 0.0, missing=[0, 1, 2])
    e = survey_errors(t, ["flat", "joint"]).set_index("estimator")
    assert e.loc["flat", "horizontal_m"] == pytest.approx(5.0) and e.loc["flat", "vertical_m"] == pytest.approx(2.0)
    assert e.loc["flat", "shape_m"] == pytest.approx(0.0, abs=1e-12)  # a pure shift has no shape error
    assert list(e.n_common) == [37, 37]  # the features both estimated
    assert e.loc["joint", "coverage"] == pytest.approx(37 / 40) and e.loc["flat", "coverage"] == 1.0


def test_interval_over_surveys_is_students_over_the_survey_values():
    t = pd.concat([_table(s, [1.0, 0.0, 0.0], 0.5) for s in range(8)], ignore_index=True)
    per = survey_errors(t, ["flat", "joint"])
    s = over_surveys(per, ("estimator",)).set_index("estimator")
    v = per[per.estimator == "flat"].shape_m.to_numpy()
    lo, hi = stats.t.interval(0.95, len(v) - 1, loc=v.mean(), scale=stats.sem(v))
    assert s.loc["flat", "shape_m"] == pytest.approx(v.mean())
    assert (s.loc["flat", "shape_m_low"], s.loc["flat", "shape_m_high"]) == pytest.approx((lo, hi))
    assert s.loc["flat", "n_surveys"] == 8
    p = paired_over_surveys(per, "joint", "flat", by=("spacing_m",)).iloc[0]
    diff = per[per.estimator == "joint"].horizontal_m.to_numpy() - per[per.estimator == "flat"].horizontal_m.to_numpy()
    assert p.horizontal_m == pytest.approx(diff.mean()) and p.horizontal_m_high < 0  # joint has no 1 m shift
