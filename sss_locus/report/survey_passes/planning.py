"""Figure, table and prose of the planning chapter (``notebooks/planning.ipynb``).

The curves and bands come from :mod:`sss_locus.experiments.survey_passes.planning`
(:func:`~sss_locus.experiments.survey_passes.planning.crossing_angle_curve`,
:func:`~sss_locus.experiments.survey_passes.planning.planning_bands`); this module draws them beside the
paper's advice (:func:`plot_planning_bands`), tabulates them (:func:`bands_table`) and writes them
as glue texts (:func:`band_texts`). Platform names come from the data.
"""

from __future__ import annotations

import textwrap
from collections.abc import Mapping

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.patches import Patch

from sss_locus.experiments.survey_passes.planning import CrossingAngleCurve, band_at
from sss_locus.experiments.datamodel.userdata import label_key
from sss_locus.report.survey_passes.figures import model_tag
from sss_locus.report.common.style import PAGE_WIDTH_IN, SMALL_FONT_PT, themed
from sss_locus.report.common.text import fmt_bands

PAPER_AVOID_DEG = (10.0, 40.0)
"""The paper's band to avoid (Norman & Mangelson, Sec. IV-D: "avoid oblique crossing angles in
roughly the 10-40 deg range")."""

PAPER_ADVICE = "avoid ~10–40°; prefer ~0° or ~180°; 90° a fallback"
"""The paper's advice (Sec. IV-D and V) in the table's last column."""

BAND_COLORS = {"prefer": "tab:green", "avoid": "tab:red"}
"""Shading of the computed bands."""


def _models_and_platforms(curves: Mapping[tuple[str, str], CrossingAngleCurve]):
    specs = list(dict.fromkeys(s for _, s in curves))
    keys = list(dict.fromkeys(k for k, _ in curves))
    return specs, keys


@themed
def plot_planning_bands(curves: Mapping[tuple[str, str], CrossingAngleCurve],
                        bands: Mapping[tuple[str, str], pd.DataFrame],
                        paper_avoid_deg: tuple[float, float] = PAPER_AVOID_DEG):
    """Median locus length (black, IQR grey) against crossing angle with the computed bands to
    prefer (green) and avoid (red) shaded and the paper's band to avoid hatched; one row per
    offset model and one column per platform (``curves`` and ``bands`` keyed
    ``(platform key, offset-model spec)``). Returns the figure.

    Parameters
    ----------
    curves : mapping of (str, str) to CrossingAngleCurve
        The curves (``crossing_angle_deg``, ``locus_length_m_median`` and quartiles, m).
    bands : mapping of (str, str) to pandas.DataFrame
        Their bands: ``kind`` (``"prefer"``/``"avoid"``), ``lo_deg``, ``hi_deg`` (grid angles,
        deg).
    paper_avoid_deg : (float, float)
        The paper's band to avoid (deg).

    Returns
    -------
    matplotlib.figure.Figure
        A new figure, legend below.
    """
    specs, keys = _models_and_platforms(curves)
    fig, axs = plt.subplots(len(specs), len(keys), figsize=(PAGE_WIDTH_IN, 3.4 * len(specs) + 0.8),
                            sharex=True, constrained_layout=True, squeeze=False)
    lo_p, hi_p = paper_avoid_deg
    # characters of a 9 pt title per line in one column (~0.55 em a character, 70 % of the column)
    chars = max(12, int(0.7 * PAGE_WIDTH_IN * 72 / len(keys) / (0.55 * 9)))
    for i, spec in enumerate(specs):
        for j, key in enumerate(keys):
            ax, cur, b = axs[i, j], curves[(key, spec)], bands[(key, spec)]
            c = cur.curve
            g = c["crossing_angle_deg"].to_numpy()
            # a grid angle covers the span up to its neighbours' midpoints
            mids = np.concatenate([[g[0]], (g[1:] + g[:-1]) / 2, [g[-1]]])
            for r in b.itertuples():
                lo, hi = np.searchsorted(g, r.lo_deg), np.searchsorted(g, r.hi_deg)
                ax.axvspan(mids[lo], mids[hi + 1], color=BAND_COLORS[r.kind], alpha=0.18, lw=0)
            ax.axvspan(lo_p, hi_p, fill=False, hatch="//", edgecolor="0.3", lw=0.8,
                       label=f"paper: avoid ~{lo_p:g}–{hi_p:g}°")
            ax.fill_between(c["crossing_angle_deg"], c["locus_length_m_q25"], c["locus_length_m_q75"],
                            color="0.6", alpha=0.35, lw=0)
            ax.plot(c["crossing_angle_deg"], c["locus_length_m_median"], color="k", lw=1.6,
                    label="median (IQR grey)")
            ax.set_title(f"{textwrap.fill(cur.platform.name, chars)}\n{textwrap.fill(cur.offset_model.label, chars)}",
                         fontsize=9)
            ax.set_ylabel("locus length (m)")
            ax.set_ylim(bottom=0)
            ax.set_xlim(0, 180)
            ax.grid(alpha=0.3)
    for ax in axs[-1]:
        ax.set_xlabel(r"crossing angle $\gamma$ (deg)")
        ax.set_xticks(np.arange(0, 181, 30))
    handles, labels = axs[0, 0].get_legend_handles_labels()
    handles += [Patch(color=BAND_COLORS[k], alpha=0.3) for k in ("prefer", "avoid")]
    labels += ["prefer (computed)", "avoid (computed)"]
    fig.legend(handles, labels, fontsize=SMALL_FONT_PT, loc="outside lower center", ncol=2)
    return fig


