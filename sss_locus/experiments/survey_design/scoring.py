"""Plans scored with the joint adjustment under the noise model over independent seeds, and a
recommendation that holds.

The search (:func:`sss_locus.experiments.survey_design.front.search_plans`) ranks plans by a cheap
noise-free objective on one seed. Here the plans the rule could recommend are flown again with
the platform's noise and per-pass navigation errors (``data/noise.toml``) and their features
and navigation adjusted jointly (:func:`~sss_locus.experiments.survey_design.joint.plan_joint_errors`):
per plan and seed the median **horizontal**, **vertical** and **map-shape** error of the joint
estimate (:data:`ERRORS`) over the features it estimated. Every seed draws other features,
seafloor, in-beam elevations and noise, so the seeds are independent replicates (independent
simulated surveys, as in the reconstruction chapter).

Per plan (:func:`score_plans`, :func:`summarise`): the mean over the seeds of each median and its
95 % interval ``mean +- t sd / sqrt(k)`` (:func:`~sss_locus.experiments.stats.replicates.replicate_interval`,
``k >= 3`` seeds). A median over fewer than :data:`MIN_FEATURES` features is not computed (NaN:
too few to be a finding), and a plan with such a seed has no interval.

**The interval's lower end is cut at 0** (:data:`ERROR_FLOOR_M`, a named choice): every error is
a median of non-negative distances, but Student's t interval is symmetric about the mean, and
over few seeds (3 at the quick profile) with a wide spread it reaches below 0 (e.g. a mean of
1.6 m with ``t sd / sqrt(k)`` = 1.8 m). The end is cut, not the interval changed: the true mean
is ``>= 0``, so an interval contains it exactly when its cut form does (the coverage is the
t interval's), and the upper end is untouched. The report says so wherever such an interval is
shown (:func:`lower_end_cut`). The rule below reads the cut ends, the ones the reader sees; it
decides as it would on the uncut ones, since a plan's upper end (``>= its mean >= 0``) is never
below a negative lower end. A log-scale interval was not chosen: it is an interval of the
geometric mean, another quantity than the mean the table reports.

Which plans (:func:`candidates`): the baselines (standard plan, equal-length lawn-mower), the plan
the noise-free rule picks, and the ``n_scored`` eligible searched plans no longer than the
standard plan with the smallest noise-free objective (the search's leading candidates: a
pre-selection, stated). Plans longer than the standard plan are not scored: the rule never
recommends them.

The recommendation (:func:`recommend_under_noise`): among the eligible scored plans no longer
than the standard plan, a plan is **recommended over the standard plan only when the interval of
its error (the one named by ``error``, :data:`DECIDING_ERROR` by default) lies wholly below the
standard plan's** (the intervals do not overlap; of several such plans, the one of smallest mean);
otherwise the standard plan is kept. The other two errors are reported beside it and never decide.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from sss_locus.experiments.stats.replicates import replicate_interval
from sss_locus.experiments.survey_design.joint import JOINT_METRICS

MIN_FEATURES = 30
"""Fewest features a median is taken over (fewer: not a finding, NaN)."""
ERRORS = {m: f"{m}_median_m" for m in JOINT_METRICS}
"""Error name -> the column of :func:`score_plans` holding its median over a seed's features."""
ERROR_FLOOR_M = 0.0
"""The lower end of every error's interval is cut here (m): an error is never negative (module
docstring)."""
COUNT = "n_joint"
"""The column of :func:`score_plans` counting the features behind every median of the row."""
DECIDING_ERROR = "horizontal"
"""The error the recommendation is decided on unless told otherwise: the horizontal position of
a feature, absolute, which hydrographic standards specify for features (IHO S-44's total
horizontal uncertainty) and a surveyor's target list is judged on."""


def candidates(plans: pd.DataFrame, objective_col: str, *, n_scored: int = 8) -> pd.Index:
    """Rows of ``plans`` (the search's table) to score (module docstring).

    Parameters
    ----------
    plans : pandas.DataFrame
        The search's plans table.
    objective_col : str
        The objective's column.
    n_scored : int
        Best searched plans scored (>= 0).

    Returns
    -------
    pandas.Index
        The baselines, the recommended row and the ``n_scored`` best eligible searched plans no
        longer than the standard plan.
    """
    if isinstance(n_scored, bool) or not isinstance(n_scored, (int, np.integer)) or n_scored < 0:
        raise ValueError(f"n_scored must be an integer >= 0; got {n_scored!r}")
    std_total = float(plans.loc[plans.kind == "standard", "total_m"].iloc[0])
    pick = plans.kind != "search"
    if "recommended" in plans:
        pick |= plans.recommended.astype(bool)
    short = plans[(plans.kind == "search") & plans.eligible & (plans.total_m <= std_total) & plans[objective_col].notna()]
    best = short.sort_values([objective_col, "total_m"], kind="stable").index[:int(n_scored)]
    return plans.index[pick | plans.index.isin(best)]


