"""Figures, tables and prose numbers of the pose-space chapter (``notebooks/pose_space.ipynb``).

The numbers come from :mod:`sss_locus.experiments.pose_space.stats`; this module only draws them
(:func:`plot_sensitivity`, the paper's Fig. 3; :func:`plot_heatmaps`, its Fig. 4), lays them
out as tables (:func:`seed_stability_table`, :func:`check_row`) and writes them as prose
(:func:`fmt_metric`, :func:`metric_texts`). The heatmaps and the scatter coloured by the
number of arcs are drawn with seaborn in the book's theme (:func:`sss_locus.report.common.style.theme`);
the bars of rho keep ``barh`` because their intervals are the replicate-batch intervals of
:func:`~sss_locus.experiments.pose_space.stats.spearman_table` (``seaborn.barplot`` would compute its own).
"""

from __future__ import annotations

import math
import textwrap
from collections.abc import Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import seaborn as sns
from matplotlib.colors import to_rgba
from matplotlib.ticker import MaxNLocator

from sss_locus.experiments.pose_space.stats import HEATMAP_PANELS, TARGETS, median_grid
from sss_locus.report.common.style import PAGE_WIDTH_IN, QUANTITY_LABELS, SMALL_FONT_PT, get_axis, themed, upward_heatmap
from sss_locus.report.pose_space.findings import fmt_rho
from sss_locus.report.common.text import NO_BATCH_CI, fmt_ci, fmt_interval, fmt_sig, fmt_span, plain_label

PANEL_TITLES = {
    "a": "(a) range vs range", "b": "(b) azimuth vs azimuth", "c": "(c) elevation vs elevation",
    "d": "(d) vehicle-2 yaw vs pitch", "e": "(e) vehicle-2 yaw vs its azimuth",
}
"""Titles of the heatmap panels of :data:`~sss_locus.experiments.pose_space.stats.HEATMAP_PANELS`."""

PANEL_AXIS_LABELS = {
    "r1_m": "$r_1$ (m)", "r2_m": "$r_2$ (m)", "azimuth1_deg": r"$\theta_1$ (deg)",
    "azimuth2_deg": r"$\theta_2$ (deg)", "elevation1_deg": r"$\phi_1$ (deg)",
    "elevation2_deg": r"$\phi_2$ (deg)", "yaw2_deg": "yaw of vehicle 2 (deg)",
    "pitch2_deg": "pitch of vehicle 2 (deg, nose up +)",
}
"""Axis labels (with units) of the heatmap panels' columns."""

SCATTER_COLUMNS = ("elevation_misalignment_deg", "locus_length_normalized", "n_arcs")
"""Columns of the scatter subset drawn in panel (c) of :func:`plot_sensitivity`."""


def scatter_subset(df: pd.DataFrame, n_points: int, seed: int) -> pd.DataFrame:
    """The random subset of at most ``n_points`` rows of ``df`` drawn in the scatter panel
    (``DataFrame.sample`` with ``random_state=seed``), columns :data:`SCATTER_COLUMNS`.

    Parameters
    ----------
    df : pandas.DataFrame
        The pose-space samples, with the columns :data:`SCATTER_COLUMNS`
        (``elevation_misalignment_deg`` in deg, ``locus_length_normalized`` without unit, ``n_arcs``).
    n_points : int
        Largest number of rows drawn.
    seed : int
        Random state of the sample.

    Returns
    -------
    pandas.DataFrame
        ``min(n_points, len(df))`` rows of ``df`` (index kept), columns :data:`SCATTER_COLUMNS`.
    """
    sub = df.sample(n=min(n_points, len(df)), random_state=seed)
    return sub[list(SCATTER_COLUMNS)]