def bands_table(curves: Mapping[tuple[str, str], CrossingAngleCurve],
                bands: Mapping[tuple[str, str], pd.DataFrame]) -> pd.DataFrame:
    """One row per offset model and platform (models outer): bands to prefer and avoid, what 90°
    is, and the paper's advice.

    Parameters
    ----------
    curves : mapping of (str, str) to CrossingAngleCurve
        The curves keyed ``(platform key, offset-model spec)``.
    bands : mapping of (str, str) to pandas.DataFrame
        Their bands, same keys.

    Returns
    -------
    pandas.DataFrame
        Columns ``platform``, ``offset model``, ``prefer (computed)``, ``avoid (computed)`` (text,
        deg), ``90° is`` and ``paper``.
    """
    specs, keys = _models_and_platforms(curves)
    rows = []
    for spec in specs:
        for key in keys:
            b = bands[(key, spec)]
            rows.append({"platform": key, "offset model": curves[(key, spec)].offset_model.label,
                         "prefer (computed)": fmt_bands(b, "prefer"),
                         "avoid (computed)": fmt_bands(b, "avoid"),
                         "90° is": band_at(b, 90.0), "paper": PAPER_ADVICE})
    return pd.DataFrame(rows)


def band_texts(bands: Mapping[tuple[str, str], pd.DataFrame]) -> dict[str, str]:
    """Glue texts ``pl-<platform>-<model tag>-prefer``, ``-avoid`` and ``-90`` (``<platform>``:
    the key with ``_`` as ``-``).

    Parameters
    ----------
    bands : mapping of (str, str) to pandas.DataFrame
        The bands keyed ``(platform key, offset-model spec)``.

    Returns
    -------
    dict of str to str
        Glue key -> text (angles in degrees).
    """
    out = {}
    for (key, spec), b in bands.items():
        tag = f"pl-{label_key(key)}-{model_tag(spec)}"
        out[f"{tag}-prefer"] = fmt_bands(b, "prefer")
        out[f"{tag}-avoid"] = fmt_bands(b, "avoid")
        out[f"{tag}-90"] = band_at(b, 90.0)
    return out


def bands_markdown(curves: Mapping[tuple[str, str], CrossingAngleCurve],
                   bands: Mapping[tuple[str, str], pd.DataFrame]) -> str:
    """The chapter's summary table (MyST): one row per platform of the run under each offset
    model (models outer), the bands to prefer and avoid and what 90° is, then the paper's advice.
    Every platform of ``curves`` has its rows, the paper's or not.

    Parameters
    ----------
    curves : mapping of (str, str) to CrossingAngleCurve
        The curves keyed ``(platform key, offset-model spec)``.
    bands : mapping of (str, str) to pandas.DataFrame
        Their bands, same keys.

    Returns
    -------
    str
        The Markdown table, ending in a newline.
    """
    specs, keys = _models_and_platforms(curves)
    rows = ["| | Prefer (computed) | Avoid (computed) | 90° |", "|---|---|---|---|"]
    for spec in specs:
        for key in keys:
            cur, b = curves[(key, spec)], bands[(key, spec)]
            name = cur.platform.name.replace("|", "/")
            rows.append(f"| {name}, {offset_model_words(cur.offset_model)} | {fmt_bands(b, 'prefer')} | "
                        f"{fmt_bands(b, 'avoid')} | {band_at(b, 90.0)} |")
    rows.append("| Paper (Sec. IV-D) | near-repeat (~0°) or anti-parallel (~180°) | oblique, roughly 10°–40° "
                "| reasonable fallback |")
    return "\n".join(rows) + "\n"


