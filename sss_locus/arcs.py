"""Exact cropping of a circle by half-space conditions.

A point on a circle ``p(alpha) = c + rho (cos(alpha) e1 + sin(alpha) e2)`` satisfies an affine
condition ``a . p + b >= 0`` exactly when

    A cos(alpha) + B sin(alpha) + D >= 0,   A = rho a.e1,  B = rho a.e2,  D = a.c + b.

With ``M = hypot(A, B)`` and ``alpha0 = atan2(B, A)`` this is ``cos(alpha - alpha0) >= -D / M``:
the whole circle when ``-D/M <= -1``, nothing when ``-D/M > 1``, and otherwise the closed arc
``[alpha0 - delta, alpha0 + delta]`` with ``delta = arccos(-D/M)``. Combining the arcs of several
conditions (intersections and unions) is an arrangement problem on the circle: sort all boundary
angles, decide membership once per gap between consecutive boundaries (membership is constant on
each gap, so this is exact, not sampling), and join consecutive inside gaps into arcs.
"""

from __future__ import annotations

import numpy as np

TWO_PI = 2.0 * np.pi

GAP_EPS_RAD = 1e-12
"""Gaps between boundary angles narrower than this (radians) are treated as rounding noise: they
take the membership of the gap before them, so abutting arcs are joined rather than split, and a
zero-width sliver is never reported as an arc."""


def halfspace_arcs(A: np.ndarray, B: np.ndarray, D: np.ndarray):
    """Arc of the circle angle where ``A cos(alpha) + B sin(alpha) + D >= 0``.

    Parameters
    ----------
    A, B, D : ndarray, same shape

    Returns
    -------
    lo, hi : ndarray
        Arc end points, ``lo`` in [-pi, pi) and ``hi`` in [-pi, pi) (both wrapped): the arc runs
        counter-clockwise from ``lo`` to ``hi``.
    width : ndarray
        The condition holds for ``alpha`` with ``mod(alpha - lo, 2 pi) <= width``. ``width`` is
        ``4 pi`` where it holds on the whole circle and ``-1`` where it holds nowhere, so the same
        membership test works in every case without branches (``lo``, ``hi`` are then dummies).
    """
    M = np.sqrt(A * A + B * B)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = -D / M
    flat = M == 0.0
    if flat.any():  # constant on the circle: the sign of D decides
        ratio[flat] = np.where(D[flat] >= 0.0, -np.inf, np.inf)
    delta = np.arccos(np.clip(ratio, -1.0, 1.0))
    alpha0 = np.arctan2(B, A)  # in [-pi, pi]
    lo = alpha0 - delta  # in [-2 pi, pi]
    np.add(lo, TWO_PI, out=lo, where=lo < -np.pi)
    np.subtract(lo, TWO_PI, out=lo, where=lo >= np.pi)
    hi = alpha0 + delta  # in [-pi, 2 pi]
    np.subtract(hi, TWO_PI, out=hi, where=hi >= np.pi)
    width = 2.0 * delta
    width[ratio <= -1.0] = 2.0 * TWO_PI
    width[ratio > 1.0] = -1.0
    return lo, hi, width


