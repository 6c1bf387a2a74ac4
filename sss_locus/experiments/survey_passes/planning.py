"""Survey planning from the two-pass simulation: the crossing-angle curve and bands to prefer
or avoid (the paper's Sec. IV-D advice, computed for any platform, envelope and offset model).

Typical use::

    from sss_locus.experiments.datamodel.envelopes import OffsetModel, load_envelope
    from sss_locus.experiments.survey_passes.planning import crossing_angle_curve, planning_bands
    from sss_locus.experiments.datamodel.platforms import load_platform

    pf = load_platform("auv")
    curve = crossing_angle_curve(pf, load_envelope("auv"), OffsetModel("independent"))
    planning_bands(curve.curve)          # rows: kind ("prefer"/"avoid"), lo_deg, hi_deg, ...

Statistics: medians and quartiles per crossing angle; the median's interval from independent
replicates (each angle's pass pairs split into ``n_batches`` batches,
:mod:`sss_locus.experiments.stats.replicates`). The peak angle is the argmax of the median curve, not a
smooth statistic, so its interval keeps a percentile bootstrap (:func:`bootstrap_median`:
resample the rows of every angle independently and take the argmax of the resampled medians).

Band rule (:func:`planning_bands`), fixed before any result was seen: with ``m(gamma)`` the
median curve and ``m_lo``, ``m_hi`` its smallest and largest values, an angle is **preferred**
where ``m <= m_lo + prefer_below * (m_hi - m_lo)`` and to be **avoided** where
``m >= m_lo + avoid_above * (m_hi - m_lo)``; runs of consecutive grid angles form bands, so band
edges have the resolution of the grid.

Simulation: every function that simulates passes takes ``simulate=``, a callable with the
signature of :func:`~sss_locus.experiments.survey_passes.study.simulate_passes` (the default). Pass a
cached version (``sss_locus.pipeline.run.cache.cached(simulate_passes)``) to reuse earlier runs;
this layer itself never touches the cache.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from sss_locus.experiments.datamodel.platforms import Platform
from sss_locus.experiments.stats.replicates import (N_BATCHES, batch_statistic, check_confidence, median_with_interval,
                                                    replicate_interval, spearman_rho)
from sss_locus.experiments.datamodel.envelopes import OffsetModel, SurveyEnvelope, load_envelope
from sss_locus.experiments.survey_passes.study import simulate_passes

VALUES = ("locus_length_m", "elevation_misalignment_deg")
"""The quantities summarised per crossing angle (the paper's Fig. 5 panels a and b)."""


def crossing_angle_grid(fine_step_deg: float = 1.0, fine_max_deg: float = 40.0,
                        coarse_step_deg: float = 5.0) -> np.ndarray:
    """Crossing angles 0..180 deg: every ``fine_step_deg`` up to ``fine_max_deg``, then every
    ``coarse_step_deg`` (always including 90 and 180 when the steps divide them).

    Parameters
    ----------
    fine_step_deg : float
        Step of the fine part, degrees.
    fine_max_deg : float
        End of the fine part, degrees.
    coarse_step_deg : float
        Step beyond it, degrees.

    Returns
    -------
    numpy.ndarray
        Increasing crossing angles, degrees.
    """
    for name, v in (("fine_step_deg", fine_step_deg), ("coarse_step_deg", coarse_step_deg)):
        if not (isinstance(v, (int, float)) and math.isfinite(v) and 0 < v <= 180):
            raise ValueError(f"{name} must be in (0, 180] degrees; got {v!r}")
    if not (isinstance(fine_max_deg, (int, float)) and 0 <= fine_max_deg <= 180):
        raise ValueError(f"fine_max_deg must be in [0, 180] degrees; got {fine_max_deg!r}")
    fine = np.arange(0.0, fine_max_deg + 1e-9, fine_step_deg)
    coarse = np.arange(0.0, 180.0 + 1e-9, coarse_step_deg)
    return np.unique(np.round(np.concatenate([fine, coarse[coarse > fine_max_deg], [180.0]]), 9))


def bootstrap_median(values, n_resamples: int, rng, *, batch: int = 64) -> np.ndarray:
    """Medians of ``n_resamples`` bootstrap resamples (rows with replacement) of ``values``.

    Vectorised in batches of ``batch`` resamples; ``rng`` a :class:`numpy.random.Generator`.
    Returns an array of shape ``(n_resamples,)``.

    Parameters
    ----------
    values : array_like, shape (n,)
        Sample.
    n_resamples : int
        Number of resamples.
    rng : numpy.random.Generator
        Source of the resampled rows.
    batch : int
        Resamples drawn per batch.

    Returns
    -------
    numpy.ndarray, shape (n_resamples,)
        The resamples' medians.
    """
    x = np.asarray(values, float)
    if x.ndim != 1 or x.size == 0:
        raise ValueError(f"values must be a non-empty 1-D array; got shape {x.shape}")
    if isinstance(n_resamples, bool) or int(n_resamples) < 1:
        raise ValueError(f"n_resamples must be a positive integer; got {n_resamples!r}")
    out = np.empty(int(n_resamples))
    zeros = np.signbit(x[x == 0])
    if np.isnan(x).any() or 0 < zeros.sum() < zeros.size:
        # NaN propagates as np.median does; with zeros of both signs which one np.median
        # returns depends on its partition, so let it choose
        for i in range(0, out.size, batch):
            k = min(batch, out.size - i)
            out[i:i + k] = np.median(x[rng.integers(0, x.size, (k, x.size))], axis=1)
        return out
    # The median of a resample is its order statistic(s) n//2 (and n//2 - 1 for even n): found
    # from how often each sorted value is drawn, without sorting or partitioning the resample.
    # Same draws and same arithmetic ((a + b) / 2), so equal to np.median bit for bit.
    n = x.size
    order = np.argsort(x, kind="stable")
    xs = x[order]
    ranks = np.empty(n, np.intp)
    ranks[order] = np.arange(n)
    kth = [n // 2] if n % 2 else [n // 2 - 1, n // 2]
    for i in range(0, out.size, batch):
        k = min(batch, out.size - i)
        idx = ranks[rng.integers(0, n, (k, n))] + n * np.arange(k)[:, None]
        cum = np.cumsum(np.bincount(idx.ravel(), minlength=k * n).reshape(k, n), axis=1)
        vals = [xs[(cum <= q).sum(axis=1)] for q in kth]
        out[i:i + k] = vals[0] if len(vals) == 1 else (vals[0] + vals[1]) / 2.0
    return out


def _interval(boot, confidence_level):
    alpha = (1.0 - confidence_level) / 2.0
    return np.quantile(boot, [alpha, 1.0 - alpha], axis=0)


def curve_summary(samples: pd.DataFrame, values=VALUES, *, n_batches: int = N_BATCHES,
                  n_resamples: int = 200, confidence_level: float = 0.95,
                  seed: int = 0) -> tuple[pd.DataFrame, dict]:
    """Median, quartiles and replicate interval of the median per crossing angle.

    Parameters
    ----------
    samples : pandas.DataFrame
        Simulated pass pairs with ``crossing_angle_deg`` and the ``values`` columns.
    values : sequence of str
        Columns summarised.
    n_batches : int
        Replicate batches per angle.
    n_resamples : int
        Bootstrap resamples for :func:`peak_angle`.
    confidence_level : float
        Level of the intervals, in (0, 1).
    seed : int
        Seed of the bootstrap.

    Returns
    -------
    curve : pandas.DataFrame
        ``crossing_angle_deg, n`` and for each value ``v``: ``v_median, v_q25, v_q75,
        v_ci_low, v_ci_high`` (the median's :func:`~sss_locus.experiments.stats.replicates.replicate_interval`
        from ``n_batches`` batches of the angle's rows, at ``confidence_level``).
    boot : dict
        ``v -> ndarray (n_resamples, n_angles)`` of bootstrap medians (seeded by ``seed``), for
        :func:`peak_angle`.
    """
    check_confidence(confidence_level)
    missing = [c for c in ("crossing_angle_deg", *values) if c not in samples.columns]
    if missing:
        raise ValueError(f"samples lacks columns {missing}")
    rng = np.random.default_rng(seed)
    groups = list(samples.groupby("crossing_angle_deg", sort=True))
    rows, boot = [], {v: np.empty((int(n_resamples), len(groups))) for v in values}
    for j, (gamma, g) in enumerate(groups):
        for v in values:
            boot[v][:, j] = bootstrap_median(g[v].to_numpy(float), n_resamples, rng)
        rows.append(curve_row(gamma, g, values, n_batches, confidence_level))
    return curve_frame(rows, values), boot


def curve_row(gamma_deg: float, g: pd.DataFrame, values=VALUES, n_batches: int = N_BATCHES,
              confidence_level: float = 0.95) -> dict:
    """One crossing angle's row of :func:`curve_summary` from its samples ``g`` (its rows only).

    Parameters
    ----------
    gamma_deg : float
        The crossing angle, degrees.
    g : pandas.DataFrame
        Its samples.
    values : sequence of str
        Columns summarised.
    n_batches : int
        Replicate batches.
    confidence_level : float
        Level of the intervals, in (0, 1).

    Returns
    -------
    dict
        ``crossing_angle_deg``, ``n`` and ``v_median, v_q25, v_q75, v_ci_low, v_ci_high`` per value.
    """
    row = {"crossing_angle_deg": float(gamma_deg), "n": len(g)}
    for v in values:
        x = g[v].to_numpy(float)
        q25, med, q75 = np.quantile(x, [0.25, 0.5, 0.75])
        lo, hi = median_with_interval(x, n_batches, confidence_level)[1:]
        row.update({f"{v}_median": med, f"{v}_q25": q25, f"{v}_q75": q75,
                    f"{v}_ci_low": float(lo), f"{v}_ci_high": float(hi)})
    return row


def curve_frame(rows: list[dict], values=VALUES) -> pd.DataFrame:
    """The rows of :func:`curve_row` as the table of :func:`curve_summary`.

    Parameters
    ----------
    rows : list of dict
        Rows of :func:`curve_row`.
    values : sequence of str
        Columns summarised.

    Returns
    -------
    pandas.DataFrame
        The curve, one row per angle.
    """
    order = ["crossing_angle_deg", "n"] + [f"{v}_{s}" for v in values
                                          for s in ("median", "q25", "q75", "ci_low", "ci_high")]
    return pd.DataFrame(rows)[order]


def peak_angle(curve: pd.DataFrame, boot: np.ndarray, value: str = "locus_length_m", *,
               confidence_level: float = 0.95) -> dict[str, float]:
    """Angle of the largest median and its percentile bootstrap interval (argmax of each
    resample's medians over the grid).

    Parameters
    ----------
    curve : pandas.DataFrame
        A curve of :func:`curve_summary`.
    boot : numpy.ndarray, shape (n_resamples, n_angles)
        Bootstrap medians of ``value`` at each angle.
    value : str
        Column whose peak is taken.
    confidence_level : float
        Level of the interval, in (0, 1).

    Returns
    -------
    dict of str to float
        ``angle_deg`` (the grid angle of the largest median), ``ci_low_deg``, ``ci_high_deg``.
    """
    angles = curve["crossing_angle_deg"].to_numpy(float)
    at = angles[np.argmax(boot, axis=1)]
    lo, hi = _interval(at, confidence_level)
    return {"angle_deg": float(angles[np.argmax(curve[f"{value}_median"].to_numpy())]),
            "ci_low_deg": float(lo), "ci_high_deg": float(hi)}


@dataclass(frozen=True)
class CrossingAngleCurve:
    """Result of :func:`crossing_angle_curve`.

    Attributes
    ----------
    curve : pandas.DataFrame
        Per crossing angle (see :func:`curve_summary`) plus ``acceptance`` (share of drawn pass
        pairs in which both passes see the feature).
    samples, acceptance : pandas.DataFrame
        From :func:`sss_locus.experiments.survey_passes.study.simulate_passes`.
    peak : dict
        ``value -> {angle_deg, ci_low_deg, ci_high_deg}`` (:func:`peak_angle`).
    """

    platform: Platform
    envelope: SurveyEnvelope
    offset_model: OffsetModel
    curve: pd.DataFrame
    samples: pd.DataFrame = field(repr=False)
    acceptance: pd.DataFrame = field(repr=False)
    peak: dict = field(default_factory=dict)

    def at(self, gamma_deg: float, value: str = "locus_length_m") -> dict[str, float]:
        """Median and its interval at one grid angle.

        Parameters
        ----------
        gamma_deg : float
            A crossing angle of the grid, degrees.
        value : str
            Column.

        Returns
        -------
        dict of str to float
            ``median``, ``ci_low``, ``ci_high``, ``q25``, ``q75`` at that angle.
        """
        row = self.curve[np.isclose(self.curve["crossing_angle_deg"], gamma_deg)]
        if row.empty:
            raise ValueError(f"gamma_deg {gamma_deg} is not on the grid")
        r = row.iloc[0]
        return {k: float(r[f"{value}_{k}"]) for k in ("median", "ci_low", "ci_high", "q25", "q75")}


def crossing_angle_curve(platform: Platform, envelope: SurveyEnvelope | None = None,
                         offset_model: OffsetModel | None = None, *, crossing_angles_deg=None,
                         n_per_angle: int = 2000, seed: int = 0, n_batches: int = N_BATCHES,
                         n_resamples: int = 200, confidence_level: float = 0.95,
                         simulate=simulate_passes) -> CrossingAngleCurve:
    """Locus length and elevation misalignment against crossing angle for two straight passes.

    Parameters
    ----------
    platform : Platform
    envelope : SurveyEnvelope, optional
        Default: the platform's envelope in ``data/survey.toml``.
    offset_model : OffsetModel, optional
        Default: ``OffsetModel("independent")``.
    crossing_angles_deg : array_like, optional
        Default :func:`crossing_angle_grid` (1 deg to 40 deg, then 5 deg).
    n_per_angle, seed : int
        Accepted pass pairs per angle; random seed.
    n_batches : int
        Replicate batches of each angle's rows for the medians' intervals (:func:`curve_summary`).
    n_resamples : int
        Bootstrap resamples for the peak angle's interval (:func:`peak_angle`).
    confidence_level : float
    simulate : callable
        :func:`~sss_locus.experiments.survey_passes.study.simulate_passes` or a cached version of it.

    Returns
    -------
    CrossingAngleCurve
        The curve (medians, quartiles and intervals per angle), the peak angle and the acceptance
        table.
    """
    envelope = envelope if envelope is not None else load_envelope(platform.key)
    offset_model = offset_model if offset_model is not None else OffsetModel("independent")
    angles = crossing_angle_grid() if crossing_angles_deg is None else crossing_angles_deg
    samples, acc = simulate(platform, envelope, offset_model, angles, n_per_angle, seed)
    curve, boot = curve_summary(samples, n_batches=n_batches, n_resamples=n_resamples,
                                confidence_level=confidence_level, seed=seed)
    curve["acceptance"] = acc.set_index("crossing_angle_deg")["acceptance"].reindex(
        curve["crossing_angle_deg"]).to_numpy()
    peak = {v: peak_angle(curve, boot[v], v, confidence_level=confidence_level) for v in VALUES}
    return CrossingAngleCurve(platform, envelope, offset_model, curve, samples, acc, peak)


def planning_bands(curve: pd.DataFrame, value: str = "locus_length_m", *,
                   prefer_below: float = 0.25, avoid_above: float = 0.5) -> pd.DataFrame:
    """Crossing-angle bands to prefer and to avoid, from a computed median curve.

    Parameters
    ----------
    curve : pandas.DataFrame
        With ``crossing_angle_deg`` and ``<value>_median`` (:attr:`CrossingAngleCurve.curve`).
    value : str
        The column whose median curve is used.
    prefer_below, avoid_above : float
        Fractions of the curve's range (module docstring), ``0 <= prefer_below < avoid_above <= 1``.

    Returns
    -------
    pandas.DataFrame
        One row per band, sorted by angle: ``kind`` ("prefer"/"avoid"), ``lo_deg``, ``hi_deg``
        (first and last grid angle of the run), ``median_min``, ``median_max`` within it.
    """
    if not 0.0 <= prefer_below < avoid_above <= 1.0:
        raise ValueError("need 0 <= prefer_below < avoid_above <= 1; got "
                         f"{prefer_below}, {avoid_above}")
    col = f"{value}_median"
    if col not in curve or "crossing_angle_deg" not in curve:
        raise ValueError(f"curve must have columns crossing_angle_deg and {col}")
    c = curve.sort_values("crossing_angle_deg")
    g, m = c["crossing_angle_deg"].to_numpy(float), c[col].to_numpy(float)
    lo, span = m.min(), m.max() - m.min()
    level = (m - lo) / span if span > 0 else np.zeros_like(m)
    rows = []
    for kind, mask in (("prefer", level <= prefer_below), ("avoid", level >= avoid_above)):
        edges = np.flatnonzero(np.diff(np.concatenate([[0], mask.astype(int), [0]])))
        for a, b in zip(edges[::2], edges[1::2]):
            rows.append({"kind": kind, "lo_deg": g[a], "hi_deg": g[b - 1],
                         "median_min": m[a:b].min(), "median_max": m[a:b].max()})
    out = pd.DataFrame(rows, columns=["kind", "lo_deg", "hi_deg", "median_min", "median_max"])
    return out.sort_values("lo_deg", ignore_index=True)


def worst_band(curve: pd.DataFrame, value: str = "locus_length_m", **rule) -> tuple[float, float]:
    """The avoid band (:func:`planning_bands`) containing the curve's largest median.

    Parameters
    ----------
    curve : pandas.DataFrame
        A median curve.
    value : str
        Column used.
    **rule
        ``prefer_below``, ``avoid_above`` of :func:`planning_bands`.

    Returns
    -------
    (float, float)
        First and last angle of the band, degrees.
    """
    bands = planning_bands(curve, value, **rule)
    peak = float(curve.loc[curve[f"{value}_median"].idxmax(), "crossing_angle_deg"])
    hit = bands[(bands["kind"] == "avoid") & (bands["lo_deg"] <= peak) & (bands["hi_deg"] >= peak)]
    return float(hit.iloc[0]["lo_deg"]), float(hit.iloc[0]["hi_deg"])


def band_at(bands: pd.DataFrame, angle_deg: float) -> str:
    """``"prefer"``, ``"avoid"`` or ``"neither"``: the kind of :func:`planning_bands` band
    holding ``angle_deg``.

    Parameters
    ----------
    bands : pandas.DataFrame
        Bands of :func:`planning_bands`.
    angle_deg : float
        Crossing angle, degrees.

    Returns
    -------
    str
        The kind of band.
    """
    hit = bands[(bands["lo_deg"] <= angle_deg) & (bands["hi_deg"] >= angle_deg)]
    return str(hit["kind"].iloc[0]) if len(hit) else "neither"


def rejected_share(acceptance: pd.DataFrame) -> tuple[float, float]:
    """Share of drawn pass pairs rejected: over the whole grid, and the largest at one angle.

    ``acceptance`` is the second table of
    :func:`~sss_locus.experiments.survey_passes.study.simulate_passes` (``n_tried``, ``n_accepted``,
    ``acceptance`` per angle).

    Parameters
    ----------
    acceptance : pandas.DataFrame
        The acceptance table.

    Returns
    -------
    (float, float)
        The share over the grid and the largest share at one angle, in [0, 1].
    """
    overall = 1 - acceptance["n_accepted"].sum() / acceptance["n_tried"].sum()
    return float(overall), float(1 - acceptance["acceptance"].min())


def curve_shape_rho(curve: pd.DataFrame, a: str = "locus_length_m",
                    b: str = "elevation_misalignment_deg") -> float:
    """Rank correlation (Spearman, as the Pearson correlation of ranks) of the median curves of
    ``a`` and ``b`` over the crossing-angle grid: whether the two curves rise and fall together
    (it says nothing about where their peaks are).

    Parameters
    ----------
    curve : pandas.DataFrame
        A curve of :func:`curve_summary`.
    a, b : str
        Values whose ``_median`` columns are compared.

    Returns
    -------
    float
        Spearman's rho, in [-1, 1].
    """
    return spearman_rho(curve[f"{a}_median"].to_numpy(float), curve[f"{b}_median"].to_numpy(float))


def median_ratio(x, y, *, n_batches: int = N_BATCHES,
                 confidence_level: float = 0.95) -> dict[str, float]:
    """``median(x) / median(y)`` and each median, each with its replicate interval.

    ``x`` and ``y`` (independent samples, each i.i.d. in its order) are each split into
    ``n_batches`` batches; batch ``j``'s ratio is the median of ``x``'s batch ``j`` over that of
    ``y``'s (NaN where the latter is not positive), and
    :func:`~sss_locus.experiments.stats.replicates.replicate_interval` turns the spread of the
    batches' statistics into intervals around the full-sample ones.

    Parameters
    ----------
    x, y : array_like
        The two samples.
    n_batches : int
        Replicate batches of each.
    confidence_level : float
        Level of the intervals, in (0, 1).

    Returns
    -------
    dict of str to float
        ``ratio``, ``median_x``, ``median_y``, each with ``_ci_low`` and ``_ci_high``.
    """
    mx, x_lo, x_hi = median_with_interval(x, n_batches, confidence_level)
    my, y_lo, y_hi = median_with_interval(y, n_batches, confidence_level)
    k = min(len(np.asarray(x)), len(np.asarray(y)), n_batches)
    bx, by = batch_statistic(x, np.median, k), batch_statistic(y, np.median, k)
    ratio = mx / my if my > 0 else math.nan
    lo, hi = replicate_interval(ratio, bx / np.where(by > 0, by, np.nan), confidence_level)
    return {"median_x": mx, "median_y": my, "ratio": ratio,
            "median_x_ci_low": x_lo, "median_x_ci_high": x_hi,
            "median_y_ci_low": y_lo, "median_y_ci_high": y_hi,
            "ratio_ci_low": float(lo), "ratio_ci_high": float(hi)}


def band_samples(platform: Platform, envelope: SurveyEnvelope, offset_model: OffsetModel,
                 band_deg: tuple[float, float], grid, n_per_angle: int, seed: int, *,
                 simulate=simulate_passes) -> pd.DataFrame:
    """Simulated pass pairs at the grid angles inside ``band_deg`` (inclusive), pooled
    (``simulate`` as in :func:`crossing_angle_curve`).

    Parameters
    ----------
    platform : Platform
        The platform surveying.
    envelope : SurveyEnvelope
        Its survey envelope.
    offset_model : OffsetModel
        How the ground offsets are drawn.
    band_deg : (float, float)
        The band of crossing angles, degrees.
    grid : array_like
        Crossing angles, degrees; those inside the band are simulated.
    n_per_angle : int
        Pass pairs per angle.
    seed : int
        Seed.
    simulate : callable
        The simulation (cached or not).

    Returns
    -------
    pandas.DataFrame
        The pass pairs of every angle in the band, pooled.
    """
    g = np.asarray(grid, float)
    angles = g[(g >= band_deg[0] - 1e-9) & (g <= band_deg[1] + 1e-9)]
    if angles.size == 0:
        raise ValueError(f"no grid angle inside band_deg {band_deg}")
    return simulate(platform, envelope, offset_model, angles, n_per_angle, seed)[0]


def pitch_study_platform(platforms: dict[str, Platform], envelopes: dict[str, SurveyEnvelope],
                         pitch_levels_deg) -> str | None:
    """The first platform key of ``platforms`` that can fly the pitch study, or ``None``.

    The study fixes both passes at each pitch of ``pitch_levels_deg`` (degrees, positive
    nose-up, either sign): a platform qualifies when its envelope draws pitch (a non-empty
    range) and its pitch limit covers the largest magnitude asked for. ``None`` (no platform of
    the run pitches, e.g. surface boats only) means the study is skipped, not run on a platform
    that would be driven past its limit.

    Parameters
    ----------
    platforms : dict of str to Platform
        The run's platforms by key, in the run's order.
    envelopes : dict of str to SurveyEnvelope
        Each platform's survey envelope, by the same keys.
    pitch_levels_deg : iterable of float
        The pitch levels of the study, degrees (positive nose-up).

    Returns
    -------
    str or None
        The first qualifying platform key, or ``None`` when no platform of the run can pitch
        that far.
    """
    need = max((abs(float(p)) for p in pitch_levels_deg), default=0.0)
    return next((k for k, p in platforms.items()
                 if envelopes[k].pitch_max_deg > envelopes[k].pitch_min_deg and p.pitch_max_deg >= need), None)
