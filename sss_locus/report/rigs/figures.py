"""The rig figure of the rigs chapter (``notebooks/rigs.ipynb``): each platform's transducer
frames and aperture frusta, seen top-down and from the stern (the paper's Fig. 2).

:func:`rig_outlines` gives the drawn numbers (frame origins, projected axes, frustum outlines) as a
table; :func:`plot_rigs` draws them, one row of panels per platform; :func:`draw_rig` draws one
panel. Everything comes from :class:`~sss_locus.experiments.datamodel.platforms.Platform` data: a platform
with a fixed depth (a surface vessel) is drawn with a waterline, any other as a round hull of the
transducers' lateral spacing.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.patches import Circle, Rectangle
from scipy.spatial import ConvexHull

from sss_locus.experiments.datamodel import userdata
from sss_locus.experiments.datamodel.platforms import Platform, frustum_points
from sss_locus.report.common.style import PAGE_WIDTH_IN, SMALL_FONT_PT, get_axis, platform_title

AXIS_COLOURS = ("tab:red", "tab:green", "tab:blue")
"""Colours of a transducer's drawn x (boresight), y and z axes."""

VIEWS = {  # (horizontal, vertical) as vehicle-frame directions; port is on the left in both
    "top-down": (np.array([0.0, -1.0, 0.0]), np.array([1.0, 0.0, 0.0])),
    "stern": (np.array([0.0, -1.0, 0.0]), np.array([0.0, 0.0, 1.0])),
}
"""Projections of the two views: page-horizontal and page-vertical vehicle-frame directions."""

VIEW_TITLES = {"top-down": "top-down", "stern": "from the stern"}
"""Panel title of each view."""

SIDE_COLOURS = {"port": "tab:orange", "starboard": "tab:purple"}
"""Frustum colour of each transducer side."""

SURFACE_HULL_WIDTH_M = 0.6
"""Width of the (dashed) hull sketch of a surface vessel; arbitrary, not from the data."""


def _project(p: np.ndarray, view: str) -> np.ndarray:
    h, v = VIEWS[view]
    return np.stack([p @ h, p @ v], axis=-1)


def _transducer_geometry(platform: Platform, view: str, plot_range_m: float,
                         axis_length_m: float) -> list[dict]:
    """Per transducer, in page coordinates of ``view``: origin, axes (3-D and projected) and the
    frustum outline (convex hull of :func:`frustum_points`)."""
    out = []
    for side, tr in platform.transducers.items():
        xy = _project(frustum_points(platform.sonar, tr, plot_range_m), view)
        hull = ConvexHull(xy, qhull_options="QJ")
        axes = tr.rotation.as_matrix().T * axis_length_m  # rows: sensor x, y, z in vehicle frame
        out.append(dict(side=side, origin=_project(tr.position_m, view), axes=axes,
                        axes_2d=[_project(vec, view) for vec in axes], outline=xy[hull.vertices]))
    return out


def _rows(platform: Platform, view: str, plot_range_m: float, axis_length_m: float) -> list[dict]:
    rows = []
    for g in _transducer_geometry(platform, view, plot_range_m, axis_length_m):
        rows.append(dict(view=view, side=g["side"], **{f"origin_{k}": c for k, c in zip("hv", g["origin"])},
                         **{f"{a}_axis_{k}": c for a, d2 in zip("xyz", g["axes_2d"])
                            for k, c in zip("hv", d2)}))
        for k, (hh, vv) in enumerate(g["outline"]):
            rows.append(dict(view=view, side=g["side"], frustum_vertex=k, h=hh, v=vv))
    return rows


def rig_outlines(platforms: Mapping[str, Platform], plot_range_m: Mapping[str, float],
                 axis_length_m: Mapping[str, float]) -> pd.DataFrame:
    """What :func:`plot_rigs` draws, in page coordinates (``h`` to starboard, ``v`` up the page),
    metres: per platform, view and side a row with the frame origin and the projected ``x``,
    ``y``, ``z`` axes, followed by the frustum outline's vertices (``frustum_vertex``, ``h``,
    ``v``). ``plot_range_m`` and ``axis_length_m`` are keyed by platform key.

    Parameters
    ----------
    platforms : mapping of str to Platform
        The platforms by key.
    plot_range_m : mapping of str to float
        Range (m) each platform's frusta are drawn to.
    axis_length_m : mapping of str to float
        Length (m) of each platform's drawn sensor axes.

    Returns
    -------
    pandas.DataFrame
        Columns ``platform``, ``view``, ``side``, ``origin_h``, ``origin_v``,
        ``<x|y|z>_axis_<h|v>`` (frame rows) and ``frustum_vertex``, ``h``, ``v`` (outline rows),
        m; the columns a row does not use are NaN.
    """
    return pd.DataFrame([dict(platform=key, **row) for key, p in platforms.items() for view in VIEWS
                         for row in _rows(p, view, plot_range_m[key], axis_length_m[key])])


