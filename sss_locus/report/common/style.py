"""Shared look of the book's figures: platform names and colours from the data, quantity labels,
and the figure sizes that fit the book's content column.

Nothing here is keyed by a platform's key: a platform's display name is its ``name`` in
``data/platforms.toml`` (or a user's file), and its colour follows its position in that file, so
every chapter draws the same platform in the same colour and a new platform needs no code.

The statistical figures are drawn inside :func:`theme`, the one seaborn theme of the book
(seaborn's ``whitegrid`` style with matplotlib's font sizes, for which the figures are laid out).
With seaborn itself: the heatmaps (binned medians of the pose-space chapter, the heading sweep of
:mod:`~sss_locus.report.three_views.figures`; both through :func:`upward_heatmap`), the pose-space scatter coloured by a
category and the three-view distributions (``seaborn.boxplot``). With matplotlib in the same
theme, where a seaborn function would be less clear or would compute the numbers again:

- the median curves with interquartile bands (:mod:`~sss_locus.report.survey_passes.figures`, :mod:`~sss_locus.report.survey_passes.planning`,
  :mod:`~sss_locus.report.noise.figures`), the median curves of :mod:`~sss_locus.report.reconstruction.figures` and the bars with intervals
  (Spearman's rho in :mod:`~sss_locus.report.pose_space.figures`, the crop effects in :mod:`~sss_locus.report.water.figures`) draw numbers the
  experiments layer computed (the quantiles, medians and replicate intervals that are also each
  figure's CSV data): ``seaborn.lineplot(errorbar=("pi", 50))`` or ``seaborn.barplot`` would
  compute them a second time, from raw samples, in the report layer;
- the stacked outcome shares of :mod:`~sss_locus.report.three_views.figures` (seaborn has no stacked bar of given shares);
- the noise check's scatter (:mod:`~sss_locus.report.noise.figures`) shares one legend below four panels, which one
  ``ax.scatter`` per platform gives directly; the survey-design front (:mod:`~sss_locus.report.survey_design.figures`)
  gives each kind of plan its own marker, size and fill, not one hue.

The theme is applied per figure (a context manager, or the :func:`themed` decorator), never
globally: importing this module changes no matplotlib setting. Drawings of geometry stay plain
matplotlib, outside the theme (a statistical grid would only clutter them): the rig drawings
(:mod:`~sss_locus.report.rigs.figures`), the 3-D locus concept (:mod:`~sss_locus.report.concept.figures`), the survey plan map of
:mod:`~sss_locus.report.survey_design.figures` and the maps of a user's survey (:mod:`~sss_locus.report.your_pings.figures`).
"""

from __future__ import annotations

import functools
import textwrap
from collections.abc import Iterable, Iterator
from contextlib import contextmanager

PALETTE = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown",
           "tab:pink", "tab:olive", "tab:cyan", "tab:gray")
"""Platform colours, in the order the platforms appear in the data (matplotlib's tab10)."""

QUANTITY_LABELS = {
    "r1_m": "range $r_1$", "r2_m": "range $r_2$", "mean_range_m": "mean range",
    "baseline_m": "baseline $|t|$", "elevation_misalignment_deg": "elevation misalignment",
    "abs_psi1_deg": r"$|\psi_1|$", "abs_psi2_deg": r"$|\psi_2|$",
    "azimuth1_deg": r"azimuth $\theta_1$", "azimuth2_deg": r"azimuth $\theta_2$",
    "abs_elevation1_deg": r"$|\phi_1|$", "abs_elevation2_deg": r"$|\phi_2|$",
    "abs_yaw2_deg": "|yaw of vehicle 2|", "pitch2_deg": "pitch of vehicle 2",
    "abs_pitch2_deg": "|pitch of vehicle 2|",
}
"""Display names (matplotlib mathtext) of the pose-space quantities."""

AXIS_LABELS = {
    "locus_length_m": "locus length (m)",
    "elevation_misalignment_deg": "elevation misalignment (deg)",
}
"""Axis labels with units of the survey-pass quantities."""


def platform_colors(platforms: Iterable, order: Iterable[str] | None = None) -> dict[str, str]:
    """Colour of each platform: its position in ``order`` (default: the data file's order of
    the given platforms' keys) picks an entry of :data:`PALETTE`.

    Parameters
    ----------
    platforms : iterable of Platform or str
        Platforms (objects with ``key``) or their keys.
    order : iterable of str, optional
        All platform keys in data-file order; default
        :func:`sss_locus.experiments.datamodel.platforms.load_platforms` order.

    Returns
    -------
    dict of str to str
        Platform key -> matplotlib colour name; keys not in ``order`` come after it.
    """
    keys = [getattr(p, "key", p) for p in platforms]
    if order is None:
        from sss_locus.experiments.datamodel.platforms import load_platforms

        order = list(load_platforms())
    order = list(order) + [k for k in keys if k not in order]
    return {k: PALETTE[order.index(k) % len(PALETTE)] for k in keys}