def crop_circle(
    A: np.ndarray,
    B: np.ndarray,
    D: np.ndarray,
    groups: list[tuple[list[int], str]],
    max_arcs: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Arcs of a circle where a combination of half-space conditions holds.

    Parameters
    ----------
    A, B, D : ndarray, shape (N, K)
        Coefficients of ``K`` conditions ``A cos(alpha) + B sin(alpha) + D >= 0`` per circle.
    groups : list of (indices, mode)
        The region is the intersection over groups; within a group the conditions are combined
        with ``mode`` ``"all"`` (intersection) or ``"any"`` (union). Every condition index must
        appear in exactly one group.
    max_arcs : int
        Width of the returned arc arrays (at least ``K``, the most arcs ``K`` conditions allow).

    Returns
    -------
    total_angle : ndarray, shape (N,)
        Summed angle (radians) of all arcs; multiply by the radius for a length.
    n_arcs : ndarray of int, shape (N,)
        Number of disjoint arcs; a region covering the whole circle is one arc.
    start, end : ndarray, shape (N, max_arcs)
        Arc end points (radians), ``start`` in [-pi, pi), ``start < end <= start + 2 pi``, in
        increasing order of ``start``; NaN beyond ``n_arcs``.
    """
    N, K = A.shape
    lo, hi, width = halfspace_arcs(A, B, D)
    proper = (width >= 0.0) & (width <= TWO_PI)  # a real interval, with an enter and a leave
    G = 2 * K
    # Boundary k (and K + k) opens (closes) condition k's arc; the dummy boundaries of
    # whole-circle or empty conditions open and close nothing.
    code = np.empty((N, G))
    code[:, :K] = np.where(proper, np.arange(1.0, K + 1.0), 0.0)
    code[:, K:] = -code[:, :K]
    angle = np.empty((N, G))
    angle[:, :K] = lo
    angle[:, K:] = hi
    angle = angle.reshape(-1)
    order = (np.argsort(angle.reshape(N, G), axis=1) + (np.arange(N) * G)[:, None]).reshape(-1)
    b = angle[order].reshape(N, G)
    event = code.reshape(-1)[order].reshape(N, G)
    right = np.empty_like(b)
    right[:, :-1] = b[:, 1:]
    right[:, -1] = b[:, 0] + TWO_PI
    gap = right - b

    # Membership is decided once, on the widest gap (never a rounding sliver), and carried
    # around the circle by counting: passing a boundary enters or leaves one condition's arc.
    rows = np.arange(N)
    ref = np.argmax(gap, axis=1)
    ref_mid = b[rows, ref] + 0.5 * gap[rows, ref]
    offset = ref_mid[:, None] - lo  # in (-2 pi, 4 pi): bring into [0, 2 pi)
    np.subtract(offset, TWO_PI, out=offset, where=offset >= TWO_PI)
    np.add(offset, TWO_PI, out=offset, where=offset < 0.0)
    ref_member = offset <= width  # (N, K)
    step = np.sign(event)
    inside = np.ones((N, G), dtype=bool)
    for indices, mode in groups:
        if mode not in ("all", "any"):
            raise ValueError(f"groups mode must be 'all' or 'any'; got {mode!r}")
        if len(groups) == 1:
            group_step = step
        else:
            member = np.zeros(K + 1, dtype=bool)
            member[np.asarray(indices) + 1] = True
            group_step = np.where(member[np.abs(event).astype(np.intp)], step, 0.0)
        passed = np.cumsum(group_step, axis=1)
        count = (ref_member[:, indices].sum(axis=1) - passed[rows, ref])[:, None] + passed
        inside &= (count == len(indices)) if mode == "all" else (count >= 0.5)

    # Rounding slivers that follow a real boundary (where membership may flip spuriously, e.g.
    # between two abutting arcs) inherit the membership of the previous real gap, cyclically.
    # Slivers after the dummy boundaries of whole-circle or empty conditions change nothing.
    sliver = (gap < GAP_EPS_RAD) & (event != 0.0)
    fix = np.nonzero(sliver.any(axis=1))[0]
    if fix.size:
        idx = np.where(sliver[fix], -1, np.arange(G))
        idx = np.maximum.accumulate(idx, axis=1)
        idx = np.where(idx < 0, idx[:, -1:], idx)
        inside[fix] = np.take_along_axis(inside[fix], idx, axis=1)

    total_angle = np.einsum("ij,ij->i", gap, inside)
    starts = inside & ~np.roll(inside, 1, axis=1)
    ends = inside & ~np.roll(inside, -1, axis=1)
    n_arcs = starts.sum(axis=1)

    W = max(max_arcs, 1)
    start = np.full((N, W), np.nan)
    end = np.full((N, W), np.nan)
    # One arc (the common case): its start and end are the only hits in their rows. An arc that
    # runs through the seam (its end lies before its start) ends one turn on.
    one = np.nonzero(n_arcs == 1)[0]
    s_col = np.argmax(starts[one], axis=1)
    e_col = np.argmax(ends[one], axis=1)
    start[one, 0] = b[one, s_col]
    end[one, 0] = right[one, e_col] + np.where(e_col < s_col, TWO_PI, 0.0)
    many = np.nonzero(n_arcs > 1)[0]
    if many.size:
        start[many], end[many] = _arcs_by_rank(starts[many], ends[many], b[many], right[many],
                                               n_arcs[many], W)

    full = inside.all(axis=1)
    n_arcs = np.where(full, 1, n_arcs)
    start[full, 0] = b[full, 0]
    end[full, 0] = b[full, 0] + TWO_PI
    total_angle = np.where(full, TWO_PI, total_angle)
    return total_angle, n_arcs, start, end


def _arcs_by_rank(starts, ends, b, right, n_arcs, W):
    """Arc end points for rows with several arcs, compacted into ``W`` slots by rank.

    An arc that runs through the seam (an end before the row's first start) pairs the last
    start with the first end, one turn on.
    """
    N, G = starts.shape
    start = np.full((N, W), np.nan)
    end = np.full((N, W), np.nan)
    srow, scol = np.nonzero(starts)
    erow, ecol = np.nonzero(ends)
    first_start = np.full(N, G)
    first_start[srow[::-1]] = scol[::-1]
    first_end = np.full(N, G)
    first_end[erow[::-1]] = ecol[::-1]
    wrapped = first_end < first_start
    # nonzero() lists hits row by row, so a hit's rank in its row is its index minus the
    # number of hits in earlier rows.
    offset = np.concatenate([[0], np.cumsum(n_arcs)[:-1]])
    srank = np.arange(srow.size) - offset[srow]
    erank = np.arange(erow.size) - offset[erow] - wrapped[erow]
    seam = erank < 0
    erank = np.where(seam, n_arcs[erow] - 1, erank)
    start[srow, srank] = b[srow, scol]
    end[erow, erank] = right[erow, ecol] + np.where(seam, TWO_PI, 0.0)
    return start, end
