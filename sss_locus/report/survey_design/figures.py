"""Figures of the survey-design chapter (``notebooks/survey_design.ipynb``).

Inputs are the tables of :mod:`sss_locus.experiments.survey_design.front` (the plans table of
``search_plans``, its noise re-evaluation, the seed-stability table) and, for the plan drawing,
the area, the plan's segments and the coverage grid of
:func:`sss_locus.experiments.survey_design.coverage.coverage`.

The Pareto front (:func:`plot_front`) is drawn in the book's seaborn theme
(:func:`~sss_locus.report.common.style.theme`) with ``ax.scatter`` per kind of plan: each kind has its own
marker, size and fill (hollow: not eligible; the recommended plan circled over its point), which
one ``seaborn.scatterplot`` hue does not give. The plan (:func:`plot_plan`) is a map, drawn in
plain matplotlib: a grid over the coverage cells would hide them. Captions and verdict sentences
are in :mod:`.prose`, tables in :mod:`.tables`.
"""

from __future__ import annotations

import math

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.colors import BoundaryNorm, ListedColormap
from matplotlib.patches import Polygon as PolygonPatch

from sss_locus.experiments.survey_design.front import OBJECTIVES
from sss_locus.report.common.style import PAGE_WIDTH_IN, platform_title, themed
from sss_locus.report.survey_design.map import LEGEND_X, add_graticule, add_scale_bar

OBJECTIVE_LABELS = {"locus": "median best-pair locus length (m)",
                    "three_view": "share of features not resolved by three views",
                    "reconstruction": "median 3-D error, two views + prior, with noise (m)"}
BASELINES = {"standard": ("standard plan (NOAA-style, 200 %, as flown)", "*", "tab:red", 190),
             "lawnmower": ("lawn-mower, same track length", "s", "tab:purple", 80)}


