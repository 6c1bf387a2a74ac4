"""Figure and glued texts of the water chapter (``notebooks/water.ipynb``).

Input: the long table of :func:`sss_locus.experiments.water.study.crop_effects`.

The figure is drawn in the book's seaborn theme (:func:`~sss_locus.report.common.style.theme`) with
matplotlib's ``barh``, not ``seaborn.barplot``: its bars and 95 % intervals are the estimates and
replicate-batch intervals :func:`~sss_locus.experiments.water.study.crop_effect` computed (the figure's
CSV data), which ``seaborn.barplot`` would compute a second time, with its own bootstrap.
"""

from __future__ import annotations

import textwrap

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from sss_locus.report.common.style import get_axis, themed

PAPER_COLOR, WATER_COLOR = "tab:gray", "tab:blue"


def _pct(row) -> str:
    return f"{100 * row.estimate:.1f} % (95 % CI {100 * row.ci_low:.1f} to {100 * row.ci_high:.1f} %)"


def effect_texts(effects: pd.DataFrame) -> dict[str, str]:
    """Glue texts ``<condition>-<subset>-<statistic>`` (e.g. ``boat-pose-tilt15-all-length_ratio``):
    percentages with their 95 % replicate interval, plus ``<condition>-<subset>-n`` (sample count).

    Parameters
    ----------
    effects : pandas.DataFrame
        The long table of :func:`~sss_locus.experiments.water.study.crop_effects`: ``condition``,
        ``subset``, ``statistic``, ``estimate``, ``ci_low``, ``ci_high`` (fractions 0–1) and ``n``.

    Returns
    -------
    dict of str to str
        Glue key -> text (percent with one decimal; counts with thousands separators).
    """
    out = {}
    for row in effects.itertuples():
        base = f"{row.condition}-{row.subset}"
        out[f"{base}-{row.statistic}"] = _pct(row)
        out[f"{base}-{row.statistic}-pct"] = f"{100 * row.estimate:.1f} %"
        out[f"{base}-n"] = f"{row.n:,}"
    return out


TABLE_COLUMNS = {"length_ratio": "length kept", "shortened_share": "loci shortened",
                 "multi_arc_share_uncropped": "fragmented, paper",
                 "multi_arc_share_cropped": "fragmented, cropped"}
"""Statistics of :func:`effect_table` and their column headings (all in %)."""


def effect_table(effects: pd.DataFrame) -> pd.DataFrame:
    """One row per condition and subset: sample count and the statistics of
    :data:`TABLE_COLUMNS` in percent, ``"estimate (low–high)"`` with the 95 % interval (compact,
    for the book's column; every statistic is in the figure's data).

    Parameters
    ----------
    effects : pandas.DataFrame
        The long table of :func:`~sss_locus.experiments.water.study.crop_effects` (``label``,
        ``subset``, ``n``, ``statistic``, ``estimate``, ``ci_low``, ``ci_high``; fractions).

    Returns
    -------
    pandas.DataFrame
        Columns ``condition``, ``samples`` (the subset), ``n`` and one text column per statistic,
        headed ``"<heading> (%)"``.
    """
    sel = effects[effects["statistic"].isin(list(TABLE_COLUMNS))]
    text = [f"{100 * r.estimate:.1f} ({100 * r.ci_low:.1f}–{100 * r.ci_high:.1f})" for r in sel.itertuples()]
    wide = sel.assign(text=text).pivot_table(index=["label", "subset", "n"], columns="statistic",
                                             values="text", aggfunc="first", sort=False)
    wide = wide[list(TABLE_COLUMNS)].rename(columns={k: f"{v} (%)" for k, v in TABLE_COLUMNS.items()})
    out = wide.reset_index().rename(columns={"label": "condition", "subset": "samples"})
    out.columns.name = None
    return out


CROP_TEXT = {"surface": ("cropped to the water", "(b) length below the surface"),
             "surface + seafloor": ("cropped to surface and seafloor", "(b) length in the water column")}