def _draw_hull(ax, platform: Platform, view: str) -> None:
    half = 0.5 * (platform.length_m or 1.0)
    if not platform.fixed_depth:  # a submerged hull: round, as wide as the transducer spacing
        d = 2 * platform.transducers["port"].lateral_offset_m
        ax.add_patch(Rectangle((-d / 2, -half), d, 2 * half, fc="0.85", ec="0.3") if view == "top-down"
                     else Circle((0, 0), d / 2, fc="0.85", ec="0.3"))
    elif view == "top-down":
        w = SURFACE_HULL_WIDTH_M
        ax.add_patch(Rectangle((-w / 2, -half), w, 2 * half, fc="0.85", ec="0.3", ls="--"))
    else:
        ax.axhline(0.0, color="tab:cyan", lw=1)
        ax.text(0.98, 0.97, "waterline", color="tab:cyan", transform=ax.transAxes,
                ha="right", va="top", fontsize=SMALL_FONT_PT)


def hull_size(platform: Platform) -> str:
    """The hull sketch's size as drawn by :func:`draw_rig`, e.g. ``"0.19 m by 1.75 m"``.

    Parameters
    ----------
    platform : Platform
        The platform (``length_m``, ``fixed_depth``, the port transducer's ``lateral_offset_m``).

    Returns
    -------
    str
        The size in m, in words.
    """
    length = f"{platform.length_m:g} m" if platform.length_m else "1 m (length not in the data)"
    if platform.fixed_depth:
        return f"{length} long, width drawn arbitrarily"
    return f"{2 * platform.transducers['port'].lateral_offset_m:g} m by {length}"


def draw_rig(platform: Platform, view: str, plot_range_m: float, axis_length_m: float, ax=None):
    """One panel: hull sketch, each transducer's frustum (filled, to ``plot_range_m``) and frame
    (``x``, ``y``, ``z`` arrows of ``axis_length_m``; an axis along the line of sight is a ring
    with a dot, toward the viewer, or a cross, away). ``view`` is a key of :data:`VIEWS`.
    Returns the axes.

    Parameters
    ----------
    platform : Platform
        The platform (vehicle frame: ``x`` forward, ``y`` to port, ``z`` up; m).
    view : str
        A key of :data:`VIEWS`.
    plot_range_m : float
        Range (m) the frusta are drawn to.
    axis_length_m : float
        Length (m) of the sensor axes' arrows.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: the current axes, :func:`~sss_locus.report.common.style.get_axis`).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on (equal aspect, m).
    """
    ax = get_axis(ax)
    h, v = VIEWS[view]
    toward_viewer = np.cross(h, v)  # unit vector pointing out of the page
    _draw_hull(ax, platform, view)
    for g in _transducer_geometry(platform, view, plot_range_m, axis_length_m):
        colour = SIDE_COLOURS[g["side"]]
        ax.fill(*g["outline"].T, color=colour, alpha=0.25, lw=1.0, ec=colour, label=f"{g['side']} frustum")
        o = g["origin"]
        for vec, d2, c in zip(g["axes"], g["axes_2d"], AXIS_COLOURS):
            if np.hypot(*d2) > 0.15 * axis_length_m:
                ax.annotate("", xy=o + d2, xytext=o, arrowprops=dict(arrowstyle="-|>", color=c, lw=1.6))
            else:  # along the line of sight: dot = toward the viewer, cross = away
                toward = vec @ toward_viewer > 0
                ax.plot(*o, marker="o", ms=8, mfc="white", mec=c, mew=1.6)
                ax.plot(*o, marker="." if toward else "x", ms=6 if toward else 5, color=c, mew=1.6)
    for name, c in zip("xyz", AXIS_COLOURS):
        ax.plot([], [], color=c, lw=1.6, label=f"sensor {name} axis")
    ax.set_aspect("equal")
    ax.set_xlabel("port  ←  −y (m)  →  starboard")
    ax.set_ylabel("x (m), bow up" if view == "top-down" else "z (m), up")
    ax.grid(alpha=0.3)
    ax.autoscale_view()
    return ax