def check_seeds(seeds) -> list[int]:
    """``seeds`` as distinct ints >= 0, at least 3 (the interval needs them); else ``ValueError``
    naming ``noise_seeds``.

    Parameters
    ----------
    seeds : iterable of int
        The noise seeds.

    Returns
    -------
    list of int
        The seeds.
    """
    try:
        out = [int(x) for x in seeds]
    except (TypeError, ValueError):
        raise ValueError(f"noise_seeds must be a list of at least 3 distinct integers >= 0; got {seeds!r}") from None
    if len(out) < 3 or len(set(out)) != len(out) or min(out) < 0:
        raise ValueError(f"noise_seeds must be at least 3 distinct seeds >= 0; got {out}")
    return out


def score_plans(platform, area_key: dict, terrain: str, plans: pd.DataFrame, noise, pass_noise, *, seeds,
                n_features: int, grid_m: float, objective_col: str, n_scored: int = 8) -> pd.DataFrame:
    """One row per (scored plan, seed).

    Parameters
    ----------
    platform : Platform
    area_key : dict
        The area (:meth:`~sss_locus.experiments.survey_design.area.SurveyArea.key`).
    terrain : str
        Seafloor model of ``data/terrain.toml``.
    plans : pandas.DataFrame
        The search's plans table (:func:`~sss_locus.experiments.survey_design.front.search_plans`).
    noise : NoiseModel
    pass_noise : PassNoise
        The platform's per-view and per-pass noise (``data/noise.toml``).
    seeds : sequence of int
        Independent seeds, at least 3 distinct (``noise_seeds``).
    n_features : int
        Features per seed, uniform over the area.
    grid_m : float
        Coverage grid (only the setting's validation uses it here).
    objective_col : str
        The search's objective column, which ranks the candidates.
    n_scored : int
        How many of the search's leading plans are scored (:func:`candidates`).

    Returns
    -------
    pandas.DataFrame
        ``plan_index`` (into ``plans``), ``kind``, ``seed``, ``total_m``, ``covered_twice`` and
        ``eligible`` (from the search), the counts of
        :func:`~sss_locus.experiments.survey_design.joint.plan_joint_errors` and its medians
        (m), each NaN where ``n_joint`` < :data:`MIN_FEATURES`.
    """
    from sss_locus.experiments.survey_design.area import area_from_key
    from sss_locus.experiments.survey_design.front import make_setting, plan_from_row
    from sss_locus.experiments.survey_design.joint import plan_joint_errors

    seeds = check_seeds(seeds)
    area = area_from_key(area_key)
    pick = candidates(plans, objective_col, n_scored=n_scored)
    rows = []
    for sd in seeds:
        s = make_setting(platform, area, terrain, n_features=n_features, seed=sd, grid_m=grid_m)
        for i in pick:
            r = plans.loc[i]
            ev = plan_joint_errors(s, plan_from_row(r), noise, pass_noise, seed=sd)
            row = {"plan_index": int(i), "kind": r["kind"], "seed": sd, "total_m": float(r["total_m"]),
                   "covered_twice": float(r["covered_twice"]), "eligible": bool(r["eligible"]), **ev}
            for col in ERRORS.values():
                row[col] = ev[col] if ev[COUNT] >= MIN_FEATURES else math.nan
            rows.append(row)
    return pd.DataFrame(rows)


def solver_path_shifts(platform, area_key: dict, terrain: str, plans: pd.DataFrame, noise, pass_noise, *, seeds,
                       n_features: int, grid_m: float) -> pd.DataFrame:
    """The standard plan's joint estimate solved along a second path on every seed
    (:func:`~sss_locus.experiments.survey_design.joint.solver_path_shift`): whether the estimates
    of features seen on only two passes, and the medians the rule reads, depend on the solver.

    Parameters
    ----------
    platform, area_key, terrain, plans, noise, pass_noise, seeds, n_features, grid_m
        As for :func:`score_plans` (``plans``: the search's table, whose ``standard`` row is
        solved).

    Returns
    -------
    pandas.DataFrame
        One row per seed: ``seed`` and the counts and shifts (m) of ``solver_path_shift``.
    """
    from sss_locus.experiments.survey_design.area import area_from_key
    from sss_locus.experiments.survey_design.front import make_setting, plan_from_row
    from sss_locus.experiments.survey_design.joint import solver_path_shift

    area = area_from_key(area_key)
    plan = plan_from_row(plans[plans.kind == "standard"].iloc[0])
    rows = []
    for sd in check_seeds(seeds):
        s = make_setting(platform, area, terrain, n_features=n_features, seed=sd, grid_m=grid_m)
        rows.append({"seed": sd, **solver_path_shift(s, plan, noise, pass_noise, seed=sd)})
    return pd.DataFrame(rows)


