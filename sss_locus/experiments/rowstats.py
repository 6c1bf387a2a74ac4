"""Row-wise statistics of Monte Carlo tables, vectorised over rows."""

from __future__ import annotations

import numpy as np


def nanquantile_rows(x, q) -> np.ndarray:
    """Row-wise quantile ignoring NaN; NaN for all-NaN rows (without a warning).

    The same numbers as ``np.nanquantile(x, q, axis=1)`` (its "linear" method: the same
    virtual index, neighbours and interpolation, operation for operation) with one sort of the
    whole table instead of one ``np.quantile`` call per row.
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


def weighted_correlations(X, Y, weights, *, rows_per_chunk: int = 8192) -> np.ndarray:
    """Weighted Pearson correlation of every column of ``X`` with every column of ``Y``, for
    each row of ``weights``.

    ``X`` is ``(n, p)``, ``Y`` ``(n, q)``, ``weights`` ``(k, n)`` (non-negative; e.g. how often
    each row is drawn in a bootstrap resample, any integer or float dtype). Returns ``(k, p, q)``
    with ``corr = (S_xy / s - m_x m_y) / sqrt((S_xx / s - m_x^2) (S_yy / s - m_y^2))``, where
    ``s`` is the weights' sum and ``S``, ``m`` are weighted sums and means. All ``k`` rows of
    weights are handled by one matrix product per chunk of ``rows_per_chunk`` table rows (the
    products ``x^2``, ``y^2``, ``x y`` are formed per chunk, in cache), so the table is read
    once for all of them. Centre and scale the columns beforehand (e.g. ranks ``(r - (n+1)/2)
    / n``) for well-conditioned sums. Several weight matrices: :func:`weighted_correlation_sets`.
    """
    return weighted_correlation_sets(X, Y, [weights], rows_per_chunk=rows_per_chunk)[0]


def weighted_correlation_sets(X, Y, weight_sets, *, rows_per_chunk: int = 8192) -> list[np.ndarray]:
    """:func:`weighted_correlations` for each matrix of ``weight_sets`` (a list of ``(k_i, n)``
    arrays), with one pass over the table: the products of each chunk of rows are formed once
    and multiplied by every matrix. Each result is the same, bit for bit, as a separate call
    (the same matrix products, accumulated in the same order)."""
    X, Y = np.asarray(X, float), np.asarray(Y, float)
    sets = [np.asarray(W) for W in weight_sets]
    n, p = X.shape
    q = Y.shape[1]
    for W in sets:
        if Y.shape[0] != n or W.ndim != 2 or W.shape[1] != n:
            raise ValueError(f"X (n, p), Y (n, q) and weights (k, n) must share n; got shapes "
                             f"{X.shape}, {Y.shape}, {W.shape}")
    sums = [np.zeros((W.shape[0], 2 * (p + q) + p * q)) for W in sets]
    for a in range(0, n, rows_per_chunk):
        x, y = X[a:a + rows_per_chunk], Y[a:a + rows_per_chunk]
        xy = (x[:, :, None] * y[:, None, :]).reshape(len(x), p * q)
        products = np.hstack([x, y, x * x, y * y, xy])
        for W, total in zip(sets, sums):
            total += W[:, a:a + rows_per_chunk].astype(float) @ products
    out = []
    for W, total in zip(sets, sums):
        s = W.sum(axis=1, dtype=float)[:, None]
        mx, my = total[:, :p] / s, total[:, p:p + q] / s
        vx = total[:, p + q:2 * p + q] / s - mx ** 2
        vy = total[:, 2 * p + q:2 * (p + q)] / s - my ** 2
        cxy = total[:, 2 * (p + q):].reshape(-1, p, q) / s[:, :, None] - mx[:, :, None] * my[:, None, :]
        out.append(cxy / np.sqrt(vx[:, :, None] * vy[:, None, :]))
    return out


def average_ranks(v) -> np.ndarray:
    """Ranks 1..n of a 1-D array, ties given their average rank; all NaN if any value is NaN.

    The numbers of :func:`scipy.stats.rankdata` (``method="average"``, ``nan_policy=
    "propagate"``), by the same formula ``(first + last) / 2`` over each run of equal sorted
    values (ranks and half-ranks are exact in float64), without importing ``scipy.stats``.
    Float64 values are put in order by sorting integer keys that order like them
    (:func:`_float_order`, faster than sorting the floats); when no two values are equal the
    ranks are written directly (the formula gives ``first = last``).
    """
    v = np.asarray(v)
    if v.ndim != 1:
        raise ValueError(f"average_ranks takes a 1-D array; got shape {v.shape}")
    n = v.size
    if v.dtype.kind == "f" and np.isnan(v).any():
        return np.full(n, np.nan)
    order = _float_order(v) if v.dtype == np.float64 else np.argsort(v)
    # any order within a run of ties gives the same ranks: no stable sort needed
    s = v[order]
    new = np.empty(n, bool)
    new[:1] = True
    np.not_equal(s[1:], s[:-1], out=new[1:])
    ranks = np.empty(n)
    if new.all():  # no ties: position i of the sorted values has rank i + 1
        ranks[order] = np.arange(1.0, n + 1.0)
        return ranks
    group = np.cumsum(new)  # 1-based run of each sorted position
    bounds = np.append(np.flatnonzero(new), n)  # first position of each run, then n
    ranks[order] = 0.5 * (bounds[group] + bounds[group - 1] + 1)
    return ranks


def _float_order(v: np.ndarray) -> np.ndarray:
    """An ``argsort`` of float64 values without NaN: the order of int64 keys of their bits
    (sign-magnitude turned into two's complement order: negative values get their magnitude
    bits flipped). Equal values stay next to each other: ``-0.0`` (key -1) sorts just before
    ``+0.0`` (key 0), and equal bits give equal keys."""
    bits = np.ascontiguousarray(v).view(np.int64)
    return np.argsort(np.where(bits < 0, bits ^ np.int64(0x7FFFFFFFFFFFFFFF), bits))


def bootstrap_draw_counts(rng, n: int, n_resamples: int):
    """How often each of ``n`` rows is drawn in each of ``n_resamples`` bootstrap resamples
    (rows drawn with replacement), shape ``(n_resamples, n)``, in the smallest unsigned dtype.

    Resample ``b`` is ``rng.integers(0, n, n)``, drawn one resample after another (the same
    draws as a loop calling it ``n_resamples`` times), then counted. The draws are asked for
    as ``uint32`` when ``n <= 2**32``: numpy's ``Generator`` draws a range that fits in 32 bits
    with the same 32-bit bounded generator for every integer dtype (one fresh buffer per call),
    so the values are the same (``tests/test_throughput.py`` checks this), and counting
    32-bit indices is faster.
    """
    out = np.empty((int(n_resamples), n), np.uint8)
    small = {"dtype": np.uint32} if n <= 2 ** 32 else {}
    for b in range(out.shape[0]):
        c = np.bincount(rng.integers(0, n, n, **small), minlength=n)
        top = int(c.max()) if n else 0
        if top > np.iinfo(out.dtype).max:
            out = out.astype(np.min_scalar_type(top))
        out[b] = c
    return out
