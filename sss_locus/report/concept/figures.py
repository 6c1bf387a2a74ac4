"""The 3-D locus concept figure of the concept chapter (``notebooks/concept.ipynb``).

:func:`concept_data` samples what the figure draws from a
:class:`~sss_locus.geometry.locus.LocusResult` (the intersection circle, the locus arcs and the
two sensor frames) as tables; :func:`plot_locus_concept` draws those tables with both sensors'
range spheres and aperture wedges in sensor 1's frame.
"""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.ticker import MaxNLocator

from sss_locus.report.common.style import SMALL_FONT_PT

AXIS_COLOURS = ("tab:red", "tab:green", "tab:blue")
"""Colours of a sensor's drawn x (boresight), y (left) and z (up) axes."""

SENSOR_COLOURS = ("tab:orange", "tab:purple")
"""Colours of sensor 1's and sensor 2's range spheres and aperture wedges."""

N_CIRCLE = 721
"""Samples of the intersection circle (angle from -pi to pi)."""


def _on_sphere(r: float, theta, phi) -> np.ndarray:
    """Points ``r (cos th cos ph, sin th cos ph, sin ph)`` in a sensor frame, broadcast over
    the angles; shape ``broadcast(theta, phi).shape + (3,)``."""
    theta, phi = np.broadcast_arrays(theta, phi)
    return r * np.stack([np.cos(theta) * np.cos(phi), np.sin(theta) * np.cos(phi), np.sin(phi)], -1)


def concept_data(locus, axes2: np.ndarray, origin2: np.ndarray, r1: float, r2: float, *,
                 n_per_arc: int = 200, names: Sequence[str] = ("sensor 1", "sensor 2"),
                 ) -> dict[str, pd.DataFrame]:
    """The numbers :func:`plot_locus_concept` draws, in sensor 1's frame (metres).

    Parameters
    ----------
    locus : LocusResult
        A single two-view locus (:func:`sss_locus.two_view_locus` with scalar inputs).
    axes2 : numpy.ndarray, shape (3, 3)
        Sensor 2's axes (columns) in sensor 1's frame.
    origin2 : numpy.ndarray, shape (3,)
        Sensor 2's origin in sensor 1's frame.
    r1, r2 : float
        The two measured ranges.
    n_per_arc : int
        Points per locus arc.
    names : sequence of str
        Names of the two sensors (the ``sensor`` column of ``sensors``).

    Returns
    -------
    dict of pandas.DataFrame
        ``circle`` (``alpha_rad``, ``x_m``, ``y_m``, ``z_m``; :data:`N_CIRCLE` samples),
        ``locus`` (``arc``, ``x_m``, ``y_m``, ``z_m``) and ``sensors`` (one row per sensor: name,
        origin, range and ``<a>_axis_<c>``, component ``c`` of its ``a`` axis).
    """
    alpha = np.linspace(-np.pi, np.pi, N_CIRCLE)
    circle = locus.point_at(alpha)
    arcs = locus.points(n_per_arc=n_per_arc)[: int(locus.n_arcs)]
    sensors = [(names[0], np.eye(3), np.zeros(3), r1), (names[1], np.asarray(axes2), np.asarray(origin2), r2)]
    return {
        "circle": pd.DataFrame({"alpha_rad": alpha, "x_m": circle[:, 0], "y_m": circle[:, 1],
                                "z_m": circle[:, 2]}),
        "locus": pd.concat([pd.DataFrame({"arc": k, "x_m": a[:, 0], "y_m": a[:, 1], "z_m": a[:, 2]})
                            for k, a in enumerate(arcs)]  # no arc (an empty locus): no rows
                           or [pd.DataFrame(columns=["arc", "x_m", "y_m", "z_m"])], ignore_index=True),
        "sensors": pd.DataFrame([dict(sensor=n, x_m=o[0], y_m=o[1], z_m=o[2], range_m=r,
                                      **{f"{a}_axis_{c}": axes[i, j] for j, a in enumerate("xyz")
                                         for i, c in enumerate("xyz")})
                                 for n, axes, o, r in sensors]),
    }


def _xyz(frame: pd.DataFrame) -> np.ndarray:
    return frame[["x_m", "y_m", "z_m"]].to_numpy()


def _sensor_axes(row: pd.Series) -> np.ndarray:
    """A :func:`concept_data` sensor row's axes as a matrix (columns: x, y, z axis)."""
    return np.array([[row[f"{a}_axis_{c}"] for a in "xyz"] for c in "xyz"])


