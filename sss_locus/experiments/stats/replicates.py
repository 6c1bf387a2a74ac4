"""Monte Carlo uncertainty from independent replicates (batch means), and the one Spearman path.

Every study's samples are i.i.d. draws (:mod:`sss_locus.experiments.pose_space.study`,
:mod:`sss_locus.experiments.survey_passes.study`: independently seeded blocks, rows in draw order), so
a table of ``n`` rows dealt into ``k`` batches (row ``i`` to batch ``i mod k``) is ``k``
independent replicate studies of ``n / k`` rows. Dealing rather than cutting the table into
consecutive runs keeps the batches alike where the rows are grouped, e.g. survey passes pooled
over several crossing angles (each batch holds the same share of every angle). For a statistic ``T`` the point estimate
stays ``T`` of the whole table, and its interval at ``confidence_level`` is

    T +- t_{k-1} * sd(T_1, ..., T_k) / sqrt(k)

(:func:`replicate_interval`; ``T_j`` the statistic of batch ``j``, ``sd`` with ``k - 1``
degrees of freedom, ``t_{k-1}`` Student's quantile): the batches' spread estimates the
standard error of a statistic whose variance falls as ``1 / n``, as for a mean, a median, a
ratio of them or a correlation. Batches cost one pass over the table (a bootstrap costs one
pass per resample) and need nothing but the batches' own statistics, so they can be computed
where the rows are.

Measured coverage (``tests/experiments/stats/test_replicates.py``, against known population values, with the
bootstrap's widths alongside) decides where this applies; with very small batches (fewer than
~10 rows) the interval is wider than needed (conservative), never narrower. A statistic that is
not smooth in the data (the argmax of a median curve, :func:`~sss_locus.experiments.survey_passes.planning.peak_angle`)
keeps its bootstrap.

Spearman's rho: :func:`spearman_rho`, the Pearson correlation of average ranks (the numbers of
:func:`scipy.stats.spearmanr`), is the package's only implementation; :func:`fisher_z_interval`
is the asymptotic interval it is cross-checked against.
"""

from __future__ import annotations

import math

import numpy as np

from sss_locus.experiments.stats.rowstats import average_ranks

N_BATCHES = 20
"""Default number of replicate batches ``k`` (at least 20: the t quantile with 19 degrees of
freedom is within 5 % of the normal one)."""


def check_batches(n_batches, name: str = "n_batches") -> int:
    """``n_batches`` as an int, ``ValueError`` naming ``name`` unless an integer >= 3.

    Parameters
    ----------
    n_batches : int
        Number of batches.
    name : str
        Name of the argument in the error message.

    Returns
    -------
    int
        ``n_batches``.
    """
    if isinstance(n_batches, bool) or not isinstance(n_batches, (int, np.integer)) or n_batches < 3:
        raise ValueError(f"{name} must be an integer >= 3 (replicate batches); got {n_batches!r}")
    return int(n_batches)


def check_confidence(confidence_level) -> float:
    """``confidence_level`` as a float, ``ValueError`` unless in (0, 1).

    Parameters
    ----------
    confidence_level : float
        Level of an interval.

    Returns
    -------
    float
        ``confidence_level``.
    """
    if not (isinstance(confidence_level, (int, float)) and 0.0 < confidence_level < 1.0):
        raise ValueError(f"confidence_level must be in (0, 1); got {confidence_level!r}")
    return float(confidence_level)


def batch_count(n: int, n_batches: int = N_BATCHES) -> int:
    """The number of batches ``k = min(n_batches, n)`` of ``n`` rows; batch ``j`` is rows
    ``j, j + k, j + 2k, ...`` (``values[j::k]``). ``ValueError`` if ``n < 3`` (an interval
    needs three replicates).

    Parameters
    ----------
    n : int
        Rows.
    n_batches : int
        Batches wanted, ``>= 3``.

    Returns
    -------
    int
        ``k``.
    """
    k = min(check_batches(n_batches), int(n))
    if k < 3:
        raise ValueError(f"need at least 3 rows for replicate batches; got {n}")
    return k


def batch_statistic(values, fn, n_batches: int = N_BATCHES) -> np.ndarray:
    """``fn`` of each batch ``values[j::k]`` of the rows of ``values`` (:func:`batch_count`),
    stacked: shape ``(k, ...)``.

    Parameters
    ----------
    values : array_like, shape (n, ...)
        Rows.
    fn : callable
        Statistic of one batch (array -> array or number).
    n_batches : int
        Batches wanted.

    Returns
    -------
    numpy.ndarray, shape (k, ...)
        The batches' statistics.
    """
    v = np.asarray(values)
    k = batch_count(len(v), n_batches)
    return np.stack([np.asarray(fn(v[j::k])) for j in range(k)])


