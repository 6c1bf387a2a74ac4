"""Figures and sentences of the survey-design chapter (``notebooks/survey_design.ipynb``).

Inputs are the tables of :mod:`sss_locus.experiments.survey_design.front` (the plans table of
``search_plans``, its noise re-evaluation, the seed-stability table) and, for the plan drawing,
the area, the plan's segments and the coverage grid of
:func:`sss_locus.experiments.survey_design.coverage.coverage`.

The Pareto front (:func:`plot_front`) is drawn in the book's seaborn theme
(:func:`~sss_locus.report.common.style.theme`) with ``ax.scatter`` per kind of plan: each kind has its own
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

from sss_locus.experiments.survey_design.coverage import reach_limits_m
from sss_locus.experiments.survey_design.front import OBJECTIVES
from sss_locus.experiments.survey_design.scoring import lower_end_cut
from sss_locus.report.common.style import PAGE_WIDTH_IN, platform_title, themed
from sss_locus.report.survey_design.map import LEGEND_X, add_graticule, add_scale_bar
from sss_locus.report.common.text import count_noun, fmt_ci, fmt_percent, fmt_sig

OBJECTIVE_LABELS = {"locus": "median best-pair locus length (m)",
                    "three_view": "share of features not resolved by three views",
                    "reconstruction": "median 3-D error, two views + prior, with noise (m)"}
BASELINES = {"standard": ("standard plan (NOAA-style, 200 %, as flown)", "*", "tab:red", 190),
             "lawnmower": ("lawn-mower, same track length", "s", "tab:purple", 80)}


def plan_label(row) -> str:
    """A plan in words, with the lines' compass heading (degrees clockwise from grid north of
    the area's local frame): ``"090°/270° lines 120 m apart + cross lines at 90°, 240 m;
    altitude 21 m"``.

    Parameters
    ----------
    row : pandas.Series
        One plan: ``heading_deg`` (deg counter-clockwise from east), ``spacing_m``,
        ``crossing_deg`` (deg, NaN without cross lines), ``cross_spacing_m``, ``altitude_m`` (m),
        ``pitch_deg`` (deg).

    Returns
    -------
    str
        The plan in words.
    """
    a = round((90.0 - row["heading_deg"]) % 180.0, 1)
    text = f"{a:03.0f}°/{a + 180:03.0f}° lines {row['spacing_m']:.0f} m apart"
    if not math.isnan(row["crossing_deg"]):
        what = "offset repeat" if row["crossing_deg"] % 180 == 0 else f"cross lines at {row['crossing_deg']:g}°"
        text += f" + {what}, {row['cross_spacing_m']:.0f} m"
    text += f"; altitude {row['altitude_m']:.3g} m"  # a boat's altitude is the water depth: 8.5 m, not "8 m"
    return text + (f", pitch {row['pitch_deg']:g}°" if row["pitch_deg"] else "")


def plan_caption(platform, area, area_file: str, row, cov: dict, files, *, water_depth_m: float,
                 depth_source: str, ardupilot: bool = True, turn_notes=()) -> str:
    """The caption of a recommended plan's figure: the plan, the water depth it used and where
    that came from, its cost and coverage (``cov`` of
    :func:`sss_locus.experiments.survey_design.front.plan_coverage`), the area file with its SHA-256
    and the mission ``files`` beside the figure (without an origin only the CSV, and why; for a
    vehicle that does not run ArduPilot no ArduPilot mission, and why); the cost is the track the
    mission flies (``row.total_m``: lines, U-turns, transits and the return to the start); in
    navigable water (a walled harbour) its clearance, and ``turn_notes`` the turns that did not fit
    (:func:`sss_locus.experiments.survey_design.route.turn_misfits`).

    Parameters
    ----------
    platform : Platform
        The vehicle (``name``, ``turn_radius_m``, ``speed_m_s``, depth limits).
    area : SurveyArea
        The survey area (``name``, ``origin_lonlat``, ``sha256``, navigable water and clearance).
    area_file : str
        The area file's name as shown.
    row : pandas.Series
        The recommended plan (:func:`plan_label`'s columns, ``run_m``, ``total_m`` in m, ``time_h``).
    cov : dict
        Its coverage: shares ``once``, ``twice`` (0–1), ``n_holes`` and the out-of-reach parts
        (:func:`reach_sentence`).
    files : iterable of str
        Names of the mission files written.
    water_depth_m : float
        The water depth the plan used (m).
    depth_source : str
        Where that depth came from, in words.
    ardupilot : bool
        Whether the vehicle runs ArduPilot (its ``.plan``/``.waypoints`` files exist).
    turn_notes : iterable of str
        The turns that did not fit, in words.

    Returns
    -------
    str
        The caption (markdown); lengths in m and km, time in h.
    """
    names = ", ".join(f"`{n}`" for n in files)
    why = ("" if area.origin_lonlat is not None else
           " (the others need longitude/latitude: give the area file an `origin_lonlat`)")
    if area.origin_lonlat is not None and not ardupilot:
        why = (" (no `.plan` or `.waypoints`: this vehicle does not run ArduPilot; convert the CSV or GeoJSON "
               "into its own planner's mission format)")
    return (f"Recommended plan for the {platform.name} over {area.name}: {plan_label(row)}; water depth "
            f"{water_depth_m:.3g} m ({depth_source}); " + (
                f"lines run past the area by their swath's reach and a run-in of {row.run_m:.0f} m; "
                if area.water() is None else
                f"lines, run-ins, turns and transits stay in the navigable water ("
                + ("its navigable outline" if area.navigable_wkt else f"{area.water_beyond_m:g} m past the area's edge")
                + f"), {area.clearance_m:g} m off its edge and holes, line ends pulled back where a turn needs room; "
                "the inclusion fence (red dashed) never reaches past it; ")
            + (f"turns that do not fit: {'; '.join(turn_notes)}; " if turn_notes else "")
            + f"{row.total_m / 1e3:.2f} km flown (the mission's track: lines, turns of radius "
            f"{platform.turn_radius_m:g} m, transits and the return to the start), "
            + f"{row.time_h:.1f} h at {platform.speed_m_s:g} m/s; seen once {fmt_percent(cov['once'])}, twice "
            f"{fmt_percent(cov['twice'])} of the area, gaps (groups of cells seen by no line): {cov['n_holes']}. "
            + reach_sentence(platform, cov) + "Grey dotted: WGS 84 meridians and "
            f"parallels. Area file `{area_file}` "
            f"(SHA-256 `{area.sha256[:12]}`); mission files beside the figure: {names}{why}.")


def reach_sentence(platform, cov: dict) -> str:
    """The part of the area no plan can see (``cov["out_of_reach"]``, its area
    ``cov["out_of_reach_m2"]`` and its parts ``too_deep``, ``too_shallow``:
    :func:`~sss_locus.experiments.survey_design.coverage.out_of_reach`) in one sentence with the
    depths the sonar reaches, ``""`` when there is none.

    Parameters
    ----------
    platform : Platform
        The vehicle (``name``, ``fixed_depth``, ``depth_min_m`` and the sonar's reach).
    cov : dict
        The coverage with ``out_of_reach`` (share 0–1), ``out_of_reach_m2`` (m²), ``too_deep``
        and ``too_shallow`` (shares).

    Returns
    -------
    str
        The sentence (areas in percent and ha, depths in m) ending in a space, or ``""``.
    """
    if float(cov.get("out_of_reach", 0.0)) <= 0:
        return ""
    area_m2 = cov["out_of_reach_m2"] / cov["out_of_reach"]
    part = lambda share: f"{fmt_percent(share)} of the area ({share * area_m2 / 1e4:.2g} ha)"
    if not platform.fixed_depth:
        return (f"{part(cov['out_of_reach'])} lies where the sonar cannot see the seafloor at the plan's altitude; "
                "no plan can see it (dark grey). ")
    low, high = (platform.depth_min_m + v for v in reach_limits_m(platform))
    parts = ([f"{part(cov['too_deep'])} lies deeper than the sonar reaches at {high:.3g} m below the surface"]
             if cov["too_deep"] > 0 else [])
    parts += ([f"{part(cov['too_shallow'])} is shallower than the {low:.3g} m the sonar needs"]
              if cov["too_shallow"] > 0 else [])
    return " and ".join(parts) + f"; no plan can see {'it' if len(parts) == 1 else 'them'} (dark grey). "


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


#: The joint estimate's errors (:data:`~sss_locus.experiments.survey_design.scoring.ERRORS`) in words.
ERROR_LABELS = {"horizontal": "horizontal", "vertical": "vertical", "shape": "map-shape"}


#: Said inside the parentheses of an interval whose lower end was cut at 0
#: (:func:`~sss_locus.experiments.survey_design.scoring.lower_end_cut`).
CUT_NOTE = "lower end cut at 0"


def with_cut_note(text: str, cut: bool) -> str:
    """An estimate with its interval, saying where the interval's lower end was cut at 0.

    Parameters
    ----------
    text : str
        An estimate with its interval in parentheses (:func:`~sss_locus.report.common.text.fmt_ci`).
    cut : bool
        Whether the lower end was cut
        (:func:`~sss_locus.experiments.survey_design.scoring.lower_end_cut`).

    Returns
    -------
    str
        ``"1.6 (95 % CI 0–3.4)"`` -> ``"1.6 (95 % CI 0–3.4, lower end cut at 0)"`` when ``cut``;
        ``text`` unchanged otherwise or without a closing parenthesis.
    """
    return f"{text[:-1]}, {CUT_NOTE})" if cut and text.endswith(")") else text


def error_text(row, name: str = "horizontal") -> str:
    """A plan's mean error ``name`` (of :data:`ERROR_LABELS`) over the seeds with its 95 %
    interval (a row of :func:`~sss_locus.experiments.survey_design.scoring.summarise`), e.g.
    ``"2.6 (95 % CI 2.4–2.8) m"``, or ``"1.6 (95 % CI 0–3.4, lower end cut at 0) m"`` where the
    symmetric interval reached below 0; ``"too few features"`` without an interval.

    Parameters
    ----------
    row : pandas.Series
        A row of ``summarise`` with ``error_<name>_m``, ``error_<name>_lo_m``,
        ``error_<name>_hi_m`` (m).
    name : str
        A key of :data:`ERROR_LABELS`.

    Returns
    -------
    str
        The error with its interval in m, or ``"too few features"``.
    """
    if not math.isfinite(row[f"error_{name}_lo_m"]):
        return "too few features"
    mean, lo, hi = (row[f"error_{name}{s}_m"] for s in ("", "_lo", "_hi"))
    return with_cut_note(fmt_ci(mean, lo, hi), lower_end_cut(mean, lo, hi)) + " m"


def _counts(row) -> str:
    return f"{count_noun(int(row.n_seeds), 'seed')}, at least {count_noun(int(row.min_features), 'feature')} each"


def _beside(row, decided: str) -> str:
    others = [e for e in ERROR_LABELS if e != decided]
    return "; ".join(f"{ERROR_LABELS[e]} {error_text(row, e)}" for e in others)


SAME_LENGTH = 5e-4
"""Tracks whose lengths differ by less than this fraction are "of the same length" in the verdict
(the lawn-mower is spaced by bisection to the standard plan's track length)."""


def _line_compass_deg(heading_deg: float) -> int:
    """A line's compass heading, its two directions as one number in [0, 180) (deg clockwise
    from north; ``heading_deg`` counter-clockwise from east)."""
    return round((90.0 - heading_deg) % 180.0) % 180


def none_as_short(plans: pd.DataFrame) -> str:
    """Why no searched plan could be recommended, when none was: the rule recommends only an
    eligible plan no longer than the standard plan; and, where the headings searched are not the
    standard plan's (which follows the area: its long axis, or the slope), that ``headings_deg``
    cannot force a heading whose lines make a longer track. ``""`` when some searched plan is
    eligible and no longer than the standard plan, or none was searched.

    Parameters
    ----------
    plans : pandas.DataFrame
        The search's plans (``kind``, ``eligible``, ``total_m``, ``heading_deg`` in deg
        counter-clockwise from east, and :func:`plan_label`'s columns).

    Returns
    -------
    str
        One sentence, or ``""``.
    """
    search = plans[plans.kind == "search"]
    std = plans[plans.kind == "standard"].iloc[0]
    if search.empty or (search.eligible.astype(bool) & (search.total_m <= std.total_m)).any():
        return ""
    searched = sorted({_line_compass_deg(h) for h in search.heading_deg})
    n_ok = int(search.eligible.astype(bool).sum())
    text = (f" None of the {len(search)} searched plans could be recommended: {n_ok} of them "
            f"{'sees' if n_ok == 1 else 'see'} enough of the area twice, and none of those is as short as the "
            f"standard plan ({plan_label(std)}); the rule recommends only a plan no longer than the standard plan.")
    if _line_compass_deg(std.heading_deg) not in searched:
        text += (f" The headings searched (lines at {', '.join(f'{a:03d}°/{a + 180:03d}°' for a in searched)}) are "
                 "not the standard plan's, which follows the area (its long axis, or the slope): where such lines make "
                 "a longer track, `headings_deg` cannot force a heading.")
    return text


def noise_verdict_sentence(summary: pd.DataFrame, verdict: dict, plans: pd.DataFrame, platform) -> str:
    """The recommendation with the joint adjustment under the noise model in one or two sentences
    (:func:`sss_locus.experiments.survey_design.scoring.recommend_under_noise`): the deciding
    error of the standard plan and of the best plan with their intervals over the seeds and the
    counts behind them, the other two errors beside, and whether the interval excludes the
    standard plan's.

    Parameters
    ----------
    summary : pandas.DataFrame
        The plans' scores (``summarise``), indexed as ``verdict`` names them.
    verdict : dict
        ``recommend_under_noise``'s verdict: ``standard``, ``best``, ``error``, ``reason``,
        ``holds``.
    plans : pandas.DataFrame
        The plans (:func:`plan_label`'s columns), same index.
    platform : Platform
        The vehicle (its ``name``).

    Returns
    -------
    str
        One to three sentences; errors in m. Where no searched plan was eligible and as short as
        the standard plan, the last one says so (:func:`none_as_short`).
    """
    return _noise_verdict(summary, verdict, plans, platform) + none_as_short(plans)


def _noise_verdict(summary: pd.DataFrame, verdict: dict, plans: pd.DataFrame, platform) -> str:
    name, std = platform.name, summary.loc[verdict["standard"]]
    e = verdict["error"]
    what = f"{ERROR_LABELS[e]} error of the joint estimate"
    if verdict["reason"] == "too few features":
        return (f"For the {name}, some seed gave the standard plan's joint estimate fewer than 30 features (fewest "
                f"{int(std.min_features)}): its errors are not findings and the standard plan is kept.")
    if verdict["reason"] == "the standard plan is the best":
        return (f"For the {name}, no plan as short as the standard plan has a smaller mean {what}: the standard plan "
                f"({error_text(std, e)}; {_beside(std, e)}; {_counts(std)}) is kept.")
    b = summary.loc[verdict["best"]]
    label = plan_label(plans.loc[verdict["best"]])
    longer = b.total_m / std.total_m - 1.0
    length = (f"a track {fmt_percent(abs(longer))} {'shorter' if longer < 0 else 'longer'}"
              if abs(longer) >= SAME_LENGTH else "a track of the same length (within 0.05 %)")
    head = (f"For the {name}, the {'plan' if verdict['holds'] else 'best plan as short as the standard plan'} of "
            f"{label} has a {what} of {error_text(b, e)} ({_beside(b, e)}; {_counts(b)}) against the standard plan's "
            f"{error_text(std, e)} ({_beside(std, e)}; {_counts(std)}), on {length}: ")
    return head + ("its interval lies below the standard plan's, so it is recommended." if verdict["holds"]
                   else "the intervals overlap, so the standard plan is kept.")


def verdict_words(verdicts: dict, platforms: dict) -> str:
    """The claims-page verdict: per platform, whether a plan beat the standard plan on the
    deciding error of the joint estimate, the platforms by their keys (``"a plan beats the
    standard plan on the horizontal error (auv); standard plan kept (boat)"``).

    Parameters
    ----------
    verdicts : dict of str to dict
        Platform key -> its verdict (``holds``, ``error``).
    platforms : dict
        The platforms shown (keys of ``verdicts`` outside it are left out).

    Returns
    -------
    str
        The verdicts, ``"; "``-separated, capitalised.
    """
    parts = [(f"a plan beats the standard plan on the {ERROR_LABELS[v['error']]} error" if v["holds"]
              else "standard plan kept") + f" ({k})" for k, v in verdicts.items() if k in platforms]
    text = "; ".join(parts)
    return text[0].upper() + text[1:]
