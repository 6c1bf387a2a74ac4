"""Figures and verdict sentences of the reconstruction chapter (``notebooks/reconstruction.ipynb``).

The data are summaries over independent simulated surveys
(:func:`~sss_locus.experiments.reconstruction.surveys.over_surveys`: per platform key, line
spacing, swept value and estimator, the mean over the surveys of each error with its 95 %
interval) and their paired differences
(:func:`~sss_locus.experiments.reconstruction.surveys.paired_over_surveys`). Platforms are
:class:`~sss_locus.experiments.datamodel.platforms.Platform` objects; their names come from the data.

The figures are drawn in the book's seaborn theme (:func:`~sss_locus.report.common.style.theme`) with
matplotlib's ``errorbar``: each point is a mean the summary computed (the figures' CSV data), its
bar the interval over surveys, not a statistic for seaborn to estimate; each estimator keeps its
colour and marker (:data:`ESTIMATORS`), each line spacing its line style.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from sss_locus.report.common.style import PAGE_WIDTH_IN, SMALL_FONT_PT, platform_title, themed
from sss_locus.report.common.text import fmt_ci_cells, fmt_sig

ESTIMATORS = {"flat": ("flat-seafloor mosaic", "black", "s"),
              "two": ("two views + prior", "tab:orange", "^"),
              "n3": ("3 views", "tab:cyan", "v"),
              "n4": ("4 views", "tab:purple", "<"),
              "n6": ("6 views", "tab:olive", ">"),
              "all": ("N views (ranges)", "tab:blue", "D"),
              "beam": ("N views + beam plane", "tab:green", "o"),
              "joint": ("joint adjustment", "tab:red", "P")}
"""Estimators: display name, colour, marker."""

METRIC_LABELS = {"horizontal_m": "horizontal error (m)", "vertical_m": "|vertical error| (m)",
                 "shape_m": "map-shape error (m)"}
"""The errors of :data:`~sss_locus.experiments.reconstruction.surveys.METRICS` as axis labels."""

SPACING_STYLES = ("-", "--", ":", "-.")
"""Line style of the first (main), second ... line spacing."""

VIEW_STEPS = (("flat", "mosaic\n(flat)"), ("two", "2\n(+prior)"), ("n3", "3"), ("n4", "4"), ("n6", "6"),
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
    """``"noise-free"``, ``"noise model × 0.1"``, ``"full noise model"``.

    Parameters
    ----------
    scale : float
        Factor on the noise model (0: none, 1: the full model).

    Returns
    -------
    str
        The label.
    """
    if scale == 0:
        return "noise-free"
    return "full noise model" if scale == 1 else f"noise model × {scale:g}"


def height_sentence(platforms: Sequence, envelopes: Sequence) -> str:
    """How each platform flies in the chapter's survey, from its envelope: one height above the
    mean seafloor (``same_altitude``, e.g. a surface boat) or following the terrain, at
    :func:`~sss_locus.experiments.reconstruction.study.survey_altitude_m`; Markdown, no final stop.

    Parameters
    ----------
    platforms : sequence of Platform
        The platforms (their ``name``).
    envelopes : sequence of SurveyEnvelope
        Their envelopes, in the same order (``same_altitude`` and the altitudes, m).

    Returns
    -------
    str
        The clauses joined by ``"; "``; heights in m.
    """
    from sss_locus.experiments.reconstruction.study import survey_altitude_m

    return "; ".join(
        f"the {pf.name} holds one height, {fmt_sig(survey_altitude_m(env), 2)} m above the mean seafloor "
        "(its envelope's `same_altitude`)" if env.same_altitude else
        f"the {pf.name} follows the terrain {fmt_sig(survey_altitude_m(env), 2)} m above the seafloor below it"
        for pf, env in zip(platforms, envelopes, strict=True))



def spacing_label(spacing_m: float, range_m: float) -> str:
    """``"lines 240 m apart (1.6 × range)"``.

    Parameters
    ----------
    spacing_m : float
        Distance between neighbouring lines (m).
    range_m : float
        The sonar's maximum slant range (m).

    Returns
    -------
    str
        The label.
    """
    return f"lines {fmt_sig(spacing_m, 3)} m apart ({fmt_sig(spacing_m / range_m, 2)} × range)"


def _errorbars(ax, x, d, col, *, color, marker, ls, label, floor=FLOOR_M):
    """``d[col]`` against ``x`` with the interval ``d[col_low]``..``d[col_high]``, floored."""
    y = np.maximum(d[col].to_numpy(float), floor)
    lo = np.maximum(d[f"{col}_low"].to_numpy(float), floor)
    hi = np.maximum(d[f"{col}_high"].to_numpy(float), floor)
    ax.errorbar(x, y, yerr=[np.maximum(y - lo, 0), np.maximum(hi - y, 0)], color=color, marker=marker, ls=ls,
                ms=4, lw=1.3, capsize=2, label=label)


def _fit_axis(ax, d: pd.DataFrame, col: str) -> None:
    """A log axis from half the smallest mean of ``d[col]`` to 1.5 times the largest interval end:
    it spans the means, and an interval reaching toward 0 runs off its bottom (not drawn down to
    an arbitrary floor)."""
    y = np.maximum(d[col].to_numpy(float), FLOOR_M)
    hi = np.maximum(d[f"{col}_high"].to_numpy(float), y)
    if np.isfinite(y).any():
        ax.set_ylim(0.5 * np.nanmin(y), 1.5 * np.nanmax(hi))


def _log_axis(ax) -> None:
    ax.set_yscale("log")
    ax.yaxis.set_major_formatter(_plain)
    ax.grid(which="minor", linewidth=0.4)  # the theme draws the major lines


@themed
def plot_sweep(platforms: Sequence, summary: pd.DataFrame, *, estimators: Sequence[str], metrics: Sequence[str],
               xlabel: str, spacings_m: Sequence[float] | None = None):
    """Mean error over surveys (log scale, 95 % interval bars) against the swept ``value``: one
    row per metric (:data:`METRIC_LABELS`), one column per platform, one colour per estimator,
    one line style per spacing (the first solid). ``summary``: :func:`over_surveys` by
    ``("platform", "spacing_m", "value", "estimator")``. Returns the figure.

    Parameters
    ----------
    platforms : sequence of Platform
        The platforms, one column each (their ``key``, ``name`` and ``sonar.max_range_m``).
    summary : pandas.DataFrame
        Columns ``platform``, ``spacing_m``, ``value``, ``estimator`` and, per metric, its mean
        (m) with ``<metric>_low``/``<metric>_high``.
    estimators : sequence of str
        Keys of :data:`ESTIMATORS` to draw.
    metrics : sequence of str
        Keys of :data:`METRIC_LABELS`, one row each.
    xlabel : str
        Label (with unit) of the swept value.
    spacings_m : sequence of float, optional
        Line spacings (m) to draw, the first solid; default all, widest first.

    Returns
    -------
    matplotlib.figure.Figure
        A new figure, legend below.
    """
    spacings = list(spacings_m) if spacings_m is not None else sorted(summary.spacing_m.unique(), reverse=True)
    fig, axs = plt.subplots(len(metrics), len(platforms), figsize=(PAGE_WIDTH_IN, 2.2 * len(metrics) + 1.2),
                            constrained_layout=True, squeeze=False, sharex=True, sharey="row")
    for j, pf in enumerate(platforms):
        s = summary[summary.platform == pf.key]
        for i, metric in enumerate(metrics):
            ax = axs[i, j]
            for k, spacing in enumerate(spacings):
                for est in estimators:
                    name, color, marker = ESTIMATORS[est]
                    d = s[(s.estimator == est) & np.isclose(s.spacing_m, spacing)].sort_values("value")
                    if len(d):
                        _errorbars(ax, d.value, d, metric, color=color, marker=marker,
                                   ls=SPACING_STYLES[k % len(SPACING_STYLES)],
                                   label=f"{name}, {spacing_label(spacing, pf.sonar.max_range_m)}")
            _log_axis(ax)
            if i == 0:
                ax.set_title(platform_title(pf, 72 // len(platforms)), fontsize=10)
            if j == 0:
                ax.set_ylabel(METRIC_LABELS[metric])
            if i == len(metrics) - 1:
                ax.set_xlabel(xlabel)
    shown = summary[summary.estimator.isin(list(estimators))]
    for i, metric in enumerate(metrics):
        _fit_axis(axs[i, 0], shown, metric)
    for ax in axs.flat:
        _label_minor(ax)
    handles, labels = axs[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=2, fontsize=SMALL_FONT_PT, frameon=False)
    return fig


@themed
def plot_slope(platforms: Sequence, single: pd.DataFrame, summary: pd.DataFrame, *, estimators: Sequence[str],
               metrics: Sequence[str]):
    """Top row: the median single-view flat-seafloor 3-D error on the slope, closed form (line)
    and simulated (markers), against the slope (``single``: per platform and ``slope_deg``,
    columns ``closed_3d_m`` and ``simulated_3d_m``). Rows below: :func:`plot_sweep`'s rows for
    ``metrics`` (``summary`` over one spacing, ``value`` the slope). Returns the figure.

    Parameters
    ----------
    platforms : sequence of Platform
        The platforms, one column each.
    single : pandas.DataFrame
        ``platform``, ``slope_deg``, ``closed_3d_m``, ``simulated_3d_m`` (m).
    summary : pandas.DataFrame
        As :func:`plot_sweep`'s, over one spacing, ``value`` the slope (deg).
    estimators : sequence of str
        Keys of :data:`ESTIMATORS` to draw.
    metrics : sequence of str
        Keys of :data:`METRIC_LABELS`, one row each below the top row.

    Returns
    -------
    matplotlib.figure.Figure
        A new figure, legend below.
    """
    fig, axs = plt.subplots(1 + len(metrics), len(platforms), figsize=(PAGE_WIDTH_IN, 2.1 * (1 + len(metrics)) + 1.0),
                            constrained_layout=True, squeeze=False, sharex=True, sharey="row")
    for j, pf in enumerate(platforms):
        d = single[single.platform == pf.key].sort_values("slope_deg")
        ax = axs[0, j]
        ax.plot(d.slope_deg, d.closed_3d_m, "-", color="0.4", lw=2.5, label="closed form (single view)")
        ax.plot(d.slope_deg, d.simulated_3d_m, "o", color="black", ms=4, label="simulated survey (single view)")
        ax.set_title(f"{platform_title(pf, 72 // len(platforms))}\n(a) one view, flat seafloor, noise-free",
                     fontsize=10)
        s = summary[summary.platform == pf.key]
        for i, metric in enumerate(metrics, start=1):
            for est in estimators:
                name, color, marker = ESTIMATORS[est]
                e = s[s.estimator == est].sort_values("value")
                _errorbars(axs[i, j], e.value, e, metric, color=color, marker=marker, ls="-", label=name)
            if j == 0:
                axs[i, j].set_ylabel(METRIC_LABELS[metric])
        axs[-1, j].set_xlabel("seafloor slope (deg)")
    axs[0, 0].set_ylabel("median 3-D error (m)")
    for ax in axs.flat:
        _log_axis(ax)
    shown = summary[summary.estimator.isin(list(estimators))]
    for i, metric in enumerate(metrics, start=1):
        _fit_axis(axs[i, 0], shown, metric)
    for ax in axs.flat:
        _label_minor(ax)
    h0, l0 = axs[0, 0].get_legend_handles_labels()
    h1, l1 = axs[1, 0].get_legend_handles_labels()
    fig.legend(h0 + h1, l0 + l1, loc="outside lower center", ncol=3, fontsize=SMALL_FONT_PT, frameon=False)
    return fig


@themed
def plot_views(platforms: Sequence, summary: pd.DataFrame, metrics: Sequence[str]):
    """Mean error over surveys (95 % interval bars) of each step of :data:`VIEW_STEPS` (the
    mosaic first), one line per metric, one column per platform; ``summary``: :func:`over_surveys`
    by ``("platform", "estimator")`` on one subset of features. Returns the figure.

    Parameters
    ----------
    platforms : sequence of Platform
        The platforms, one panel each.
    summary : pandas.DataFrame
        ``platform``, ``estimator`` and, per metric, its mean (m) with ``<metric>_high`` (and
        ``_low``).
    metrics : sequence of str
        Keys of :data:`METRIC_LABELS`, one line each.

    Returns
    -------
    matplotlib.figure.Figure
        A new figure of one row of panels, legend below.
    """
    fig, axs = plt.subplots(1, len(platforms), figsize=(PAGE_WIDTH_IN, 3.6), constrained_layout=True,
                            squeeze=False, sharey=True)
    x = np.arange(len(VIEW_STEPS))
    colors = dict(zip(METRIC_LABELS, ("tab:blue", "tab:green", "tab:red")))
    for j, pf in enumerate(platforms):
        s = summary[summary.platform == pf.key].set_index("estimator").reindex([e for e, _ in VIEW_STEPS])
        ax = axs[0, j]
        for metric in metrics:
            _errorbars(ax, x, s, metric, color=colors[metric], marker="o", ls="-", label=METRIC_LABELS[metric])
        if not np.isfinite(s[list(metrics)].to_numpy(float)).any():  # said, not left blank
            ax.text(0.5, 0.5, "no feature estimated\nby every step", transform=ax.transAxes, ha="center",
                    va="center", fontsize=SMALL_FONT_PT, color="0.35")
        _log_axis(ax)
        ax.set_xticks(x, [lab for _, lab in VIEW_STEPS])
        ax.set_xlabel("estimate")
        ax.set_title(platform_title(pf, 72 // len(platforms)), fontsize=10)
    stacked = pd.concat([summary[[m, f"{m}_high"]].set_axis(["v", "v_high"], axis=1) for m in metrics])
    _fit_axis(axs[0, 0], stacked, "v")
    for ax in axs.flat:
        _label_minor(ax)
    axs[0, 0].set_ylabel("mean over surveys (m)")
    handles, labels = axs[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=3, fontsize=SMALL_FONT_PT, frameon=False)
    return fig


def difference_text(row, metric: str) -> str:
    """``"-1.2 m (95 % CI -1.5 to -0.9)"``: a paired difference of ``metric`` with its interval.

    Parameters
    ----------
    row : mapping or pandas.Series
        A paired-difference row with ``metric``, ``<metric>_low``, ``<metric>_high`` (m).
    metric : str
        A key of :data:`METRIC_LABELS`.

    Returns
    -------
    str
        The difference with its interval, m.
    """
    return (f"{fmt_sig(row[metric], 2)} m (95 % CI {fmt_sig(row[f'{metric}_low'], 2)} to "
            f"{fmt_sig(row[f'{metric}_high'], 2)})")


def comparison_word(row, metric: str) -> str:
    """``"closer"``, ``"farther"`` or ``"not distinguishable"``: the sign of the interval of a
    paired difference (a minus b) of ``metric``.

    Parameters
    ----------
    row : mapping or pandas.Series
        A paired-difference row with ``<metric>_low`` and ``<metric>_high`` (m).
    metric : str
        A key of :data:`METRIC_LABELS`.

    Returns
    -------
    str
        One of the three words.
    """
    if row[f"{metric}_high"] < 0:
        return "closer"
    if row[f"{metric}_low"] > 0:
        return "farther"
    return "not distinguishable"


def verdict_sentence(platform, paired: pd.DataFrame, metric: str, *, a_name: str, b_name: str, range_m: float,
                     value_unit: str = "m RMS relief") -> str:
    """One Markdown sentence per platform, error and comparison: for each spacing, at which swept
    values ``a`` is closer / farther than ``b`` in ``metric`` (the interval over surveys of the
    paired difference below / above 0) and the difference at the largest value.

    Parameters
    ----------
    platform : Platform
        The platform (its ``name``).
    paired : pandas.DataFrame
        Its paired differences: ``spacing_m``, ``value`` and the metric with ``_low``/``_high`` (m).
    metric : str
        A key of :data:`METRIC_LABELS`.
    a_name, b_name : str
        The two estimators compared (a minus b), in words.
    range_m : float
        The sonar's maximum slant range (m), for the spacing labels.
    value_unit : str
        Unit of the swept value, in words.

    Returns
    -------
    str
        The sentence (Markdown).
    """
    parts = []
    for spacing, c in paired.groupby("spacing_m", sort=False):
        c = c.sort_values("value")
        words = {w: [fmt_sig(v, 2) for v, r in zip(c.value, c.itertuples()) if comparison_word(r._asdict(), metric) == w]
                 for w in ("closer", "farther", "not distinguishable")}
        said = "; ".join(f"{w} at {', '.join(v)} {value_unit}" for w, v in words.items() if v)
        last = c.iloc[-1]
        parts.append(f"{spacing_label(spacing, range_m)}: {said} (at {fmt_sig(last.value, 2)}, "
                     f"{difference_text(last, metric)})")
    return (f"**{platform.name}**, {METRIC_LABELS[metric].replace(' (m)', '')}, {a_name} against {b_name}: "
            + "; ".join(parts) + ".")


def with_intervals(frame: pd.DataFrame, columns: Sequence[str], digits: int = 2) -> pd.DataFrame:
    """``frame`` with each of ``columns`` and its interval (``<column>_low``, ``<column>_high``)
    as one text column ``"value (95 % CI low–high)"``, for a table a reader reads.

    Parameters
    ----------
    frame : pandas.DataFrame
        Holds each of ``columns`` with ``<column>_low`` and ``<column>_high`` (the rows of
        :func:`~sss_locus.experiments.reconstruction.surveys.over_surveys` or
        :func:`~sss_locus.experiments.reconstruction.surveys.paired_over_surveys`).
    columns : sequence of str
        The columns to join with their intervals.
    digits : int
        Significant figures (more where the interval's ends would print alike).

    Returns
    -------
    pandas.DataFrame
        A copy: each of ``columns`` is text, the ``_low``/``_high`` columns are gone (a missing
        value reads ``"—"``).

    >>> f = pd.DataFrame({"shape_m": [-0.42], "shape_m_low": [-0.51], "shape_m_high": [-0.33]})
    >>> with_intervals(f, ["shape_m"])["shape_m"].tolist()
    ['-0.42 (95 % CI -0.51–-0.33)']
    """
    out = frame.copy()
    for c in columns:
        out[c] = fmt_ci_cells(out[c], out[f"{c}_low"], out[f"{c}_high"], digits)
        out = out.drop(columns=[f"{c}_low", f"{c}_high"])
    return out
