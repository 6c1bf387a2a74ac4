"""The numbers behind the paper's pose-space claims (Sec. IV-B, IV-C), with their precision.

:func:`claim_metrics` measures each claim on a pose-space table (the heatmap subset) and says how
precisely the sampling pins it down, so the chapter prints each number only as far as the
samples support it:

* a ratio of medians or a share comes with a 95 % replicate-batch interval
  (:mod:`~sss_locus.experiments.stats.replicates`: the rows, i.i.d. draws, dealt into ``k`` batches,
  row ``i`` to batch ``i mod k``; the statistic of each batch; the t interval of their spread
  around the whole table's statistic), keys ``<name>_ci_low`` and ``<name>_ci_high``;
* the location of a largest bin median (the peaks of the median over yaw, the peaks of the
  yaw-azimuth panel, the azimuth hotspot) is an argmax over bins. Where the top is flat, nearby
  bins have medians within sampling noise of the largest, and which of them wins changes from
  seed to seed at any affordable sample size. So the peak is reported as a **peak region**
  (:func:`peak_region`): the bins whose median lies inside the 95 % replicate interval of the
  largest median, with the span of their centres (keys ``<name>_lo_deg`` and ``<name>_hi_deg``).

Angles in degrees, lengths in metres.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pandas as pd

from sss_locus.experiments.pose_space.stats import binned_profile, grouped_binned, grouped_binned_medians
from sss_locus.experiments.stats.replicates import N_BATCHES, batch_count, check_confidence, replicate_interval, spearman_rho


def batches(df: pd.DataFrame, n_batches: int = N_BATCHES) -> list[pd.DataFrame]:
    """The replicate batches of the rows of ``df``: batch ``j`` holds rows ``j, j + k, ...``
    (:func:`~sss_locus.experiments.stats.replicates.batch_count`).

    Parameters
    ----------
    df : pandas.DataFrame
        The table.
    n_batches : int
        Batches wanted (at most ``len(df) // 3`` are made).

    Returns
    -------
    list of pandas.DataFrame
        The ``k`` batches, in order.
    """
    k = batch_count(len(df), n_batches)
    return [df.iloc[j::k] for j in range(k)]


def _edges(lo: pd.Series, hi: pd.Series) -> np.ndarray:
    return np.unique(np.concatenate([lo.to_numpy(float), hi.to_numpy(float)]))


def batch_medians(parts: list[pd.DataFrame], binned: pd.DataFrame) -> np.ndarray:
    """The per-bin medians of each replicate batch in ``parts``, in the bins of ``binned`` (a
    :func:`~sss_locus.experiments.pose_space.stats.binned_median` or
    :func:`~sss_locus.experiments.pose_space.stats.binned_profile` table): shape ``(k, n_bins)``, NaN
    where a batch has no row in a bin. The numbers of ``binned_median`` (``binned_profile``) of
    each part (:func:`~sss_locus.experiments.pose_space.stats.grouped_binned_medians`).

    Parameters
    ----------
    parts : list of pandas.DataFrame
        The replicate batches (:func:`batches`).
    binned : pandas.DataFrame
        The binned table whose bins are used (its ``attrs`` name the columns).

    Returns
    -------
    numpy.ndarray, shape (k, n_bins)
        The medians, batch by batch, in the order of ``binned``'s rows.
    """
    a = binned.attrs
    columns, edges = _binning(binned)
    coords = np.column_stack([np.concatenate([p[c].to_numpy(float) for p in parts]) for c in columns])
    v = np.concatenate([p[a["value"]].to_numpy(float) for p in parts])
    groups = np.repeat(np.arange(len(parts)), [len(p) for p in parts])
    ok = ~(np.isnan(coords).any(axis=1) | np.isnan(v))
    _, med = grouped_binned_medians(coords[ok], v[ok], edges, groups[ok], len(parts))
    return med.reshape(len(parts), -1)


def dealt_batch_medians(df: pd.DataFrame, binned: pd.DataFrame, n_batches: int = N_BATCHES) -> np.ndarray:
    """:func:`batch_medians` of ``batches(df, n_batches)`` (the same numbers), without cutting
    ``df``: row ``i`` is in batch ``i mod k``
    (:func:`~sss_locus.experiments.pose_space.stats.grouped_binned`).

    Parameters
    ----------
    df : pandas.DataFrame
        The whole table.
    binned : pandas.DataFrame
        The binned table of ``df``.
    n_batches : int
        Batches wanted.

    Returns
    -------
    numpy.ndarray, shape (k, n_bins)
        As :func:`batch_medians`.
    """
    k = batch_count(len(df), n_batches)
    columns, edges = _binning(binned)
    _, med, _ = grouped_binned(df, columns, edges, binned.attrs["value"], np.arange(len(df)) % k, k)
    return med.reshape(k, -1)


def _binning(binned: pd.DataFrame) -> tuple[list[str], list[np.ndarray]]:
    """The columns and edges of a :func:`~sss_locus.experiments.pose_space.stats.binned_median` or
    ``binned_profile`` table."""
    a = binned.attrs
    if "y" in a:
        return [a["x"], a["y"]], [_edges(binned.x_lo, binned.x_hi), _edges(binned.y_lo, binned.y_hi)]
    return [a["x"]], [_edges(binned.lo, binned.hi)]


def peak_region(binned: pd.DataFrame, batch_meds: np.ndarray, select=None,
                confidence_level: float = 0.95) -> tuple[pd.DataFrame, float, float]:
    """The bins the sampling cannot tell from the one with the largest median.

    ``binned``: a table of :func:`~sss_locus.experiments.pose_space.stats.binned_median` or
    ``binned_profile``; ``batch_meds``: its bins' medians in each replicate batch
    (:func:`batch_medians`); ``select``: a boolean mask of the bins to search (default all).
    Every bin's median gets its 95 % interval,
    :func:`~sss_locus.experiments.stats.replicates.replicate_interval` of its batch medians. Among the
    shown (unmasked) selected bins the largest median is found; the region is the shown selected
    bins whose interval reaches the peak's (upper end at least the peak's lower end; a bin
    without an interval, empty in some batch, by its median). Returns ``(region, low, high)``:
    the region (the peak bin always in it) and the peak median's interval. Overlapping
    intervals are a screen, not a test: the region is the set of bins that may hold the
    largest median at this sample size.

    Parameters
    ----------
    binned : pandas.DataFrame
        A binned table.
    batch_meds : numpy.ndarray, shape (k, n_bins)
        Its bins' medians in each replicate batch.
    select : numpy.ndarray of bool, shape (n_bins,), optional
        Bins searched (default all).
    confidence_level : float
        Level of the intervals, in (0, 1).

    Returns
    -------
    region : pandas.DataFrame
        The rows of ``binned`` in the region.
    low, high : float
        The peak median's interval, metres.
    """
    check_confidence(confidence_level)
    keep = ~binned["masked"].to_numpy()
    if select is not None:
        keep &= np.asarray(select, bool)
    if not keep.any():
        raise ValueError("binned has no shown bin in the selection")
    med = binned["median"].to_numpy(float)
    i = int(np.flatnonzero(keep)[np.argmax(med[keep])])
    lo, hi = replicate_interval(med, batch_meds, confidence_level)
    reach = np.where(np.isnan(hi), med, hi)
    floor = med[i] if np.isnan(lo[i]) else lo[i]
    inside = keep & (reach >= floor)
    inside[i] = True
    return binned[inside], float(lo[i]), float(hi[i])


def _with_interval(m: dict, name: str, full: float, per_batch, confidence_level: float, bounds=None) -> None:
    """``m[name]`` and its replicate interval ``m[name + "_ci_low"]``, ``m[name + "_ci_high"]``."""
    lo, hi = replicate_interval(full, np.asarray(per_batch, float), confidence_level, bounds=bounds)
    m[name], m[f"{name}_ci_low"], m[f"{name}_ci_high"] = float(full), float(lo), float(hi)


def _span(m: dict, name: str, values) -> None:
    m[f"{name}_lo_deg"], m[f"{name}_hi_deg"] = float(np.min(values)), float(np.max(values))


def claim_metrics(df: pd.DataFrame, rho: pd.DataFrame, maps: dict[str, pd.DataFrame], *,
                  yaw_bin_deg: float = 10.0, min_count: int = 30, n_batches: int = N_BATCHES,
                  confidence_level: float = 0.95) -> dict[str, float | str]:
    """The measured numbers behind each claim of the paper's Sec. IV-B and IV-C.

    ``df`` is the table the heatmaps were made from (feature on the port side), ``rho`` the
    :func:`~sss_locus.experiments.pose_space.stats.spearman_table` of the whole table, ``maps`` the
    :func:`~sss_locus.experiments.pose_space.stats.heatmaps` of ``df``. Keys ending in ``_rho`` are
    Spearman correlations (``_rank`` their rank); ``*_ratio`` are ratios of medians and
    ``*_fraction`` shares, each with ``_ci_low``/``_ci_high`` (module docstring; the ratios over
    the yaw profile keep the bins chosen on the whole table, e.g. its peak bin, in every batch).
    ``multi_arc_fraction`` is the share of the rows of ``df`` (not of the whole table: in the
    pose-space chapter ``df`` is the heatmap subset, sensor 2 on the port side like sensor 1)
    whose locus has more than one arc. Peaks: ``<name>_deg`` the centre of the bin with the
    largest median and ``<name>_lo_deg``/``_hi_deg`` the span of its :func:`peak_region`. The
    azimuth hotspot is quoted as its bin (``azimuth_peak_theta1_deg``, ``_theta2_deg``), which
    the chapter re-measures with targeted samples where it is sparse (a sparse bin's batch
    medians are too noisy for a useful region); its region is ``azimuth_region_theta1_lo_deg``
    etc., ``azimuth_region_bins`` bins, ``azimuth_region_equal`` 1.0 if one of them has equal
    azimuths.

    Parameters
    ----------
    df : pandas.DataFrame
        The heatmaps' table.
    rho : pandas.DataFrame
        The :func:`~sss_locus.experiments.pose_space.stats.spearman_table` of the whole table.
    maps : dict of str to pandas.DataFrame
        The heatmaps of ``df``.
    yaw_bin_deg : float
        Width of the yaw profile's bins, degrees.
    min_count : int
        Rows a bin needs to be shown.
    n_batches : int
        Replicate batches.
    confidence_level : float
        Level of the intervals, in (0, 1).

    Returns
    -------
    dict of str to float or str
        The numbers by key (units in the key: ``_deg``, ``_m``; ratios and shares plain).
    """
    m: dict[str, float | str] = {}
    for target, tag in (("locus_length_m", "raw"), ("locus_length_normalized", "norm")):
        tab = rho[rho["target"] == target].reset_index(drop=True)
        m[f"top_{tag}"] = tab.loc[0, "quantity"]
        for i, row in tab.iterrows():
            m[f"{tag}_{row.quantity}_rho"] = row.rho
            m[f"{tag}_{row.quantity}_rank"] = float(i + 1)
    parts = batches(df, n_batches)

    def interval(name: str, fn: Callable[[pd.DataFrame], float], bounds=None) -> None:
        _with_interval(m, name, fn(df), [fn(p) for p in parts], confidence_level, bounds)

    interval("multi_arc_fraction", lambda d: float((d["n_arcs"] > 1).mean()), bounds=(0.0, 1.0))
    # (a) range x range: median length with both ranges above half the maximum over the median
    # with both below it (from the samples, not from bin medians)
    half_r = maps["a"]["x_hi"].max() / 2

    def far_near(d: pd.DataFrame) -> float:  # (the one column filtered, not the frame)
        length = d["locus_length_m"]
        far = length[(d.r1_m > half_r) & (d.r2_m > half_r)].median()
        return float(far / length[(d.r1_m <= half_r) & (d.r2_m <= half_r)].median())

    interval("range_far_over_near_ratio", far_near)
    m["range_r1_rho"] = spearman_rho(df["r1_m"].to_numpy(), df["locus_length_m"].to_numpy())
    m["range_r2_rho"] = spearman_rho(df["r2_m"].to_numpy(), df["locus_length_m"].to_numpy())
    # (b) azimuth x azimuth: where the largest bin median is, and the bins within its interval
    b = maps["b"]
    region, _, _ = peak_region(b, dealt_batch_medians(df, b, n_batches), confidence_level=confidence_level)
    pk = region.loc[region["median"].idxmax()]
    m["azimuth_peak_theta1_deg"], m["azimuth_peak_theta2_deg"] = float(pk.x_mid), float(pk.y_mid)
    m["azimuth_peak_count"] = float(pk["count"])  # samples behind the peak bin's median
    _span(m, "azimuth_region_theta1", region.x_mid)  # not azimuth_peak_*: the point is what is quoted
    _span(m, "azimuth_region_theta2", region.y_mid)
    m["azimuth_region_bins"] = float(len(region))
    m["azimuth_region_equal"] = float(np.isclose(region.x_mid, region.y_mid).any())
    azimuths = rho[(rho["target"] == "locus_length_normalized") & rho["quantity"].isin(["azimuth1_deg", "azimuth2_deg"])]
    if len(azimuths):  # share of rank variance the azimuths explain, with the interval of that rho
        top = azimuths.loc[azimuths["rho"].abs().idxmax()]
        ends = np.array([top.ci_low, top.ci_high]) ** 2
        m["norm_azimuth_max_rho2_fraction"] = float(top.rho ** 2)
        m["norm_azimuth_max_rho2_fraction_ci_low"] = 0.0 if top.ci_low * top.ci_high <= 0 else float(ends.min())
        m["norm_azimuth_max_rho2_fraction_ci_high"] = float(ends.max())
    # (c) elevation x elevation: median with both |phi| in the inner third of the half-aperture
    # over the median with both in the outer third (from the samples)
    third = maps["c"]["x_hi"].max() / 3

    def centre_corner(d: pd.DataFrame) -> float:
        e1, e2, length = d["elevation1_deg"].abs(), d["elevation2_deg"].abs(), d["locus_length_m"]
        inner = length[(e1 < third) & (e2 < third)].median()
        return float(inner / length[(e1 > 2 * third) & (e2 > 2 * third)].median())

    interval("elevation_centre_over_corner_ratio", centre_corner)
    _yaw_metrics(m, df, parts, maps["e"], yaw_bin_deg, min_count, confidence_level)
    m["n_heatmap_samples"] = float(len(df))
    return m


def _yaw_metrics(m: dict, df: pd.DataFrame, parts: list[pd.DataFrame], e: pd.DataFrame, yaw_bin_deg: float,
                 min_count: int, confidence_level: float) -> None:
    """(d, e) of :func:`claim_metrics`: the profile of the median over vehicle 2's yaw and the
    peaks of the yaw-azimuth panel."""
    prof = binned_profile(df, "yaw2_deg", edges=np.arange(-180.0, 180.0 + yaw_bin_deg, yaw_bin_deg),
                          min_count=min_count)
    meds = dealt_batch_medians(df, prof, len(parts))
    shown, mid, med = ~prof["masked"].to_numpy(), prof["mid"].to_numpy(), prof["median"].to_numpy()
    for half, sel in (("neg", mid < 0), ("pos", mid > 0)):
        region, _, _ = peak_region(prof, meds, sel, confidence_level)
        m[f"yaw_peak_{half}_deg"] = float(region.loc[region["median"].idxmax(), "mid"])
        _span(m, f"yaw_peak_{half}", region["mid"])
    top = int(np.flatnonzero(shown)[np.argmax(med[shown])])  # the peak bin, kept in every batch
    neg = int(np.flatnonzero(shown & (mid < 0))[np.argmax(med[shown & (mid < 0)])])
    pos = int(np.flatnonzero(shown & (mid > 0))[np.argmax(med[shown & (mid > 0)])])
    near0, near180 = shown & (np.abs(mid) < yaw_bin_deg), shown & (np.abs(mid) > 180 - yaw_bin_deg)
    m["yaw_peak_median_m"] = float(med[top])
    with np.errstate(invalid="ignore", divide="ignore"):
        for name, fn in (("yaw_near0_over_peak_ratio", lambda v: np.mean(v[..., near0], axis=-1) / v[..., top]),
                         ("yaw_near180_over_peak_ratio", lambda v: np.mean(v[..., near180], axis=-1) / v[..., top]),
                         ("yaw_peak_over_near0_ratio", lambda v: v[..., top] / np.mean(v[..., near0], axis=-1)),
                         ("yaw_peak_asymmetry_ratio", lambda v: v[..., neg] / v[..., pos])):
            _with_interval(m, name, float(fn(med)), fn(meds), confidence_level)
    em = dealt_batch_medians(df, e, len(parts))
    for half, sel in (("neg", e.x_mid < 0), ("pos", e.x_mid > 0)):
        region, _, _ = peak_region(e, em, sel.to_numpy(), confidence_level)
        pk = region.loc[region["median"].idxmax()]
        m[f"azimuth2_yaw_peak_{half}_yaw_deg"] = float(pk.x_mid)
        m[f"azimuth2_yaw_peak_{half}_theta2_deg"] = float(pk.y_mid)
        _span(m, f"azimuth2_yaw_peak_{half}_yaw", region.x_mid)
        _span(m, f"azimuth2_yaw_peak_{half}_theta2", region.y_mid)


def map_intervals(df: pd.DataFrame, maps: dict[str, pd.DataFrame], n_batches: int = N_BATCHES,
                  confidence_level: float = 0.95) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Per panel of ``maps`` (:func:`~sss_locus.experiments.pose_space.stats.heatmaps` of ``df``), the
    95 % replicate interval ``(low, high)`` of every bin's median, in the bins' order (NaN where
    a batch has no row in the bin).

    Parameters
    ----------
    df : pandas.DataFrame
        The heatmaps' table.
    maps : dict of str to pandas.DataFrame
        The heatmaps of ``df``.
    n_batches : int
        Replicate batches.
    confidence_level : float
        Level of the intervals, in (0, 1).

    Returns
    -------
    dict of str to (numpy.ndarray, numpy.ndarray)
        Per panel letter, the lower and upper ends, metres, one per bin.
    """
    return {p: replicate_interval(b["median"].to_numpy(float), dealt_batch_medians(df, b, n_batches), confidence_level)
            for p, b in maps.items()}
