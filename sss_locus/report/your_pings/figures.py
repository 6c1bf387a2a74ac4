"""Figures and sentences of the your-pings chapter (``notebooks/your_pings.ipynb``): a plan view
of a user's sightings and estimates, the disagreement of the flat-seafloor positions, and an
interactive 3-D view (plotly, offline). Inputs are the tables of
:func:`sss_locus.experiments.your_pings.study.analyse` (local frame, metres).

Plain matplotlib, outside the book's seaborn theme: the figures are maps of one survey's sensors,
sightings, loci and estimates in metres, drawings of geometry like the rigs
(:mod:`sss_locus.report.rigs.figures`), where each feature is named beside its own marks; the bars of
the plan view's right panel share its legend and belong with the map."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.colors import to_hex
from matplotlib.patches import Ellipse

from sss_locus.experiments.your_pings.views import ONE_SIGHTING, excluded_sentence
from sss_locus.report.common.style import PAGE_WIDTH_IN, platform_title
from sss_locus.report.common.text import count_noun, fmt_sig

ESTIMATES = {"flat": ("flat seafloor, mean of the sightings", "black", "s"),
             "two_view": ("two views, best pair (non-empty locus only)", "tab:orange", "^"),
             "nview": ("N views, least squares (1-sigma ellipse x 3)", "tab:blue", "D"),
             "joint": ("joint adjustment (1-sigma ellipse x 3)", "tab:green", "o")}
ELLIPSES = {"nview": "ellipse", "joint": "joint_ellipse"}
"""The estimators drawn with their ellipses: the prefix of their ellipse columns."""
MIN_HALF_WIDTH_M = 1.0
"""A feature's panel shows at least this far (m) around its flat-seafloor mean."""
ELLIPSE_SCALE = 3.0
"""The drawn ellipses are this many standard deviations (1-sigma ones would be invisible)."""


def truth_label(notice: str = "") -> str:
    """The legend's name of the truth: ``"truth (synthetic example)"`` for the chapter's worked
    example (``notice``), plain ``"truth (known positions)"`` for a user's own truth file.

    Parameters
    ----------
    notice : str
        The worked example's notice (e.g. ``"synthetic example"``); ``""`` for a user's truth.

    Returns
    -------
    str
        The legend entry.
    """
    return f"truth ({notice})" if notice else "truth (known positions)"


def plan_view(res, platform, *, truth: pd.DataFrame | None = None, notice: str = ""):
    """Left: the survey in plan (grid east/north): the sensors at each sighting and every
    feature's estimates; right, per feature: the horizontal distance of each estimate from the
    truth (with ``truth``) or of the flat-seafloor mean from the best estimate (N views, else two
    views). Returns ``(fig, data)``.

    Parameters
    ----------
    res : PingResults
        The run's results (:func:`~sss_locus.experiments.your_pings.study.analyse`): ``features`` and
        ``sightings`` tables with ``*_east_m``/``*_north_m`` columns in the local frame (m).
    platform : Platform
        The platform, named in the title.
    truth : pandas.DataFrame, optional
        Known positions: ``feature``, ``east_m``, ``north_m``, ``up_m`` (local frame, m).
    notice : str
        Notice of a worked example, in the title and the truth's label.

    Returns
    -------
    fig : matplotlib.figure.Figure
        A new figure of two panels, legend below.
    data : pandas.DataFrame
        The bars drawn: ``feature``, ``estimator``, ``distance_h_m``, ``distance_up_m`` (m).
    """
    f, s = res.features, res.sightings
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(PAGE_WIDTH_IN, 4.2), width_ratios=(1.2, 1.0), layout="constrained")
    ax.scatter(s["sensor_east_m"], s["sensor_north_m"], s=6, c="0.6", marker=".", label="sensor at each sighting")
    for key, (name, colour, marker) in _drawn(f):
        g = drawn(f, key)
        ax.scatter(g[f"{key}_east_m"], g[f"{key}_north_m"], s=22, c=colour, marker=marker, label=name, zorder=3)
    if "joint_east_m" in f:
        for _, r in f.iterrows():
            _ellipse(ax, r, "joint", 0.0, 0.0)
    if truth is not None:
        ax.scatter(truth["east_m"], truth["north_m"], s=40, c="gold", marker="*", edgecolors="k", linewidths=0.4,
                   label=truth_label(notice), zorder=4)
    for _, r in f.iterrows():
        ax.annotate(r["feature"] + ("\n(" + ONE_SIGHTING + ")" if r["n_sightings"] == 1 else ""),
                    (r["flat_east_m"], r["flat_north_m"]), xytext=(4, 4), textcoords="offset points",
                    fontsize=8.5)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("grid east (m)")
    ax.set_ylabel("grid north (m)")
    data = _distances(res, truth)
    y = np.arange(len(f))
    keys = [k for k in ESTIMATES if k in set(data["estimator"])]
    for j, key in enumerate(keys):
        d = data[data["estimator"] == key].set_index("feature").reindex(f["feature"])
        bx.barh(y + (j - (len(keys) - 1) / 2) * 0.8 / len(keys), d["distance_h_m"], height=0.8 / len(keys),
                color=ESTIMATES[key][1])
    if not len(data):
        why = ("every feature seen once\n(" + ONE_SIGHTING + ")" if (f["n_sightings"] == 1).all()
               else "no feature has an N-view position\nor a non-empty two-view locus")
        bx.text(0.5, 0.5, "no second estimate to compare with:\n" + why, ha="center", va="center",
                transform=bx.transAxes, fontsize=8.5)
    bx.set_yticks(y, f["feature"])
    bx.invert_yaxis()
    bx.set_xlabel("horizontal error against the truth (m)" if truth is not None
                  else "flat-seafloor mean minus best estimate (m)")
    fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncol=2, fontsize=8.5, frameon=False)
    fig.suptitle(platform.name + (f" ({notice})" if notice else ""), fontsize=9.5)
    return fig, data


