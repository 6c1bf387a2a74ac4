"""Verdicts of the reconstruction chapter, generated from a run's own numbers, for any platform.

One function per paragraph (CONTRIBUTING.md, "One source per sentence"): each turns the chapter's
summaries over independent simulated surveys (:func:`~sss_locus.experiments.reconstruction.surveys.over_surveys`,
:func:`~sss_locus.experiments.reconstruction.surveys.paired_over_surveys`) and its single-view slope
errors into one platform's paragraph, the paper's AUV and boat included. Every error is named
(horizontal, |vertical|, map shape) and quoted with its 95 % interval over the surveys; every
comparison word is :func:`~sss_locus.report.reconstruction.figures.comparison_word` of an interval.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pandas as pd

from sss_locus.report.common.text import fmt_ci, fmt_percent, fmt_sig
from sss_locus.report.reconstruction.figures import ESTIMATORS, METRIC_LABELS, comparison_word

METRIC_WORDS = {"shape_m": "map-shape", "vertical_m": "|vertical|", "horizontal_m": "horizontal"}
"""Each error as the book names it in a sentence, in the order the chapter quotes them."""


def _error(row: pd.Series, metric: str) -> str:
    return fmt_ci(row[metric], row[f"{metric}_low"], row[f"{metric}_high"]) + " m"


def errors_finding(summary: pd.DataFrame, estimators: Sequence[str], *, relief_m: float, spacing_m: float) -> str:
    """Each estimator's errors at one spacing and relief, for one platform.

    Parameters
    ----------
    summary : pandas.DataFrame
        The platform's rows of :func:`~sss_locus.experiments.reconstruction.surveys.over_surveys` by
        ``spacing_m``, ``value`` (RMS relief, m) and ``estimator``: each metric of
        :data:`METRIC_WORDS` with ``_low``/``_high`` (m) and ``coverage`` (share of the seen
        features estimated).
    estimators : sequence of str
        The estimators compared (keys of :data:`~sss_locus.report.reconstruction.figures.ESTIMATORS`),
        the mosaic ``"flat"`` first.
    relief_m, spacing_m : float
        The RMS relief and the main-line spacing quoted (m).

    Returns
    -------
    str
        Per error, each estimator's mean over the surveys of its median error with the 95 %
        interval (the paired verdicts compare them), and the coverage of the estimators that need more
        than one view.
    """
    s = summary[np.isclose(summary["spacing_m"], spacing_m) & np.isclose(summary["value"], relief_m)]
    rows = {e: s[s["estimator"] == e].iloc[0] for e in estimators}
    parts = [f"**{word}** error " + ", ".join(f"{ESTIMATORS[e][0]} {_error(r, metric)}" for e, r in rows.items())
             for metric, word in METRIC_WORDS.items()]
    cover = [f"{ESTIMATORS[e][0]} {fmt_percent(rows[e]['coverage'])}" for e in estimators if e != "flat"]
    return (f"at lines {spacing_m:.0f} m apart and {fmt_sig(relief_m, 2)} m RMS relief (mean over the surveys of the "
            "median error, 95 % interval over the surveys), " + "; ".join(parts) + ". These are over the features "
            "every estimator estimated; of the seen features, these shares are estimated: " + ", ".join(cover) + ".")


def slope_finding(single: pd.DataFrame, slope_deg: float) -> str:
    """One noise-free view's slant-range correction error on the steepest slope, for one platform.

    Parameters
    ----------
    single : pandas.DataFrame
        The platform's median single-view errors by ``slope_deg``
        (:func:`~sss_locus.experiments.reconstruction.slope_error.slope_views`, medians): ``closed_3d_m``,
        ``simulated_3d_m``, ``closed_vertical_m``, ``closed_across_m``.
    slope_deg : float
        The slope quoted (deg).

    Returns
    -------
    str
        The median 3-D error in closed form and simulated, and its vertical and across-track
        parts (signed medians), with which of them is larger.
    """
    r = single[np.isclose(single["slope_deg"], slope_deg)].iloc[0]
    vertical, across = r["closed_vertical_m"], r["closed_across_m"]
    return (f"on a slope of {slope_deg:g}° a single view's slant-range correction is off by a median "
            f"{fmt_sig(r['closed_3d_m'], 2)} m in closed form and {fmt_sig(r['simulated_3d_m'], 2)} m in the simulated "
            f"survey; its vertical part (median {fmt_sig(vertical, 2)} m) is "
            + ("larger" if abs(vertical) > abs(across) else "not larger")
            + f" than its across-track part ({fmt_sig(across, 2)} m).")


def models_finding(models: pd.DataFrame, spacing_m: float, navigation: str = "per_pass") -> str:
    """The same estimators under per-view and per-pass navigation errors, for one platform.

    Parameters
    ----------
    models : pandas.DataFrame
        The platform's rows of :func:`~sss_locus.experiments.reconstruction.surveys.over_surveys` by
        ``spacing_m`` and ``estimator``, with ``navigation`` (``"per_view"`` or ``navigation``) and
        ``horizontal_m`` with ``_low``/``_high``; may be empty (the chapter run with per-view
        errors only).
    spacing_m : float
        The main-line spacing quoted (m).
    navigation : str
        The chapter's navigation model.

    Returns
    -------
    str
        Per estimator the horizontal error under both models with intervals, and whether the
        intervals put the per-view error below or above the per-pass one (apart) or overlap.
    """
    if models.empty:
        return "not run: the chapter ran with `navigation = \"per_view\"` only."
    m = models[np.isclose(models["spacing_m"], spacing_m)]
    at = {(r.navigation, r.estimator): r for r in m.itertuples()}
    ests = list(dict.fromkeys(m["estimator"]))
    parts = []
    for e in ests:
        pv, pp = (pd.Series(at[(model, e)]._asdict()) for model in ("per_view", navigation))
        word = comparison_word({"horizontal_m_low": pv["horizontal_m_low"] - pp["horizontal_m_high"],
                                "horizontal_m_high": pv["horizontal_m_high"] - pp["horizontal_m_low"]}, "horizontal_m")
        said = {"closer": "lower with per-view errors (intervals apart)",
                "farther": "higher with per-view errors (intervals apart)",
                "not distinguishable": "the intervals overlap"}[word]
        parts.append(f"{ESTIMATORS[e][0]} {_error(pv, 'horizontal_m')} per view against {_error(pp, 'horizontal_m')} "
                     f"per pass ({said})")
    return (f"horizontal error at lines {spacing_m:.0f} m apart (mean over the surveys of the median, 95 % interval): "
            + "; ".join(parts) + ".")


def _where(paired: pd.DataFrame, metric: str) -> str:
    words: dict[str, list[str]] = {}
    for r in paired.sort_values("rms_relief_m").itertuples():
        words.setdefault(comparison_word(r._asdict(), metric), []).append(fmt_sig(r.rms_relief_m, 2))
    if len(words) == 1:
        return f"{next(iter(words))} at every relief"
    return ", ".join(f"{w} at {', '.join(v)} m" for w, v in words.items())


def comparisons_finding(paired: pd.DataFrame, spacing_m: float) -> str:
    """Every estimator against the mosaic at the routine spacing, each error, over the reliefs.

    Parameters
    ----------
    paired : pandas.DataFrame
        The platform's paired differences (``a`` minus ``b`` = ``"flat"``) of
        :func:`~sss_locus.experiments.reconstruction.surveys.paired_over_surveys` by ``spacing_m``
        and ``rms_relief_m``, each metric with ``_low``/``_high`` (m).
    spacing_m : float
        The main-line spacing (m).

    Returns
    -------
    str
        Per estimator and error: closer, farther or not distinguishable, at which RMS reliefs.
    """
    p = paired[np.isclose(paired["spacing_m"], spacing_m)]
    parts = []
    for a, g in p.groupby("a", sort=False):
        parts.append(f"{ESTIMATORS[a][0]} against the mosaic: " + "; ".join(
            f"{METRIC_WORDS[m]} error {_where(g, m)}" for m in METRIC_WORDS if m in METRIC_LABELS))
    return ". ".join(parts) + "."
