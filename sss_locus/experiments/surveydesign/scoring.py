"""Plans scored under the noise model over independent seeds, and a recommendation that holds.

The search (:func:`sss_locus.experiments.survey_design.search_plans`) ranks plans by a
noise-free objective on one seed. Here the plans the rule could recommend are scored again
under the platform's noise model (``data/noise.toml``): the **two-view error** (the 3-D error
of the reconstruction chapter's two-view estimate, the locus point nearest the flat-seafloor
prior) and the **all-views error** (its N-view least-squares estimate, over the features it
estimates), each as the median over the features of one seed; every seed draws other features,
in-beam elevations and noise, so the seeds are independent replicates.

Per plan (:func:`score_plans`, :func:`summarise`): the mean over the seeds of each median and its
95 % interval ``mean +- t sd / sqrt(k)`` (:func:`~sss_locus.experiments.replicates.replicate_interval`,
``k >= 3`` seeds). A median over fewer than :data:`MIN_FEATURES` features is not computed (NaN:
too few to be a finding), and a plan with such a seed has no interval.

Which plans (:func:`candidates`): the baselines, the noise-free front, the plan the noise-free
rule recommends, and the ``n_best`` eligible plans no longer than the standard plan with the
smallest noise-free objective (a pre-selection, stated).

The recommendation (:func:`recommend_under_noise`): among the eligible scored plans no longer
than the standard plan, a plan is **recommended over the standard plan only when the interval of
its two-view error lies wholly below the standard plan's** (the intervals do not overlap; of
several such plans, the one of smallest mean); otherwise the standard plan is kept. The all-views error is reported beside it
and never decides (it leaves most features of a surface vessel unestimated).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..replicates import replicate_interval

MIN_FEATURES = 30
"""Fewest features a median is taken over (fewer: not a finding, NaN)."""
ERRORS = {"two": ("error_two_median_m", "n_two_estimated"), "all": ("error_all_median_m", "n_all_estimated")}


def candidates(plans: pd.DataFrame, objective_col: str, *, n_best: int = 8) -> pd.Index:
    """Rows of ``plans`` (the search's table) to score (module docstring)."""
    std_total = float(plans.loc[plans.kind == "standard", "total_m"].iloc[0])
    pick = (plans.kind != "search") | plans.front
    if "recommended" in plans:
        pick |= plans.recommended
    short = plans[(plans.kind == "search") & plans.eligible & (plans.total_m <= std_total) & plans[objective_col].notna()]
    best = short.sort_values([objective_col, "total_m"], kind="stable").index[:n_best]
    return plans.index[pick | plans.index.isin(best)]


def score_plans(platform, area_key: dict, terrain: str, plans: pd.DataFrame, noise, *, seeds, n_features: int,
                grid_m: float, objective_col: str, n_best: int = 8) -> pd.DataFrame:
    """One row per (plan, seed): the plan's index in ``plans``, its kind, track length, share of
    the area seen twice, eligibility, and the medians and counts of :data:`ERRORS` (a median
    over fewer than :data:`MIN_FEATURES` features NaN)."""
    from ..survey_area import area_from_key
    from ..survey_design import evaluate, make_setting, plan_from_row

    seeds = [int(x) for x in seeds]
    if len(seeds) < 3 or len(set(seeds)) != len(seeds):
        raise ValueError(f"noise_seeds must be at least 3 distinct seeds; got {seeds}")
    area = area_from_key(area_key)
    pick = candidates(plans, objective_col, n_best=n_best)
    rows = []
    for sd in seeds:
        s = make_setting(platform, area, terrain, n_features=n_features, seed=sd, grid_m=grid_m)
        for i in pick:
            r = plans.loc[i]
            ev = evaluate(s, plan_from_row(r), noise=noise)
            row = {"plan_index": int(i), "kind": r["kind"], "seed": sd, "total_m": ev["total_m"],
                   "covered_twice": ev["covered_twice"], "eligible": bool(r["eligible"])}
            for col, n_col in ERRORS.values():
                row[n_col] = ev[n_col]
                row[col] = ev[col] if ev[n_col] >= MIN_FEATURES else math.nan
            rows.append(row)
    return pd.DataFrame(rows)


def summarise(scores: pd.DataFrame) -> pd.DataFrame:
    """Per plan (index ``plan_index``): ``kind``, ``total_m``, ``eligible``, the number of seeds,
    the fewest features any of its medians used, and for each error its mean over the seeds
    with the 95 % interval (``<error>``, ``<error>_lo``, ``<error>_hi``; NaN where a seed had too
    few features)."""
    out = []
    for i, g in scores.groupby("plan_index", sort=False):
        row = {"plan_index": i, "kind": g.kind.iloc[0], "total_m": float(g.total_m.mean()),
               "covered_twice": float(g.covered_twice.mean()), "eligible": bool(g.eligible.iloc[0]),
               "n_seeds": len(g)}
        for name, (col, n_col) in ERRORS.items():
            v = g[col].to_numpy(float)
            mean = float(np.mean(v))
            lo, hi = replicate_interval(mean, v) if np.all(np.isfinite(v)) else (math.nan, math.nan)
            row.update({f"error_{name}_m": mean, f"error_{name}_lo_m": float(lo), f"error_{name}_hi_m": float(hi),
                        f"min_features_{name}": int(g[n_col].min())})
        out.append(row)
    return pd.DataFrame(out).set_index("plan_index")


def recommend_under_noise(summary: pd.DataFrame) -> dict:
    """The rule of the module docstring on a :func:`summarise` table. ``standard``: its index;
    among the eligible plans no longer than the standard plan, those whose two-view interval lies
    wholly below the standard plan's **hold**; ``best``: the holding plan of smallest mean, or,
    when none holds, the plan of smallest mean (shown beside the standard plan); ``holds``;
    ``recommended`` (``best`` when it holds, else ``standard``); ``reason`` (``"interval below
    the standard plan's"``, ``"intervals overlap"``, ``"the standard plan is the best"``, ``"too
    few features"``)."""
    std = summary.index[summary.kind == "standard"][0]
    s = summary.loc[std]
    cand = summary[summary.eligible & (summary.total_m <= s.total_m) & summary.error_two_m.notna()]
    if cand.empty or not np.isfinite(s.error_two_hi_m):
        return {"best": None, "standard": std, "holds": False, "recommended": std, "reason": "too few features"}
    order = ["error_two_m", "total_m"]
    holding = cand[np.isfinite(cand.error_two_hi_m) & (cand.error_two_hi_m < s.error_two_lo_m)]
    if not holding.empty:
        best = holding.sort_values(order, kind="stable").index[0]
        return {"best": best, "standard": std, "holds": True, "recommended": best,
                "reason": "interval below the standard plan's"}
    best = cand.sort_values(order, kind="stable").index[0]
    reason = "the standard plan is the best" if best == std else "intervals overlap"
    return {"best": best, "standard": std, "holds": False, "recommended": std, "reason": reason}