def plot_rigs(platforms: Mapping[str, Platform], plot_range_m: Mapping[str, float],
              axis_length_m: Mapping[str, float]):
    """The rig figure: one row per platform (in the data's order), top-down (left) and from the
    stern (right), each panel titled with its letter, the platform's name and the view;
    ``plot_range_m`` and ``axis_length_m`` are keyed by platform key. Returns the figure.

    Parameters
    ----------
    platforms : mapping of str to Platform
        The platforms by key, in the data's order.
    plot_range_m : mapping of str to float
        Range (m) each platform's frusta are drawn to.
    axis_length_m : mapping of str to float
        Length (m) of each platform's drawn sensor axes.

    Returns
    -------
    matplotlib.figure.Figure
        A new figure of ``len(platforms)`` x ``len(VIEWS)`` panels, legend below.
    """
    fig, axs = plt.subplots(len(platforms), len(VIEWS), figsize=(PAGE_WIDTH_IN, 4.2 * len(platforms)),
                            constrained_layout=True, squeeze=False)
    for r, (key, p) in enumerate(platforms.items()):
        for c, view in enumerate(VIEWS):
            draw_rig(p, view, plot_range_m[key], axis_length_m[key], ax=axs[r, c])
            letter = chr(ord("a") + len(VIEWS) * r + c)
            axs[r, c].set_title(f"{platform_title(p, 38, prefix=f'({letter}) ')}\n{VIEW_TITLES[view]}",
                                fontsize=9)
    handles, labels = axs[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=3, fontsize=SMALL_FONT_PT)
    return fig


def coverage_text(platforms: Mapping[str, Platform]) -> str:
    """One sentence per platform: its port transducer's tilt (with whether the data give a source
    or an assumption for it), fan and the elevation angles the fan spans (MyST, for gluing).

    Parameters
    ----------
    platforms : mapping of str to Platform
        The platforms by key (their sonar's ``azimuth_deg``, the port transducer's ``tilt_deg`` and
        its provenance).

    Returns
    -------
    str
        The sentences, angles in degrees.
    """
    out = []
    for key, p in platforms.items():
        t = p.transducers["port"]
        note = p.provenance.get(f"platforms.{key}.transducers.port.tilt_deg", "")
        kind = "assumed" if note.startswith("assumption") else "documented" if note.startswith("source") \
            else "stated"
        top, bottom = p.sonar.azimuth_deg / 2 - t.tilt_deg, t.tilt_deg + p.sonar.azimuth_deg / 2
        where = ("the horizontal" if top == 0 else f"{top:g}° above the horizontal" if top > 0
                 else f"{-top:g}° below the horizontal")
        past = " (past nadir at 90°)" if bottom > 90 else ""
        article = "an" if kind[0] in "aeiou" else "a"
        out.append(f"{p.name}: {article} {kind} {t.tilt_deg:g}° look-down with a {p.sonar.azimuth_deg:g}° fan "
                   f"spans from {where} to {bottom:g}° below it{past}.")
    return " ".join(out)


def data_sources(platform_keys: Iterable[str], inputs: userdata.DataInputs | None = None) -> str:
    """The data files the drawn platforms and their sonars come from, for the caption: the ones
    the figure's manifest lists (:func:`~sss_locus.experiments.datamodel.userdata.figure_record`), shipped
    files by their repository path, a user's file by its name.

    Parameters
    ----------
    platform_keys : iterable of str
        The platforms drawn.
    inputs : DataInputs, optional
        A user's data files (default: the shipped ones).

    Returns
    -------
    str
        The files joined by ``" and "``.
    """
    files = userdata.figure_record(list(platform_keys), inputs, read=set())["files"]
    return " and ".join(f["path"] if f["role"] == "shipped" else Path(f["path"]).name for f in files)
