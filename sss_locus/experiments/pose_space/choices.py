"""The pose-space study's open modelling choices, measured (numbers only).

The paper leaves several choices open that move the results; each is a named parameter of the
study, and this module measures what it does:

- :func:`fan_share_removed`: the share of a sensor's fan (its azimuth-elevation aperture, angles
  uniform as in the sampler's default ``feature_distribution="angles"``) that the rule "the
  feature lies below the sensor" (:mod:`sss_locus.experiments.pose_space.study`) never samples;
- :func:`reading_effect`: the rank correlation and rank of elevation misalignment, and the top
  normalised quantity, under each reading of the paper's ``max(psi1, psi2)``
  (:data:`~sss_locus.experiments.pose_space.stats.MISALIGNMENT_READINGS`);
- :func:`bin_window`: the azimuth window of one heatmap bin, for targeted extra sampling of a
  sparse bin (``PoseSpaceSpec(azimuth1_window_deg=..., azimuth2_window_deg=...)``).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from sss_locus.experiments.datamodel.platforms import Platform
from sss_locus.experiments.stats.replicates import N_BATCHES, median_with_interval, replicate_interval
from sss_locus.experiments.pose_space.stats import MISALIGNMENT_READINGS, spearman_table, with_derived
from sss_locus.experiments.passes.straight_pass import vehicle_attitude


def fan_share_removed(platform: Platform, side: str = "port", pitch_deg: float = 0.0, *,
                      n_grid: int = 721) -> dict[str, float]:
    """Share of one transducer's fan where a feature would be at or above the sensor.

    The sensor belongs to a vehicle at zero roll and pitch ``pitch_deg`` (positive nose-up);
    yaw does not change heights. Whether a feature at ``r (cos t cos p, sin t cos p, sin p)`` in
    the sensor frame is below the sensor depends on its direction only, so the share is the
    fraction of the ``(theta, phi)`` aperture, both uniform (the sampler's ``"angles"``
    distribution), whose direction has a world ``z >= 0``: the part of the fan the pose-space
    sampler's "feature below both sensors" rule never samples. Midpoint rule on an
    ``n_grid x n_grid`` grid (error O(1/n_grid) at the boundary).

    Parameters
    ----------
    platform : Platform
        The platform.
    side : {"port", "starboard"}
        The transducer.
    pitch_deg : float
        Vehicle pitch, degrees, nose-up positive.
    n_grid : int
        Grid points per axis.

    Returns
    -------
    dict
        ``share`` in [0, 1]; ``theta_min_deg``: the smallest azimuth (deg) of the fan with a
        sampled (below-sensor) direction at zero elevation, NaN if none.
    """
    if side not in platform.transducers:
        raise ValueError(f"side must be one of {sorted(platform.transducers)}; got {side!r}")
    if not (isinstance(n_grid, (int, np.integer)) and n_grid >= 3):
        raise ValueError(f"n_grid must be an integer >= 3; got {n_grid!r}")
    if not -90.0 <= float(pitch_deg) <= 90.0:
        raise ValueError(f"pitch_deg must be in [-90, 90] degrees; got {pitch_deg!r}")
    ap = platform.sonar.aperture()
    k = (np.arange(n_grid) + 0.5) / n_grid * 2.0 - 1.0  # midpoints in (-1, 1)
    theta, phi = np.meshgrid(k * ap.half_azimuth_rad, k * ap.half_elevation_rad, indexing="ij")
    d = np.stack([np.cos(theta) * np.cos(phi), np.sin(theta) * np.cos(phi), np.sin(phi)], axis=-1)
    world = vehicle_attitude(0.0, pitch_deg, 0.0).as_matrix() @ platform.transducers[side].rotation.as_matrix()
    z = d @ world[2]
    mid = n_grid // 2  # the elevation row nearest phi = 0
    below0 = theta[:, mid][z[:, mid] < 0]
    return {"share": float(np.mean(z >= 0.0)),
            "theta_min_deg": float(np.degrees(below0.min())) if below0.size else float("nan")}


def reading_effect(table: pd.DataFrame, readings=MISALIGNMENT_READINGS, *,
                   n_batches: int = N_BATCHES) -> pd.DataFrame:
    """Elevation misalignment under each reading of the paper's ``max(psi1, psi2)``.

    ``table`` is a pose-space table (:func:`~sss_locus.experiments.pose_space.study.sample_pose_space`,
    with ``psi1_deg`` and ``psi2_deg``). For each reading the misalignment column is recomputed
    (:func:`~sss_locus.experiments.pose_space.stats.with_derived`) and the candidates ranked again
    (:func:`~sss_locus.experiments.pose_space.stats.spearman_table`).

    Parameters
    ----------
    table : pandas.DataFrame
        A pose-space table.
    readings : sequence of str
        Readings of :data:`~sss_locus.experiments.pose_space.stats.MISALIGNMENT_READINGS`.
    n_batches : int
        Replicate batches.

    Returns
    -------
    pandas.DataFrame
        One row per reading and target (``raw``/``norm``): ``reading, target, rho, ci_low,
        ci_high, rank`` of elevation misalignment and ``top`` (the top quantity).
    """
    rows = []
    for reading in readings:
        rho = spearman_table(with_derived(table, misalignment=reading), n_batches=n_batches)
        for target, tag in (("locus_length_m", "raw"), ("locus_length_normalized", "norm")):
            tab = rho[rho["target"] == target].reset_index(drop=True)
            i = int(np.flatnonzero(tab["quantity"] == "elevation_misalignment_deg")[0])
            rows.append({"reading": reading, "target": tag, "rho": tab.loc[i, "rho"],
                         "ci_low": tab.loc[i, "ci_low"], "ci_high": tab.loc[i, "ci_high"],
                         "rank": i + 1, "top": tab.loc[0, "quantity"]})
    return pd.DataFrame(rows)


def bin_window(binned: pd.DataFrame, row) -> tuple[tuple[float, float], tuple[float, float]]:
    """The ``(x_lo, x_hi)`` and ``(y_lo, y_hi)`` edges of one bin of a
    :func:`~sss_locus.experiments.pose_space.stats.binned_median` table (``row`` an index label).

    Parameters
    ----------
    binned : pandas.DataFrame
        A binned table.
    row : label
        Index label of the bin.

    Returns
    -------
    x_window, y_window : (float, float)
        The bin's edges.
    """
    r = binned.loc[row]
    return (float(r.x_lo), float(r.x_hi)), (float(r.y_lo), float(r.y_hi))


def in_bin(df: pd.DataFrame, x: str, y: str, x_window, y_window) -> pd.DataFrame:
    """Rows of ``df`` with ``x`` in ``x_window`` and ``y`` in ``y_window`` (closed intervals).

    Parameters
    ----------
    df : pandas.DataFrame
        The table.
    x, y : str
        Columns.
    x_window, y_window : (float, float)
        Closed intervals.

    Returns
    -------
    pandas.DataFrame
        The rows inside.
    """
    return df[df[x].between(*x_window) & df[y].between(*y_window)]


def hotspot_check(binned: pd.DataFrame, targeted: pd.DataFrame, *, value: str = "locus_length_m",
                  n_batches: int = N_BATCHES, confidence_level: float = 0.95, batch_meds=None) -> dict[str, float]:
    """The heatmap's peak bin, re-measured with targeted extra samples.

    Parameters
    ----------
    binned : pandas.DataFrame
        A :func:`~sss_locus.experiments.pose_space.stats.binned_median` table (e.g. the azimuth panel).
    targeted : pandas.DataFrame
        Extra samples drawn inside the peak bin's window (rows outside it are ignored), from the
        same distribution as the samples behind ``binned`` conditioned on the bin.

    value : str
        The column whose median is taken.
    n_batches : int
        Replicate batches of the targeted samples.
    confidence_level : float
        Level of the intervals, in (0, 1).
    batch_meds : numpy.ndarray, shape (k, n_bins), optional
        The bins' medians in each replicate batch of the samples behind ``binned``.

    Returns
    -------
    dict
        ``x_mid``, ``y_mid`` of the peak bin (among the shown bins); ``count`` and ``median``
        there; ``target_count``, ``target_median`` and its replicate interval (``n_batches`` batches,
        :func:`~sss_locus.experiments.stats.replicates.median_with_interval`)
        ``target_ci_low``/``target_ci_high``; ``runner_up_median``, ``runner_up_count``,
        ``runner_up_x_mid``, ``runner_up_y_mid`` (the second-largest shown bin); and
        ``still_peak`` (a bool: whether the targeted interval lies above the runner-up's median).
        With ``batch_meds``, the bins' medians in the replicate batches of the samples behind
        ``binned`` (:func:`~sss_locus.experiments.pose_space.claims.batch_medians`, in ``binned``'s
        row order), also the intervals of the peak bin's and the runner-up's medians
        (``median_ci_low``/``_high``, ``runner_up_ci_low``/``_high``), and ``still_peak`` asks
        that the targeted interval lie above the runner-up's whole interval.
    """
    shown = binned[~binned["masked"]].sort_values("median", ascending=False)
    if len(shown) < 2:
        raise ValueError("binned needs at least two shown (unmasked) bins")
    top, second = shown.iloc[0], shown.iloc[1]
    x, y = binned.attrs.get("x"), binned.attrs.get("y")
    if x is None or y is None:
        raise ValueError("binned lacks the attrs x and y of binned_median")
    inside = in_bin(targeted, x, y, (top.x_lo, top.x_hi), (top.y_lo, top.y_hi))[value].to_numpy(float)
    if inside.size == 0:
        raise ValueError("no targeted sample lies inside the peak bin")
    med, lo, hi = median_with_interval(inside, n_batches, confidence_level)
    out = {"x_mid": float(top.x_mid), "y_mid": float(top.y_mid), "count": int(top["count"]),
           "median": float(top["median"]), "target_count": int(inside.size),
           "target_median": med, "target_ci_low": float(lo), "target_ci_high": float(hi),
           "runner_up_median": float(second["median"]), "runner_up_count": int(second["count"]),
           "runner_up_x_mid": float(second.x_mid), "runner_up_y_mid": float(second.y_mid),
           "still_peak": bool(lo > second["median"])}
    if batch_meds is not None:
        meds = np.asarray(batch_meds, float)
        for name, row in (("median", top), ("runner_up", second)):
            r_lo, r_hi = replicate_interval(row["median"], meds[:, binned.index.get_loc(row.name)], confidence_level)
            out[f"{name}_ci_low"], out[f"{name}_ci_high"] = float(r_lo), float(r_hi)
        out["still_peak"] = bool(lo > out["runner_up_ci_high"])
    return out
