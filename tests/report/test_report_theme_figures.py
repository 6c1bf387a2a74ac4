"""The statistical figures of the three-views, water and reconstruction chapters, drawn in the
book's theme (sss_locus.report.common.style.theme): what is drawn where, checked against the tables
themselves (quantiles, shares and medians computed here with numpy, not by the report code)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import LogNorm, to_rgba  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

from sss_locus.report.reconstruction.figures import METRIC_LABELS, VIEW_STEPS, plot_views  # noqa: E402
from sss_locus.report.three_views.figures import OUTCOMES, pattern_label, plot_heading_sweep, plot_patterns  # noqa: E402
from sss_locus.report.water.figures import PAPER_COLOR, WATER_COLOR, plot_crop_effects  # noqa: E402

PLATFORMS = [SimpleNamespace(key="a", name="Platform A"), SimpleNamespace(key="b", name="Platform B")]


def _centre_y(artist) -> float:
    """Middle of an artist's vertical extent in data coordinates (a bar, a box or a line)."""
    if isinstance(artist, Rectangle):
        return artist.get_y() + 0.5 * artist.get_height()
    y = artist.get_path().vertices[:, 1] if hasattr(artist, "get_path") else artist.get_ydata()
    return 0.5 * (float(np.min(y)) + float(np.max(y)))


def _pattern_tables(seed: int) -> dict[str, pd.DataFrame]:
    rng = np.random.default_rng(seed)
    out = {}
    for name, n, scale in (("repeat + reciprocal", 101, 5.0), ("two lines + cross line", 57, 40.0),
                           ("three headings 60 deg apart", 80, 45.0)):
        out[name] = pd.DataFrame({"n_valid": rng.choice([0, 1, 1, 1, 2], n),
                                  "plane_angle_deg": scale * rng.lognormal(0, 0.8, n),
                                  "point_error_q95_m": rng.lognormal(-1, 1.2, n)})
    return out


def test_pattern_panels_follow_the_tables():
    tables = {"a": _pattern_tables(1), "b": _pattern_tables(2)}
    fig = plot_patterns(PLATFORMS, tables, 0.01)
    axs = np.array(fig.axes[:6]).reshape(3, 2)
    for j, pf in enumerate(PLATFORMS):
        col = axs[:, j]
        # the patterns on the shared y axis, the tables' first at the top
        where = {t.get_text(): t.get_position()[1] for t in axs[0, 0].get_yticklabels()}
        assert list(where) == [pattern_label(n) for n in tables[pf.key]]
        lo, hi = col[0].get_ylim()
        assert lo > hi and all(hi < y < lo for y in where.values())
        bars = col[0].patches
        for name, t in tables[pf.key].items():
            y = where[pattern_label(name)]
            counts = np.bincount(t.n_valid.to_numpy(), minlength=3) / len(t)
            segments = sorted((p for p in bars if abs(_centre_y(p) - y) < 1e-9), key=lambda p: p.get_x())
            assert [s.get_facecolor() for s in segments] == [to_rgba(c) for _, _, c in OUTCOMES]
            assert [s.get_width() for s in segments] == pytest.approx([counts[v] for _, v, _ in OUTCOMES])
            assert segments[0].get_x() == 0 and segments[-1].get_x() + segments[-1].get_width() == pytest.approx(1)
            for ax, column in ((col[1], "plane_angle_deg"), (col[2], "point_error_q95_m")):
                assert ax.get_xscale() == "log"
                v = np.sort(t[column].to_numpy())
                q1, med, q3 = np.percentile(v, [25, 50, 75])
                p5, p95 = np.percentile(v, [5, 95])  # whiskers: the data's extremes inside 5-95 %
                (box,) = [p for p in ax.patches if abs(_centre_y(p) - y) < 1e-9]
                xs = box.get_path().vertices[:, 0]
                assert (xs.min(), xs.max()) == pytest.approx((q1, q3))
                at_y = [ln for ln in ax.lines if abs(_centre_y(ln) - y) < 0.45 and len(ln.get_xdata())]
                (median,) = [ln for ln in at_y if ln.get_color() == "tab:orange"]
                assert np.allclose(median.get_xdata(), med)
                ends = {float(x) for ln in at_y if ln is not median for x in ln.get_xdata()}
                assert {v[v >= p5].min(), v[v <= p95].max()} <= ends <= {q1, q3, v[v >= p5].min(), v[v <= p95].max()}
    plt.close(fig)


def _sweep(step: float) -> pd.DataFrame:
    h = np.arange(0.0, 180.0 + step / 2, step)
    h2, h3 = np.meshgrid(h, h, indexing="ij")
    keep = h2 <= h3
    s = pd.DataFrame({"heading2_deg": h2[keep], "heading3_deg": h3[keep]})
    s["plane_angle_median_deg"] = 1 + 0.1 * s.heading2_deg + 0.01 * s.heading3_deg
    s["point_error_q95_median_m"] = 10.0 ** (-1 + (s.heading3_deg - s.heading2_deg) / 90)
    return s


