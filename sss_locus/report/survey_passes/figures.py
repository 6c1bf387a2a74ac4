"""Figures, tables and prose numbers of the survey-pass chapter (``notebooks/survey_passes.ipynb``).

The curves come from :func:`sss_locus.experiments.survey_passes.planning.crossing_angle_curve`; this module only
draws them (:func:`plot_fig5`, the paper's Fig. 5; :func:`plot_offset_models`, the offset-model
comparison; :func:`plot_pitch_depth`, the AUV's pitch and altitude ratios), lays them out as
tables (:func:`peak_table`, :func:`offset_model_table`) and writes them as prose for glue
(:func:`curve_texts`, :func:`offset_model_texts`, :func:`pitch_depth_texts`,
:func:`describe_setup`, :func:`describe_offset_model`). Platform names and colours come from the
data (:mod:`sss_locus.report.common.style`).
"""

from __future__ import annotations

import textwrap

from collections.abc import Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from sss_locus.experiments.datamodel.envelopes import OffsetModel, SurveyEnvelope
from sss_locus.experiments.datamodel.userdata import label_key
from sss_locus.experiments.survey_passes.planning import VALUES, CrossingAngleCurve, curve_shape_rho, rejected_share
from sss_locus.experiments.survey_passes.verdicts import over_peak
from sss_locus.report.common.style import AXIS_LABELS, PAGE_WIDTH_IN, SMALL_FONT_PT, get_axis, platform_colors, platform_title, themed
from sss_locus.report.common.text import fmt_change, fmt_ci, fmt_interval, fmt_sig

UNITS = {"locus_length_m": "m", "elevation_misalignment_deg": "°"}
"""Prose unit of each curve quantity."""

TAGS = {"locus_length_m": "len", "elevation_misalignment_deg": "mis"}
"""Short name of each curve quantity in glue keys (``sp-boat-len-90``)."""

GAMMAS = (0, 90, 180)
"""Crossing angles (deg) whose medians are stated in the prose and tables."""


def model_tag(spec: str) -> str:
    """An offset-model spec as a glue-key and file-name part: ``"matched:2.5:same"`` ->
    ``"matched-2p5-same"``.

    Parameters
    ----------
    spec : str
        Offset-model spec as given on the command line or in a profile (``kind:jitter_m:side``).

    Returns
    -------
    str
        ``spec`` with ``:`` as ``-`` and ``.`` as ``p``.
    """
    return spec.replace(":", "-").replace(".", "p")


def _pitch_range(lo: float, hi: float) -> str:
    if lo == hi:
        return f"{hi:g}°"
    return f"within ±{hi:g}°" if lo == -hi else f"{lo:g}° to {hi:g}°"


def describe_setup(platform, envelope: SurveyEnvelope) -> str:
    """One platform's passes in words, from its data: ``"<name>: <altitude and pitch>"``.

    Parameters
    ----------
    platform : Platform
        The platform (its ``name`` is used).
    envelope : SurveyEnvelope
        Its survey envelope: altitude above the feature (m) and pitch (deg) ranges of the passes.

    Returns
    -------
    str
        One sentence fragment, altitudes in m and pitches in degrees.
    """
    lo, hi = envelope.altitude_min_m, envelope.altitude_max_m
    alt = f"{lo:g} m" if lo == hi else f"{lo:g}–{hi:g} m"
    level = envelope.pitch_min_deg == envelope.pitch_max_deg == 0
    pitch = "level" if level else f"pitch {_pitch_range(envelope.pitch_min_deg, envelope.pitch_max_deg)}"
    if envelope.level_pass1 and not level:
        pitch = f"pass 1 level, pass 2 at {pitch}"
    if envelope.same_altitude:
        return f"{platform.name}: {pitch}, both passes at one altitude above the feature, {alt} (the water depth)"
    return f"{platform.name}: altitude above the feature {alt} and {pitch}, drawn per pass"


SIDE_RULE_TEXT = {"random": "on a random side of the vehicle", "same": "on the same side as pass 1",
                  "opposite": "on the opposite side to pass 1"}
"""Pass 2's side of the vehicle under each ``OffsetModel.side_rule``, in words."""