@themed
def plot_rho_bars(rho: pd.DataFrame, target: str = TARGETS[0], *, title: str = "", ax=None):
    """One panel of the paper's Fig. 3: Spearman rho of each quantity with ``target``, bars
    with their replicate-batch intervals (positive blue, negative grey).

    Parameters
    ----------
    rho : pandas.DataFrame
        A :func:`~sss_locus.experiments.pose_space.stats.spearman_table`.
    target : str
        One of :data:`~sss_locus.experiments.pose_space.stats.TARGETS`.
    title : str
        Panel title.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: the current axes, :func:`~sss_locus.report.common.style.get_axis`).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    ax = get_axis(ax)
    tab = rho[rho["target"] == target].iloc[::-1]
    err = np.vstack([tab["rho"] - tab["ci_low"], tab["ci_high"] - tab["rho"]])
    ax.barh([QUANTITY_LABELS[q] for q in tab["quantity"]], tab["rho"], xerr=err, capsize=2,
            color=np.where(tab["rho"] >= 0, "tab:blue", "tab:gray"))
    ax.axvline(0, color="k", lw=0.8)
    ax.set_xlim(-1, 1)
    what = "length" if target == TARGETS[0] else "length / mean range"
    ax.set_xlabel(r"Spearman $\rho$ with " + what)
    ax.set_title(title)
    ax.grid(axis="y", visible=False)  # no line through the bars
    return ax


@themed
def plot_length_scatter(subset: pd.DataFrame, *, title: str = "", ax=None):
    """Panel (c) of the paper's Fig. 3: normalised locus length against elevation misalignment,
    fragmented loci in orange, drawn last (on top).

    Parameters
    ----------
    subset : pandas.DataFrame
        Rows to draw, columns :data:`SCATTER_COLUMNS` (:func:`scatter_subset`).
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
    arcs = np.where(subset["n_arcs"] > 1, "several arcs (fragmented)", "one arc")
    shown = subset.assign(arcs=arcs).sort_values("arcs", key=lambda a: a != "one arc", kind="stable")
    # no legend entry for a class with no points
    sns.scatterplot(shown, x="elevation_misalignment_deg", y="locus_length_normalized", hue="arcs",
                    size="arcs", sizes={"one arc": 3, "several arcs (fragmented)": 9},
                    palette={"one arc": to_rgba("tab:blue", 0.35),  # the many single arcs faint
                             "several arcs (fragmented)": to_rgba("tab:orange", 0.9)}, lw=0, ax=ax)
    ax.set_yscale("log")
    ax.set_xlabel("elevation misalignment (deg)")
    ax.set_ylabel("locus length / mean range")
    ax.set_title(title)
    sns.move_legend(ax, "best", title=None, fontsize=SMALL_FONT_PT, markerscale=2)  # covers fewest points
    return ax


@themed
def plot_sensitivity(rho: pd.DataFrame, subset: pd.DataFrame, *, title: str = ""):
    """The paper's Fig. 3 for one platform: (a, b) Spearman rho of each quantity with the raw and
    the range-normalised locus length, with replicate-batch intervals (:func:`plot_rho_bars`);
    (c) normalised length against elevation misalignment for ``subset`` (:func:`scatter_subset`),
    fragmented loci in orange (:func:`plot_length_scatter`).

    Parameters
    ----------
    rho : pandas.DataFrame
        A :func:`~sss_locus.experiments.pose_space.stats.spearman_table`.
    subset : pandas.DataFrame
        The scatter's rows (:func:`scatter_subset`).
    title : str
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, mosaic = plt.subplot_mosaic([["a", "b"], ["c", "c"]], figsize=(PAGE_WIDTH_IN, 8), constrained_layout=True)
    names = ("(a) raw locus length", "(b) range-normalised length")
    for panel, target, name in zip("ab", TARGETS, names):
        plot_rho_bars(rho, target, title=name, ax=mosaic[panel])
    plot_length_scatter(subset, title="(c) normalised length vs misalignment", ax=mosaic["c"])
    fig.suptitle(textwrap.fill(title, 75))
    return fig


@themed
def plot_heatmap(binned: pd.DataFrame, *, title: str = "", x_label: str | None = None,
                 y_label: str | None = None, ax=None):
    """One panel of the paper's Fig. 4: the median locus length per bin of a
    :func:`~sss_locus.experiments.pose_space.stats.binned_median` table as a ``seaborn.heatmap``
    (masked bins blank on grey, ``y`` increasing upwards, ticks at round values of the binned
    quantities, a colour bar); with one bin along ``y`` (e.g. a boat that never pitches), the
    medians as a 1-D profile.

    Parameters
    ----------
    binned : pandas.DataFrame
        A :func:`~sss_locus.experiments.pose_space.stats.binned_median` table (its ``attrs`` name the
        columns binned).
    title : str
        Panel title, ``"<x> vs <y>"`` (a profile keeps the part before ``" vs "``).
    x_label, y_label : str, optional
        Axis labels with units; default :data:`PANEL_AXIS_LABELS` of the columns binned.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: the current axes).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    ax = get_axis(ax)
    x_label = PANEL_AXIS_LABELS.get(binned.attrs.get("x"), binned.attrs.get("x")) if x_label is None else x_label
    y_label = PANEL_AXIS_LABELS.get(binned.attrs.get("y"), binned.attrs.get("y")) if y_label is None else y_label
    xe, ye, z = median_grid(binned)
    if len(ye) == 2:  # one bin along y: a 1-D profile
        ax.hlines(z[0], xe[:-1], xe[1:], color="tab:blue", lw=2)  # sparse (masked) bins: no line
        ax.set_xlabel(x_label)
        ax.set_ylabel("median locus length (m)")
        ax.set_title(f"{title.split(' vs ')[0]}\n({y_label.split(' (')[0]} "
                     f"always {0.5 * (ye[0] + ye[1]):g})")
        ax.set_ylim(bottom=0)
        return ax
    _heatmap(ax, xe, ye, z)
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label)
    ax.set_title(title)
    return ax


