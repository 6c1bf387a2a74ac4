"""A waterfall of an XTF file: every channel's pings as an image with ping and sample axes, so
that a user can read the ``ping``, ``channel`` and ``sample`` of a matches file from it.

Samples are drawn as stored (sample 0 on the left of each panel), so that a ``sample`` read
off the axis is what the matches file takes; each panel's title says which end is the near
end (:func:`~sss_locus.experiments.sonar_files.xtf_summary.summary`)."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from sss_locus.experiments.sonar_files.xtf_summary import summary, waterfall_data
from sss_locus.report.common.style import PAGE_WIDTH_IN


def waterfall(path, *, marks: pd.DataFrame | None = None, sample_order: str = "detect", height_in: float = 5.0):
    """One panel per sidescan channel (ping number down, sample as stored across, intensity on
    a log scale); ``marks`` (``channel``, ``ping``, ``sample``, ``label``) are circled and named.
    Returns ``(fig, data)``: ``data`` the marks drawn with the panel they are in.

    Parameters
    ----------
    path : str or path-like
        The XTF file.
    marks : pandas.DataFrame, optional
        Marks to circle: ``channel``, ``ping``, ``sample`` (as stored), ``label``.
    sample_order : str
        How each channel's near end is found: ``"detect"``, ``"near_first"`` or
        ``"port_far_first"`` (:data:`~sss_locus.experiments.sonar_files.sample_order.CHOICES`).
    height_in : float
        Figure height (inches).

    Returns
    -------
    fig : matplotlib.figure.Figure
        A new figure, one panel per sidescan channel.
    data : pandas.DataFrame
        ``marks`` as given (an empty table of its four columns without).
    """
    info = summary(path, sample_order)
    chans = [c for c in info["channels"] if c["type"] in (1, 2)]
    fig, axes = plt.subplots(1, max(len(chans), 1), figsize=(PAGE_WIDTH_IN, height_in), layout="constrained",
                             squeeze=False)
    for ax, c in zip(axes[0], chans):
        numbers, image = waterfall_data(path, c["channel"])
        ax.imshow(np.log1p(np.maximum(image, 0)), aspect="auto", cmap="gray", interpolation="nearest",
                  extent=(-0.5, image.shape[1] - 0.5, numbers[-1] + 0.5, numbers[0] - 0.5))
        near = {"near_first": "near end at sample 0", "far_first": "near end at the last sample"}.get(c.get("order"),
                                                                                                    "near end unknown")
        ax.set_title(f"channel {c['channel']} ({c['side']}): {near}", fontsize=8.5)
        ax.set_xlabel("sample (as stored)")
        if marks is not None:
            m = marks[marks["channel"] == c["channel"]]
            ax.scatter(m["sample"], m["ping"], s=120, facecolors="none", edgecolors="tab:red", linewidths=1.2)
            for r in m.itertuples():
                ax.annotate(str(r.label), (r.sample, r.ping), xytext=(6, -10), textcoords="offset points", color="tab:red",
                            fontsize=8.5, bbox=dict(fc="white", alpha=0.75, lw=0, pad=1))
    axes[0, 0].set_ylabel("ping (PingNumber)")
    cut = f" (truncated at byte {info['truncated_at']}: its complete pings)" if info["truncated"] else ""
    fig.suptitle(f"{info['file']}: {info['n_pings']} pings{cut}", fontsize=9.5)
    return fig, (marks if marks is not None else pd.DataFrame(columns=["channel", "ping", "sample", "label"]))