def draw_sensor(ax, aperture, axes: np.ndarray, origin: np.ndarray, r: float, colour: str,
                axis_length_m: float = 3.0) -> np.ndarray:
    """One sensor on 3-D axes ``ax``: its range sphere of radius ``r`` (faint wireframe), the part
    inside ``aperture`` (filled), the wedge's edges and the sensor frame (``axes`` columns, at
    ``origin``). Returns the filled cap's points, shape (n, 3), for the axis limits.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D
        3-D axes in sensor 1's frame (m).
    aperture : Aperture
        The sensor's aperture (``half_azimuth_rad``, ``half_elevation_rad``).
    axes : numpy.ndarray, shape (3, 3)
        The sensor's axes (columns x, y, z) in the drawing's frame.
    origin : numpy.ndarray, shape (3,)
        The sensor's origin in the drawing's frame (m).
    r : float
        The measured range (m).
    colour : str
        Colour of its sphere and wedge.
    axis_length_m : float
        Length of the drawn frame's arrows (m).

    Returns
    -------
    numpy.ndarray, shape (n, 3)
        The cap's points (m).
    """
    def world(p):
        return p @ axes.T + origin

    ring = np.linspace(-np.pi, np.pi, 181)
    for ph in np.radians([-60, -30, 0, 30, 60]):
        ax.plot(*world(_on_sphere(r, ring, ph)).T, color=colour, lw=0.5, alpha=0.35, axlim_clip=True)
    for th in np.radians(np.arange(0, 360, 30)):
        ax.plot(*world(_on_sphere(r, th, ring / 2)).T, color=colour, lw=0.5, alpha=0.35, axlim_clip=True)
    th = np.linspace(-aperture.half_azimuth_rad, aperture.half_azimuth_rad, 41)
    ph = np.linspace(-aperture.half_elevation_rad, aperture.half_elevation_rad, 9)
    cap = world(_on_sphere(r, th[:, None], ph[None, :]))
    ax.plot_surface(*np.moveaxis(cap, -1, 0), color=colour, alpha=0.18, linewidth=0, shade=False)
    ax.plot(*np.concatenate([cap[0], cap[:, -1], cap[-1, ::-1], cap[::-1, 0]]).T, color=colour, lw=0.9)
    for corner in (cap[0, 0], cap[0, -1], cap[-1, 0], cap[-1, -1]):
        ax.plot(*np.stack([origin, corner]).T, color=colour, lw=0.7, ls=":")
    for j, c in enumerate(AXIS_COLOURS):
        ax.quiver(*origin, *(axis_length_m * axes[:, j]), color=c, lw=2, arrow_length_ratio=0.2)
    return cap.reshape(-1, 3)


