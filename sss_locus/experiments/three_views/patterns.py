"""Three passes over one feature: survey patterns and heading sweeps through the three-view kernel.

Draws configurations with :func:`~sss_locus.experiments.passes.view_sets.draw_pattern`, runs
:func:`sss_locus.geometry.three_view_points` on them and summarises whether the third view
resolves the feature, how well conditioned the solution is and, with a noise model, how large the
first-order 95 % point error is.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from sss_locus.geometry import Aperture, three_view_points
from sss_locus.experiments.passes.propagation import first_order
from sss_locus.experiments.stats.gaussian_norm import gaussian_norm_quantile
from sss_locus.experiments.stats.replicates import N_BATCHES, median_with_interval
from sss_locus.experiments.passes.view_sets import Views, draw_pattern

PATTERNS = {
    "repeat + reciprocal": (0.0, 0.0, 180.0),
    "two lines + cross line": (0.0, 180.0, 90.0),
    "three headings 60 deg apart": (0.0, 60.0, 120.0),
}
"""Survey patterns of three passes (headings in degrees, positive toward port): a line flown
twice the same way and once the other way; two adjacent lawn-mower lines (flown in opposite
directions) and a cross line; three headings 60 deg apart."""


def three_view_table(views: Views, aperture, noise=None) -> pd.DataFrame:
    """The three-view kernel on every configuration of three views (views 0, 1, 2 = sensors 1-3).

    Returns one row per configuration: ``status`` (:class:`~sss_locus.geometry.ThreeViewStatus`),
    ``n_valid`` (1 resolved, 2 two-fold ambiguity), ``plane_angle_deg``, ``tangency_margin``
    (``half_separation / r1``), ``candidate_separation_m`` (``2 h``), ``feature_error_m``
    (distance from the true feature to the nearest candidate: rounding only), ``r1_m``, and
    ``n_valid_no_elevation`` / ``n_valid_no_azimuth``: the same count with the elevation bound
    (azimuth and range bounds) of every aperture lifted, to show which bound rejects the second
    candidate. With a
    :class:`~sss_locus.experiments.datamodel.noise_model.NoiseModel` ``noise``, also ``point_error_q95_m``: the first-order
    95 % error of the point (:func:`sss_locus.experiments.passes.propagation.first_order`).

    Parameters
    ----------
    views : Views
        Configurations of three views.
    aperture : Aperture
        The views' aperture.
    noise : NoiseModel, optional
        Error model for the first-order point error.

    Returns
    -------
    pandas.DataFrame
        One row per configuration, the columns named above.
    """
    if views.origin.shape[1] != 3:
        raise ValueError(f"views must hold 3 views; got {views.origin.shape[1]}")
    R12, t12 = views.relative(0, 1)
    R13, t13 = views.relative(0, 2)
    r = views.ranges
    res = three_view_points(R12, t12, R13, t13, r[:, 0], r[:, 1], r[:, 2], aperture, aperture, aperture)
    f1 = np.einsum("nji,nj->ni", views.W[:, 0], views.feature - views.origin[:, 0])
    err = np.linalg.norm(res.candidates - f1[:, None, :], axis=-1).min(axis=1)
    lifted = {}
    for name, ap in (("no_elevation", Aperture(aperture.azimuth_deg, 180.0, aperture.max_range, aperture.min_range)),
                     ("no_azimuth", Aperture(360.0, aperture.elevation_deg, 1e12, 0.0))):
        lifted[f"n_valid_{name}"] = three_view_points(R12, t12, R13, t13, r[:, 0], r[:, 1], r[:, 2],
                                                      ap, ap, ap).n_valid.astype(np.int8)
    out = pd.DataFrame({
        **lifted, "status": res.status.astype(np.int8), "n_valid": res.n_valid.astype(np.int8),
        "plane_angle_deg": res.plane_angle_deg, "tangency_margin": res.half_separation / r[:, 0],
        "candidate_separation_m": 2 * res.half_separation, "feature_error_m": err, "r1_m": r[:, 0]})
    if noise is not None:
        out["point_error_q95_m"] = gaussian_norm_quantile(first_order(views, noise, aperture, kind="three"))
    return out


def heading_sweep(platform, envelope, headings2_deg, headings3_deg, n: int, seed: int,
                  noise=None, n_batches: int = N_BATCHES) -> pd.DataFrame:
    """Three passes at headings (0, h2, h3) for every pair of the two grids (``h3 >= h2``).

    Returns one row per pair: ``heading2_deg``, ``heading3_deg``, ``resolved_fraction``,
    ``ambiguous_fraction``, ``plane_angle_median_deg``, ``tangency_margin_median``, ``n`` and,
    with ``noise``, ``point_error_q95_median_m`` (see :func:`three_view_table`) with its 95 %
    replicate-batch interval ``point_error_q95_median_ci_low_m``/``_ci_high_m`` (``n_batches``
    batches, :func:`~sss_locus.experiments.stats.replicates.median_with_interval`). Each pair is
    drawn with its own seed (``seed`` plus the pair's index in the grid).

    Parameters
    ----------
    platform : Platform
        The platform surveying.
    envelope : SurveyEnvelope
        Its survey envelope.
    headings2_deg, headings3_deg : sequence of float
        Headings of passes 2 and 3, degrees.
    n : int
        Configurations per pair.
    seed : int
        Seed of the first pair.
    noise : NoiseModel, optional
        Error model for the point error.
    n_batches : int
        Replicate batches of the intervals.

    Returns
    -------
    pandas.DataFrame
        One row per pair, the columns named above.
    """
    rows, i = [], 0
    for h2 in np.asarray(headings2_deg, float):
        for h3 in np.asarray(headings3_deg, float):
            if h3 < h2:
                continue
            views, _ = draw_pattern(platform, envelope, (0.0, h2, h3), n, seed + i)
            tab = three_view_table(views, platform.sonar.aperture(), noise)
            extra = {}
            if noise is not None:
                med, lo, hi = median_with_interval(tab.point_error_q95_m.to_numpy(), n_batches)
                extra = {"point_error_q95_median_m": med, "point_error_q95_median_ci_low_m": lo,
                         "point_error_q95_median_ci_high_m": hi}
            rows.append({**extra, "heading2_deg": h2, "heading3_deg": h3,
                         "resolved_fraction": float((tab.n_valid == 1).mean()),
                         "ambiguous_fraction": float((tab.n_valid == 2).mean()),
                         "plane_angle_median_deg": float(tab.plane_angle_deg.median()),
                         "tangency_margin_median": float(tab.tangency_margin.median()), "n": n})
            i += 1
    return pd.DataFrame(rows)


def share_upper_bound(count: int, n: int, confidence_level: float = 0.95) -> float:
    """One-sided exact (Clopper-Pearson) upper confidence bound of a share ``count / n``.

    The largest true share ``p`` with ``P(Binomial(n, p) <= count) >= 1 - confidence_level``:
    ``betaincinv(count + 1, n - count, confidence_level)``; 1 when ``count == n``. For a share
    seen in few of ``n`` configurations (e.g. the two-fold ambiguities), it says how large the
    share could be.

    Parameters
    ----------
    count : int
        Configurations with the property, ``0 <= count <= n``.
    n : int
        Configurations, ``>= 1``.
    confidence_level : float
        Level, in (0, 1).

    Returns
    -------
    float
        The bound, in [0, 1].
    """
    from scipy.special import betaincinv

    for name, v in (("count", count), ("n", n)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)):
            raise ValueError(f"{name} must be an integer; got {v!r}")
    if not 0 <= count <= n or n < 1:
        raise ValueError(f"need 0 <= count <= n and n >= 1; got count={count}, n={n}")
    if not 0.0 < confidence_level < 1.0:
        raise ValueError(f"confidence_level must be in (0, 1); got {confidence_level!r}")
    return 1.0 if count == n else float(betaincinv(count + 1, n - count, confidence_level))


def cells_within(sweep: pd.DataFrame, best: str = "min", value: str = "point_error_q95_median_m") -> pd.DataFrame:
    """The cells of a :func:`heading_sweep` (with noise) that the sampling cannot tell from its
    best (``best="min"``) or worst (``"max"``) cell: those whose median ``value`` lies inside the
    95 % interval (``value`` with its ending ``_m`` read as ``_ci_low_m``/``_ci_high_m``) of the
    smallest (largest) median, that cell always among them.

    Parameters
    ----------
    sweep : pandas.DataFrame
        A heading sweep with noise.
    best : {"min", "max"}
        Which extreme cell.
    value : str
        Column compared (ending ``_m``, with its interval columns).

    Returns
    -------
    pandas.DataFrame
        The rows of ``sweep`` in the region.
    """
    if best not in ("min", "max"):
        raise ValueError(f"best must be 'min' or 'max'; got {best!r}")
    if not value.endswith("_m"):
        raise ValueError(f"value must name a column in metres (ending in _m); got {value!r}")
    v = sweep[value]
    i = v.idxmin() if best == "min" else v.idxmax()
    if best == "min":
        return sweep[v <= max(v[i], sweep.loc[i, value[:-2] + "_ci_high_m"])]
    return sweep[v >= min(v[i], sweep.loc[i, value[:-2] + "_ci_low_m"])]


def share_interval(count: int, n: int, confidence_level: float = 0.95) -> tuple[float, float]:
    """Two-sided exact (Clopper-Pearson) interval of a share ``count / n``: the ``(1 - level)
    / 2`` and ``(1 + level) / 2`` quantiles of Beta(count, n - count + 1) and Beta(count + 1,
    n - count), 0 and 1 at the ends. Checks its arguments like :func:`share_upper_bound`.

    Parameters
    ----------
    count : int
        Configurations with the property, ``0 <= count <= n``.
    n : int
        Configurations, ``>= 1``.
    confidence_level : float
        Level, in (0, 1).

    Returns
    -------
    (float, float)
        Lower and upper ends, in [0, 1].
    """
    from scipy.special import betaincinv

    share_upper_bound(count, n, confidence_level)  # the same argument checks
    a = (1.0 - confidence_level) / 2.0
    lo = 0.0 if count == 0 else float(betaincinv(count, n - count + 1, a))
    hi = 1.0 if count == n else float(betaincinv(count + 1, n - count, 1.0 - a))
    return lo, hi


def median_intervals(table: pd.DataFrame, columns, n_batches: int = N_BATCHES) -> dict[str, dict[str, float]]:
    """Per column of ``table`` (the rows i.i.d. configurations), its median and 95 %
    replicate-batch interval (:func:`~sss_locus.experiments.stats.replicates.median_with_interval`,
    NaN rows left out): ``{column: {"median", "ci_low", "ci_high"}}``.

    Parameters
    ----------
    table : pandas.DataFrame
        Rows of i.i.d. configurations.
    columns : sequence of str
        Columns summarised.
    n_batches : int
        Replicate batches.

    Returns
    -------
    dict of str to dict of str to float
        Per column, ``median``, ``ci_low`` and ``ci_high``.
    """
    out = {}
    for c in columns:
        v = table[c].to_numpy(float)
        med, lo, hi = median_with_interval(v[~np.isnan(v)], n_batches)
        out[c] = {"median": med, "ci_low": lo, "ci_high": hi}
    return out