def feature_panels(res, *, truth: pd.DataFrame | None = None, max_features: int = 12, notice: str = ""):
    """One small plan view per feature (up to ``max_features``), centred on its flat-seafloor
    mean: each sighting's flat-seafloor position, the two-view locus, the estimates, the N-view
    ellipse (x3) and the truth (named by :func:`truth_label` of ``notice``). Returns ``(fig, data)``
    (the positions drawn, relative).

    Parameters
    ----------
    res : PingResults
        The run's results (``features``, ``sightings`` and ``locus`` tables, local frame, m).
    truth : pandas.DataFrame, optional
        Known positions: ``feature``, ``east_m``, ``north_m`` (local frame, m).
    max_features : int
        Largest number of panels (the first features of ``res.features``).
    notice : str
        Notice of a worked example, in the truth's label.

    Returns
    -------
    fig : matplotlib.figure.Figure
        A new figure of up to four panels a row, legend below.
    data : pandas.DataFrame
        The sightings drawn: ``feature``, ``line``, ``flat_east_m``, ``flat_north_m`` (m from the
        feature's flat-seafloor mean).
    """
    f = res.features.head(max_features)
    n = len(f)
    cols = min(4, n)
    rows = int(np.ceil(n / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(PAGE_WIDTH_IN, 1.95 * rows + 0.9), layout="constrained", squeeze=False)
    out = []
    for ax, (_, r) in zip(axes.ravel(), f.iterrows()):
        e0, n0 = r["flat_east_m"], r["flat_north_m"]
        sg = res.sightings[res.sightings["feature"] == r["feature"]]
        ax.scatter(sg["flat_east_m"] - e0, sg["flat_north_m"] - n0, s=12, facecolors="none", edgecolors="0.3",
                   linewidths=0.7, label="flat seafloor, each sighting")
        for _, arc in res.locus[res.locus["feature"] == r["feature"]].groupby("arc"):
            ax.plot(arc["east_m"] - e0, arc["north_m"] - n0, color="tab:red", lw=2)
        for key, (name, colour, marker) in _drawn(f):
            g = drawn(r.to_frame().T, key)
            ax.scatter(g[f"{key}_east_m"].astype(float) - e0, g[f"{key}_north_m"].astype(float) - n0, s=28, c=colour,
                       marker=marker, label=name, zorder=3)
        for key, _ in _drawn(f, ELLIPSES):
            _ellipse(ax, r, key, e0, n0)
        if truth is not None and r["feature"] in set(truth["feature"]):
            t = truth.set_index("feature").loc[r["feature"]]
            ax.scatter([t["east_m"] - e0], [t["north_m"] - n0], s=60, c="gold", marker="*", edgecolors="k",
                       linewidths=0.4, label=truth_label(notice), zorder=4)
        ax.set_title(f"{r['feature']}: {panel_status(r)}", fontsize=8.5)
        ax.update_datalim([[-MIN_HALF_WIDTH_M, -MIN_HALF_WIDTH_M], [MIN_HALF_WIDTH_M, MIN_HALF_WIDTH_M]])
        ax.autoscale_view()
        ax.set_aspect("equal", adjustable="datalim")
        ax.tick_params(labelsize=8.5)
        out.append(sg[["feature", "line", "flat_east_m", "flat_north_m"]].assign(flat_east_m=lambda d: d.flat_east_m - e0,
                                                                              flat_north_m=lambda d: d.flat_north_m - n0))
    for ax in axes.ravel()[n:]:
        ax.set_visible(False)
    for k, ax in enumerate(axes.ravel()[:n]):
        if k + cols >= n:  # the lowest panel of its column
            ax.set_xlabel("grid east (m)", fontsize=8.5)
    if rows > 1:
        fig.supylabel("grid north from the flat mean (m)", fontsize=9)
    else:  # a figure-high label of one row of panels would run into the legend below them
        axes[0, 0].set_ylabel("grid north from\nthe flat mean (m)", fontsize=8.5)
    handles, labels = axes.ravel()[0].get_legend_handles_labels()
    handles.insert(1, plt.Line2D([], [], color="tab:red", lw=2))
    labels.insert(1, "two-view locus (best pair)")
    fig.legend(handles, labels, loc="outside lower center", ncol=2, fontsize=8.5, frameon=False)
    return fig, pd.concat(out, ignore_index=True)


def drawn(f: pd.DataFrame, key: str) -> pd.DataFrame:
    """The features whose ``key`` estimate is drawn: the two-view point only on a non-empty
    locus (where the locus is empty it is a fallback on the circle or sphere, not a locus point).

    Parameters
    ----------
    f : pandas.DataFrame
        Features table (with ``two_view_status``).
    key : str
        An estimator of :data:`ESTIMATES`.

    Returns
    -------
    pandas.DataFrame
        The rows of ``f`` to draw.
    """
    return f[f["two_view_status"] == "locus"] if key == "two_view" else f


def panel_status(r) -> str:
    """A feature's statuses in a few words: one sighting, or the two-view locus (its pair,
    empty or not) and the N-view status.

    Parameters
    ----------
    r : pandas.Series
        One row of the features table (``n_sightings``, ``two_view_status``, ``two_view_pair``,
        ``nview_status``).

    Returns
    -------
    str
        Up to three lines of text (a panel title).
    """
    n = int(r["n_sightings"])
    if n == 1:
        return "\n" + ONE_SIGHTING
    two = "locus" if r["two_view_status"] == "locus" else "empty locus"
    return f"{n} sightings\n2 views ({r['two_view_pair']}): {two}\nN views: {r['nview_status']}"


def _distances(res, truth):
    f = res.features
    rows = []
    if truth is not None:
        for key, _ in _drawn(f):
            t = drawn(f, key).merge(truth, on="feature", suffixes=("", "_true"))
            d = np.hypot(t[f"{key}_east_m"] - t["east_m"], t[f"{key}_north_m"] - t["north_m"])
            rows.append(pd.DataFrame({"feature": t["feature"], "estimator": key, "distance_h_m": d,
                                      "distance_up_m": t[f"{key}_up_m"] - t["up_m"]}))
    else:
        rows.append(pd.DataFrame({"feature": f["feature"], "estimator": "flat",
                                  "distance_h_m": f["flat_minus_estimate_h_m"],
                                  "distance_up_m": f["flat_minus_estimate_up_m"]}))
    out = pd.concat(rows, ignore_index=True)
    return out[np.isfinite(out["distance_h_m"])]


def _drawn(f: pd.DataFrame, among=ESTIMATES):
    """The ``(key, value)`` of ``among`` whose estimate is in the features table ``f`` (the joint
    adjustment's columns are there only when the chapter computed it)."""
    return [(k, v) for k, v in among.items() if f"{k}_east_m" in f]


def _ellipse(ax, r, key, e0, n0):
    """Draw the 1-sigma ellipse (x ``ELLIPSE_SCALE``) of estimator ``key`` of feature row ``r``."""
    pre = ELLIPSES[key]
    if np.isfinite(r[f"{pre}_major_m"]):
        ax.add_patch(Ellipse((r[f"{key}_east_m"] - e0, r[f"{key}_north_m"] - n0), 2 * ELLIPSE_SCALE * r[f"{pre}_major_m"],
                             2 * ELLIPSE_SCALE * r[f"{pre}_minor_m"], angle=90.0 - r[f"{pre}_azimuth_deg"], fill=False,
                             color=ESTIMATES[key][1], lw=0.8))


def map_caption(n_sightings: int, *, known: bool, synthetic: bool, geojson: bool) -> str:
    """The caption of the chapter's map (:func:`plan_view`) of ``n_sightings``, against the truth
    when ``known``, listing the result files written beside it (a GeoJSON file only with
    ``geojson``: sightings in local metres without an origin have no longitude/latitude).

    Parameters
    ----------
    n_sightings : int
        Number of sightings drawn.
    known : bool
        Whether the right panel is against known positions.
    synthetic : bool
        Whether the data is the synthetic worked example (the caption starts by saying so).
    geojson : bool
        Whether a GeoJSON file was written.

    Returns
    -------
    str
        The caption (markdown).
    """
    files = ("every feature's results (`--features.csv`), every sighting (`--sightings.csv`), the loci's "
             "points (`--locus.csv`)")
    return (("**Synthetic example** (made by the project's simulator over a known seafloor). " if synthetic else "")
            + "Left: the sensor at " + (f"each of the {n_sightings} sightings" if n_sightings != 1 else "the one sighting")
            + " and each feature's estimates (grid "
            "east/north of the local frame): the flat-seafloor mean, the two-view point (of the best pair's "
            "locus, where non-empty, the point nearest the flat mean), the N-view position and, where the "
            "chapter computed it, the joint adjustment's (features and the passes' navigation estimated "
            "together). Right: the horizontal distance of each estimate from "
            + ("the true position." if known else "the best estimate (flat-seafloor mean minus the N-view position, "
               "else the two-view point on a non-empty locus).")
            + f" The result files beside the figure: {files}"
            + (" and all of it as GeoJSON (`--results.geojson`)." if geojson else
               "; no GeoJSON, which needs longitude/latitude: the sightings are in local metres and the run "
               "gave no origin (`-p origin '[lon, lat]'`)."))


def page_data_words(synthetic: bool, inputs) -> tuple[str, str]:
    """What the page's results are computed from, for its introduction and for the sentence
    before the real pass: the shipped worked example (``synthetic``: made by the project's
    simulator over a known seafloor) or the run's own sightings (``inputs``, their files, named).

    Parameters
    ----------
    synthetic : bool
        Whether the page shows the shipped synthetic example.
    inputs : iterable of str or path-like
        The run's sightings files (only their names are used).

    Returns
    -------
    intro : str
        The introduction's sentence (markdown).
    before_real : str
        The sentence before the real pass.
    """
    if synthetic:
        return ("The page below shows a worked example, **synthetic**: a small survey made by the project's own "
                "simulator over a known random seafloor (`tools/make_your_pings_example.py`), so the estimates can "
                "be compared with the truth.", "Everything above is synthetic.")
    names = ", ".join(f"`{Path(p).name}`" for p in inputs)
    return (f"The page below shows this run's own sightings, {names}.",
            f"Everything above is computed from this run's own sightings ({names}).")


def summary_sentence(res, errors: pd.DataFrame | None = None) -> str:
    """What the run found, in numbers: features, sightings, statuses, the flat-seafloor spread and,
    with ``errors`` (:func:`~sss_locus.experiments.your_pings.files.against_truth`), the median
    errors of each estimator.

    Parameters
    ----------
    res : PingResults
        The run's results (``features``, ``sightings`` and optionally ``excluded`` tables).
    errors : pandas.DataFrame, optional
        Errors against the truth: ``estimator``, ``feature``, ``error_h_m``, ``error_up_m`` (m).

    Returns
    -------
    str
        A paragraph; lengths in m.
    """
    f = res.features
    st = f["nview_status"].value_counts()
    nonempty = f["locus_arcs"] > 0
    once = int((f["n_sightings"] == 1).sum())
    parts = [f"{count_noun(len(f), 'feature')} from {count_noun(len(res.sightings), 'sighting')}"]
    if once:
        parts.append(f"{once} seen once ({ONE_SIGHTING}: a flat-seafloor position only)")
    if (f["n_sightings"] >= 3).any():
        parts.append(f"N-view positions for {int(st.get('resolved', 0))} (resolved) and {int(st.get('ambiguous', 0))} "
                     f"(ambiguous) of the {int((f['n_sightings'] >= 3).sum())} seen three or more times")
    if (f["n_sightings"] >= 2).any():
        parts.append(f"{int(nonempty.sum())} of {int((f['n_sightings'] >= 2).sum())} two-view loci (best pair) non-empty"
                     + (f" (median length of those {fmt_sig(f.loc[nonempty, 'locus_length_m'].median())} m)"
                        if nonempty.any() else ""))
    multi = f["n_sightings"] >= 2
    if multi.any():
        parts.append(f"the flat-seafloor positions of one feature disagree by up to "
                     f"{fmt_sig(f.loc[multi, 'flat_spread_m'].max())} m (median over the features seen more than once "
                     f"{fmt_sig(f.loc[multi, 'flat_spread_m'].median())} m)")
    text = "; ".join(parts) + "." + order_sentence(res.sightings)
    excluded = getattr(res, "excluded", None)
    if excluded is not None and len(excluded):
        text += " " + excluded_sentence(excluded)
    if errors is not None and len(errors):
        med = errors.groupby("estimator", sort=False).agg(h=("error_h_m", "median"), v=("error_up_m", lambda x: x.abs().median()),
                                                          n=("feature", "size"))
        text += " Against the truth, median horizontal / vertical errors: " + "; ".join(
            f"{ESTIMATES[k][0].split(',')[0].split(':')[0]} {fmt_sig(r.h)} m / {fmt_sig(r.v)} m ({count_noun(int(r.n), 'feature')})"
            for k, r in med.iterrows()) + "."
        closest = med["h"].idxmin()
        text += (f" Closest to the truth horizontally in this run: {ESTIMATES[closest][0].split(',')[0].split(':')[0]}"
                 + (" (averaging the mosaic's positions beats the geometry here; the reconstruction chapter measures "
                    "when)" if closest == "flat" else "") + ".")
    return text


def order_sentence(sightings: pd.DataFrame) -> str:
    """For XTF sightings, which end of each matched channel was taken as the near end and how it
    was decided (" ..." or "" for a sightings CSV).

    Parameters
    ----------
    sightings : pandas.DataFrame
        The sightings table; XTF ones carry ``xtf_file``, ``channel``, ``side``, ``sample_order``
        and ``sample_order_how``.

    Returns
    -------
    str
        The sentence with a leading space, or ``""``.
    """
    if "sample_order" not in sightings.columns:
        return ""
    rows = sightings.drop_duplicates(["xtf_file", "channel"]).sort_values(["xtf_file", "channel"])
    return (" Samples counted from each channel's near end: " + "; ".join(
        f"{r.xtf_file} channel {r.channel} ({r.side}) {r.sample_order.replace('_', '-')} ({r.sample_order_how})"
        for r in rows.itertuples()) + ".")


def view_3d(res, *, truth: pd.DataFrame | None = None, notice: str = ""):
    """The sensors, each sighting's line of sight to its flat-seafloor position, the loci and
    the estimates in 3-D (grid east, north, up; plotly figure, drag to rotate); the truth named
    by :func:`truth_label` of ``notice``.

    Parameters
    ----------
    res : PingResults
        The run's results (``sightings``, ``features``, ``locus`` tables in the local frame, m).
    truth : pandas.DataFrame, optional
        Known positions: ``feature``, ``east_m``, ``north_m``, ``up_m`` (m).
    notice : str
        Notice of a worked example, in the truth's label.

    Returns
    -------
    plotly.graph_objects.Figure
        The 3-D figure (axes in m, up exaggerated by the aspect ratio).
    """
    import plotly.graph_objects as go

    s, f, loc = res.sightings, res.features, res.locus
    sens = s[["sensor_east_m", "sensor_north_m", "sensor_up_m"]].to_numpy()
    flat = s[["flat_east_m", "flat_north_m", "flat_up_m"]].to_numpy()
    seg = [v for a, b in zip(sens, flat) for v in (a, b, [None] * 3)]
    seg = np.array(seg, dtype=object)
    traces = [go.Scatter3d(x=s["sensor_east_m"], y=s["sensor_north_m"], z=s["sensor_up_m"], mode="markers",
                           marker=dict(size=2, color="grey"), name="sensor at each sighting",
                           text=s["feature"] + " line " + s["line"].astype(str)),
              go.Scatter3d(x=seg[:, 0], y=seg[:, 1], z=seg[:, 2], mode="lines", line=dict(color="lightgrey", width=1),
                           name="slant range to the flat-seafloor position", hoverinfo="skip"),
              go.Scatter3d(x=s["flat_east_m"], y=s["flat_north_m"], z=s["flat_up_m"], mode="markers",
                           marker=dict(size=3, color="black", symbol="circle-open"), name="flat seafloor, each sighting",
                           text=s["feature"])]
    xs, ys, zs = [], [], []
    for _, arc in loc.groupby(["feature", "arc"], sort=False):
        for v, c in zip((xs, ys, zs), ("east_m", "north_m", "up_m")):
            v.extend([*arc[c].tolist(), None])
    traces.append(go.Scatter3d(x=xs, y=ys, z=zs, mode="lines", line=dict(color="crimson", width=6), name="two-view locus"))
    if "joint_east_m" in f:  # the joint estimate's 1-sigma ellipses (x 3), horizontal, at its height
        a = np.linspace(0.0, 2 * np.pi, 37)
        xs, ys, zs = [], [], []
        for _, r in f[np.isfinite(f["joint_ellipse_major_m"])].iterrows():
            t = np.radians(90.0 - r["joint_ellipse_azimuth_deg"])
            u, v = ELLIPSE_SCALE * r["joint_ellipse_major_m"] * np.cos(a), ELLIPSE_SCALE * r["joint_ellipse_minor_m"] * np.sin(a)
            xs += [*(r["joint_east_m"] + u * np.cos(t) - v * np.sin(t)), None]
            ys += [*(r["joint_north_m"] + u * np.sin(t) + v * np.cos(t)), None]
            zs += [*np.full(a.size, r["joint_up_m"]), None]
        traces.append(go.Scatter3d(x=xs, y=ys, z=zs, mode="lines", line=dict(color=to_hex("tab:green"), width=2),
                                   name="joint adjustment, 1-sigma ellipse x 3", hoverinfo="skip"))
    for key, (name, colour, _) in _drawn(f):
        g = drawn(f, key)
        traces.append(go.Scatter3d(x=g[f"{key}_east_m"], y=g[f"{key}_north_m"], z=g[f"{key}_up_m"], mode="markers",
                                   marker=dict(size=4, color=to_hex(colour)), name=name.split(" (")[0], text=g["feature"]))
    if truth is not None:
        traces.append(go.Scatter3d(x=truth["east_m"], y=truth["north_m"], z=truth["up_m"], mode="markers",
                                   marker=dict(size=5, color="gold", symbol="diamond", line=dict(color="black", width=1)),
                                   name=truth_label(notice), text=truth["feature"]))
    fig = go.Figure(traces)
    fig.update_layout(scene=dict(xaxis_title="grid east (m)", yaxis_title="grid north (m)", zaxis_title="up (m)",
                                 aspectmode="manual", aspectratio=dict(x=1, y=1, z=0.35)),
                      legend=dict(orientation="h", yanchor="top", y=-0.02), margin=dict(l=0, r=0, t=10, b=0), height=620)
    return fig