def describe_offset_model(model: OffsetModel) -> str:
    """Where the passes see the feature across their swaths, in words.

    Parameters
    ----------
    model : OffsetModel
        The offset model (``kind``, ``jitter_m`` in m, ``side_rule``, ``side1``).

    Returns
    -------
    str
        A sentence fragment without a capital or full stop.
    """
    if model.kind == "independent":
        text = "each pass sees the feature anywhere in its swath"
        text += "" if model.side_rule == "random" else f", pass 2 {SIDE_RULE_TEXT[model.side_rule]}"
    else:
        text = (f"pass 2 sees the feature at pass 1's ground offset ±{model.jitter_m:g} m, "
                f"{SIDE_RULE_TEXT[model.side_rule]}")
    return text if model.side1 == "random" else f"{text}; pass 1 sees it on its {model.side1} side"


@themed
def plot_crossing_curves(curves: Mapping[str, CrossingAngleCurve], value: str = VALUES[0], *,
                         title: str = "", colors: Mapping[str, str] | None = None, ax=None):
    """One panel of the paper's Fig. 5: ``value`` against crossing angle, median line and
    interquartile band per platform.

    Parameters
    ----------
    curves : mapping of str to CrossingAngleCurve
        The curves, keyed by platform key.
    value : str
        One of :data:`VALUES`.
    title : str
        Panel title.
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
    colors = platform_colors([cur.platform for cur in curves.values()]) if colors is None else colors
    for k, cur in curves.items():
        c = cur.curve
        ax.fill_between(c["crossing_angle_deg"], c[f"{value}_q25"], c[f"{value}_q75"], color=colors[k],
                        alpha=0.2, lw=0)
        ax.plot(c["crossing_angle_deg"], c[f"{value}_median"], color=colors[k], lw=1.8,
                label=f"{cur.platform.name}: median, IQR shaded")
    ax.set_ylabel(AXIS_LABELS[value])
    ax.set_title(title)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    return ax


@themed
def plot_fig5(curves: Mapping[str, CrossingAngleCurve]):
    """The paper's Fig. 5: (a) locus length and (b) elevation misalignment against crossing
    angle, median line and interquartile band per platform (:func:`plot_crossing_curves`).
    Returns the figure.

    Parameters
    ----------
    curves : mapping of str to CrossingAngleCurve
        The curves keyed by platform key, each with its median and quartile columns of
        ``locus_length_m`` (m) and ``elevation_misalignment_deg`` (deg) per ``crossing_angle_deg``.

    Returns
    -------
    matplotlib.figure.Figure
        A new figure of two panels sharing the crossing-angle axis (deg), legend below.
    """
    colors = platform_colors([cur.platform for cur in curves.values()])
    fig, axs = plt.subplots(2, 1, figsize=(PAGE_WIDTH_IN, 6.8), sharex=True, constrained_layout=True)
    for ax, v, tag in zip(axs, VALUES, "ab"):
        plot_crossing_curves(curves, v, title=f"({tag}) {AXIS_LABELS[v].split(' (')[0]} against crossing angle",
                             colors=colors, ax=ax)
    handles, labels = axs[0].get_legend_handles_labels()  # below the panels: never over a band
    fig.legend(handles, labels, loc="outside lower center", ncol=1, fontsize=SMALL_FONT_PT, frameon=False)
    axs[1].set_xlabel(r"crossing angle $\gamma$ between the passes (deg)")
    axs[1].set_xticks(np.arange(0, 181, 20))
    axs[1].set_xlim(0, 180)
    return fig


def curve_texts(prefix: str, cur: CrossingAngleCurve, over: bool = True) -> dict[str, str]:
    """Glue texts of one main curve, keyed ``<prefix>-<len|mis>-...``: peak angle and its
    interval, medians at 0/90/180°, the peak median and (``over``: needs the curve's samples)
    the medians there over the peak; plus ``<prefix>-rejected`` (share of drawn pairs rejected),
    ``-rejected-max`` (largest share at one angle) and ``-shape-rho`` (rank correlation of the two
    median curves over the grid).

    Parameters
    ----------
    prefix : str
        Start of every glue key (e.g. ``sp-boat``).
    cur : CrossingAngleCurve
        The curve: its medians and quartiles (m, deg), peaks with bootstrap intervals (deg) and
        acceptance per angle.
    over : bool
        Whether to add the ``-over-peak`` ratios (needs the curve's samples).

    Returns
    -------
    dict of str to str
        Glue key -> text; lengths in m, misalignments and angles in degrees, shares in percent.
    """
    out = {}
    c = cur.curve
    for v in VALUES:
        tag, unit, pk = TAGS[v], UNITS[v], cur.peak[v]
        out[f"{prefix}-{tag}-peak-deg"] = f"{pk['angle_deg']:.0f}"
        out[f"{prefix}-{tag}-peak-ci"] = f"{pk['ci_low_deg']:.0f}–{pk['ci_high_deg']:.0f}"
        for g in GAMMAS:
            out[f"{prefix}-{tag}-{g}"] = fmt_interval(cur.at(g, v), unit)
        peak_med = c[f"{v}_median"].max()
        out[f"{prefix}-{tag}-peak-value"] = f"{fmt_sig(peak_med, 2)} {unit}"
        for g in GAMMAS if over else ():  # with its replicate interval
            r = over_peak(cur, g, v)
            out[f"{prefix}-{tag}-{g}-over-peak"] = fmt_ci(r["median"], r["ci_low"], r["ci_high"])
    rejected, rejected_max = rejected_share(cur.acceptance)
    out[f"{prefix}-rejected"] = f"{100 * rejected:.2g} %"
    out[f"{prefix}-rejected-max"] = f"{100 * rejected_max:.2g} %"
    out[f"{prefix}-shape-rho"] = f"{curve_shape_rho(c):.2f}"
    return out


def peak_table(curves: Mapping[str, CrossingAngleCurve]) -> pd.DataFrame:
    """Peak angle with its interval and the medians at 0/90/180° of each platform and quantity.

    Parameters
    ----------
    curves : mapping of str to CrossingAngleCurve
        The curves keyed by platform key.

    Returns
    -------
    pandas.DataFrame
        One row per platform and quantity: ``platform``, ``quantity``, ``peak angle (deg)``,
        ``95 % CI (deg)`` (text) and ``median at <γ>°`` (3 significant digits, m or deg).
    """
    rows = []
    for k, cur in curves.items():
        for name, pk in cur.peak.items():
            rows.append({"platform": k, "quantity": name, "peak angle (deg)": pk["angle_deg"],
                         "95 % CI (deg)": f"{pk['ci_low_deg']:.0f}–{pk['ci_high_deg']:.0f}",
                         **{f"median at {g}°": fmt_sig(cur.at(g, name)["median"], 3) for g in GAMMAS}})
    return pd.DataFrame(rows)


@themed
def plot_offset_models(main: Mapping[str, CrossingAngleCurve],
                       sensitivity: Mapping[tuple[str, str], CrossingAngleCurve], main_label: str):
    """Median length (row a) and misalignment (row b) per platform (columns): the main curves
    (black, legend ``main_label``) and one line per offset model of ``sensitivity`` (keyed
    ``(platform key, spec)``). Returns the figure.

    Parameters
    ----------
    main : mapping of str to CrossingAngleCurve
        The main curves keyed by platform key (one column of panels each).
    sensitivity : mapping of (str, str) to CrossingAngleCurve
        The offset-model curves keyed ``(platform key, offset-model spec)``.
    main_label : str
        Legend entry of the main curves.

    Returns
    -------
    matplotlib.figure.Figure
        A new figure of 2 x ``len(main)`` panels against crossing angle (deg), legend below.
    """
    keys = list(main)
    fig, axs = plt.subplots(2, len(keys), figsize=(PAGE_WIDTH_IN, 8.5), sharex=True,
                            constrained_layout=True, squeeze=False)
    styles = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for j, k in enumerate(keys):
        own = [cur for (kk, _), cur in sensitivity.items() if kk == k]
        for i, v in enumerate(VALUES):
            ax = axs[i, j]
            c = main[k].curve
            ax.plot(c["crossing_angle_deg"], c[f"{v}_median"], color="k", lw=2, label=main_label)
            for n, cur in enumerate(own):
                color = styles[n % len(styles)]
                ax.plot(cur.curve["crossing_angle_deg"], cur.curve[f"{v}_median"],
                        color=color, lw=1.3, label=cur.offset_model.label)
                if _mixes_sides(cur):  # two modes: show where the middle half lies, not only the median
                    ax.fill_between(cur.curve["crossing_angle_deg"], cur.curve[f"{v}_q25"],
                                    cur.curve[f"{v}_q75"], color=color, alpha=0.15, lw=0,
                                    label=f"{cur.offset_model.label}: 25–75 %" if i == 0 else None)
            ax.set_ylabel("median " + AXIS_LABELS[v])
            ax.set_ylim(bottom=0)
            ax.grid(alpha=0.3)
            ax.set_title(platform_title(main[k].platform, 40, prefix=f"({'ab'[i]}{j + 1}) "), fontsize=10)
        axs[1, j].set_xlabel(r"crossing angle $\gamma$ (deg)")
        axs[1, j].set_xticks(np.arange(0, 181, 30))
        axs[1, j].set_xlim(0, 180)
    handles, labels = axs[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=2, fontsize=SMALL_FONT_PT)
    return fig


def _mixes_sides(cur: CrossingAngleCurve) -> bool:
    """Whether a curve's pass pairs mix same-side and opposite-side views (side rule random):
    its values then come from two populations and its median can jump between them."""
    return cur.offset_model.kind == "matched" and cur.offset_model.side_rule == "random"


def offset_models_bimodal_note(sensitivity: Mapping[tuple[str, str], CrossingAngleCurve],
                               value: str = "elevation_misalignment_deg") -> str:
    """Caption sentence for the offset models whose pass pairs mix sides (:func:`_mixes_sides`):
    their median jumps between the same-side and the opposite-side population from angle to
    angle, with the widest quartile range (angle, quartiles) as computed. Empty if none mixes.

    Parameters
    ----------
    sensitivity : mapping of (str, str) to CrossingAngleCurve
        The offset-model curves keyed ``(platform key, offset-model spec)``.
    value : str
        The quantity whose quartiles are quoted, one of :data:`VALUES` (default the elevation
        misalignment, deg).

    Returns
    -------
    str
        The sentence, starting with a space; ``""`` if no curve mixes sides.
    """
    out = []
    for (k, _), cur in sensitivity.items():
        if not _mixes_sides(cur):
            continue
        c = cur.curve
        iqr = c[f"{value}_q75"] - c[f"{value}_q25"]
        r = c.loc[iqr.idxmax()]
        out.append(f"{cur.platform.name}: at {r['crossing_angle_deg']:.0f}° its quartiles are "
                   f"{r[f'{value}_q25']:.0f}° and {r[f'{value}_q75']:.0f}°, median {r[f'{value}_median']:.0f}°")
    if not out:
        return ""
    label = next(cur.offset_model.label for cur in sensitivity.values() if _mixes_sides(cur))
    return (f" With its side random (`{label}`), about half of the pass pairs see the feature from the "
            "same side and half from opposite sides, so each angle's values fall in two groups (near the "
            "same-side and the opposite-side curves) and the median jumps between them from one angle to "
            "the next: that zig-zag is sampling between two modes, not structure. The shaded band is its "
            "25–75 % range (widest " + "; ".join(out) + ").")


def offset_model_table(sensitivity: Mapping[tuple[str, str], CrossingAngleCurve]) -> pd.DataFrame:
    """Peak angle, medians at 0°, the peak, 90° and 180°, and the smallest acceptance of each
    (platform, offset model) curve.

    Parameters
    ----------
    sensitivity : mapping of (str, str) to CrossingAngleCurve
        The offset-model curves keyed ``(platform key, offset-model spec)``.

    Returns
    -------
    pandas.DataFrame
        One row per curve: ``platform``, ``offset model``, ``peak angle (deg)``, ``peak 95 % CI
        (deg)``, the medians of the locus length (m, 2 significant digits) and the smallest
        acceptance (share of drawn pairs, 0–1).
    """
    rows = []
    for (k, _), cur in sensitivity.items():
        pk, peak = cur.peak["locus_length_m"], cur.curve["locus_length_m_median"].max()
        rows.append({"platform": k, "offset model": cur.offset_model.label,
                     "peak angle (deg)": pk["angle_deg"],
                     "peak 95 % CI (deg)": f"{pk['ci_low_deg']:.0f}–{pk['ci_high_deg']:.0f}",
                     "median at 0°": fmt_sig(cur.at(0)["median"], 2), "at peak": fmt_sig(peak, 2),
                     "at 90°": fmt_sig(cur.at(90)["median"], 2),
                     "at 180°": fmt_sig(cur.at(180)["median"], 2),
                     "acceptance (min over angles)": f"{cur.acceptance['acceptance'].min():.3f}"})
    return pd.DataFrame(rows)


def offset_model_texts(sensitivity: Mapping[tuple[str, str], CrossingAngleCurve]) -> dict[str, str]:
    """Glue texts ``sp-<platform>-<model tag>-...`` of the offset-model curves: length and
    misalignment peak angles with their bootstrap intervals, medians at 0/90/180° over the peak
    (with their replicate intervals, :func:`~sss_locus.experiments.survey_passes.verdicts.over_peak`).

    Parameters
    ----------
    sensitivity : mapping of (str, str) to CrossingAngleCurve
        The offset-model curves keyed ``(platform key, offset-model spec)``.

    Returns
    -------
    dict of str to str
        Glue key -> text; angles in degrees, ratios over the peak without unit.
    """
    out = {}
    for (k, spec), cur in sensitivity.items():
        p, pk = f"sp-{label_key(k)}-{model_tag(spec)}", cur.peak["locus_length_m"]
        out[f"{p}-len-peak-deg"] = f"{pk['angle_deg']:.0f}"
        out[f"{p}-len-peak-ci"] = f"{pk['ci_low_deg']:.0f}–{pk['ci_high_deg']:.0f}"
        mis = cur.peak["elevation_misalignment_deg"]
        out[f"{p}-mis-peak-deg"] = f"{mis['angle_deg']:.0f}"
        out[f"{p}-mis-peak-ci"] = f"{mis['ci_low_deg']:.0f}–{mis['ci_high_deg']:.0f}"
        for g in GAMMAS:
            r = over_peak(cur, g)
            out[f"{p}-len-{g}-over-peak"] = fmt_ci(r["median"], r["ci_low"], r["ci_high"])
    return out


def _change(r) -> str:
    return fmt_change(r["ratio"], r["ratio_ci_low"], r["ratio_ci_high"])


def pitch_depth_texts(pitch: pd.DataFrame, depth: pd.DataFrame,
                      pitch_levels_deg: Sequence[float], prefix: str = "sp-auv") -> dict[str, str]:
    """Glue texts ``<prefix>-pitch-*``, ``<prefix>-pitchvar-*`` and ``<prefix>-depth-*``
    (``prefix``: ``sp-`` plus the studied platform's label key, e.g. ``sp-auv``).

    ``pitch`` has one row per pitch level (both passes pitched) followed by the level-pass-1
    rows turning to port and to starboard; ``depth`` one row per altitude, the first the
    reference. Both hold :func:`~sss_locus.experiments.survey_passes.planning.median_ratio` columns.

    Parameters
    ----------
    pitch : pandas.DataFrame
        Nose-up over nose-down ratios, rows as above; columns ``ratio``, ``ratio_ci_low``,
        ``ratio_ci_high``, ``median_x``, ``median_y`` (m).
    depth : pandas.DataFrame
        Ratios per altitude, rows as above; columns ``altitude (m)``, ``ratio``, ``norm_ratio`` and
        their ``_ci_low``/``_ci_high``.
    pitch_levels_deg : sequence of float
        The pitch levels (deg) of the first rows of ``pitch``.
    prefix : str
        Start of every glue key.

    Returns
    -------
    dict of str to str
        Glue key -> text: changes as percentages with intervals, pitches in degrees, altitudes
        and medians in m.
    """
    out = {}
    for i, p in enumerate(pitch_levels_deg):
        out[f"{prefix}-pitch-{i}-effect"] = _change(pitch.iloc[i])
        out[f"{prefix}-pitch-{i}-deg"] = f"{p:g}"
    r = pitch.iloc[len(pitch_levels_deg) - 1]
    out[f"{prefix}-pitch-max-up"] = fmt_sig(r["median_x"], 2)
    out[f"{prefix}-pitch-max-down"] = fmt_sig(r["median_y"], 2)
    out[f"{prefix}-pitchvar-deg"] = f"{pitch_levels_deg[-1]:g}"
    out[f"{prefix}-pitchvar-port-effect"] = _change(pitch.iloc[-2])
    out[f"{prefix}-pitchvar-stbd-effect"] = _change(pitch.iloc[-1])
    hi, lo = depth.iloc[-1], depth.iloc[0]
    out[f"{prefix}-depth-effect"] = _change(hi)
    out[f"{prefix}-depth-effect-norm"] = fmt_change(hi["norm_ratio"], hi["norm_ratio_ci_low"],
                                                 hi["norm_ratio_ci_high"])
    out[f"{prefix}-depth-lo"] = f"{lo['altitude (m)']:g}"
    out[f"{prefix}-depth-hi"] = f"{hi['altitude (m)']:g}"
    return out


VARIANT_COLORS = ("tab:purple", "tab:green")
"""Colours of the level-pass-1 rows of :func:`plot_pitch_depth` (turning to port, starboard)."""


@themed
def plot_pitch_depth(pitch: pd.DataFrame, depth: pd.DataFrame, band_deg: tuple[float, float],
                     n_both: int):
    """(a) Nose-up over nose-down median-length ratios with intervals, one row per ``pitch`` row
    (the first ``n_both`` with both passes pitched, in black; the rest in
    :data:`VARIANT_COLORS`); (b) median length and length per unit range at each altitude of
    ``depth`` relative to the first. ``band_deg`` is the crossing-angle band both were run in.
    Returns the figure.

    Parameters
    ----------
    pitch : pandas.DataFrame
        One row per comparison: ``comparison`` (row label), ``ratio``, ``ratio_ci_low``,
        ``ratio_ci_high``.
    depth : pandas.DataFrame
        One row per altitude: ``altitude (m)``, ``ratio``, ``norm_ratio`` and their
        ``_ci_low``/``_ci_high`` columns.
    band_deg : (float, float)
        The crossing-angle band (deg), for panel (a)'s title.
    n_both : int
        Number of leading ``pitch`` rows with both passes pitched.

    Returns
    -------
    matplotlib.figure.Figure
        A new figure with the two panels side by side.
    """
    # side by side: (a)'s long row labels are wrapped, (b) takes the rest of the width
    fig, axs = plt.subplots(1, 2, figsize=(PAGE_WIDTH_IN, 4.2), constrained_layout=True,
                            gridspec_kw={"width_ratios": [1, 1.1]})
    ax = axs[0]
    y = np.arange(len(pitch))[::-1]
    colors = ["k"] * n_both + [VARIANT_COLORS[i % 2] for i in range(len(pitch) - n_both)]
    for yi, (_, r), c in zip(y, pitch.iterrows(), colors):
        ax.errorbar(r["ratio"], yi, xerr=[[r["ratio"] - r["ratio_ci_low"]], [r["ratio_ci_high"] - r["ratio"]]],
                    fmt="o", color=c, capsize=3)
    ax.set_yticks(y, [textwrap.fill(c, 22) for c in pitch["comparison"]], fontsize=SMALL_FONT_PT)
    ax.set_ylim(y.min() - 0.5, y.max() + 0.5)
    ax.axvline(1, color="k", lw=0.8)
    ax.set_xlabel("median locus length,\nnose-up / nose-down")
    ax.set_title(f"(a) pitch sign, γ in {band_deg[0]:.0f}–{band_deg[1]:.0f}°", fontsize=10)
    ax.grid(alpha=0.3)
    ax = axs[1]
    h = depth["altitude (m)"]
    for col, fmt, color, label in (("ratio", "o-", "k", "locus length"),
                                   ("norm_ratio", "s--", "0.5", "length / mean range")):
        ax.errorbar(h, depth[col], yerr=[depth[col] - depth[f"{col}_ci_low"], depth[f"{col}_ci_high"] - depth[col]],
                    fmt=fmt, capsize=3, color=color, label=label)
    ax.axhline(1, color="k", lw=0.8)
    ax.set_xlabel("altitude of both passes above the feature (m)")
    ax.set_ylabel(f"median relative to {h.iloc[0]:g} m")
    ax.set_title("(b) altitude, same band", fontsize=10)
    ax.legend(fontsize=SMALL_FONT_PT)
    ax.grid(alpha=0.3)
    return fig


def near_end_texts(checks: Mapping[str, pd.DataFrame]) -> dict[str, str]:
    """Glue texts of :func:`~sss_locus.experiments.survey_passes.verdicts.near_end_check` over several curves
    (``checks`` keyed by a label such as ``"AUV, matched ±10 m, same side"``):
    ``sp-near-<0|180>-held`` ("k of n curves"), ``sp-near-<0|180>-worst`` (the worst curve, with
    the median at the end and at its worst nearby angle).

    Parameters
    ----------
    checks : mapping of str to pandas.DataFrame
        Label -> the rows of ``near_end_check`` (``end_deg``, ``all_preferred``, ``ratio``,
        ``worst_median`` and ``end_median`` in m, ``worst_angle_deg``).

    Returns
    -------
    dict of str to str
        Glue key -> text; lengths in m, angles in degrees.
    """
    out = {}
    for end in (0.0, 180.0):
        rows = {lab: c[c["end_deg"] == end].iloc[0] for lab, c in checks.items()}
        held = sum(bool(r.all_preferred) for r in rows.values())
        out[f"sp-near-{end:.0f}-held"] = f"{held} of {len(rows)}"
        lab, r = max(rows.items(), key=lambda kv: -1.0 if np.isnan(kv[1].ratio) else kv[1].ratio)
        if np.isnan(r.ratio):
            out[f"sp-near-{end:.0f}-worst"] = "no grid angle near this end"
            continue
        out[f"sp-near-{end:.0f}-worst"] = (f"{lab}: {fmt_sig(r.worst_median, 2)} m at {r.worst_angle_deg:.0f}° "
                                           f"against {fmt_sig(r.end_median, 2)} m at {end:.0f}°")
    return out


def near_end_caption(window_deg: float) -> str:
    """The caption sentence of a table of :func:`~sss_locus.experiments.survey_passes.verdicts.near_end_check`
    rows (one curve and end a row).

    Parameters
    ----------
    window_deg : float
        Half-width (deg) of the window looked at next to each end.

    Returns
    -------
    str
        The caption sentence.

    Examples
    --------
    >>> near_end_caption(10.0).split(":")[0]
    'Each curve within 10° of each end'
    """
    return (f"Each curve within {window_deg:g}° of each end: the median locus length (m) at the end, the largest "
            f"median nearby and its angle, their ratio, the grid angles looked at, and whether every one of them "
            f"is in the preferred band.")


def peak_agreement_texts(prefix: str, agreement: Mapping[str, float | bool]) -> dict[str, str]:
    """Glue texts ``<prefix>-peak-gap`` (degrees, misalignment minus length) and
    ``<prefix>-peaks-overlap`` ("overlap"/"do not overlap") of
    :func:`~sss_locus.experiments.survey_passes.verdicts.peak_agreement`.

    Parameters
    ----------
    prefix : str
        Start of both glue keys.
    agreement : mapping of str to float or bool
        ``gap_deg`` (deg) and ``intervals_overlap`` of ``peak_agreement``.

    Returns
    -------
    dict of str to str
        The two glue texts.
    """
    return {f"{prefix}-peak-gap": f"{agreement['gap_deg']:+.0f}",
            f"{prefix}-peaks-overlap": "overlap" if agreement["intervals_overlap"] else "do not overlap"}
