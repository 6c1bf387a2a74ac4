"""Figures and sentences of the survey-design chapter (``notebooks/survey_design.ipynb``).

Inputs are the tables of :mod:`sss_locus.experiments.survey_design` (the plans table of
``search_plans``, its noise re-evaluation, the seed-stability table) and, for the plan drawing,
the area, the plan's segments and the coverage grid of
:func:`sss_locus.experiments.survey_coverage.coverage`.

The Pareto front (:func:`plot_front`) is drawn in the book's seaborn theme
(:func:`~sss_locus.report.style.theme`) with ``ax.scatter`` per kind of plan: each kind has its own
marker, size and fill (hollow: not eligible; the recommended plan circled over its point), which
one ``seaborn.scatterplot`` hue does not give. The plan (:func:`plot_plan`) is a map, drawn in
plain matplotlib: a grid over the coverage cells would hide them.
"""

from __future__ import annotations

import math

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.colors import BoundaryNorm, ListedColormap
from matplotlib.patches import Polygon as PolygonPatch

from ..experiments.survey_design import OBJECTIVES
from .style import PAGE_WIDTH_IN, platform_title, themed
from .text import fmt_percent, fmt_sig

OBJECTIVE_LABELS = {"locus": "median best-pair locus length (m)",
                    "three_view": "share of features not resolved by three views",
                    "reconstruction": "median 3-D error, two views + prior, with noise (m)"}
BASELINES = {"standard": ("standard plan (NOAA-style, 200 %)", "*", "tab:red", 190),
             "lawnmower": ("lawn-mower, same track length", "s", "tab:purple", 80)}


def plan_label(row) -> str:
    """A plan in words: ``"0° lines 120 m apart + cross lines at 90°, 240 m; altitude 21 m"``."""
    text = f"{round(row['heading_deg'] % 180, 1):g}° lines {row['spacing_m']:.0f} m apart"
    if not math.isnan(row["crossing_deg"]):
        what = "offset repeat" if row["crossing_deg"] % 180 == 0 else f"cross lines at {row['crossing_deg']:g}°"
        text += f" + {what}, {row['cross_spacing_m']:.0f} m"
    text += f"; altitude {row['altitude_m']:.0f} m"
    return text + (f", pitch {row['pitch_deg']:g}°" if row["pitch_deg"] else "")


def plan_caption(platform, area, area_file: str, row, cov: dict, files) -> str:
    """The caption of a recommended plan's figure: the plan, its cost and coverage (``cov`` of
    :func:`sss_locus.experiments.survey_design.plan_coverage`), the area file with its SHA-256 and
    the mission ``files`` beside the figure (without an origin only the CSV, and why)."""
    names = ", ".join(f"`{n}`" for n in files)
    why = ("" if area.origin_lonlat is not None else
           " (the others need longitude/latitude: give the area file an `origin_lonlat`)")
    return (f"Recommended plan for the {platform.name} over {area.name}: {plan_label(row)}; "
            f"{row.total_m / 1e3:.2f} km including turns of radius {platform.turn_radius_m:g} m, "
            f"{row.time_h:.1f} h at {platform.speed_m_s:g} m/s; seen once {fmt_percent(cov['once'])}, twice "
            f"{fmt_percent(cov['twice'])} of the area, holes: {cov['n_holes']}. Area file `{area_file}` "
            f"(SHA-256 `{area.sha256[:12]}`); mission files beside the figure: {names}{why}.")