def _heatmap(ax, xe: np.ndarray, ye: np.ndarray, z: np.ndarray) -> None:
    """``seaborn.heatmap`` of ``z`` (shape ``(n_y, n_x)``, NaN for a masked bin, drawn blank on
    grey) with ``y`` increasing upwards and ticks at round values of the binned quantities (a
    heatmap's own ticks name its cells; these bins are intervals of numbers). Cells are drawn
    of equal size, so the axes are linear for equal-width bins (those of
    :func:`~sss_locus.experiments.pose_space.stats.panel_edges`)."""
    mesh = upward_heatmap(ax, z, cmap="viridis")
    ax.figure.colorbar(mesh, ax=ax, pad=0.02).outline.set_linewidth(0)
    for axis, e in ((ax.xaxis, xe), (ax.yaxis, ye)):  # data values -> cell positions
        values = [v for v in MaxNLocator(nbins=7, steps=[1, 2, 2.5, 5, 10]).tick_values(e[0], e[-1])
                  if e[0] <= v <= e[-1]]
        axis.set_ticks(np.interp(values, e, np.arange(len(e))),  # edge k at cell position k
                       [f"{v:g}".replace("-", "\N{MINUS SIGN}") for v in values], rotation=0)
    mesh.colorbar.ax.set_title("m", fontsize=plt.rcParams["axes.labelsize"])  # the title names it