def offset_model_words(model) -> str:
    """An offset model in plain words: where the two passes see the feature across their swaths.

    Parameters
    ----------
    model : OffsetModel
        The offset model (``kind``, ``jitter_m`` in m, ``side_rule``).

    Returns
    -------
    str
        The words.
    """
    if model.kind == "independent":
        return "passes flown without regard to the feature (independent offsets)"
    side = {"same": "on the same side", "opposite": "on opposite sides",
            "random": "on either side"}.get(model.side_rule, model.side_rule)
    return f"both passes aimed at the feature, ±{model.jitter_m:g} m, {side} (matched offsets)"


def paper_band_finding(curve: pd.DataFrame, bands: pd.DataFrame,
                       paper_avoid_deg: tuple[float, float] = PAPER_AVOID_DEG) -> str:
    """One curve's bands against the paper's advice to avoid ``paper_avoid_deg``: the one source
    of this paragraph (CONTRIBUTING.md, "One source per sentence").

    Parameters
    ----------
    curve : pandas.DataFrame
        The median curve (``crossing_angle_deg``), whose grid angles are counted.
    bands : pandas.DataFrame
        Its bands (:func:`~sss_locus.experiments.survey_passes.planning.planning_bands`).
    paper_avoid_deg : (float, float)
        The paper's band to avoid (Sec. IV-D), degrees.

    Returns
    -------
    str
        The first avoid band after a repeat pass and whether it ends before or past the paper's
        upper edge, the shares of the grid angles inside the paper's band that the computed bands
        avoid and prefer, and what a cross-line (90°) is.
    """
    lo, hi = paper_avoid_deg
    avoid = bands[bands["kind"] == "avoid"].sort_values("lo_deg")
    if avoid.empty:
        first = "no angle is to be avoided"
    else:
        a = avoid.iloc[0]
        first = (f"the first avoided band is {a.lo_deg:.0f}–{a.hi_deg:.0f}°, "
                 + (f"ending by the paper's {hi:g}°" if a.hi_deg <= hi else f"reaching past the paper's {hi:g}°"))
    inside = [g for g in curve["crossing_angle_deg"] if lo <= g <= hi]
    kinds = [band_at(bands, g) for g in inside]
    share = {k: 100 * kinds.count(k) / len(kinds) for k in ("avoid", "prefer")} if kinds else {"avoid": 0, "prefer": 0}
    return (f"{first}; of the grid angles in the paper's {lo:g}°–{hi:g}°, {share['avoid']:.0f} % are avoided and "
            f"{share['prefer']:.0f} % preferred; a cross-line (90°) is \"{band_at(bands, 90.0)}\".")


def cross_line_finding(curves: Mapping[tuple[str, str], CrossingAngleCurve],
                       bands: Mapping[tuple[str, str], pd.DataFrame], key: str) -> str:
    """What a cross-line (90°) is for platform ``key`` under each offset model of ``curves``
    (keyed ``(platform key, spec)``), and whether the offset model changes it.

    Parameters
    ----------
    curves : mapping of (str, str) to CrossingAngleCurve
        The curves keyed ``(platform key, offset-model spec)``.
    bands : mapping of (str, str) to pandas.DataFrame
        Their bands, same keys.
    key : str
        The platform.

    Returns
    -------
    str
        The sentence.

    Raises
    ------
    ValueError
        When ``bands`` has no curve of ``key``.
    """
    said = {spec: band_at(b, 90.0) for (k, spec), b in bands.items() if k == key}
    if not said:
        raise ValueError(f"no curve of platform {key!r}")
    parts = [f"\"{kind}\" with {curves[(key, spec)].offset_model.label} offsets" for spec, kind in said.items()]
    text = "a cross-line (90°) is " + (parts[0] if len(parts) == 1 else ", ".join(parts[:-1]) + " and " + parts[-1])
    if len(said) > 1:
        text += (": the offset model decides whether it is a fallback" if len(set(said.values())) > 1 else
                 ": the same under every offset model shown")
    return text + "."
