"""Figures of the noise chapter (``notebooks/noise.ipynb``): the crossing-angle curves with
measurement noise, the band width by error group, and the Monte Carlo against first-order check.

The curves are those of :func:`sss_locus.experiments.survey_passes.planning.curve_summary` on
:func:`sss_locus.experiments.noise.study.survey_noise_table`, passed as ``curves[platform_key][label]``
(``label`` the noise model's label, e.g. ``"×1"``, ``"range only"``). Platforms are
:class:`~sss_locus.experiments.datamodel.platforms.Platform` objects: their names and colours come from the
data (:mod:`sss_locus.report.common.style`).

Drawn with matplotlib in the book's seaborn theme (:func:`~sss_locus.report.common.style.theme`), not
with seaborn's functions: the curves' medians and interquartile bands are the quantiles
:func:`~sss_locus.experiments.survey_passes.planning.curve_summary` computed (and the figures' CSV data);
``seaborn.lineplot(errorbar=("pi", 50))`` would compute them a second time from the raw
samples. The check's scatter shares one legend below four panels, which one ``ax.scatter`` per
platform gives directly (a seaborn legend per panel would have to be taken apart).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.ticker import NullFormatter

from sss_locus.experiments.datamodel.datadoc import label_key
from sss_locus.report.common.style import PAGE_WIDTH_IN, SMALL_FONT_PT, get_axis, platform_colors, platform_title, themed
from sss_locus.report.survey_passes.figures import model_tag
from sss_locus.report.common.text import fmt_sig

LEVEL_COLORS = ("tab:red", "tab:orange", "gold", "tab:pink")
"""Colours of the noise levels (``noise_scales`` in order, repeating)."""

GROUP_STYLE = {"range only": {"color": "tab:green", "ls": ":"},
               "attitude only": {"color": "tab:purple", "ls": ":"},
               "position only": {"color": "tab:brown", "ls": ":"}}
"""Line style of the curves with one error group alone."""

BREAKDOWN_COLORS = {"position only": "tab:brown", "range only": "tab:green"}
"""Colours of the error groups in :func:`plot_breakdown` (all errors: red)."""


def level_label(scale: float) -> str:
    """Label of a noise level, as in the notebook's noise models: ``level_label(0.1) == "×0.1"``.

    Parameters
    ----------
    scale : float
        Factor on every standard deviation of the noise model.

    Returns
    -------
    str
        The label.
    """
    return f"×{scale:g}"


def scale_text(bases: Mapping, scale: float) -> str:
    """What a noise level scales, with the standard deviations it gives: ``bases`` maps platform
    keys to their :class:`~sss_locus.experiments.datamodel.noise_model.NoiseModel` (the file's values).

    Parameters
    ----------
    bases : mapping of str to NoiseModel
        Platform key -> its noise model as in the file.
    scale : float
        The level's factor.

    Returns
    -------
    str
        One clause: range sigma in mm and percent of the range, position sigmas in m, attitude
        sigmas in degrees.
    """
    parts = []
    for key, base in bases.items():
        m = base.scaled(scale)
        cell_mm = 1000 * m.range_sigma_per_resolution * m.range_resolution_m
        parts.append(f"{key}: range {fmt_sig(cell_mm, 3)} mm and {fmt_sig(100 * m.sound_speed_relative_sigma, 2)} % "
                     f"of the range, position {fmt_sig(m.horizontal_sigma_m, 2)} m per horizontal axis and "
                     f"{fmt_sig(m.vertical_sigma_m, 2)} m vertical, roll {fmt_sig(m.roll_sigma_deg, 2)}°, "
                     f"pitch {fmt_sig(m.pitch_sigma_deg, 2)}°, heading {fmt_sig(m.heading_sigma_deg, 2)}°")
    return (f"{level_label(scale)}: every standard deviation of the platform's noise model times {scale:g}, range, position "
            f"and attitude alike ({'; '.join(parts)})")


def advice_texts(prefix: str, verdicts: Mapping[tuple[str, str, float], Mapping[str, float]],
                 head_scale: float) -> dict[str, str]:
    """Glue texts of :func:`~sss_locus.experiments.survey_passes.verdicts.advice_verdict` on the median extent,
    ``verdicts`` keyed ``(platform key, offset-model spec, noise scale)``: per key,
    ``<prefix>-<platform>-<model>-<level>-verdict`` ("holds"/"fails") and ``-ends-extent``,
    ``-oblique-extent``, ``-perpendicular-extent`` (m); the ``independent`` model without its
    tag (``nz-auv-x0p1-verdict``), the headline level also without the level
    (``nz-auv-matched-10-same-verdict``).

    Parameters
    ----------
    prefix : str
        Start of every glue key (e.g. ``nz``).
    verdicts : mapping of (str, str, float) to mapping of str to float
        The verdicts, each with ``holds`` and the median extents ``ends``, ``oblique``,
        ``perpendicular`` (m).
    head_scale : float
        The headline noise level.

    Returns
    -------
    dict of str to str
        Glue key -> text; extents in m (2 significant figures).
    """
    out = {}
    for (key, spec, scale), v in verdicts.items():
        model = "" if spec == "independent" else f"-{model_tag(spec)}"
        tags = [f"{model}-{file_label(level_label(scale))}"] + ([model] if model and scale == head_scale else [])
        for tag in tags:
            base = f"{prefix}-{label_key(key)}{tag}"
            out[f"{base}-verdict"] = "holds" if v["holds"] else "fails"
            for name in ("ends", "oblique", "perpendicular"):
                out[f"{base}-{name}-extent"] = fmt_sig(v[name], 2)
    return out


def file_label(label: str) -> str:
    """A noise model's label as part of a file name: ``"×0.1"`` -> ``"x0p1"``,
    ``"range only"`` -> ``"range-only"``.

    Parameters
    ----------
    label : str
        The noise model's label.

    Returns
    -------
    str
        The label with ``×`` as ``x``, spaces as ``-`` and ``.`` as ``p``.
    """
    return label.replace("×", "x").replace(" ", "-").replace(".", "p")


def curve_frames(curves: Mapping[str, Mapping[str, pd.DataFrame]],
                 labels: Iterable[str] | None = None) -> dict[str, pd.DataFrame]:
    """The plotted curves as one table per platform and noise model, named
    ``"<platform key>-<file_label(label)>"`` (the figure data of :func:`sss_locus.pipeline.publish.publish`).

    ``labels`` restricts (and orders) the noise models; default: all of each platform.

    Parameters
    ----------
    curves : mapping of str to mapping of str to pandas.DataFrame
        ``curves[platform key][label]``: crossing-angle curves (medians and quartiles, m).
    labels : iterable of str, optional
        Noise-model labels to keep, in order.

    Returns
    -------
    dict of str to pandas.DataFrame
        Name -> the curve table, unchanged.
    """
    return {f"{key}-{file_label(lab)}": by_label[lab]
            for key, by_label in curves.items()
            for lab in (by_label if labels is None else labels)}


def _title(platform, what: str, width: int = 34) -> str:
    return f"{platform_title(platform, width)}:\n{what}"


def _angle_axis(ax, ncol: int = 1, legend: bool = True) -> None:
    """Crossing-angle axis, grid, and (``legend``) the legend below the panel (never over the
    bands; the panels of one column share it, drawn under the bottom one)."""
    ax.set_xlim(0, 180)
    ax.set_xticks(np.arange(0, 181, 30))
    ax.set_xlabel(r"crossing angle $\gamma$ (deg)")
    ax.grid(alpha=0.3, which="both")
    if legend:
        ax.legend(fontsize=SMALL_FONT_PT, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=ncol,
                  frameon=False)


@themed
def plot_noise_extent(by_label: Mapping[str, pd.DataFrame], noise_scales: Sequence[float], *,
                      title: str = "", legend: bool = True, ax=None):
    """Noise-free locus length (black, median and interquartile range) and the median extent at
    every level of ``noise_scales`` and with range errors only, against crossing angle (log scale).

    Parameters
    ----------
    by_label : mapping of str to pandas.DataFrame
        One platform's crossing-angle curves keyed by :func:`level_label` of every scale and
        ``"range only"``.
    noise_scales : sequence of float
        Noise levels, the first the reference (its noise-free length is drawn).
    title : str
        Panel title.
    legend : bool
        Whether to put the legend below the panel.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: the current axes).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    ax = get_axis(ax)
    c0 = by_label[level_label(noise_scales[0])]
    g = c0["crossing_angle_deg"]
    ax.fill_between(g, c0["locus_length_m_q25"], c0["locus_length_m_q75"], color="k", alpha=0.12, lw=0)
    ax.plot(g, c0["locus_length_m_median"], color="k", lw=2, label="locus length, no noise")
    for i, s in enumerate(noise_scales):
        ax.plot(g, by_label[level_label(s)]["extent_m_median"], color=LEVEL_COLORS[i % len(LEVEL_COLORS)],
                lw=1.8, label=f"extent, every σ ×{s:g}")
    ax.plot(g, by_label["range only"]["extent_m_median"], lw=1.5, label="extent, range errors only",
            **GROUP_STYLE["range only"])
    ax.set_yscale("log")
    ax.set_ylabel("median over pass pairs (m)")
    ax.set_title(title, fontsize=10)
    _angle_axis(ax, legend=legend)
    return ax