def plot_locus_concept(data: dict[str, pd.DataFrame], aperture, feature: np.ndarray, *,
                       locus_length_m: float, view_elev_deg: float = 20.0,
                       view_azim_deg: float = -80.0, ax=None):
    """The locus concept figure: both sensors (:func:`draw_sensor`, same ``aperture``), the
    intersection circle (dashed), the locus arcs (thick red), the ``feature`` (star) and the
    baseline, from :func:`concept_data` tables; legend states the ranges and
    ``locus_length_m``.

    Parameters
    ----------
    data : dict of str to pandas.DataFrame
        :func:`concept_data` tables.
    aperture : Aperture
        Both sensors' aperture.
    feature : numpy.ndarray, shape (3,)
        The feature in sensor 1's frame, metres.
    locus_length_m : float
        Length of the locus, stated in the legend.
    view_elev_deg, view_azim_deg : float
        Camera elevation and azimuth, degrees.
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D, optional
        3-D axes to draw on (the legend then goes below them); default: a new figure of 8 x 6.4
        in with the legend below the scene.

    Returns
    -------
    matplotlib.figure.Figure
        The figure holding the scene (what :func:`~sss_locus.pipeline.publish.publish.publish` takes).
    """
    circle, sensors = _xyz(data["circle"]), data["sensors"]
    origin2 = _xyz(sensors)[1]
    own = ax is None
    if own:
        fig = plt.figure(figsize=(8, 6.4))
        ax = fig.add_subplot(projection="3d", computed_zorder=False)
    else:
        fig = ax.figure
    caps = [draw_sensor(ax, aperture, _sensor_axes(row), _xyz(sensors)[i], row["range_m"], colour)
            for (i, row), colour in zip(sensors.iterrows(), SENSOR_COLOURS)]
    ax.plot(*circle.T, color="0.3", lw=1.3, ls="--")
    for _, arc in data["locus"].groupby("arc", sort=True):
        ax.plot(*_xyz(arc).T, color="crimson", lw=4, solid_capstyle="round")
    ax.scatter(*feature, marker="*", s=170, color="gold", edgecolor="k", linewidth=0.8,
               depthshade=False, alpha=1.0, zorder=10)
    ax.plot(*np.stack([np.zeros(3), origin2]).T, color="k", lw=0.8, ls="-.")
    for name, origin in zip(sensors["sensor"], _xyz(sensors)):
        ax.text(*(origin + [-1.0, 0.0, 0.0]), name, fontsize=9, ha="right", va="center",
                bbox=dict(boxstyle="round,pad=0.2", fc="white", ec="none", alpha=0.85), zorder=11)

    extent = np.concatenate([circle, *caps, [origin2, np.zeros(3)]])
    lo, hi = extent.min(0) - 1.0, extent.max(0) + 1.0
    ax.set(xlim=(lo[0], hi[0]), ylim=(lo[1], hi[1]), zlim=(lo[2], hi[2]),
           xlabel="$x_1$ (m)", ylabel="$y_1$ (m)", zlabel="$z_1$ (m)")
    ax.set_box_aspect(hi - lo, zoom=1.1)
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(5))
    ax.view_init(elev=view_elev_deg, azim=view_azim_deg)
    handles = [
        *(Patch(color=c, alpha=0.4, label=f"range sphere {k}, $r_{k}$ = {r:.1f} m "
                                          f"(filled: inside aperture {k})")
          for k, (c, r) in enumerate(zip(SENSOR_COLOURS, sensors["range_m"]), start=1)),
        Line2D([], [], color="0.3", ls="--", label="intersection circle (spheres meet)"),
        Line2D([], [], color="crimson", lw=4,
               label=f"ambiguity locus (inside both), {locus_length_m:.1f} m"),
        Line2D([], [], marker="*", color="gold", mec="k", ls="", ms=13, label="feature"),
        Line2D([], [], color="k", lw=0.8, ls="-.", label="baseline"),
        *(Line2D([], [], color=c, lw=2, label=f"sensor ${a}$ axis") for c, a in zip(AXIS_COLOURS, "xyz")),
    ]
    if not own:
        ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=2, fontsize=SMALL_FONT_PT,
                  frameon=False)  # below the scene
        return fig
    fig.legend(handles=handles, loc="lower center", ncol=2, fontsize=9.5, frameon=False)
    fig.subplots_adjust(left=0.0, right=1.0, top=1.05, bottom=0.12)
    return fig


# --- The interactive view (plotly): the same scene, to turn and zoom in a browser. -------------

PLOTLY_JS = "../plotly/plotly.min.js"
"""Where a book page finds plotly.js: the site's own copy (``sss_locus.pipeline.book.bookbuild``)."""


def _lines(points: np.ndarray) -> tuple[list, list, list]:
    """Coordinates of a list of polylines, separated by ``None`` (one plotly trace)."""
    xs, ys, zs = [], [], []
    for line in points:
        for values, coords in zip((xs, ys, zs), np.asarray(line).T):
            values.extend([*coords.tolist(), None])
    return xs, ys, zs


def _sensor_traces(go, aperture, axes: np.ndarray, origin: np.ndarray, r: float, colour: str,
                   k: int) -> list:
    """One sensor's sphere (faint), aperture cap and wedge edges, and frame, as plotly traces."""
    def world(p):
        return p @ axes.T + origin

    th, ph = np.meshgrid(np.linspace(-np.pi, np.pi, 49), np.linspace(-np.pi / 2, np.pi / 2, 25))
    sphere = world(_on_sphere(r, th, ph))
    th = np.linspace(-aperture.half_azimuth_rad, aperture.half_azimuth_rad, 41)
    ph = np.linspace(-aperture.half_elevation_rad, aperture.half_elevation_rad, 9)
    cap = world(_on_sphere(r, th[:, None], ph[None, :]))
    edges = [np.concatenate([cap[0], cap[:, -1], cap[-1, ::-1], cap[::-1, 0]])]
    edges += [np.stack([origin, c]) for c in (cap[0, 0], cap[0, -1], cap[-1, 0], cap[-1, -1])]
    flat = dict(colorscale=[[0, colour], [1, colour]], showscale=False, hoverinfo="skip")
    traces = [
        go.Surface(x=sphere[..., 0], y=sphere[..., 1], z=sphere[..., 2], opacity=0.12,
                   name=f"range sphere {k}, r{k} = {r:.1f} m", legendgroup=f"sphere{k}",
                   showlegend=True, **flat),
        go.Surface(x=cap[..., 0], y=cap[..., 1], z=cap[..., 2], opacity=0.45,
                   name=f"aperture {k} (sphere inside it)", legendgroup=f"aperture{k}",
                   showlegend=True, **flat),
        go.Scatter3d(**dict(zip("xyz", _lines(edges))), mode="lines", legendgroup=f"aperture{k}",
                     showlegend=False, line=dict(color=colour, width=3, dash="dot"), hoverinfo="skip"),
    ]
    for j, (c, a) in enumerate(zip(AXIS_COLOURS, "xyz")):
        end = origin + 3.0 * axes[:, j]
        traces.append(go.Scatter3d(x=[origin[0], end[0]], y=[origin[1], end[1]], z=[origin[2], end[2]],
                                   mode="lines", line=dict(color=c.removeprefix("tab:"), width=6),
                                   name="sensor frames (x red, y green, z blue)", legendgroup="frames",
                                   showlegend=(k == 1 and j == 0), hoverinfo="skip"))
    return traces


