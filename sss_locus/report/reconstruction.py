"""Figures and verdict sentences of the reconstruction chapter (``notebooks/reconstruction.ipynb``).

Tables are the per-feature tables of :func:`sss_locus.experiments.reconstruction_study.relief_sweep`
(one per platform key), summarised by :func:`sss_locus.experiments.reconstruction.summarise`.
Platforms are :class:`~sss_locus.experiments.platforms.Platform` objects; their names come from
the data.

The figures are drawn in the book's seaborn theme (:func:`~sss_locus.report.style.theme`) with
matplotlib's ``plot``, not ``seaborn.lineplot``: each point is a median
:func:`~sss_locus.experiments.reconstruction.summarise` computed (the figures' CSV data, floored at
:data:`FLOOR_M`), not a statistic for seaborn to estimate, and each estimator keeps its own line
style, marker and marker fill (:data:`ESTIMATORS`), so lines that coincide stay visible.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from ..experiments.reconstruction import summarise
from .style import PAGE_WIDTH_IN, SMALL_FONT_PT, platform_title, themed
from .text import fmt_percent, fmt_sig

ESTIMATORS = {"flat1": ("flat seafloor, one view", "tab:gray", ":", "o"),
              "flat": ("flat seafloor, all views averaged", "black", "--", "s"),
              "two": ("two views + prior", "tab:orange", "-", "^"),
              "n3": ("3 views", "tab:blue", "-", "D"),
              "all": ("all views", "tab:green", "-", "o")}
"""Estimators drawn against relief: display name, colour, line style, marker (distinct, so lines
that coincide, e.g. 3 and all views at the 1 mm floor without noise, stay visible)."""

VIEW_STEPS = (("flat1", "1\n(flat)"), ("two", "2\n(+prior)"), ("n3", "3"), ("n4", "4"), ("n6", "6"),
              ("all", "all"))
"""The x axis of the number-of-views figure: estimator and tick label."""

FLOOR_M = 1e-3
"""Errors below this are drawn at it (noise-free N-view errors are at rounding level)."""


@plt.FuncFormatter
def _plain(value, _pos):
    """Log-axis labels as plain numbers (``0.1``, ``1``, ``10``)."""
    return f"{value:g}"


@plt.FuncFormatter
def _plain_minor(value, _pos):
    """Minor labels 2 and 5 of each decade: an axis of less than two decades keeps readable values."""
    # plain floats, not numpy scalars: called for every minor tick of every draw
    mantissa = value / 10 ** math.floor(math.log10(value) + 1e-9)
    near = [abs(mantissa - m) <= 1e-8 + 1e-5 * m for m in (2, 5)]  # numpy.isclose's tolerances
    return f"{value:g}" if any(near) else ""


def _label_minor(ax) -> None:
    """Minor labels of a log error axis: every one on an axis of less than a decade (which may
    hold no labelled major tick), 2 and 5 on one of less than two decades, none otherwise."""
    lo, hi = ax.get_ylim()
    ax.yaxis.set_minor_formatter(_plain if hi / lo < 10 else _plain_minor if hi / lo < 100 else plt.NullFormatter())


def _mark_floor(ax) -> None:
    ax.annotate("< 1 mm, drawn at 1 mm", (0.98, FLOOR_M), xycoords=("axes fraction", "data"),
                xytext=(0, 5), textcoords="offset points", ha="right", va="bottom",
                fontsize=SMALL_FONT_PT, color="0.35")


def noise_label(scale: float) -> str:
    """``"noise-free"``, ``"noise model × 0.1"``, ``"full noise model"``."""
    if scale == 0:
        return "noise-free"
    return "full noise model" if scale == 1 else f"noise model × {scale:g}"


def height_sentence(platforms: Sequence, envelopes: Sequence) -> str:
    """How each platform flies in the chapter's survey, from its envelope: one height above the
    mean seafloor (``same_altitude``, e.g. a surface boat) or following the terrain, at
    :func:`~sss_locus.experiments.reconstruction_study.survey_altitude_m`; Markdown, no final stop."""
    from ..experiments.reconstruction_study import survey_altitude_m

    return "; ".join(
        f"the {pf.name} holds one height, {fmt_sig(survey_altitude_m(env), 2)} m above the mean seafloor "
        "(its envelope's `same_altitude`)" if env.same_altitude else
        f"the {pf.name} follows the terrain {fmt_sig(survey_altitude_m(env), 2)} m above the seafloor below it"
        for pf, env in zip(platforms, envelopes, strict=True))


@themed
def plot_relief(platforms: Sequence, summary: pd.DataFrame):
    """Median 3-D error (log scale) against RMS relief, one column per platform and one row per
    noise scale (each row its own error axis, so the noisy rows are not squeezed by the
    noise-free row's rounding-level errors), one line per estimator of :data:`ESTIMATORS`;
    returns the figure. ``summary`` is the figure's data: :func:`summarise` of each platform's
    table by ``("noise_scale", "rms_relief_m", "estimator")`` with a column ``platform`` (its key)."""
    scales = sorted(summary.noise_scale.unique())
    fig, axs = plt.subplots(len(scales), len(platforms), figsize=(PAGE_WIDTH_IN, 2.3 * len(scales) + 0.9),
                            constrained_layout=True, squeeze=False, sharex=True, sharey="row")
    for j, pf in enumerate(platforms):
        s = summary[summary.platform == pf.key]
        for i, k in enumerate(scales):
            ax = axs[i, j]
            floored = False
            for est, (label, color, ls, marker) in ESTIMATORS.items():
                d = s[(s.noise_scale == k) & (s.estimator == est)].sort_values("rms_relief_m")
                floored |= bool((d.error_3d_median_m < FLOOR_M).any())
                ax.plot(d.rms_relief_m, np.maximum(d.error_3d_median_m, FLOOR_M), ls, color=color,
                        marker=marker, ms=6 if est == "n3" else 3.5, mfc="none" if est == "n3" else color,
                        label=label)
            if floored:
                _mark_floor(ax)
            ax.set_yscale("log")
            ax.yaxis.set_major_formatter(_plain)
            ax.grid(which="minor", linewidth=0.4)  # the theme draws the major lines
            ax.set_title(f"{platform_title(pf, 72 // len(platforms))}\n{noise_label(k)}" if i == 0
                         else noise_label(k), fontsize=10)
            if j == 0:
                ax.set_ylabel("median 3-D error (m)")
            if i == len(scales) - 1:
                ax.set_xlabel("RMS seafloor relief (m)")
    for ax in axs.flat:  # a row spanning less than two decades also labels minor ticks
        _label_minor(ax)
    handles, labels = axs[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=3, fontsize=SMALL_FONT_PT, frameon=False)
    return fig


@themed
def plot_views(platforms: Sequence, tables: Mapping[str, pd.DataFrame], rms_relief_m: float):
    """At one RMS relief: (a) median 3-D error and (b) share of features with an estimate
    (resolved or ambiguous) among those seen by at least the views used, against the number of
    views used, one line per noise scale, one column per platform; returns the figure."""
    fig, axs = plt.subplots(2, len(platforms), figsize=(PAGE_WIDTH_IN, 5.6), constrained_layout=True,
                            squeeze=False, sharex=True)
    x = np.arange(len(VIEW_STEPS))
    for j, pf in enumerate(platforms):
        t = tables[pf.key]
        t = t[np.isclose(t.rms_relief_m, rms_relief_m) & ~t.status.isin(["too few views", "unseen"])]
        s = summarise(t, by=("noise_scale", "estimator"))
        for k, color in zip(sorted(s.noise_scale.unique()), ("tab:green", "tab:blue", "tab:red", "tab:purple")):
            d = s[s.noise_scale == k].set_index("estimator").reindex([e for e, _ in VIEW_STEPS])
            axs[0, j].plot(x, np.maximum(d.error_3d_median_m, FLOOR_M), "-o", color=color, ms=4,
                           label=noise_label(k))
            axs[1, j].plot(x, d.estimated, "-o", color=color, ms=4, label=noise_label(k))
            axs[1, j].plot(x, d.ambiguous, ":", color=color, lw=1)
        for i, (est, lab) in enumerate(VIEW_STEPS):  # a step no feature reaches: said, not left blank
            if est not in set(s.estimator):
                axs[1, j].text(x[i], 0.5, f"no feature\nseen by {lab}\nviews", ha="center", va="center",
                               fontsize=SMALL_FONT_PT, color="0.35")
        axs[0, j].set_yscale("log")
        axs[0, j].yaxis.set_major_formatter(_plain)
        _label_minor(axs[0, j])
        if (s.error_3d_median_m < FLOOR_M).any():
            _mark_floor(axs[0, j])
        axs[0, j].set_title(f"{platform_title(pf, 72 // len(platforms))}\n(a) median 3-D error", fontsize=10)
        axs[1, j].set_title("(b) share estimated (dotted: ambiguous)", fontsize=10)
        axs[1, j].set_ylim(-0.02, 1.02)
        axs[1, j].set_xticks(x, [lab for _, lab in VIEW_STEPS])
        axs[1, j].set_xlabel("views used")
        for ax in axs[:, j]:
            ax.grid(which="minor", linewidth=0.4)  # the theme draws the major lines
    axs[0, 0].set_ylabel("median 3-D error (m)")
    axs[1, 0].set_ylabel("share of features")
    handles, labels = axs[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=len(labels), fontsize=SMALL_FONT_PT,
               frameon=False)
    return fig


def verdict_relief(comparison: pd.DataFrame, alpha: float):
    """The smallest RMS relief from which on (at it and at every larger relief of ``comparison``,
    one noise scale of :func:`~sss_locus.experiments.reconstruction_study.paired_comparison`)
    the p-value is below ``alpha``; None if the largest relief fails."""
    c = comparison.sort_values("rms_relief_m")
    from_ = None
    for r, p in zip(c.rms_relief_m[::-1], c.p_value[::-1]):
        if not p < alpha:
            break
        from_ = float(r)
    return from_


def verdict_text(comparison: pd.DataFrame, alpha: float) -> str:
    """``"from 0.50 m RMS relief on"`` or ``"at no relief up to 4.0 m"`` for one noise scale."""
    r = verdict_relief(comparison, alpha)
    if r is None:
        return f"at no relief up to {fmt_sig(comparison.rms_relief_m.max(), 2)} m"
    return f"from {fmt_sig(r, 2)} m RMS relief on"


def verdict_sentence(platform, comparison: pd.DataFrame, alpha: float) -> str:
    """One Markdown sentence: for each noise scale, the smallest RMS relief from which on all
    views beat the flat-seafloor mosaic (one-sided paired Wilcoxon p < ``alpha``), or that they
    never do. ``comparison`` is :func:`~sss_locus.experiments.reconstruction_study.paired_comparison`
    of ``"all"`` against ``"flat"`` by noise scale and relief."""
    parts = []
    for k, c in comparison.groupby("noise_scale", sort=True):
        r = verdict_relief(c, alpha)
        text = f"{noise_label(k)}: {verdict_text(c, alpha)}"
        if r is not None:
            row = c[c.rms_relief_m == r].iloc[0]
            text += (f" (there, closer for {fmt_percent(row.share_closer)} of the features, median "
                     f"difference {fmt_sig(row.median_difference_m, 2)} m)")
        parts.append(text)
    return f"**{platform.name}**: " + "; ".join(parts) + "."


def loss_sentence(platform, comparison: pd.DataFrame, alpha: float, noise_scale: float) -> str:
    """One Markdown sentence: at which RMS reliefs, at ``noise_scale``, the flat-seafloor mosaic
    is significantly closer than all views (one-sided paired Wilcoxon ``p_value_b_closer`` <
    ``alpha`` of :func:`~sss_locus.experiments.reconstruction_study.paired_comparison` of
    ``"all"`` against ``"flat"``), with the median excess error of all views there, and at which
    neither estimator is significantly closer."""
    c = comparison[np.isclose(comparison.noise_scale, noise_scale)].sort_values("rms_relief_m")
    lost = c[c.p_value_b_closer < alpha]
    tie = c[~(c.p_value_b_closer < alpha) & ~(c.p_value < alpha)]
    head = f"**{platform.name}** ({noise_label(noise_scale)}): "
    if lost.empty:
        text = (head + "the flat-seafloor mosaic is significantly closer at no RMS relief up to "
                f"{fmt_sig(c.rms_relief_m.max(), 2)} m")
    else:
        text = head + "the flat-seafloor mosaic is significantly closer than all views at " + "; ".join(
            f"{fmt_sig(r.rms_relief_m, 2)} m RMS relief (all views farther by a median "
            f"{fmt_sig(r.median_difference_m, 2)} m, closer for only {fmt_percent(r.share_closer)} of "
            "the features)" for r in lost.itertuples())
    if not tie.empty:
        text += "; neither is significantly closer at " + ", ".join(
            f"{fmt_sig(r, 2)} m" for r in tie.rms_relief_m)
    return text + "."