@themed
def plot_front(fronts: dict, objective: str, platforms: dict):
    """Track length against the objective for every plan of each platform (one panel each):
    searched plans grey (hollow: not eligible), the Pareto front joined, the baselines marked,
    the recommended plan circled.

    Parameters
    ----------
    fronts : dict of str to pandas.DataFrame
        Platform key -> every scored plan: ``kind``, ``eligible``, ``front``, optional
        ``recommended``, ``total_m`` (m) and the objective's column.
    objective : str
        A key of :data:`OBJECTIVES`.
    platforms : dict of str to Platform
        The platforms by key (panel titles).

    Returns
    -------
    matplotlib.figure.Figure
        A new figure, one panel per platform, track length in km, legend below.
    """
    col = OBJECTIVES[objective]
    keys = list(fronts)
    fig, axes = plt.subplots(1, len(keys), figsize=(PAGE_WIDTH_IN, 3.6), squeeze=False, constrained_layout=True)
    for ax, key in zip(axes[0], keys):
        t = fronts[key]
        s = t[t.kind == "search"]
        ax.scatter(s.total_m[s.eligible] / 1e3, s[col][s.eligible], s=16, color="0.55", label="searched plan")
        ax.scatter(s.total_m[~s.eligible] / 1e3, s[col][~s.eligible], s=16, facecolors="none",
                   edgecolors="0.65", label="less seen twice than standard")
        f = t[t.front].sort_values("total_m")
        ax.plot(f.total_m / 1e3, f[col], "-", color="black", lw=1.2, label="Pareto front", zorder=3)
        for kind, (name, marker, colour, size) in BASELINES.items():
            b = t[t.kind == kind]
            ax.scatter(b.total_m / 1e3, b[col], marker=marker, s=size, color=colour, label=name, zorder=4)
        rec = t[t.recommended] if "recommended" in t else t.iloc[:0]
        ax.scatter(rec.total_m / 1e3, rec[col], s=220, facecolors="none", edgecolors="tab:green", lw=2.2,
                   label="recommended", zorder=5)
        ax.set_xlabel("track flown: lines, turns, transits (km)")
        ax.set_title(platform_title(platforms[key], width=90 // len(keys)), fontsize=9)  # a panel's width
    axes[0][0].set_ylabel(OBJECTIVE_LABELS[objective])
    handles, labels = _drawn_legend(axes[0])
    fig.legend(handles, labels, loc="outside lower center", ncol=3, fontsize=8.5, frameon=False)
    return fig


def _drawn_legend(axes) -> tuple[list, list]:
    """The legend entries of what ``axes`` draw, each label once: a line of under two points (a
    Pareto front of one plan) or a scatter of no point draws nothing and gets no entry."""
    from matplotlib.collections import Collection
    from matplotlib.lines import Line2D

    seen = {}
    for ax in axes:
        for h, label in zip(*ax.get_legend_handles_labels()):
            if isinstance(h, Line2D) and len(h.get_xdata()) < 2 and h.get_marker() in (None, "None", "", " "):
                continue
            if isinstance(h, Collection) and len(h.get_offsets()) == 0:
                continue
            seen.setdefault(label, h)
    return list(seen.values()), list(seen)


#: The survey area's outline in the plan figures (dashed, so it is not read as a line to run).
AREA_EDGE = "0.3"
#: Cells no plan can see (the seafloor beyond the sonar's reach), apart from a plan's gaps.
OUT_OF_REACH = "0.25"


def plot_plan(area, lines: pd.DataFrame, grid: pd.DataFrame, grid_m: float, nadir_gap_m: float, platform,
              title: str, ax=None, track: pd.DataFrame | None = None, fence=None, bathymetry=None):
    """The plan over the area: coverage cells by the number of lines that see them (holes red),
    cut at the area's edge (dashed), the lines as arrows in run order, the nadir gap of each line
    hatched; with ``track`` (the waypoints of :func:`sss_locus.pipeline.publish.missions.waypoints`) the
    turns and transits, with ``fence`` the inclusion fence, with ``bathymetry`` (a
    :class:`~sss_locus.experiments.survey_design.bathymetry.Bathymetry`) its depth contours inside
    the area, labelled in metres; on the area's WGS 84 graticule with a scale bar
    (:mod:`sss_locus.report.survey_design.map`).

    Parameters
    ----------
    area : SurveyArea
        The survey area (its ``polygon`` in the local frame, m; ``origin_lonlat``).
    lines : pandas.DataFrame
        The plan's lines in run order: ``x0_m``, ``y0_m``, ``x1_m``, ``y1_m``, ``length_m`` (local
        frame, m) and ``set`` (``"main"`` or a cross/repeat set).
    grid : pandas.DataFrame
        Coverage cells: centres ``x_m``, ``y_m`` (m), ``n_lines`` and optionally ``out_of_reach``.
    grid_m : float
        Cell size (m).
    nadir_gap_m : float
        Half-width (m) of each line's nadir gap; 0 draws none.
    platform : Platform
        The vehicle (not drawn; kept for the caller's signature).
    title : str
        Axes title.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; ``None``: a new figure of the page's width.
    track : pandas.DataFrame, optional
        The mission's waypoints (``east_m``, ``north_m``).
    fence : shapely.geometry.Polygon, optional
        The inclusion fence (local frame, m).
    bathymetry : Bathymetry, optional
        Depth grid whose contours (m) are drawn inside the area.

    Returns
    -------
    matplotlib.figure.Figure
        The figure of the axes drawn on.
    """
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
    beyond = None
    if "out_of_reach" in grid and grid.out_of_reach.any():  # no plan sees these: drawn apart from the gaps
        far = np.full(counts.shape, np.nan)
        far[j[grid.out_of_reach], i[grid.out_of_reach]] = 1.0
        beyond = ax.pcolormesh(x0 + (np.arange(i.max() + 2) - 0.5) * grid_m,
                               y0 + (np.arange(j.max() + 2) - 0.5) * grid_m, np.ma.masked_invalid(far),
                               cmap=ListedColormap([OUT_OF_REACH]), rasterized=True)
        beyond.set_clip_path(PolygonPatch(xy, closed=True, transform=ax.transData))
    mesh.set_clip_path(PolygonPatch(xy, closed=True, transform=ax.transData))  # cells cut at the area's edge
    ax.add_patch(PolygonPatch(xy, closed=True, fill=False, edgecolor=AREA_EDGE, lw=1.3, ls=(0, (5, 2))))
    for ring in area.polygon.interiors:  # holes of the area: islands, exclusion zones
        ax.add_patch(PolygonPatch(np.asarray(ring.coords), closed=True, facecolor="0.85", edgecolor=AREA_EDGE,
                                  lw=1.0, hatch="xx"))
    if bathymetry is not None:
        b = bathymetry
        gx, gy = b.x0_m + b.spacing_m * np.arange(b.depth_m.shape[1]), b.y0_m + b.spacing_m * np.arange(b.depth_m.shape[0])
        bx0, by0, bx1, by1 = area.polygon.bounds  # the grid over the area only (it spans more)
        ix = (gx >= bx0 - b.spacing_m) & (gx <= bx1 + b.spacing_m)
        iy = (gy >= by0 - b.spacing_m) & (gy <= by1 + b.spacing_m)
        depth = np.round(b.depth_m[np.ix_(iy, ix)], CONTOUR_DECIMALS)  # a flat floor on a level: one value
        cs = ax.contour(gx[ix], gy[iy], depth, levels=_depth_levels(b.area_depths_m),
                        colors="saddlebrown", linewidths=0.6, alpha=0.8, zorder=2)
        inside = PolygonPatch(xy, closed=True, transform=ax.transData)
        cs.set_clip_path(inside)
        for label in ax.clabel(cs, fmt=lambda v: f"{v:g} m", fontsize=7, inline=True):
            label.set_clip_path(inside)
    if track is not None:
        ax.plot(track.east_m, track.north_m, color="0.35", lw=0.6, zorder=2)
    if fence is not None:
        ax.plot(*fence.exterior.xy, color="tab:red", lw=0.8, ls="--", zorder=2)
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
    ax.autoscale_view()
    pad = 0.04 * max(np.ptp(ax.get_xlim()), np.ptp(ax.get_ylim()))
    ax.set_xlim(ax.get_xlim()[0] - pad, ax.get_xlim()[1] + pad)
    ax.set_ylim(ax.get_ylim()[0] - pad, ax.get_ylim()[1] + pad)
    add_graticule(ax, area)
    add_scale_bar(ax)
    origin = "" if area.origin_lonlat is None else f" of {area.origin_lonlat[0]:.4f}°, {area.origin_lonlat[1]:.4f}°"
    ax.set_xlabel(f"east of the origin{origin} (m)")
    ax.set_ylabel("north (m)")
    ax.set_title(title, fontsize=9)
    handles = [plt.Line2D([], [], marker="s", ls="", color=c, markersize=8) for c in cmap.colors]
    labels = ["gap (seen by no line)", "seen by 1 line", "2 lines", "3 or more"]
    handles += [plt.Line2D([], [], color=AREA_EDGE, lw=1.3, ls=(0, (5, 2))), plt.Line2D([], [], color="black")]
    labels += ["survey area", "main line"]
    if beyond is not None:
        handles.insert(1, plt.Line2D([], [], marker="s", ls="", color=OUT_OF_REACH, markersize=8))
        labels.insert(1, "beyond the sonar's reach")
    if track is not None:
        handles.append(plt.Line2D([], [], color="0.35", lw=0.6))
        labels.append("turns and transits")
    if fence is not None:
        handles.append(plt.Line2D([], [], color="tab:red", lw=0.8, ls="--"))
        labels.append("inclusion fence")
    if (lines["set"] != "main").any():
        handles.append(plt.Line2D([], [], color="tab:orange"))
        labels.append("cross / repeat line")
    if bathymetry is not None:
        handles.append(plt.Line2D([], [], color="saddlebrown", lw=0.6))
        labels.append(f"depth contour ({bathymetry.file})")
    if nadir_gap_m > 0:
        handles.append(PolygonPatch([[0, 0], [1, 0], [1, 1]], fill=False, hatch="////", edgecolor="0.3"))
        labels.append(f"nadir gap (±{nadir_gap_m:.0f} m)")
    ax.legend(handles, labels, loc="upper left", bbox_to_anchor=(LEGEND_X, 1.0), fontsize=9, frameon=False)
    return ax.figure


#: Decimals (of a metre) the depth grid is rounded to before its contours are drawn. A flat floor
#: whose depth is a contour level (a 140 m trench, levels every 20 m) comes out of the grid's
#: reprojection as 140 m give or take 1e-13 m, and the contour at 140 m then circled each cell of
#: the floor that came out a hair deeper: small blobs over the whole floor. Rounded to the
#: millimetre, the floor is exactly the level, which the contour treats as not deeper than it:
#: the line runs where the depth crosses the level, not around rounding noise.
CONTOUR_DECIMALS = 3


def _depth_levels(depths_m) -> list[float]:
    """About six round depth contours spanning ``depths_m`` (m)."""
    lo, hi = float(np.min(depths_m)), float(np.max(depths_m))
    if hi - lo <= 0:
        return [lo]
    step = 10 ** math.floor(math.log10((hi - lo) / 6))
    step *= next(k for k in (1, 2, 5, 10) if (hi - lo) / (k * step) <= 7)
    return [float(v) for v in np.arange(math.ceil(lo / step) * step, hi + 1e-9, step)]