@themed
def plot_empty_share(by_label: Mapping[str, pd.DataFrame], noise_scales: Sequence[float], *,
                     title: str = "", legend: bool = True, ax=None):
    """Median share of noisy draws with an empty locus at every level of ``noise_scales`` and
    with attitude errors only, against crossing angle.

    Parameters
    ----------
    by_label : mapping of str to pandas.DataFrame
        One platform's crossing-angle curves keyed by :func:`level_label` of every scale and
        ``"attitude only"``.
    noise_scales : sequence of float
        Noise levels.
    title : str
        Panel title.
    legend : bool
        Whether to put the legend below the panel.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: the current axes).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    ax = get_axis(ax)
    g = by_label[level_label(noise_scales[0])]["crossing_angle_deg"]
    for i, s in enumerate(noise_scales):
        ax.plot(g, by_label[level_label(s)]["empty_fraction_median"], color=LEVEL_COLORS[i % len(LEVEL_COLORS)],
                lw=1.8, label=f"every σ ×{s:g}")
    ax.plot(g, by_label["attitude only"]["empty_fraction_median"], lw=1.5,
            label="attitude errors only", **GROUP_STYLE["attitude only"])
    ax.set_ylim(0, 1)
    ax.set_ylabel("share of draws with an empty locus\n(median over pass pairs)")
    ax.set_title(title, fontsize=10)
    _angle_axis(ax, legend=legend)
    return ax


@themed
def plot_noise_curves(platforms: Sequence, curves: Mapping[str, Mapping[str, pd.DataFrame]],
                      noise_scales: Sequence[float]):
    """Crossing-angle curves with noise, one row per platform; returns the figure.

    Left: noise-free locus length (black, median and interquartile range) and the median extent
    at every level of ``noise_scales`` and with range errors only (log scale;
    :func:`plot_noise_extent`). Right: median share of noisy draws with an empty locus at every
    level and with attitude errors only (:func:`plot_empty_share`).
    ``curves[platform.key]`` must hold the labels :func:`level_label` of every scale,
    ``"range only"`` and ``"attitude only"``.

    Parameters
    ----------
    platforms : sequence of Platform
        The platforms, one row each (their ``key`` and ``name``).
    curves : mapping of str to mapping of str to pandas.DataFrame
        ``curves[platform key][label]``: crossing-angle curves with ``locus_length_m_*``,
        ``extent_m_median`` (m) and ``empty_fraction_median`` (0–1).
    noise_scales : sequence of float
        The noise levels, the first the reference.

    Returns
    -------
    matplotlib.figure.Figure
        A new figure of ``len(platforms)`` x 2 panels.
    """
    fig, axs = plt.subplots(len(platforms), 2, figsize=(PAGE_WIDTH_IN, 3.9 * len(platforms) + 1.2),
                            constrained_layout=True, squeeze=False)
    for row, ((ax, ax2), pf) in enumerate(zip(axs, platforms)):
        last = row == len(platforms) - 1
        plot_noise_extent(curves[pf.key], noise_scales, title=_title(pf, "size of the uncertainty"),
                          legend=last, ax=ax)
        plot_empty_share(curves[pf.key], noise_scales, title=_title(pf, "crop fails"), legend=last, ax=ax2)
    return fig


@themed
def plot_band_widths(by_label: Mapping[str, pd.DataFrame], head: str, *, title: str = "",
                     y_label: bool = True, ax=None):
    """Band width against crossing angle by error group (all errors at level ``head``; sensor
    position only; range only; median and interquartile range, log scale) with the noise-free
    locus length.

    Parameters
    ----------
    by_label : mapping of str to pandas.DataFrame
        One platform's crossing-angle curves keyed by ``head`` and the keys of
        :data:`BREAKDOWN_COLORS`.
    head : str
        Label of the all-errors curves.
    title : str
        Panel title.
    y_label : bool
        Whether to label the ``y`` axis.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: the current axes).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    ax = get_axis(ax)
    for lab, col in ((head, "tab:red"), *BREAKDOWN_COLORS.items()):
        c = by_label[lab]
        ax.fill_between(c["crossing_angle_deg"], c["band_width_m_q25"], c["band_width_m_q75"], color=col,
                        alpha=0.15, lw=0)
        ax.plot(c["crossing_angle_deg"], c["band_width_m_median"], color=col, lw=1.8,
                label="all errors" if lab == head else lab)
    c = by_label[head]
    ax.plot(c["crossing_angle_deg"], c["locus_length_m_median"], color="k", lw=1.5,
            label="locus length, no noise")
    ax.set_yscale("log")
    if y_label:
        ax.set_ylabel("band width (m): median, IQR shaded")
    ax.set_title(title, fontsize=10)
    _angle_axis(ax, legend=False)
    return ax