def platform_name(platform) -> str:
    """Display name of a platform: its ``name`` in the data file.

    Parameters
    ----------
    platform : Platform
        The platform (its ``name``).

    Returns
    -------
    str
        The display name.
    """
    return platform.name


def platform_title(platform, width: int = 60, prefix: str = "") -> str:
    """``prefix`` plus the platform's display name, wrapped to lines of at most ``width``
    characters (names from the data can be long).

    Parameters
    ----------
    platform : Platform
        The platform (its ``name``).
    width : int
        Largest line length (characters).
    prefix : str
        Text before the name (e.g. a panel letter ``"(a) "``).

    Returns
    -------
    str
        The title, lines joined by newlines.
    """
    return textwrap.fill(f"{prefix}{platform_name(platform)}", width)

PAGE_WIDTH_IN = 7.8
"""Largest figure width (inches) for the book's content column. A chapter shows a figure at most
660 CSS px wide (the column at a 1280 px window; :mod:`sss_locus.pipeline.publish.readability`), so
``size_pt`` text appears ``size_pt / 72 * 660 / width_in`` px: at 7.8 in, 10 pt is 11.8 px and
8.5 pt (the smallest used) 10 px; the readability test fails below 9 px."""

SMALL_FONT_PT = 8.5
"""Font size of legends and annotations (the smallest text of the book's figures)."""


THEME_RC = {
    "font.size": 10.0, "axes.labelsize": 10.0, "axes.titlesize": 12.0,
    "xtick.labelsize": 10.0, "ytick.labelsize": 10.0, "legend.fontsize": 10.0,
    "legend.title_fontsize": 10.0, "grid.color": "0.88", "axes.edgecolor": "0.3",
}
"""Settings of :func:`theme` over seaborn's ``whitegrid`` style and ``notebook`` context: the
font sizes of matplotlib's defaults, for which the book's figures are sized (10 pt labels, 12 pt
titles; legends that want less pass :data:`SMALL_FONT_PT`), and which the readability check
(:mod:`sss_locus.pipeline.publish.readability`) measures at :data:`PAGE_WIDTH_IN`."""


@contextmanager
def theme() -> Iterator[None]:
    """The book's seaborn theme for the figures created inside the ``with`` block: style
    ``whitegrid``, context ``notebook`` with :data:`THEME_RC`, palette :data:`PALETTE`.

    Yields
    ------
    None
        Inside the block, the theme's settings apply; after it, the previous ones.
    """
    import seaborn as sns

    with sns.axes_style("whitegrid", rc=THEME_RC), sns.plotting_context("notebook", rc=THEME_RC), \
            sns.color_palette(list(PALETTE)):
        yield


def themed(fn):
    """Decorator: ``fn`` draws its figure inside :func:`theme`.

    Parameters
    ----------
    fn : callable
        A function that creates and draws a figure.

    Returns
    -------
    callable
        ``fn`` wrapped (name and docstring kept).
    """
    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        with theme():
            return fn(*args, **kwargs)
    return wrapper


def get_axis(ax=None, figsize: tuple[float, float] | None = None):
    """The axes a one-panel plot function draws on (the pattern of xarray's ``plot.utils.get_axis``).

    Parameters
    ----------
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; returned as given.
    figsize : (float, float), optional
        Size in inches of a new figure with one axes, when ``ax`` is ``None``.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``; else the axes of a new figure of ``figsize``; else the current axes
        (``plt.gca()``, a new figure if there is none).
    """
    import matplotlib.pyplot as plt

    if ax is not None:
        if figsize is not None:
            raise ValueError("give either ax or figsize, not both")
        return ax
    if figsize is not None:
        return plt.figure(figsize=figsize, layout="constrained").add_subplot()
    return plt.gca()


def upward_heatmap(ax, z, **kwargs):
    """``seaborn.heatmap`` of ``z`` (shape ``(n_y, n_x)``, NaN cells blank on grey) on ``ax`` with
    row 0 at the bottom (``y`` increasing upwards, as on a numeric axis) and no grid, without a
    colour bar (add one with ``fig.colorbar(mesh, ax=ax)``); returns the mesh. Cell ``(j, i)``
    spans ``[i, i + 1] x [j, j + 1]``: the caller puts ticks at the values its cells stand for.
    ``kwargs`` go to ``seaborn.heatmap`` (``cmap``, ``norm``, ``square``, ...).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes to draw on.
    z : numpy.ndarray, shape (n_y, n_x)
        Cell values, NaN for blank cells.
    **kwargs
        Passed to ``seaborn.heatmap``.

    Returns
    -------
    matplotlib.collections.QuadMesh
        The heatmap's mesh (for a colour bar).
    """
    import numpy as np
    import seaborn as sns

    fig = ax.figure
    layout = fig.get_layout_engine()
    fig.set_layout_engine("none")  # seaborn draws the figure once per heatmap: without the layout
    try:  # pass, a fraction of the time
        sns.heatmap(z, mask=np.isnan(z), ax=ax, cbar=False, **kwargs)
    finally:
        fig.set_layout_engine(layout)
    ax.invert_yaxis()
    ax.set_facecolor("0.85")
    ax.grid(False)
    return ax.collections[-1]