def interactive_locus_concept(data: dict[str, pd.DataFrame], aperture, feature: np.ndarray, *,
                              locus_length_m: float):
    """The concept scene of :func:`plot_locus_concept` as a plotly figure: drag to rotate, scroll
    to zoom, click a legend entry to hide or show the spheres, apertures, circle or locus.
    Returns a ``plotly.graph_objects.Figure``.

    Parameters
    ----------
    data : dict of str to pandas.DataFrame
        :func:`concept_data` tables (sensor 1's frame, m).
    aperture : Aperture
        Both sensors' aperture.
    feature : numpy.ndarray, shape (3,)
        The feature in sensor 1's frame (m).
    locus_length_m : float
        The locus length (m), stated in the legend.

    Returns
    -------
    plotly.graph_objects.Figure
        The figure (axes ``x1``, ``y1``, ``z1`` in m, equal aspect).
    """
    import plotly.graph_objects as go

    circle, sensors = _xyz(data["circle"]), data["sensors"]
    traces = []
    for (i, row), colour in zip(sensors.iterrows(), ("darkorange", "rebeccapurple")):
        traces += _sensor_traces(go, aperture, _sensor_axes(row), _xyz(sensors)[i], row["range_m"],
                                 colour, i + 1)
    traces.append(go.Scatter3d(x=circle[:, 0], y=circle[:, 1], z=circle[:, 2], mode="lines",
                               line=dict(color="#4d4d4d", width=4, dash="dash"),
                               name="intersection circle"))
    arcs = [_xyz(arc) for _, arc in data["locus"].groupby("arc", sort=True)]
    traces.append(go.Scatter3d(**dict(zip("xyz", _lines(arcs))), mode="lines",
                               line=dict(color="crimson", width=10),
                               name=f"ambiguity locus, {locus_length_m:.1f} m"))
    traces.append(go.Scatter3d(x=[feature[0]], y=[feature[1]], z=[feature[2]], mode="markers",
                               marker=dict(symbol="diamond", size=6, color="gold",
                                           line=dict(color="black", width=1)), name="feature"))
    fig = go.Figure(traces)
    fig.update_layout(
        scene=dict(xaxis_title="x1 (m)", yaxis_title="y1 (m)", zaxis_title="z1 (m)", aspectmode="data"),
        legend=dict(orientation="h", yanchor="top", y=-0.02, itemclick="toggle"),
        margin=dict(l=0, r=0, t=10, b=0), height=640,
    )
    return fig


def offline_html(fig, div_id: str, plotly_js: str = PLOTLY_JS) -> str:
    """HTML of a plotly figure that loads plotly.js from ``plotly_js`` (the site's copy), not
    from a CDN.

    Parameters
    ----------
    fig : plotly.graph_objects.Figure
        The figure.
    div_id : str
        The HTML id of its ``div`` (stable ids: the same figure, the same page).
    plotly_js : str
        Path of plotly.js as the page sees it; must end in ``.js``.

    Returns
    -------
    str
        An HTML fragment (no ``<html>``), without the plotly logo, responsive.

    Raises
    ------
    ValueError
        When ``plotly_js`` is not a ``.js`` path.
    """
    if not plotly_js.endswith(".js"):
        raise ValueError(f"plotly_js must be the path of a .js file, got {plotly_js!r}")
    return fig.to_html(full_html=False, include_plotlyjs=plotly_js, div_id=div_id,
                       config={"displaylogo": False, "responsive": True})
