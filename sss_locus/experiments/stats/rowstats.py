"""Row-wise statistics of Monte Carlo tables, vectorised over rows."""

from __future__ import annotations

import numpy as np
from scipy.stats import rankdata


def nanquantile_rows(x, q) -> np.ndarray:
    """Row-wise quantile ignoring NaN; NaN for all-NaN rows (without a warning).

    The same numbers as ``np.nanquantile(x, q, axis=1)`` (its "linear" method: the same
    virtual index, neighbours and interpolation, operation for operation) with one sort of the
    whole table instead of one ``np.quantile`` call per row.

    Parameters
    ----------
    x : array_like, shape (m, n)
        Table, one sample per row.
    q : float
        Quantile, in [0, 1].

    Returns
    -------
    numpy.ndarray, shape (m,)
        The quantile of each row.
    """
    x = np.asarray(x, float)
    s = np.sort(x, axis=1)  # NaN last
    k = (~np.isnan(x)).sum(axis=1)
    out = np.full(x.shape[0], np.nan)
    ok = k > 0
    if not ok.any():
        return out
    s, k = s[ok], k[ok]
    q = np.asanyarray(q, dtype=float)
    virtual = (k - 1) * q
    prev = np.floor(virtual)
    above = virtual >= k - 1
    i_prev = np.where(above, k - 1, prev).astype(np.intp)
    i_next = np.where(above, k - 1, prev + 1).astype(np.intp)
    gamma = virtual - np.where(above, -1.0, prev)
    rows = np.arange(len(k))
    out[ok] = _lerp(s[rows, i_prev], s[rows, i_next], gamma)
    return out


def _lerp(a, b, gamma):
    """numpy's quantile interpolation between neighbours ``a <= b``, operation for operation."""
    diff = b - a
    return np.where(gamma >= 0.5, b - diff * (1 - gamma), a + diff * gamma)


def average_ranks(v) -> np.ndarray:
    """Ranks 1..n of a 1-D array, ties given their average rank; all NaN if any value is NaN.

    Parameters
    ----------
    v : array_like, shape (n,)
        Values to rank (numbers or anything :func:`numpy.sort` orders).

    Returns
    -------
    numpy.ndarray, shape (n,), float64
        :func:`scipy.stats.rankdata` of ``v`` (``method="average"``, ``nan_policy="propagate"``).
    """
    return np.asarray(rankdata(_one_d(v)), float)


def batch_average_ranks(v, n_batches: int) -> np.ndarray:
    """The ranks of each replicate batch ``v[j::k]`` (``k = n_batches``) within the batch, the
    batches one after another.

    Parameters
    ----------
    v : array_like, shape (n,)
        Values to rank.
    n_batches : int
        Number of batches ``k >= 1``; row ``i`` is in batch ``i mod k``.

    Returns
    -------
    numpy.ndarray, shape (n,), float64
        ``np.concatenate([average_ranks(v[j::k]) for j in range(k)])``: a batch holding a NaN
        gets NaN ranks.
    """
    v, k = _one_d(v), int(n_batches)
    if k < 1:
        raise ValueError(f"n_batches must be a positive integer; got {n_batches!r}")
    return np.concatenate([average_ranks(v[j::k]) for j in range(k)]) if v.size else np.empty(0)


def _one_d(v) -> np.ndarray:
    v = np.asarray(v)
    if v.ndim != 1:
        raise ValueError(f"average_ranks takes a 1-D array; got shape {v.shape}")
    return v
