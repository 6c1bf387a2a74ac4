"""Shared look of the book's figures: platform names and colours from the data, quantity labels,
and the figure sizes that fit the book's content column.

Nothing here is keyed by a platform's key: a platform's display name is its ``name`` in
``data/platforms.toml`` (or a user's file), and its colour follows its position in that file, so
every chapter draws the same platform in the same colour and a new platform needs no code.

The statistical figures are drawn inside :func:`theme`, the one seaborn theme of the book
(seaborn's ``whitegrid`` style with matplotlib's font sizes, for which the figures are laid out):
the pose-space heatmaps of binned medians and its scatter coloured by a category with seaborn
itself, the median curves with interquartile bands of the survey-pass, planning and noise
chapters with matplotlib in the same theme. The theme is applied per figure (a context manager,
or the :func:`themed` decorator), never globally: importing this module changes no matplotlib
setting.

Where plain matplotlib is clearer than a seaborn function, the figures keep it:

- the rig drawings (:mod:`.rigs`), the 3-D locus concept (:mod:`.concept`) and the terrain
  profiles (:mod:`.reconstruction`) are drawings of geometry, not statistics;
- the median curves with interquartile bands (:mod:`.survey_passes`, :mod:`.planning`,
  :mod:`.noise`) and the bars with intervals (Spearman's rho in :mod:`.pose_space`, the crop
  effects in :mod:`.water`, the stacked shares of :mod:`.three_views`) draw numbers the
  experiments layer computed (the quantiles and replicate intervals that are also each figure's
  CSV data): ``seaborn.lineplot(errorbar=("pi", 50))`` or ``seaborn.barplot`` would compute
  them a second time, from raw samples, in the report layer;
- the heading sweep of :mod:`.three_views` is a grid of computed values on a logarithmic colour
  scale with headings as numeric axes, which ``pcolormesh`` draws directly;
- the noise check's scatter (:mod:`.noise`) shares one legend below four panels, which one
  ``ax.scatter`` per platform gives directly.
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
        :func:`sss_locus.experiments.platforms.load_platforms` order.
    """
    keys = [getattr(p, "key", p) for p in platforms]
    if order is None:
        from ..experiments.platforms import load_platforms

        order = list(load_platforms())
    order = list(order) + [k for k in keys if k not in order]
    return {k: PALETTE[order.index(k) % len(PALETTE)] for k in keys}


def platform_name(platform) -> str:
    """Display name of a platform: its ``name`` in the data file."""
    return platform.name


def platform_title(platform, width: int = 60, prefix: str = "") -> str:
    """``prefix`` plus the platform's display name, wrapped to lines of at most ``width``
    characters (names from the data can be long)."""
    return textwrap.fill(f"{prefix}{platform_name(platform)}", width)

PAGE_WIDTH_IN = 7.8
"""Largest figure width (inches) for the book's content column. A chapter shows a figure at most
660 CSS px wide (the column at a 1280 px window; :mod:`sss_locus.pipeline.readability`), so
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
(:mod:`sss_locus.pipeline.readability`) measures at :data:`PAGE_WIDTH_IN`."""


@contextmanager
def theme() -> Iterator[None]:
    """The book's seaborn theme for the figures created inside the ``with`` block: style
    ``whitegrid``, context ``notebook`` with :data:`THEME_RC`, palette :data:`PALETTE`."""
    import seaborn as sns

    with sns.axes_style("whitegrid", rc=THEME_RC), sns.plotting_context("notebook", rc=THEME_RC), \
            sns.color_palette(list(PALETTE)):
        yield


def themed(fn):
    """Decorator: ``fn`` draws its figure inside :func:`theme`."""
    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        with theme():
            return fn(*args, **kwargs)
    return wrapper