def summarise(scores: pd.DataFrame) -> pd.DataFrame:
    """Per plan (index ``plan_index``): ``kind``, ``total_m``, ``covered_twice``, ``eligible``,
    ``n_seeds``, ``min_features`` (the fewest features any of its seeds' medians used) and
    ``mean_features``, with ``scores``' ``seed`` and ``n_seen_twice``: ``fewest_seed`` (that
    seed) and ``fewest_seen_twice`` (the features the plan saw on two or more passes on it: more
    than ``min_features`` when the joint solve did not converge), and for each error of :data:`ERRORS` its mean over the seeds with the 95 %
    interval (``error_<name>_m``, ``error_<name>_lo_m``, ``error_<name>_hi_m``; the lower end cut
    at :data:`ERROR_FLOOR_M`, :func:`lower_end_cut`; the mean and the interval NaN where a seed
    had too few features).

    Parameters
    ----------
    scores : pandas.DataFrame
        One row per plan and seed (``plan_index``, ``kind``, ``total_m``, errors in m, ...).

    Returns
    -------
    pandas.DataFrame
        One row per plan, index ``plan_index``.
    """
    out = []
    for i, g in scores.groupby("plan_index", sort=False):
        row = {"plan_index": i, "kind": g.kind.iloc[0], "total_m": float(g.total_m.mean()),
               "covered_twice": float(g.covered_twice.mean()), "eligible": bool(g.eligible.iloc[0]),
               "n_seeds": len(g), "min_features": int(g[COUNT].min()), "mean_features": float(g[COUNT].mean())}
        if {"seed", "n_seen_twice"} <= set(g.columns):  # why the fewest were so few (the report's words)
            few = g.loc[g[COUNT].idxmin()]
            row.update(fewest_seed=int(few["seed"]), fewest_seen_twice=int(few["n_seen_twice"]))
        for name, col in ERRORS.items():
            v = g[col].to_numpy(float)
            ok = bool(np.all(np.isfinite(v)))
            mean = float(np.mean(v)) if ok else math.nan
            lo, hi = replicate_interval(mean, v, bounds=(ERROR_FLOOR_M, math.inf)) if ok else (math.nan, math.nan)
            row.update({f"error_{name}_m": mean, f"error_{name}_lo_m": float(lo), f"error_{name}_hi_m": float(hi)})
        out.append(row)
    return pd.DataFrame(out).set_index("plan_index")


def lower_end_cut(mean, low, high):
    """Whether an interval of :func:`summarise` had its lower end cut at :data:`ERROR_FLOOR_M`:
    the symmetric interval ``mean +- h`` reached below it, i.e. ``h = high - mean`` exceeds
    ``mean - ERROR_FLOOR_M`` (then ``low`` is the floor). False where any value is NaN.

    Parameters
    ----------
    mean, low, high : float or array_like
        An error's mean over the seeds and the ends of its interval (m), as :func:`summarise`
        gives them.

    Returns
    -------
    bool or numpy.ndarray of bool
        Per interval, whether its lower end was cut.
    """
    m, lo, hi = (np.asarray(a, float) for a in (mean, low, high))
    with np.errstate(invalid="ignore"):
        cut = (lo == ERROR_FLOOR_M) & (hi - m > m - ERROR_FLOOR_M)
    return bool(cut) if cut.ndim == 0 else cut


def recommend_under_noise(summary: pd.DataFrame, error: str = DECIDING_ERROR) -> dict:
    """The rule of the module docstring on a :func:`summarise` table, decided on ``error`` (one of
    :data:`ERRORS`).

    Parameters
    ----------
    summary : pandas.DataFrame
        :func:`summarise`'s table.
    error : str
        A key of :data:`ERRORS`.

    Returns
    -------
    dict
        ``error``; ``standard``: its index; among the eligible plans no longer than the standard
        plan, those whose interval lies wholly below the standard plan's **hold**; ``best``: the
        holding plan of smallest mean, or, when none holds, the plan of smallest mean (shown
        beside the standard plan; ``None`` when no plan has an interval); ``holds``;
        ``recommended`` (``best`` when it holds, else ``standard``); ``reason`` (``"interval
        below the standard plan's"``, ``"intervals overlap"``, ``"the standard plan is the
        best"``, ``"too few features"``: the standard plan has a seed under :data:`MIN_FEATURES`
        features). A plan with such a seed has no interval and is never recommended.
    """
    if error not in ERRORS:
        raise ValueError(f"error must be one of {list(ERRORS)}; got {error!r}")
    col, lo_col, hi_col = (f"error_{error}{s}_m" for s in ("", "_lo", "_hi"))
    std = summary.index[summary.kind == "standard"][0]
    s = summary.loc[std]
    cand = summary[summary.eligible & (summary.total_m <= s.total_m) & np.isfinite(summary[hi_col])]
    base = {"error": error, "standard": std, "holds": False, "recommended": std}
    if not np.isfinite(s[hi_col]) or cand.empty:
        return {**base, "best": None, "reason": "too few features"}
    order = [col, "total_m"]
    holding = cand[cand[hi_col] < s[lo_col]]
    if not holding.empty:
        best = holding.sort_values(order, kind="stable").index[0]
        return {**base, "best": best, "holds": True, "recommended": best, "reason": "interval below the standard plan's"}
    best = cand.sort_values(order, kind="stable").index[0]
    return {**base, "best": best, "reason": "the standard plan is the best" if best == std else "intervals overlap"}
