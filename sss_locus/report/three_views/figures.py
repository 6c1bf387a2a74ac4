"""Figures of the three-views chapter (``notebooks/three_views.ipynb``): the survey patterns
(resolution, plane angle, conditioning) and the sweep over the headings of passes 2 and 3.

Tables are those of :func:`sss_locus.experiments.three_views.patterns.three_view_table` (per
platform key and pattern name) and
:func:`sss_locus.experiments.three_views.patterns.heading_sweep` (per platform key). Platforms are
:class:`~sss_locus.experiments.datamodel.platforms.Platform` objects; their names come from the data.

Both figures are drawn in the book's seaborn theme (:func:`~sss_locus.report.common.style.theme`): the
distributions of plane angle and conditioning with ``seaborn.boxplot`` (quartiles and 5-95 %
whiskers of each pattern's configurations), the heading sweep with ``seaborn.heatmap`` (one cell
per heading pair, the cells' headings on the axes). The outcome shares of panel (a) stay stacked
``barh``: seaborn has no stacked bar of precomputed shares.
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import seaborn as sns
from matplotlib.colors import LogNorm
from matplotlib.ticker import NullFormatter

from sss_locus.experiments.three_views.patterns import cells_within, share_interval, share_upper_bound
from sss_locus.report.common.style import PAGE_WIDTH_IN, SMALL_FONT_PT, get_axis, platform_title, themed, upward_heatmap
from sss_locus.report.common.text import fmt_interval, fmt_percent, fmt_span

PATTERN_TAGS = {"repeat + reciprocal": "rr", "two lines + cross line": "cross",
                "three headings 60 deg apart": "sixty"}
"""Short tag of each pattern of :data:`~sss_locus.experiments.three_views.patterns.PATTERNS` in
the chapter's glue keys (``tv-<platform>-<tag>-...``)."""

OUTCOMES = (("resolved (1 point)", 1, "tab:green"), ("two-fold ambiguity", 2, "tab:orange"),
            ("no candidate", 0, "tab:gray"))
"""Bars of panel (a): label, number of valid candidates, colour."""


def pattern_label(name: str) -> str:
    """A pattern's name on two lines, for an axis: ``"two lines +\\ncross line"``.

    Parameters
    ----------
    name : str
        The pattern's name.

    Returns
    -------
    str
        The name with a line break after ``" + "`` and before the separation of 60° patterns.
    """
    return name.replace(" + ", " +\n").replace(" 60 deg apart", "\n60° apart")


@themed
def plot_outcome_shares(by_pattern: Mapping[str, pd.DataFrame], *, title: str = "", ax=None):
    """Share of configurations with one, two or no valid candidate, one stacked bar per pattern
    (the tables' first at the top).

    Parameters
    ----------
    by_pattern : mapping of str to pandas.DataFrame
        Three-view tables (column ``n_valid``) keyed by pattern name.
    title : str
        Panel title.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: the current axes).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    ax = get_axis(ax)
    short = [pattern_label(name) for name in by_pattern]
    fr = np.array([[(t.n_valid == v).mean() for _, v, _ in OUTCOMES] for t in by_pattern.values()])
    left = np.zeros(len(short))
    for j, (lab, _, color) in enumerate(OUTCOMES):  # the patterns as categories, as seaborn's
        ax.barh(short, fr[:, j], left=left, color=color, label=lab, height=0.8)
        left += fr[:, j]
    ax.set_xlim(0, 1)
    ax.set_xlabel("fraction of configurations")
    ax.set_title(title, fontsize=10)
    ax.grid(axis="y", visible=False)  # no line through the bars
    return ax


@themed
def plot_pattern_boxes(by_pattern: Mapping[str, pd.DataFrame], column: str, *, xlabel: str = "",
                       title: str = "", ax=None):
    """Distribution of ``column`` per pattern (box: quartiles, whiskers: 5-95 %, log scale).

    Parameters
    ----------
    by_pattern : mapping of str to pandas.DataFrame
        Three-view tables keyed by pattern name.
    column : str
        Column drawn (e.g. ``plane_angle_deg``, ``point_error_q95_m``), positive values.
    xlabel, title : str
        Axis label and panel title.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: the current axes).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    ax = get_axis(ax)
    short = [pattern_label(name) for name in by_pattern]
    long = pd.DataFrame({"pattern": np.repeat(short, [len(t) for t in by_pattern.values()]),
                         column: np.concatenate([t[column].to_numpy() for t in by_pattern.values()])})
    # quartiles of the values themselves (the axis turns logarithmic after, not before)
    with warnings.catch_warnings():  # seaborn 0.13.2 passes Axes.bxp the vert= of matplotlib < 3.11
        warnings.filterwarnings("ignore", message="vert: bool", category=DeprecationWarning)
        sns.boxplot(long, x=column, y="pattern", order=short, whis=(5, 95), showfliers=False, ax=ax,
                    color="0.92", linecolor="0.2", medianprops={"color": "tab:orange", "linewidth": 2})
    ax.set_xscale("log")
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel(xlabel)
    ax.set_ylabel("")
    ax.set_title(title, fontsize=10)
    ax.grid(axis="y", visible=False)  # no line through the boxes
    return ax