def replicate_interval(estimate, batch_stats, confidence_level: float = 0.95, bounds=None):
    """``(low, high)``: ``estimate +- t_{k-1} sd(batch_stats) / sqrt(k)`` (module docstring),
    clipped to ``bounds = (lo, hi)`` when given (the statistic's range, e.g. ``(0, 1)`` for a
    share: a symmetric interval of a rare share would otherwise reach below 0).

    ``batch_stats`` has the ``k`` replicates along axis 0; ``estimate`` broadcasts against the
    rest. NaN where any replicate is NaN (a batch whose statistic is undefined).

    Parameters
    ----------
    estimate : float or numpy.ndarray
        The full-sample statistic.
    batch_stats : numpy.ndarray, shape (k, ...)
        The replicates' statistics.
    confidence_level : float
        Level, in (0, 1).
    bounds : (float, float), optional
        Range of the statistic.

    Returns
    -------
    low, high : float or numpy.ndarray
        Ends of the interval, shaped like ``estimate`` broadcast with ``batch_stats[0]``.
    """
    from scipy.special import stdtrit  # not at import: scipy.special loads in ~0.2 s

    b = np.asarray(batch_stats, float)
    k = b.shape[0]
    if k < 3:
        raise ValueError(f"need at least 3 replicates; got {k}")
    q = stdtrit(k - 1, 0.5 + check_confidence(confidence_level) / 2.0)
    half = q * np.std(b, axis=0, ddof=1) / math.sqrt(k)
    lo, hi = np.asarray(estimate, float) - half, np.asarray(estimate, float) + half
    if bounds is not None:
        lo, hi = np.clip(lo, *bounds), np.clip(hi, *bounds)
    return lo, hi


def median_with_interval(values, n_batches: int = N_BATCHES,
                         confidence_level: float = 0.95) -> tuple[float, float, float]:
    """Median of ``values`` (1-D) and its :func:`replicate_interval` from batch medians, within
    the values' range.

    Parameters
    ----------
    values : array_like, shape (n,)
        Sample, i.i.d. in its order.
    n_batches : int
        Replicate batches.
    confidence_level : float
        Level, in (0, 1).

    Returns
    -------
    median, low, high : float
        The median and its interval.
    """
    x = np.asarray(values, float)
    if x.ndim != 1 or x.size == 0:
        raise ValueError(f"values must be a non-empty 1-D array; got shape {x.shape}")
    med = float(np.median(x))
    lo, hi = replicate_interval(med, batch_statistic(x, np.median, n_batches), confidence_level,
                                bounds=(x.min(), x.max()))
    return med, float(lo), float(hi)


def centred_from(ranks: np.ndarray) -> np.ndarray:
    """Ranks ``(n, p)`` (1..n) centred and scaled, ``(r - (n + 1) / 2) / n`` (well-conditioned
    sums).

    Parameters
    ----------
    ranks : numpy.ndarray, shape (n, p)
        Ranks of ``p`` columns.

    Returns
    -------
    numpy.ndarray, shape (n, p)
        Centred, scaled ranks.
    """
    n = ranks.shape[0]
    return (ranks - (n + 1) / 2.0) / n


def centred_ranks(columns) -> np.ndarray:
    """:func:`centred_from` of the average ranks of each column of ``columns`` (a list of 1-D
    arrays), as an ``(n, p)`` array.

    Parameters
    ----------
    columns : sequence of numpy.ndarray, each shape (n,)
        The columns.

    Returns
    -------
    numpy.ndarray, shape (n, p)
        Centred, scaled average ranks.
    """
    return centred_from(np.column_stack([average_ranks(np.asarray(c)) for c in columns]))


def rank_correlation(rx: np.ndarray, ry: np.ndarray) -> np.ndarray:
    """Pearson correlation of every column of ``rx`` ``(n, p)`` with every column of ``ry``
    ``(n, q)``, shape ``(p, q)``: Spearman's rho when the columns are (centred) ranks.

    Parameters
    ----------
    rx : numpy.ndarray, shape (n, p)
        Centred columns.
    ry : numpy.ndarray, shape (n, q)
        Centred columns.

    Returns
    -------
    numpy.ndarray, shape (p, q)
        Correlations, in [-1, 1] (NaN for a constant column).
    """
    dx, dy = rx - rx.mean(axis=0), ry - ry.mean(axis=0)
    return (dx.T @ dy) / np.sqrt(np.outer((dx * dx).sum(axis=0), (dy * dy).sum(axis=0)))


def spearman_rho(x, y) -> float:
    """Spearman's rho of two 1-D samples (average ranks for ties; NaN if either holds NaN).

    Parameters
    ----------
    x, y : array_like, shape (n,)
        The samples.

    Returns
    -------
    float
        Spearman's rho, in [-1, 1].
    """
    return float(rank_correlation(centred_ranks([x]), centred_ranks([y]))[0, 0])


def fisher_z_interval(rho, n, confidence_level: float = 0.95):
    """Asymptotic interval of Spearman's rho: ``tanh(atanh(rho) +- z sqrt((1 + rho^2 / 2) /
    (n - 3)))`` (Bonett & Wright 2000, *Psychometrika* 65, 23-28), the cross-check of the
    replicate interval. ``rho`` and ``n`` broadcast; returns ``(low, high)``.

    Parameters
    ----------
    rho : float or array_like
        Spearman's rho.
    n : int or array_like
        Sample sizes, ``> 3``.
    confidence_level : float
        Level, in (0, 1).

    Returns
    -------
    low, high : numpy.ndarray
        Ends of the interval.
    """
    from scipy.special import ndtri

    r = np.asarray(rho, float)
    se = np.sqrt((1.0 + r ** 2 / 2.0) / (np.asarray(n, float) - 3.0))
    z = ndtri(0.5 + check_confidence(confidence_level) / 2.0)
    with np.errstate(divide="ignore"):
        centre = np.arctanh(r)
    return np.tanh(centre - z * se), np.tanh(centre + z * se)
