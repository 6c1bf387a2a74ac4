"""The seaborn figures of the pose-space chapter (sss_locus.report.pose_space.figures) and the book's theme
(sss_locus.report.common.style.theme): what is drawn where, checked against the binned table itself."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from sss_locus.experiments.pose_space.stats import HEATMAP_PANELS, binned_median  # noqa: E402
from sss_locus.report.pose_space.figures import plot_heatmaps, plot_sensitivity  # noqa: E402
from sss_locus.report.common.style import theme  # noqa: E402


def _maps():
    rng = np.random.default_rng(4)
    n = 4000
    df = pd.DataFrame({"x": rng.uniform(-60, 60, n), "y": rng.uniform(10, 100, n)})
    df["locus_length_m"] = 0.01 * (df.x + 60) + 0.001 * df.y  # grows to the right and upwards
    xe, ye = np.linspace(-60, 60, 9), np.array([10.0, 20.0, 40.0, 70.0, 100.0])  # uneven y bins
    binned = binned_median(df, "x", "y", x_edges=xe, y_edges=ye, min_count=10)
    binned.loc[0, "masked"] = True  # the lowest-left bin hidden
    return {p: binned for p, _, _ in HEATMAP_PANELS}, xe, ye, binned


def test_heatmap_cells_and_ticks_follow_the_binned_table():
    maps, xe, ye, binned = _maps()
    fig = plot_heatmaps(maps)
    ax = fig.axes[0]
    # y grows upwards: the first row of cells (the lowest y bin) at the bottom
    assert ax.get_ylim()[0] < ax.get_ylim()[1] and min(ax.get_ylim()) == 0
    mesh = ax.collections[0]
    shape = (len(ye) - 1, len(xe) - 1)
    drawn = np.ma.masked_array(np.ma.getdata(mesh.get_array()).reshape(shape),
                               mask=np.ma.getmaskarray(mesh.get_array()).reshape(shape))
    for _, row in binned.iterrows():  # cell (i, j): x bin i at columns [i, i + 1), y bin j at rows [j, j + 1)
        i, j = int(np.searchsorted(xe, row.x_lo)), int(np.searchsorted(ye, row.y_lo))
        if row.masked:
            assert drawn.mask[j, i]
        else:
            assert drawn[j, i] == pytest.approx(row["median"])
    # a tick labelled v sits inside the cell whose bin holds v, at v's place within it
    for axis, edges in ((ax.xaxis, xe), (ax.yaxis, ye)):
        ticks = [(t.get_loc(), float(t.label1.get_text().replace("\N{MINUS SIGN}", "-")))
                 for t in axis.get_major_ticks() if t.label1.get_text()]
        assert len(ticks) >= 3
        for pos, v in ticks:
            k = min(int(np.searchsorted(edges, v, side="right")) - 1, len(edges) - 2)
            assert pos == pytest.approx(k + (v - edges[k]) / (edges[k + 1] - edges[k]))
    plt.close(fig)


def test_theme_is_per_figure_and_the_scatter_keeps_every_point():
    before = dict(plt.rcParams)
    with theme():
        assert plt.rcParams["axes.grid"]
    rng = np.random.default_rng(1)
    subset = pd.DataFrame({"elevation_misalignment_deg": rng.uniform(0, 80, 300),
                           "locus_length_normalized": rng.lognormal(-5, 1, 300),
                           "n_arcs": np.where(np.arange(300) % 10 == 0, 2, 1)})
    rho = pd.DataFrame({"target": ["locus_length_m", "locus_length_normalized"], "quantity": ["r1_m"] * 2,
                        "rho": [0.5, -0.2], "ci_low": [0.4, -0.3], "ci_high": [0.6, -0.1]})
    fig = plot_sensitivity(rho, subset)
    assert dict(plt.rcParams) == before  # drawing in the theme left no setting behind
    points = fig.axes[2].collections[0].get_offsets()
    assert len(points) == 300
    fragmented = subset[subset.n_arcs > 1]
    drawn_last = points[-len(fragmented):]  # fragmented loci drawn on top of the others
    assert np.allclose(np.sort(drawn_last[:, 0]), np.sort(fragmented.elevation_misalignment_deg))
    labels = [t.get_text() for t in fig.axes[2].get_legend().texts]
    assert labels == ["one arc", "several arcs (fragmented)"]
    plt.close(fig)