@themed
def plot_front(fronts: dict, objective: str, platforms: dict):
    """Track length against the objective for every plan of each platform (one panel each):
    searched plans grey (hollow: not eligible), the Pareto front joined, the baselines marked,
    the recommended plan circled."""
    col = OBJECTIVES[objective]
    keys = list(fronts)
    fig, axes = plt.subplots(1, len(keys), figsize=(PAGE_WIDTH_IN, 3.6), squeeze=False, constrained_layout=True)
    for ax, key in zip(axes[0], keys):
        t = fronts[key]
        s = t[t.kind == "search"]
        ax.scatter(s.total_m[s.eligible] / 1e3, s[col][s.eligible], s=16, color="0.55", label="searched plan")
        ax.scatter(s.total_m[~s.eligible] / 1e3, s[col][~s.eligible], s=16, facecolors="none",
                   edgecolors="0.65", label="too few features seen twice")
        f = t[t.front].sort_values("total_m")
        ax.plot(f.total_m / 1e3, f[col], "-", color="black", lw=1.2, label="Pareto front", zorder=3)
        for kind, (name, marker, colour, size) in BASELINES.items():
            b = t[t.kind == kind]
            ax.scatter(b.total_m / 1e3, b[col], marker=marker, s=size, color=colour, label=name, zorder=4)
        rec = t[t.recommended] if "recommended" in t else t.iloc[:0]
        ax.scatter(rec.total_m / 1e3, rec[col], s=220, facecolors="none", edgecolors="tab:green", lw=2.2,
                   label="recommended", zorder=5)
        ax.set_xlabel("track length incl. turns (km)")
        ax.set_title(platform_title(platforms[key], width=90 // len(keys)), fontsize=9)  # a panel's width
    axes[0][0].set_ylabel(OBJECTIVE_LABELS[objective])
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=3, fontsize=8.5, frameon=False)
    return fig


#: The survey area's outline in the plan figures (dashed, so it is not read as a line to run).
AREA_EDGE = "0.3"


def plot_plan(area, lines: pd.DataFrame, grid: pd.DataFrame, grid_m: float, nadir_gap_m: float, platform,
              title: str, ax=None):
    """The plan over the area: coverage cells by the number of lines that see them (holes red),
    cut at the area's edge (dashed), the lines as arrows in run order, the nadir gap of each line
    hatched."""
    if ax is None:
        fig, ax = plt.subplots(figsize=(PAGE_WIDTH_IN, 5.2), constrained_layout=True)
    cmap = ListedColormap(["tab:red", "#c6dbef", "#6baed6", "#2171b5"])
    norm = BoundaryNorm([-0.5, 0.5, 1.5, 2.5, 1e9], cmap.N)
    x0, y0 = grid.x_m.min(), grid.y_m.min()
    i = np.rint((grid.x_m - x0) / grid_m).astype(int)
    j = np.rint((grid.y_m - y0) / grid_m).astype(int)
    counts = np.full((j.max() + 1, i.max() + 1), np.nan)
    counts[j, i] = grid.n_lines
    mesh = ax.pcolormesh(x0 + (np.arange(i.max() + 2) - 0.5) * grid_m, y0 + (np.arange(j.max() + 2) - 0.5) * grid_m,
                         np.ma.masked_invalid(counts), cmap=cmap, norm=norm, rasterized=True)
    xy = np.asarray(area.polygon.exterior.coords)
    mesh.set_clip_path(PolygonPatch(xy, closed=True, transform=ax.transData))  # cells cut at the area's edge
    ax.add_patch(PolygonPatch(xy, closed=True, fill=False, edgecolor=AREA_EDGE, lw=1.3, ls=(0, (5, 2))))
    for _, r in lines.iterrows():
        p0, p1 = np.array([r.x0_m, r.y0_m]), np.array([r.x1_m, r.y1_m])
        d = (p1 - p0) / max(r.length_m, 1e-9)
        n = np.array([-d[1], d[0]])
        if nadir_gap_m > 0:
            band = [p0 + n * nadir_gap_m, p1 + n * nadir_gap_m, p1 - n * nadir_gap_m, p0 - n * nadir_gap_m]
            ax.add_patch(PolygonPatch(band, closed=True, fill=False, hatch="////", edgecolor="0.3", lw=0.3))
        colour = "black" if r["set"] == "main" else "tab:orange"
        ax.annotate("", p1, p0, arrowprops=dict(arrowstyle="-|>", color=colour, lw=1.1, mutation_scale=9))
    ax.set_aspect("equal")
    ax.set_xlabel("east (m)")
    ax.set_ylabel("north (m)")
    ax.set_title(title, fontsize=9)
    handles = [plt.Line2D([], [], marker="s", ls="", color=c, markersize=8) for c in cmap.colors]
    labels = ["hole (no line)", "seen by 1 line", "2 lines", "3 or more"]
    handles += [plt.Line2D([], [], color=AREA_EDGE, lw=1.3, ls=(0, (5, 2))), plt.Line2D([], [], color="black")]
    labels += ["survey area", "main line"]
    if (lines["set"] != "main").any():
        handles.append(plt.Line2D([], [], color="tab:orange"))
        labels.append("cross / repeat line")
    if nadir_gap_m > 0:
        handles.append(PolygonPatch([[0, 0], [1, 0], [1, 1]], fill=False, hatch="////", edgecolor="0.3"))
        labels.append(f"nadir gap (±{nadir_gap_m:.0f} m)")
    ax.legend(handles, labels, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8.5, frameon=False)
    return ax.figure


def comparison_sentence(t: pd.DataFrame, objective: str, platform) -> str:
    """How the recommended plan compares with the standard plan, in one or two sentences."""
    col = OBJECTIVES[objective]
    std = t[t.kind == "standard"].iloc[0]
    rec = t[t.recommended]
    name = platform.name
    if rec.empty:
        return f"For the {name}, no plan searched shows as many features twice as the standard plan."
    r = rec.iloc[0]
    unit = " m" if col.endswith("_m") else ""
    show = (lambda v: fmt_sig(v, 3) + unit) if unit else fmt_percent
    if r.name == std.name or (r[col] >= std[col] and r.total_m >= std.total_m):
        return (f"For the {name}, no searched plan as short as the standard plan ({std.total_m / 1e3:.2f} km) "
                f"does better on this objective: the standard plan ({show(std[col])}) is kept.")
    change = r[col] / std[col] - 1.0 if std[col] > 0 else math.nan
    longer = r.total_m / std.total_m - 1.0
    length = (f"on a track {fmt_percent(abs(longer))} {'shorter' if longer < 0 else 'longer'} "
              f"({r.total_m / 1e3:.2f} km against {std.total_m / 1e3:.2f} km)")
    which = (f"the recommended plan is the lawn-mower baseline itself ({plan_label(r)}; no plan of the search "
             f"does better under the same rule): it gives" if r.kind == "lawnmower"
             else f"the recommended plan ({plan_label(r)}) gives")
    return (f"For the {name}, {which} {show(r[col])} against the "
            f"standard plan's {show(std[col])} ({fmt_percent(abs(change))} {'less' if change < 0 else 'more'}) "
            f"{length}; it shows {fmt_percent(r.two_view_share)} of the features to two lines "
            f"(standard: {fmt_percent(std.two_view_share)}).")