"""Legend entry and panel (b) title of :func:`plot_crop_effects` for each ``crop``."""


def _crop_rows(effects: pd.DataFrame, crop: str) -> pd.DataFrame:
    if crop not in CROP_TEXT:
        raise ValueError(f"crop must be one of {list(CROP_TEXT)}; got {crop!r}")
    sel = effects[(effects["subset"] == "all") & (effects["crop"] == crop)]
    if sel.empty:
        raise ValueError(f"effects has no condition with crop {crop!r}")
    return sel


@themed
def plot_crop_bars(effects: pd.DataFrame, statistics, *, crop: str = "surface", xmax: float = 100.0,
                   xlabel: str = "", title: str = "", ax=None):
    """One panel of the water figure: per condition (one row each, the first at the top), a bar
    of each of ``statistics`` in per cent with its 95 % replicate-batch interval and its value
    written beside it (inside the bar's left end where it would run past ``xmax``).

    Parameters
    ----------
    effects : pandas.DataFrame
        The long table of :func:`~sss_locus.experiments.water.study.crop_effects`.
    statistics : sequence of (str, str or None, str)
        ``(statistic, legend label, colour)`` of each bar of a row, top to bottom (at most two).
    crop : str
        The conditions drawn: those whose ``crop`` is this (a key of :data:`CROP_TEXT`), all
        samples.
    xmax : float
        End of the axis, per cent.
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
    sel = _crop_rows(effects, crop)
    allrows = sel.set_index(["label", "statistic"])
    labels = list(dict.fromkeys(sel["label"]))
    y = np.arange(len(labels))[::-1]
    ax.set_xlim(0, xmax)
    offsets = (0.0,) if len(statistics) == 1 else (0.2, -0.2)
    for (stat, label, color), offset in zip(statistics, offsets):
        est = np.array([allrows.loc[(lab, stat), "estimate"] for lab in labels]) * 100
        lo = np.array([allrows.loc[(lab, stat), "ci_low"] for lab in labels]) * 100
        hi = np.array([allrows.loc[(lab, stat), "ci_high"] for lab in labels]) * 100
        bar = ax.barh(y + offset, est, height=0.38, color=color, label=label,
                      xerr=[est - lo, hi - est], error_kw={"lw": 1, "capsize": 2})
        # a share is at most 100 %: the axis stops there, and labels of bars that would run past
        # it sit inside the bar's left end
        inside = est > 0.7 * xmax
        ax.bar_label(bar, labels=[f"{v:.1f}" if i else "" for v, i in zip(est, inside)], fontsize=9,
                     label_type="center", color="white")
        ax.bar_label(bar, labels=["" if i else f"{v:.1f}" for v, i in zip(est, inside)], fontsize=9, padding=4)
    ax.set_xlabel(xlabel, fontsize=10)
    ax.set_title(title, fontsize=10, loc="left")
    ax.set_yticks(y, [textwrap.fill(lab, 28) for lab in labels], fontsize=9)
    ax.tick_params(labelsize=9)
    ax.grid(axis="y", visible=False)  # no line through the bars
    return ax


@themed
def plot_crop_effects(effects: pd.DataFrame, crop: str = "surface"):
    """(a) Share of fragmented loci without and with the crop; (b) share of the total locus
    length the crop keeps; one row per condition whose ``crop`` column is ``crop`` (all
    samples), 95 % replicate-batch intervals (:func:`plot_crop_bars`). Returns the figure.

    Parameters
    ----------
    effects : pandas.DataFrame
        The long table of :func:`~sss_locus.experiments.water.study.crop_effects`.
    crop : str
        A key of :data:`CROP_TEXT`.

    Returns
    -------
    matplotlib.figure.Figure
        A new figure of two panels sharing the conditions, legend below.

    Raises
    ------
    ValueError
        When ``crop`` is unknown or no condition has it.
    """
    sel = _crop_rows(effects, crop)
    labels = list(dict.fromkeys(sel["label"]))
    fig, axs = plt.subplots(1, 2, figsize=(7.2, 0.55 * len(labels) + 1.9), sharey=True,
                            gridspec_kw={"width_ratios": [1.2, 1]}, layout="constrained")
    cropped, title_b = CROP_TEXT[crop]
    top = 100 * sel.loc[sel["statistic"].str.startswith("multi_arc_share"), "ci_high"].max()
    plot_crop_bars(effects, [("multi_arc_share_uncropped", "paper's locus (apertures only)", PAPER_COLOR),
                             ("multi_arc_share_cropped", cropped, WATER_COLOR)], crop=crop,
                   xmax=min(100.0, 1.3 * max(top, 1.0)), xlabel="fragmented loci (% of samples)",
                   title="(a) loci with more than one arc", ax=axs[0])
    plot_crop_bars(effects, [("length_ratio", None, WATER_COLOR)], crop=crop, xlabel="total locus length kept (%)",
                   title=title_b, ax=axs[1])
    handles, names = axs[0].get_legend_handles_labels()  # below the panels: never over a bar
    fig.legend(handles, names, loc="outside lower center", ncol=2, fontsize=9, frameon=False)
    return fig


def crop_caption(*, n_samples: int, n_per_angle: int, crossing_step_deg: float, seed: int, n_batches: int) -> str:
    """Caption of the figure of the crop to the water (``fig-water-crop``).

    Parameters
    ----------
    n_samples : int
        Pose-space samples per run.
    n_per_angle : int
        Survey pass pairs per crossing angle.
    crossing_step_deg : float
        Crossing-angle step of the survey passes (deg).
    seed : int
        The samplers' seed.
    n_batches : int
        Replicate batches of the intervals.

    Returns
    -------
    str
        The caption (MyST).
    """
    return (f"Cropping the locus to the water, per platform and study (pose space: {n_samples:,} samples per "
            f"run; survey passes: {n_per_angle:,} pass pairs per crossing angle, every {crossing_step_deg:g}°; "
            f"seed {seed}); every row counts all samples or pass pairs of its run "
            "(pose space: sensor 2 on either side, not the heatmaps' port–port subset): (a) share of loci with "
            "more than one arc, for the paper's locus (apertures only, "
            "grey) and cropped to the water (blue); (b) share of the total locus length that lies below "
            f"the sea surface. Bars: 95 % intervals from {n_batches} replicate batches of the pairs.")


def effects_caption(*, seed: int, n_batches: int) -> str:
    """Caption of the table of crop effects (``tab-water-effects``), without its files sentence.

    Parameters
    ----------
    seed, n_batches : int
        As for :func:`crop_caption`.

    Returns
    -------
    str
        The caption.
    """
    return (f"Each condition (platform, its depth or tilt, study; a seafloor margin where the crop also bounds the "
            f"water column) and subset of its samples: the count, and in percent with a 95 % interval over "
            f"{n_batches} replicate batches the share of locus length the crop keeps, the share of loci it "
            f"shortens, and the shares fragmented without and with it (seed {seed}).")


def seafloor_caption(*, seafloor_margins_m: list[float], seed: int, n_batches: int) -> str:
    """Caption of the figure of the crop to the water column (``fig-water-seafloor``).

    Parameters
    ----------
    seafloor_margins_m : list of float
        Depths of the seafloor below each feature (m).
    seed, n_batches : int
        As for :func:`crop_caption`.

    Returns
    -------
    str
        The caption (MyST).
    """
    return (f"Cropping the locus to the water column between the sea surface and a seafloor "
            f"{' or '.join(f'{m:g} m' for m in seafloor_margins_m)} below each feature (`seafloor_margins_m`), per "
            f"platform and study (samples as in the figure above, all of them, seed {seed}): (a) share of loci "
            "with more than "
            "one arc, for the paper's locus (grey) and cropped (blue); (b) share of the total locus length that "
            f"lies in the water column. Bars: 95 % intervals from {n_batches} replicate batches of the pairs.")