@themed
def plot_heatmaps(maps: Mapping[str, pd.DataFrame], *, title: str = ""):
    """The paper's Fig. 4 for one platform: median locus length per bin for each panel of
    :data:`~sss_locus.experiments.pose_space.stats.HEATMAP_PANELS` (:func:`plot_heatmap`); masked
    (sparse) bins blank.

    Parameters
    ----------
    maps : mapping of str to pandas.DataFrame
        A :func:`~sss_locus.experiments.pose_space.stats.heatmaps` result, keyed by panel letter.
    title : str
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axs = plt.subplots(3, 2, figsize=(PAGE_WIDTH_IN, 10.5), constrained_layout=True)
    for ax, (panel, x, y) in zip(axs.flat, HEATMAP_PANELS):
        plot_heatmap(maps[panel], title=PANEL_TITLES[panel], x_label=PANEL_AXIS_LABELS[x],
                     y_label=PANEL_AXIS_LABELS[y], ax=ax)
    axs.flat[-1].axis("off")
    fig.suptitle(textwrap.fill(title, 75))
    return fig


def fmt_metric(name: str, v) -> str:
    """One claim metric of :func:`~sss_locus.experiments.pose_space.claims.claim_metrics` as prose,
    by the kind its name ends in: quantity names as plain text, ranks as integers, rank
    correlations to two decimals, ratios to two significant figures, fractions in percent and
    angles in whole degrees (without the intervals and peak regions of :func:`printed_metric`).

    Parameters
    ----------
    name : str
        The metric's name (its ending gives the kind).
    v : float or str
        Its value.

    Returns
    -------
    str
        The printed text.

    Examples
    --------
    >>> fmt_metric("top_raw", "mean_range_m"), fmt_metric("raw_baseline_m_rank", 3.0)
    ('mean range', '3')
    >>> fmt_metric("norm_azimuth1_deg_rho", -0.0569), fmt_metric("multi_arc_fraction", 0.0123)
    ('-0.06', '1.2 %')
    >>> fmt_metric("yaw_peak_neg_deg", -95.0), fmt_metric("range_far_over_near_ratio", 2.345)
    ('-95', '2.3')
    """
    return printed_metric(name, {name: v})[0]


def _sig_unit(x: float, digits: int = 2) -> float:
    """A unit of the last of ``digits`` significant figures of ``x``."""
    return 10.0 ** (math.floor(math.log10(abs(x))) - (digits - 1)) if x and math.isfinite(x) else 0.0


def printed_metric(name: str, metrics: Mapping[str, float | str]) -> tuple[str, str, object]:
    """How the chapter prints claim metric ``name`` of ``metrics`` and what two seeds must share
    for it to count as stable at what is printed: ``(text, kind, what)``.

    ``kind`` is ``"text"`` (a quantity name: equal names), ``"unit"`` (``what`` the unit of the
    last printed digit: the seeds differ by at most half of it), ``"interval"`` (a ratio or
    share printed with its 95 % replicate interval ``what = (low, high)``: the seeds' intervals
    overlap) or ``"span"`` (a peak printed as the span ``what = (low, high)`` of its peak region,
    :func:`~sss_locus.experiments.pose_space.claims.peak_region`: the seeds' spans overlap).

    Parameters
    ----------
    name : str
        The metric's name.
    metrics : mapping of str to float or str
        All claim metrics of one run (with ``<name>_ci_low``/``_ci_high`` or the peak's
        ``_lo_deg``/``_hi_deg`` where it has them).

    Returns
    -------
    text : str
        What the chapter prints.
    kind : str
        ``"text"``, ``"unit"``, ``"interval"`` or ``"span"``.
    what : object
        What two seeds compare: the text, the unit of the last digit, or ``(low, high)``.

    Examples
    --------
    >>> printed_metric("x_ratio", {"x_ratio": 2.13, "x_ratio_ci_low": 2.07, "x_ratio_ci_high": 2.19})
    ('2.1 (95 % CI 2.1–2.2)', 'interval', (2.07, 2.19))
    >>> printed_metric("p_deg", {"p_deg": -75.0, "p_lo_deg": -85.0, "p_hi_deg": -75.0})[:2]
    ('-85° to -75°', 'span')
    """
    v = metrics[name]
    if isinstance(v, str):
        return plain_label(v), "text", v
    if f"{name}_ci_low" in metrics:
        lo, hi = float(metrics[f"{name}_ci_low"]), float(metrics[f"{name}_ci_high"])
        return fmt_ci(v, lo, hi, percent=name.endswith("_fraction"), no_ci=NO_BATCH_CI), "interval", (lo, hi)
    base = name[:-len("_deg")]
    if name.endswith("_deg") and f"{base}_lo_deg" in metrics:
        lo, hi = float(metrics[f"{base}_lo_deg"]), float(metrics[f"{base}_hi_deg"])
        return fmt_span(lo, hi), "span", (lo, hi)
    if name.endswith(("_rank", "_count")) or name.startswith("n_"):
        return f"{v:,.0f}", "unit", 1.0
    if name.endswith("_rho"):
        return fmt_rho(v), "unit", 0.01
    if name.endswith("_fraction"):
        return f"{fmt_sig(100 * v, 2)} %", "unit", _sig_unit(v)
    if name.endswith("_deg"):
        return f"{v:.0f}", "unit", 1.0
    return fmt_sig(v, 2), "unit", _sig_unit(v)


def agree_at_print(kind: str, a, b) -> bool:
    """Whether two seeds' ``what`` of :func:`printed_metric` (of one metric, same ``kind``)
    agree at what the chapter prints: equal texts, a difference of at most half a unit of the
    last printed digit (``a``, ``b`` are ``(value, unit)``; the larger unit counts), or
    overlapping intervals or spans (``a``, ``b`` are ``(low, high)``).

    Parameters
    ----------
    kind : str
        ``kind`` of :func:`printed_metric`.
    a, b : object
        The two seeds' ``what`` (texts, ``(value, unit)`` or ``(low, high)``).

    Returns
    -------
    bool
        Whether the two agree at the printed precision.

    Examples
    --------
    >>> agree_at_print("unit", (-0.0569, 0.01), (-0.0582, 0.01)), agree_at_print("unit", (0.0569, 0.001), (0.0582, 0.001))
    (True, False)
    >>> agree_at_print("interval", (2.07, 2.19), (2.01, 2.12)), agree_at_print("span", (-85, -85), (-75, -65))
    (True, False)
    """
    if kind == "text":
        return a == b
    if kind == "unit":
        return bool(abs(a[0] - b[0]) <= 0.5 * max(a[1], b[1]) * (1 + 1e-9))
    return bool(max(a[0], b[0]) <= min(a[1], b[1]))


SKIPPED_SUFFIXES = ("_ci_low", "_ci_high", "_lo_deg", "_hi_deg", "_count", "_bins", "_equal", "_median_m")
"""Metric names left out of the seed table: the parts of an interval or span (checked with
their metric), sample counts (a description of the run, which grows with it) and values the
chapter does not print."""

QUOTED_RANKS = ("raw_baseline_m_rank", "raw_mean_range_m_rank")
"""The ranks in the Spearman table that the book quotes (the chapter and the claims page; a
test keeps this list in step with them): the only ranks the seed table compares. Other ranks
of near-equal correlations (e.g. the AUV's two ranges) may swap between seeds, and are not
printed."""


def metric_texts(metrics: Mapping[str, float | str], rho: pd.DataFrame) -> dict[str, str]:
    """Prose of every claim metric (:func:`printed_metric`; a peak's span under
    ``<name>_span`` besides the bin of its largest median under ``<name>``) plus the replicate
    interval of every rank correlation, ``"<raw|norm>_<quantity>_ci"`` -> ``"[lo, hi]"`` (three
    decimals).

    Parameters
    ----------
    metrics : mapping of str to float or str
        The claim metrics of one run
        (:func:`~sss_locus.experiments.pose_space.claims.claim_metrics`).
    rho : pandas.DataFrame
        The Spearman table: ``target``, ``quantity``, ``ci_low``, ``ci_high``.

    Returns
    -------
    dict of str to str
        Metric or interval name -> text.
    """
    out = {}
    for name, v in metrics.items():
        if name.endswith(SKIPPED_SUFFIXES[:4]):
            continue
        text, kind, _ = printed_metric(name, metrics)
        if kind == "span":
            out[f"{name[:-len('_deg')]}_span"] = text
            text = f"{v:.0f}"
        out[name] = text
    for row in rho.itertuples():
        tag = "raw" if row.target == TARGETS[0] else "norm"
        out[f"{tag}_{row.quantity}_ci"] = f"[{row.ci_low:.3f}, {row.ci_high:.3f}]"
    return out


def seed_stability_table(runs: Mapping[str, tuple[Mapping, Mapping]], seeds: tuple[int, int]) -> pd.DataFrame:
    """Every rank correlation and claim metric of two seeds side by side, with whether they
    agree at what the chapter prints (:func:`printed_metric`, :func:`agree_at_print`), and
    the heatmaps' bins.

    ``runs`` maps a platform key to the two runs (dicts with ``rho``, ``metrics``, ``maps`` and
    optionally ``map_ci``, :func:`~sss_locus.experiments.pose_space.claims.map_intervals`) of the
    seeds in ``seeds``. Rank correlations are printed to two decimals. The seed columns hold the
    printed texts, ``stable`` the verdict and ``rule`` what was compared. A heatmap row (one per
    panel, ``stable`` empty: the bins are drawn, not printed) gives the share of bins shown in
    both seeds whose 95 % intervals overlap (with ``map_ci``) in ``bins agreeing (share)`` and
    the median relative difference of their medians in ``median relative difference``.

    Parameters
    ----------
    runs : mapping of str to (mapping, mapping)
        Platform key -> the two seeds' runs.
    seeds : (int, int)
        The two seeds (they name the columns ``seed <s>``).

    Returns
    -------
    pandas.DataFrame
        One row per compared number: ``platform``, ``quantity``, the two seed columns, ``stable``,
        ``rule`` and, on the heatmap rows, ``median relative difference`` (a fraction) and
        ``bins agreeing (share)``.
    """
    sa, sb = (f"seed {s}" for s in seeds)
    rules = {"text": "same quantity", "unit": "within half a unit of the last printed digit",
             "interval": "95 % intervals overlap", "span": "peak regions overlap"}
    rows = []
    for key, (a, b) in runs.items():
        ra = a["rho"].set_index(["target", "quantity"])["rho"]
        rb = b["rho"].set_index(["target", "quantity"])["rho"].reindex(ra.index)
        for (target, q), x in ra.items():
            y = float(rb[(target, q)])
            kind = "raw" if target == TARGETS[0] else "normalised"
            rows.append({"platform": key, "quantity": f"rho {q} ~ {kind}", sa: fmt_rho(x), sb: fmt_rho(y),
                         "stable": agree_at_print("unit", (x, 0.01), (y, 0.01)), "rule": rules["unit"]})
        for name in a["metrics"]:
            if (name.endswith(SKIPPED_SUFFIXES) or name == "n_heatmap_samples"
                    or (name.startswith(("raw_", "norm_")) and name.endswith("_rho"))
                    or (name.endswith("_rank") and name not in QUOTED_RANKS)):
                continue
            (ta, kind, wa), (tb, _, wb) = printed_metric(name, a["metrics"]), printed_metric(name, b["metrics"])
            if kind == "unit":
                wa, wb = (a["metrics"][name], wa), (b["metrics"][name], wb)
            rows.append({"platform": key, "quantity": name, sa: ta, sb: tb,
                         "stable": agree_at_print(kind, wa, wb), "rule": rules[kind]})
        rows += _heatmap_rows(key, a, b, sa, sb)
    return pd.DataFrame(rows)


def _heatmap_rows(key: str, a: Mapping, b: Mapping, sa: str, sb: str) -> list[dict]:
    rows = []
    for p, ma in a["maps"].items():
        mb = b["maps"][p]
        both = (~ma["masked"] & ~mb["masked"]).to_numpy()
        if not both.any():
            continue
        x, y = ma["median"].to_numpy()[both], mb["median"].to_numpy()[both]
        row = {"platform": key, "quantity": f"heatmap ({p}): bins shown in both seeds", sa: None, sb: None,
               "stable": None, "median relative difference": float(np.median(np.abs(x - y) / x)),
               "rule": "bins' 95 % intervals overlap"}
        if "map_ci" in a and "map_ci" in b:
            (la, ha), (lb, hb) = a["map_ci"][p], b["map_ci"][p]
            row["bins agreeing (share)"] = float(np.mean(np.maximum(la, lb)[both] <= np.minimum(ha, hb)[both]))
        rows.append(row)
    return rows


NO_CI_CELL = "none: too few samples (a replicate batch has no sample in a yaw bin the ratio uses)"
"""The modelling-choice table's cell for a yaw-0 interval that could not be computed."""


def _ci_cell(low: float, high: float) -> tuple[float, float] | str:
    """An interval's ends to 3 decimals for a table cell, or :data:`NO_CI_CELL` when one is not finite."""
    if not (np.isfinite(low) and np.isfinite(high)):
        return NO_CI_CELL
    return (round(low, 3), round(high, 3))


def check_row(run: str, metrics: Mapping[str, float | str]) -> dict:
    """One row of the modelling-choice table: the headline claim metrics of one run, with the
    hotspot's peak region (bins whose median is within the interval of the largest, as spans of
    bin centres and whether one has equal azimuths) and the interval of the yaw dip (its ends, or
    :data:`NO_CI_CELL` when a replicate batch leaves it undefined).

    Parameters
    ----------
    run : str
        Name of the run (its modelling choice).
    metrics : mapping of str to float or str
        Its claim metrics (:func:`~sss_locus.experiments.pose_space.claims.claim_metrics`).

    Returns
    -------
    dict
        Column -> value; rank correlations without unit, azimuths in whole degrees, the yaw ratio
        and the fragmented share as fractions.
    """
    m = metrics
    return {"run": run, "top raw": plain_label(m["top_raw"]),
            "top normalised": plain_label(m["top_norm"]),
            "rho misalignment (norm.)": m["norm_elevation_misalignment_deg_rho"],
            "rho theta1 (norm.)": m["norm_azimuth1_deg_rho"],
            "hotspot theta1, theta2 (deg)": (round(m["azimuth_peak_theta1_deg"]), round(m["azimuth_peak_theta2_deg"])),
            "hotspot region theta1 (deg)": (round(m["azimuth_region_theta1_lo_deg"]),
                                            round(m["azimuth_region_theta1_hi_deg"])),
            "hotspot region theta2 (deg)": (round(m["azimuth_region_theta2_lo_deg"]),
                                            round(m["azimuth_region_theta2_hi_deg"])),
            "hotspot region at equal azimuths": bool(m["azimuth_region_equal"]),
            "yaw 0 / peak": m["yaw_near0_over_peak_ratio"],
            "yaw 0 / peak CI": _ci_cell(m["yaw_near0_over_peak_ratio_ci_low"], m["yaw_near0_over_peak_ratio_ci_high"]),
            "fragmented (port-port)": m["multi_arc_fraction"]}


def reading_texts(prefix: str, effect: pd.DataFrame) -> dict[str, str]:
    """Glue texts of :func:`~sss_locus.experiments.pose_space.choices.reading_effect`:
    ``<prefix>-<reading>-<raw|norm>-mis-rho``, ``-mis-rank`` and ``-top`` for each reading.

    Parameters
    ----------
    prefix : str
        Start of every glue key.
    effect : pandas.DataFrame
        The reading effect table: ``reading``, ``target``, ``rho``, ``rank``, ``top``.

    Returns
    -------
    dict of str to str
        Glue key -> text.
    """
    out = {}
    for r in effect.itertuples():
        p = f"{prefix}-{r.reading}-{r.target}"
        out[f"{p}-mis-rho"] = fmt_rho(r.rho)
        out[f"{p}-mis-rank"] = f"{r.rank:d}"
        out[f"{p}-top"] = plain_label(r.top)
    return out


def hotspot_texts(prefix: str, check: Mapping[str, float]) -> dict[str, str]:
    """Glue texts of :func:`~sss_locus.experiments.pose_space.choices.hotspot_check`, keyed
    ``<prefix>-hotspot-...``: the peak bin, its count and median, the targeted re-measurement
    with its interval, the runner-up bin (with its interval where the check has one) and whether
    the peak survives (``yes``/``no``).

    Parameters
    ----------
    prefix : str
        Start of every glue key.
    check : mapping of str to float
        The hotspot check: bin centres ``x_mid``/``y_mid`` (deg), counts, medians and intervals
        (m), ``still_peak``.

    Returns
    -------
    dict of str to str
        Glue key -> text; azimuths in degrees, lengths in m.
    """
    p = f"{prefix}-hotspot"
    return {
        f"{p}-bin": f"({check['x_mid']:.0f}°, {check['y_mid']:.0f}°)",
        f"{p}-count": f"{check['count']:,.0f}",
        f"{p}-median": (fmt_interval({"median": check["median"], "ci_low": check["median_ci_low"],
                                      "ci_high": check["median_ci_high"]}, "m")
                        if "median_ci_low" in check else f"{fmt_sig(check['median'], 2)} m"),
        f"{p}-target-count": f"{check['target_count']:,.0f}",
        f"{p}-target-median": (f"{fmt_sig(check['target_median'], 2)} m (95 % CI "
                               f"{fmt_sig(check['target_ci_low'], 3)}–{fmt_sig(check['target_ci_high'], 3)} m)"),
        f"{p}-runner-up": ((fmt_interval({"median": check["runner_up_median"], "ci_low": check["runner_up_ci_low"],
                                          "ci_high": check["runner_up_ci_high"]}, "m")
                            if "runner_up_ci_low" in check else f"{fmt_sig(check['runner_up_median'], 2)} m")
                           + f" at ({check['runner_up_x_mid']:.0f}°, {check['runner_up_y_mid']:.0f}°), "
                             f"{check['runner_up_count']:,.0f} samples"),
        f"{p}-still-peak": "yes" if check["still_peak"] else "no",
    }


def fan_texts(prefix: str, level: Mapping[str, float], pitched: Sequence[Mapping[str, float]]) -> dict[str, str]:
    """Glue texts of :func:`~sss_locus.experiments.pose_space.choices.fan_share_removed` for a level sensor
    (``level``) and the same sensor at other pitches (``pitched``): ``<prefix>-fan-removed``,
    ``-fan-removed-pitched`` (the largest over ``pitched``, or the level share if empty) and
    ``-fan-theta-min`` (degrees).

    Parameters
    ----------
    prefix : str
        Start of every glue key.
    level : mapping of str to float
        The level sensor's ``share`` (0–1) and ``theta_min_deg`` (deg).
    pitched : sequence of mapping of str to float
        The same at other pitches (each with ``share``).

    Returns
    -------
    dict of str to str
        Glue key -> text; shares in percent, angle in degrees.
    """
    worst = max([level["share"]] + [p["share"] for p in pitched])
    return {f"{prefix}-fan-removed": f"{100 * level['share']:.0f} %",
            f"{prefix}-fan-removed-pitched": f"{100 * worst:.0f} %",
            f"{prefix}-fan-theta-min": f"{level['theta_min_deg']:.1f}"}