@themed
def plot_patterns(platforms: Sequence, tables: Mapping[str, Mapping[str, pd.DataFrame]],
                  range_sigma_m: float):
    """Three panels per platform (one column each); returns the figure.

    (a) share of configurations with one, two or no valid candidate (:func:`plot_outcome_shares`);
    (b) angle between the two planes (box: quartiles, whiskers: 5-95 %, log scale); (c)
    first-order 95 % point error for a ``range_sigma_m`` range error (``point_error_q95_m``, log
    scale; both :func:`plot_pattern_boxes`).
    ``tables[platform.key][pattern]`` is a three-view table. Rows (a), (b), (c); columns the
    platforms; the patterns, in the tables' order from the top, label the rows of the left
    column only (shared).

    Parameters
    ----------
    platforms : sequence of Platform
        The platforms, one column each.
    tables : mapping of str to mapping of str to pandas.DataFrame
        ``tables[platform key][pattern]``: three-view tables with ``n_valid``,
        ``plane_angle_deg`` (deg) and ``point_error_q95_m`` (m).
    range_sigma_m : float
        The range error (m) the point errors are per.

    Returns
    -------
    matplotlib.figure.Figure
        A new figure of 3 x ``len(platforms)`` panels, legend below.
    """
    n = len(platforms)
    fig, axs = plt.subplots(3, n, figsize=(PAGE_WIDTH_IN, 6.4), constrained_layout=True,
                            squeeze=False, sharey=True)
    for col, pf in zip(axs.T, platforms):
        by_pattern = tables[pf.key]
        plot_outcome_shares(by_pattern, title=platform_title(pf, 72 // n) + "\n(a) outcome", ax=col[0])  # 36 a column for two
        plot_pattern_boxes(by_pattern, "plane_angle_deg", xlabel="angle between the two planes (deg)",
                           title="(b) plane angle", ax=col[1])
        plot_pattern_boxes(by_pattern, "point_error_q95_m",
                           xlabel=f"95 % point error per {100 * range_sigma_m:g} cm\nrange error (m)",
                           title="(c) conditioning, first order", ax=col[2])
    handles, labels = axs[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=len(OUTCOMES), fontsize=SMALL_FONT_PT,
               frameon=False)
    return fig


def sym_grid(sweep: pd.DataFrame, value: str) -> tuple[np.ndarray, np.ndarray]:
    """The headings and a symmetric square grid of ``sweep[value]`` over them.

    The sweep holds one row per pair ``heading2_deg <= heading3_deg``; swapping passes 2 and 3
    changes nothing, so each value fills both ``z[i, j]`` and ``z[j, i]`` (NaN where no pair
    was run): row ``j`` is heading ``h[j]`` of pass 3, column ``i`` heading ``h[i]`` of pass 2.

    Parameters
    ----------
    sweep : pandas.DataFrame
        A heading sweep: ``heading2_deg``, ``heading3_deg`` (deg) and ``value``.
    value : str
        The column to grid.

    Returns
    -------
    h : numpy.ndarray, shape (n,)
        The headings run (deg), increasing.
    z : numpy.ndarray, shape (n, n)
        The values, symmetric, NaN where no pair was run.
    """
    h = np.unique(np.concatenate([sweep.heading2_deg, sweep.heading3_deg]))
    z = np.full((h.size, h.size), np.nan)
    i, j = np.searchsorted(h, sweep.heading2_deg), np.searchsorted(h, sweep.heading3_deg)
    z[i, j] = sweep[value].to_numpy()
    z[j, i] = sweep[value].to_numpy()
    return h, z


@themed
def plot_sweep_heatmap(sweep: pd.DataFrame, value: str, *, label: str = "", title: str = "",
                       y_label: bool = True, ax=None, **style):
    """``sweep[value]`` against the headings of passes 2 and 3, one ``seaborn.heatmap`` cell per
    heading pair (:func:`sym_grid`), with a colour bar and ticks at the headings run.

    Parameters
    ----------
    sweep : pandas.DataFrame
        A heading sweep (``heading2_deg``, ``heading3_deg`` and ``value``).
    value : str
        Column drawn.
    label : str
        Colour bar label.
    title : str
        Panel title.
    y_label : bool
        Whether to label the ``y`` axis (the left panel of a row).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: the current axes).
    **style
        Passed to ``seaborn.heatmap`` (``cmap``, ``norm``).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    ax = get_axis(ax)
    h, z = sym_grid(sweep, value)
    mesh = upward_heatmap(ax, z, square=True, **style)
    ax.figure.colorbar(mesh, ax=ax, label=label, shrink=0.8).outline.set_linewidth(0)
    ticks = np.unique(sweep.heading2_deg)
    ticks = ticks if ticks.size <= 7 else ticks[::2]
    at = np.searchsorted(h, ticks) + 0.5  # the centres of their cells
    ax.set_xlabel("heading of pass 2, $h_2$ (deg)")
    ax.set_ylabel("heading of pass 3, $h_3$ (deg)" if y_label else "")
    ax.set_title(title, fontsize=10)
    ax.set_xticks(at, [f"{v:g}" for v in ticks], rotation=0)
    ax.set_yticks(at, [f"{v:g}" for v in ticks], rotation=0)
    return ax


@themed
def plot_heading_sweep(platforms: Sequence, sweeps: Mapping[str, pd.DataFrame], range_sigma_m: float):
    """Median plane angle (left) and median first-order 95 % point error for a ``range_sigma_m``
    range error (right, log colour scale) against the headings of passes 2 and 3, one row per
    platform (:func:`plot_sweep_heatmap`); returns the figure. ``sweeps[platform.key]`` is a
    heading sweep with noise.

    Parameters
    ----------
    platforms : sequence of Platform
        The platforms, one row each.
    sweeps : mapping of str to pandas.DataFrame
        Platform key -> heading sweep with ``plane_angle_median_deg`` (deg) and
        ``point_error_q95_median_m`` (m).
    range_sigma_m : float
        The range error (m) the point errors are per.

    Returns
    -------
    matplotlib.figure.Figure
        A new figure of ``len(platforms)`` x 2 heatmaps.
    """
    fig, axs = plt.subplots(len(platforms), 2, figsize=(PAGE_WIDTH_IN, 3.5 * len(platforms)), constrained_layout=True,
                            squeeze=False)
    for row, pf in zip(axs, platforms):
        sweep = sweeps[pf.key]
        plot_sweep_heatmap(sweep, "plane_angle_median_deg", label="plane angle (deg)",
                           title=f"{platform_title(pf, 32)}:\nmedian plane angle", ax=row[0], cmap="viridis")
        plot_sweep_heatmap(sweep, "point_error_q95_median_m", label="95 % point error (m)",
                           title=f"{platform_title(pf, 32)}:\nmedian error per {100 * range_sigma_m:g} cm range error",
                           y_label=False, ax=row[1], cmap="magma_r", norm=LogNorm())
    return fig


def cells_text(cells: pd.DataFrame) -> str:
    """Cells of a heading sweep in words: each ``(h2, h3)`` when there are at most three, else
    their number and the spans of their headings.

    Parameters
    ----------
    cells : pandas.DataFrame
        Cells with ``heading2_deg`` and ``heading3_deg`` (deg).

    Returns
    -------
    str
        The cells in words, headings in whole degrees.

    Examples
    --------
    >>> cells_text(pd.DataFrame({"heading2_deg": [0.0, 180.0], "heading3_deg": [0.0, 180.0]}))
    '(0°, 0°), (180°, 180°)'
    >>> cells_text(pd.DataFrame({"heading2_deg": [45.0, 60, 90, 75], "heading3_deg": [90.0, 120, 135, 105]}))
    '4 cells with h₂ 45° to 90° and h₃ 90° to 135°'
    """
    if len(cells) <= 3:
        return ", ".join(f"({a:.0f}°, {b:.0f}°)" for a, b in zip(cells.heading2_deg, cells.heading3_deg))
    return (f"{len(cells)} cells with h₂ {fmt_span(cells.heading2_deg.min(), cells.heading2_deg.max())} and "
            f"h₃ {fmt_span(cells.heading3_deg.min(), cells.heading3_deg.max())}")


def sweep_texts(sweep: pd.DataFrame) -> dict[str, str]:
    """The heading sweep of one platform (with noise) as the chapter prints it, keyed by glue
    suffix: ``best`` / ``worst``, the cells the sampling cannot tell from the smallest / largest
    median error (:func:`~sss_locus.experiments.three_views.patterns.cells_within`), and
    ``best-err`` / ``worst-err`` that median with its 95 % interval; ``spread-err`` and
    ``parallel-err``, the largest median (with its interval) among the cells with the three
    headings spread out (passes 2 and 3 each at least 45° from pass 1 and from each other,
    within 45–135°) and on the diagonal away from the corners (``h2 = h3``, not 0° or 180°);
    ``resolved``, the share resolved over all cells, and ``unresolved-upper``, the one-sided
    exact 95 % bound of the share left unresolved over all cells.

    Parameters
    ----------
    sweep : pandas.DataFrame
        One platform's heading sweep: ``heading2_deg``, ``heading3_deg`` (deg),
        ``point_error_q95_median_m`` with ``point_error_q95_median_ci_low_m``/``_ci_high_m`` (m),
        ``n`` (configurations per cell) and ``resolved_fraction`` (0–1).

    Returns
    -------
    dict of str to str
        Glue suffix -> text; errors in m with intervals, shares in percent.
    """
    v = "point_error_q95_median_m"

    def err(row) -> str:
        return fmt_interval({"median": row[v], "ci_low": row[v[:-2] + "_ci_low_m"],
                             "ci_high": row[v[:-2] + "_ci_high_m"]}, "m")

    h2, h3 = sweep.heading2_deg, sweep.heading3_deg
    spread = sweep[(h3 - h2 >= 45) & (h2 >= 45) & (h3 <= 135)]
    diagonal = sweep[np.isclose(h2, h3) & ~np.isclose(np.mod(h2, 180.0), 0.0)]
    n_all = float(sweep["n"].sum())
    unresolved = int(round(float(((1.0 - sweep["resolved_fraction"]) * sweep["n"]).sum())))
    out = {"best": cells_text(cells_within(sweep, "min")), "best-err": err(sweep.loc[sweep[v].idxmin()]),
           "worst": cells_text(cells_within(sweep, "max")), "worst-err": err(sweep.loc[sweep[v].idxmax()]),
           "resolved": fmt_percent(1.0 - unresolved / n_all),
           "unresolved-upper": fmt_percent(share_upper_bound(unresolved, int(n_all)))}
    for name, cells in (("spread-err", spread), ("parallel-err", diagonal)):
        out[name] = err(cells.loc[cells[v].idxmax()]) if len(cells) else "n/a"
    return out


def share_text(share: float, n: int) -> str:
    """A share of ``n`` configurations with its exact 95 % interval
    (:func:`~sss_locus.experiments.three_views.patterns.share_interval`), in percent with one
    decimal, or more while the interval's ends would print alike.

    Parameters
    ----------
    share : float
        The share, 0 to 1.
    n : int
        Number of configurations it is a share of.

    Returns
    -------
    str
        The share with its interval, in percent.

    Examples
    --------
    >>> share_text(0.996, 4000), share_text(1.0, 4000), share_text(0.0, 4000)
    ('99.6 % (95 % CI 99.4–99.8 %)', '100.0 % (95 % CI 99.9–100.0 %)', '0.0 % (95 % CI 0.0–0.1 %)')
    """
    lo, hi = share_interval(int(round(share * n)), int(n))
    dec = 1
    while dec < 3 and f"{100 * lo:.{dec}f}" == f"{100 * hi:.{dec}f}":
        dec += 1
    return f"{100 * share:.{dec}f} % (95 % CI {100 * lo:.{dec}f}–{100 * hi:.{dec}f} %)"