@pytest.mark.parametrize("step", [45.0, 15.0])
def test_heading_sweep_cells_and_ticks_follow_the_sweep(step):
    sweep = _sweep(step)
    fig = plot_heading_sweep(PLATFORMS[:1], {"a": sweep}, 0.01)
    heads = np.unique(sweep.heading2_deg)
    for ax, value in zip(fig.axes[:2], ("plane_angle_median_deg", "point_error_q95_median_m")):
        assert ax.get_ylim()[0] < ax.get_ylim()[1]  # pass 3's heading grows upwards
        mesh = ax.collections[0]
        z = np.ma.getdata(mesh.get_array()).reshape(heads.size, heads.size)
        for r in sweep.itertuples():  # cell (row h3, column h2) and its mirror hold the value
            i, j = np.flatnonzero(heads == r.heading2_deg)[0], np.flatnonzero(heads == r.heading3_deg)[0]
            assert z[j, i] == z[i, j] == pytest.approx(getattr(r, value))
        assert isinstance(mesh.norm, LogNorm) == (value == "point_error_q95_median_m")
        for axis in (ax.xaxis, ax.yaxis):  # a tick labelled h at the centre of h's cell
            ticks = [(t.get_loc(), float(t.label1.get_text())) for t in axis.get_major_ticks() if t.label1.get_text()]
            shown = heads if heads.size <= 7 else heads[::2]
            assert [v for _, v in ticks] == list(shown)
            assert [p for p, _ in ticks] == pytest.approx([np.flatnonzero(heads == v)[0] + 0.5 for v in shown])
    plt.close(fig)


def _effects() -> pd.DataFrame:
    rows = []
    for k, label in enumerate(["auv, pose space", "boat, pose space, a long label that wraps", "auv, survey"]):
        for stat, est in (("multi_arc_share_uncropped", 0.02 + 0.05 * k), ("multi_arc_share_cropped", 0.01 * k),
                          ("length_ratio", 0.99 - 0.2 * k)):
            rows.append(dict(label=label, statistic=stat, estimate=est, ci_low=est * 0.8, ci_high=est * 1.1 + 0.001,
                             subset="all", crop="surface", n=100))
    return pd.DataFrame(rows)


def _bars(ax, color):
    """(centre y, width, error-bar x extent) of each bar of ``color`` on ``ax``, top first."""
    out = []
    for c in ax.containers:
        if not hasattr(c, "errorbar") or c.patches[0].get_facecolor() != to_rgba(color):
            continue
        segments = c.errorbar.lines[2][0].get_segments()
        out += [(_centre_y(p), p.get_width(), (s[:, 0].min(), s[:, 0].max())) for p, s in zip(c.patches, segments)]
    return sorted(out, key=lambda b: -b[0])


def test_crop_effect_bars_and_intervals_follow_the_table():
    effects = _effects()
    fig = plot_crop_effects(effects)
    labels = list(dict.fromkeys(effects.label))
    panels = ((fig.axes[0], PAPER_COLOR, "multi_arc_share_uncropped"), (fig.axes[0], WATER_COLOR, "multi_arc_share_cropped"),
              (fig.axes[1], WATER_COLOR, "length_ratio"))
    for ax, color, stat in panels:
        rows = effects[effects.statistic == stat].set_index("label").loc[labels]  # first label at the top
        drawn = _bars(ax, color)
        assert [w for _, w, _ in drawn] == pytest.approx(list(100 * rows.estimate))
        assert [e for _, _, e in drawn] == pytest.approx(list(zip(100 * rows.ci_low, 100 * rows.ci_high)))
    ticks = sorted(fig.axes[0].get_yticklabels(), key=lambda t: -t.get_position()[1])
    assert [t.get_text().replace("\n", " ") for t in ticks] == labels
    plt.close(fig)
    with pytest.raises(ValueError, match="crop must be one of"):
        plot_crop_effects(effects, crop="seafloor")


def test_views_points_are_the_survey_means_in_step_order():
    """The views figure: for each platform one line per error, its points the summary's means in the
    order of VIEW_STEPS (the mosaic first) whatever the row order of the summary."""
    rng = np.random.default_rng(1)
    rows = []
    for key in ("a", "b"):
        for est, _ in VIEW_STEPS:
            row = dict(platform=key, estimator=est)
            for col in METRIC_LABELS:
                m = float(rng.uniform(0.1, 3.0))
                row.update({col: m, f"{col}_low": 0.8 * m, f"{col}_high": 1.2 * m})
            rows.append(row)
    summary = pd.DataFrame(rows)
    fig = plot_views(PLATFORMS, summary.sample(frac=1.0, random_state=2), list(METRIC_LABELS))
    for j, pf in enumerate(PLATFORMS):
        ax = fig.axes[j]
        s = summary[summary.platform == pf.key].set_index("estimator")
        data = [ln for ln in ax.lines if ln.get_linestyle() == "-"]  # not the caps of the bars
        for col, ln in zip(METRIC_LABELS, data):
            assert np.allclose(ln.get_xdata(), np.arange(len(VIEW_STEPS)))
            assert np.allclose(ln.get_ydata(), [s.loc[e, col] for e, _ in VIEW_STEPS])
        assert [t.get_text() for t in ax.get_xticklabels()] == [lab for _, lab in VIEW_STEPS]
        assert VIEW_STEPS[0][0] == "flat"  # the mosaic is the flat point
    plt.close(fig)
