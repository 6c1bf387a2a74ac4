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


def average_ranks(v) -> np.ndarray:
    """Ranks 1..n of a 1-D array, ties given their average rank; all NaN if any value is NaN.

    The numbers of :func:`scipy.stats.rankdata` (``method="average"``, ``nan_policy=
    "propagate"``), by the same formula ``(first + last) / 2`` over each run of equal sorted
    values (ranks and half-ranks are exact in float64), without importing ``scipy.stats``.
    Float64 values are put in order by sorting integer keys that order like them
    (:func:`_float_order`, faster than sorting the floats); when no two values are equal the
    ranks are written directly (the formula gives ``first = last``).
    """
    v = _one_d(v)
    if v.dtype.kind == "f" and np.isnan(v).any():
        return np.full(v.size, np.nan)
    return ranks_in_order(v, value_order(v))


def batch_average_ranks(v, n_batches: int, order=None) -> np.ndarray:
    """``np.concatenate([average_ranks(v[j::k]) for j in range(k)])`` (``k = n_batches``): the
    ranks of each replicate batch ``v[j::k]`` within the batch, batches one after another, the
    same numbers bit for bit (half-integer ranks are exact), from one sort of the whole column.

    ``order`` is :func:`value_order` of ``v`` if already known. The rows in the order of their
    values are dealt to their batches by a stable sort of the batch numbers (a radix sort of
    small integers, linear in ``n``), which keeps each batch in the order of its values; the
    runs of equal values are then found within each batch. A batch holding a NaN gets NaN
    ranks, as :func:`average_ranks` gives it.
    """
    v, k = _one_d(v), int(n_batches)
    n = v.size
    if k < 1:
        raise ValueError(f"n_batches must be a positive integer; got {n_batches!r}")
    if v.dtype.kind == "f" and np.isnan(v).any():
        return np.concatenate([average_ranks(v[j::k]) for j in range(k)])
    order = value_order(v) if order is None else order
    sizes = np.array([len(range(j, n, k)) for j in range(k)], np.intp)
    start = np.concatenate([[0], np.cumsum(sizes)[:-1]]).astype(np.intp)  # each batch's first output position
    batch = (order % k).astype(np.min_scalar_type(max(k - 1, 0)))
    by_batch = order[np.argsort(batch, kind="stable")]  # batch by batch, each in value order
    offset = np.repeat(start, sizes)  # ranks count from each batch's first position
    s = v[by_batch]
    tie = np.empty(n, bool)  # equal to the value before it in the same batch
    tie[:1] = False
    np.equal(s[1:], s[:-1], out=tie[1:])
    tie[start[sizes > 0]] = False
    ranks = np.empty(n)
    where = offset + by_batch // k  # output position: batch j's rows j, j + k, ... in order
    if not tie.any():  # no two values equal within a batch: position in the batch, plus one
        ranks[where] = np.arange(1.0, n + 1.0) - offset
        return ranks
    group = np.cumsum(~tie)  # 1-based run of each dealt position
    bounds = np.append(np.flatnonzero(~tie), n)  # first position of each run, then n
    ranks[where] = 0.5 * (bounds[group] + bounds[group - 1] + 1 - 2 * offset)
    return ranks


def value_order(v: np.ndarray) -> np.ndarray:
    """An order that sorts the 1-D array ``v`` (without NaN), equal values next to each other."""
    return _float_order(v) if v.dtype == np.float64 else np.argsort(v)


def _one_d(v) -> np.ndarray:
    v = np.asarray(v)
    if v.ndim != 1:
        raise ValueError(f"average_ranks takes a 1-D array; got shape {v.shape}")
    return v


def ranks_in_order(v: np.ndarray, order: np.ndarray) -> np.ndarray:
    """Average ranks of ``v`` given an order that sorts it (:func:`value_order`)."""
    n = v.size
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