@themed
def plot_breakdown(platforms: Sequence, curves: Mapping[str, Mapping[str, pd.DataFrame]],
                   head: str):
    """Band width against crossing angle by error group, one panel per platform
    (:func:`plot_band_widths`), one legend below; returns the figure.

    Parameters
    ----------
    platforms : sequence of Platform
        The platforms, one panel each (two a row).
    curves : mapping of str to mapping of str to pandas.DataFrame
        ``curves[platform key][label]`` with ``head`` and the keys of :data:`BREAKDOWN_COLORS`
        (``band_width_m_*`` and ``locus_length_m_median`` columns, m).
    head : str
        Label of the all-errors curves.

    Returns
    -------
    matplotlib.figure.Figure
        A new figure, legend below.
    """
    ncols = min(len(platforms), 2)  # side by side: one row per two platforms, one legend
    nrows = -(-len(platforms) // ncols)
    fig, axs = plt.subplots(nrows, ncols, figsize=(PAGE_WIDTH_IN, 3.6 * nrows + 1.0),
                            constrained_layout=True, squeeze=False, sharey=True)
    fig.get_layout_engine().set(wspace=0.08)  # the 180 and 0 tick labels of neighbours apart
    for ax in axs.flat[len(platforms):]:
        ax.set_visible(False)
    for ax, pf in zip(axs.flat, platforms):
        plot_band_widths(curves[pf.key], head, title=platform_title(pf, 34), y_label=ax in axs[:, 0], ax=ax)
    handles, labels = axs.flat[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=4, fontsize=SMALL_FONT_PT, frameon=False)
    return fig


@themed
def plot_check_panel(check: pd.DataFrame, platforms: Sequence, kind: str, scale: float, *,
                     colors: Mapping[str, str] | None = None, ax=None):
    """Monte Carlo against first-order 95 % distances of one kind at one noise scale, one colour
    per platform, with the line of equality (log-log).

    Parameters
    ----------
    check : pandas.DataFrame
        As :func:`plot_check`.
    platforms : sequence of Platform
        Platforms drawn, in legend order.
    kind : {"two", "three"}
        Distance to the circle (two views) or three-view point error.
    scale : float
        Noise scale.
    colors : mapping of str to str, optional
        Colour per platform key (default :func:`~sss_locus.report.common.style.platform_colors`).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: the current axes).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    ax = get_axis(ax)
    colors = platform_colors(platforms) if colors is None else colors
    what = "distance to the circle" if kind == "two" else "three-view point error"
    d = check[(check.kind == kind) & (check.scale == scale)]
    for pf in platforms:
        dk = d[d.platform == pf.key]
        ax.scatter(dk.monte_carlo_m, dk.first_order_m, s=12, color=colors[pf.key],
                   label=platform_title(pf, 60))
    both = d[["monte_carlo_m", "first_order_m"]]
    lo, hi = both.min().min(), both.max().max()
    ax.plot([lo, hi], [lo, hi], color="k", lw=0.8, label="equal")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.xaxis.set_minor_formatter(NullFormatter())  # crowded minor labels on a short decade
    ax.set_xlabel(f"Monte Carlo 95 % {what} (m)")
    ax.set_ylabel("first-order estimate (m)")
    ax.set_title(f"{'two views' if kind == 'two' else 'three views'}, noise ×{scale:g}", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    return ax


@themed
def plot_check(check: pd.DataFrame, platforms: Sequence, scales: Sequence[float]):
    """Monte Carlo against first-order 95 % distances, a 2 x len(scales) grid; returns the figure.

    ``check`` has one row per pass pair (or configuration), noise scale and kind: columns
    ``platform`` (key), ``kind`` (``"two"``: distance to the circle, top row; ``"three"``:
    three-view point error, bottom row), ``scale``, ``monte_carlo_m`` and ``first_order_m``.

    Parameters
    ----------
    check : pandas.DataFrame
        The rows described above (distances in m).
    platforms : sequence of Platform
        The platforms, in legend order.
    scales : sequence of float
        Noise scales, one column each.

    Returns
    -------
    matplotlib.figure.Figure
        A new figure of 2 x ``len(scales)`` log-log panels, legend below.
    """
    colors = platform_colors(platforms)
    fig, axs = plt.subplots(2, len(scales), figsize=(PAGE_WIDTH_IN, 7.4), constrained_layout=True,
                            squeeze=False)
    for row, kind in zip(axs, ("two", "three")):
        for ax, scale in zip(row, scales):
            plot_check_panel(check, platforms, kind, scale, colors=colors, ax=ax)
    # one legend for the four panels, below them (a legend in a panel covers points)
    handles, labels = axs[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=1, fontsize=SMALL_FONT_PT, frameon=False)
    return fig
