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

Speed notes (the kernel's hot path; see benchmarks/bench_locus.py). Per-condition arrays are
condition-major, shape (K, N), so every operation runs over long contiguous rows. Updates under
a data-dependent mask that is true about half the time are written as arithmetic
(``x + 2 pi * mask``): a masked ``np.add(..., where=)`` or ``np.where`` branches per element and
mispredicts. Scans and reductions along the short rows of boundaries use the byte tricks of
:mod:`sss_locus.geometry.fastpath`.
"""

from __future__ import annotations

import functools

import numpy as np

from .fastpath import (
    cyclic_edges, diagonal_matches, first_true, prefix_sums, row_sums, rows_all, rows_any, transpose_into,
)

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
        ratio = np.divide(D, M)
    np.negative(ratio, out=ratio)  # -(D / M) is bit-identical to (-D) / M
    flat = M == 0.0
    if flat.any():  # constant on the circle: the sign of D decides
        ratio[flat] = np.where(D[flat] >= 0.0, -np.inf, np.inf)
    whole = ratio <= -1.0
    empty = ratio > 1.0
    delta = np.arccos(np.minimum(np.maximum(ratio, -1.0), 1.0))
    alpha0 = np.arctan2(B, A)  # in [-pi, pi]
    lo = alpha0 - delta  # in [-2 pi, pi]
    lo += TWO_PI * (lo < -np.pi)  # arithmetic, not a masked add: the mask is random (see above)
    np.subtract(lo, TWO_PI, out=lo, where=lo >= np.pi)  # rare (alpha0 = pi, delta = 0)
    hi = alpha0 + delta  # in [-pi, 2 pi]
    hi -= TWO_PI * (hi >= np.pi)
    # Whole circle: the ratio was clipped to -1 and arccos(-1) is pi, so 2 delta + 2 pi = 4 pi
    # exactly. Empty: arccos(1) = 0, so 2 delta - 1 = -1 exactly. Elsewhere both terms are 0.
    width = 2.0 * delta
    width += TWO_PI * whole
    width -= empty
    return lo, hi, width


def crop_circle(
    A: np.ndarray,
    B: np.ndarray,
    D: np.ndarray,
    groups: list[tuple[list[int], str]],
    max_arcs: int,
    out: tuple[np.ndarray, np.ndarray] | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Arcs of a circle where a combination of half-space conditions holds.

    Parameters
    ----------
    A, B, D : ndarray, shape (K, N)
        Coefficients of ``K`` conditions ``A cos(alpha) + B sin(alpha) + D >= 0`` on each of
        ``N`` circles (condition-major: row ``k`` holds condition ``k`` for every circle).
    groups : list of (indices, mode)
        The region is the intersection over groups; within a group the conditions are combined
        with ``mode`` ``"all"`` (intersection) or ``"any"`` (union). Every condition index must
        appear in exactly one group.
    max_arcs : int
        Width of the returned arc arrays (at least ``K``, the most arcs ``K`` conditions allow).
    out : tuple of two ndarrays, shape (N, max_arcs), optional
        Arrays to receive ``start`` and ``end`` (C-contiguous float64); fresh ones by default.

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
    K, N = A.shape
    for indices, mode in groups:
        if mode not in ("all", "any"):
            raise ValueError(f"groups mode must be 'all' or 'any'; got {mode!r}")
    lo, hi, width = halfspace_arcs(A, B, D)
    proper = (width >= 0.0) & (width <= TWO_PI)  # a real interval, with an enter and a leave
    G = 2 * K
    # Boundary k (and K + k) opens (closes) condition k's arc. Its step code is 1 + (change in
    # the number of arcs the circle is inside): 2 to enter, 0 to leave, 1 for the dummy
    # boundaries of whole-circle or empty conditions, which open and close nothing.
    angle = np.empty((N, G))  # (for 16 float columns NumPy's own transposing copy is faster)
    angle[:, :K] = lo.T
    angle[:, K:] = hi.T
    entering = proper.view(np.uint8)
    code = transpose_into(np.empty((N, G), dtype=np.uint8), np.concatenate([entering + 1, 1 - entering]))
    row_start = np.arange(N) * G
    order = np.argsort(angle, axis=1)
    order += _row_offsets(N, G)  # a flat index: adding a full array avoids a short broadcast
    flat_order = order.reshape(-1)  # flat gathers are much cheaper than take_along_axis
    b = angle.reshape(-1)[flat_order].reshape(N, G)
    right = np.empty_like(b)
    right[:, :-1] = b[:, 1:]
    right[:, -1] = b[:, 0] + TWO_PI
    gap = right - b

    # Membership is decided once, on the widest gap (never a rounding sliver), and carried
    # around the circle by counting: passing a boundary enters or leaves one condition's arc.
    ref = np.argmax(gap, axis=1)
    ref_flat = row_start + ref
    ref_mid = b.reshape(-1)[ref_flat] + 0.5 * gap.reshape(-1)[ref_flat]
    offset = ref_mid - lo  # (K, N), in (-2 pi, 4 pi): bring into [0, 2 pi)
    np.subtract(offset, TWO_PI, out=offset, where=offset >= TWO_PI)  # rare
    offset += TWO_PI * (offset < 0.0)  # about half the entries: arithmetic, not a masked add
    ref_member = offset <= width  # (K, N)

    # With P = running sum of the step codes along the sorted row, the number of a group's
    # conditions holding on gap j is count_j = n_ref + passed_j - passed_ref, where
    # passed_j = P_j - (j + 1) and n_ref counts the conditions holding on the reference gap.
    # A group needing all its Kg conditions is inside where P_j == Kg - n_ref + P_ref - ref + j.
    columns = np.arange(G)
    sorted_code = code.reshape(-1)[flat_order].reshape(N, G)
    inside = None
    for indices, mode in groups:
        if len(groups) == 1:
            group_code = sorted_code
            n_ref = np.count_nonzero(ref_member, axis=0)
        else:  # other groups' boundaries count as dummies here
            others = np.setdiff1d(np.arange(K), indices)
            group_code = code.copy()
            group_code[:, others] = 1
            group_code[:, others + K] = 1
            group_code = group_code.reshape(-1)[flat_order].reshape(N, G)
            n_ref = np.count_nonzero(ref_member[indices], axis=0)
        P = prefix_sums(group_code)
        shift = P.reshape(-1)[ref_flat].astype(np.int64) - ref - n_ref  # P_ref - ref - n_ref
        if mode == "all":
            group_inside = diagonal_matches(P, shift + len(indices))
        else:  # at least one condition: count_j = P_j - j - shift >= 1
            group_inside = (P.astype(np.int64) - columns) >= (shift + 1)[:, None]
        inside = group_inside if inside is None else inside & group_inside

    # Rounding slivers (where membership may flip spuriously, e.g. between two abutting arcs)
    # inherit the membership of the previous gap that is not a sliver, cyclically. This
    # includes slivers after the dummy boundaries of whole-circle or empty conditions: a dummy
    # changes no count, but the gap after it carries the unrepaired count of a real boundary
    # just before it (a zero-width arc at a tangency would otherwise survive there).
    # Whole-circle conditions put their two dummy boundaries at the same angle, so the repair
    # only runs for rows where a sliver follows a real boundary (code != 1).
    sliver = gap < GAP_EPS_RAD
    if sliver.any():
        fix = np.nonzero(rows_any(sliver & (sorted_code != 1)))[0]
        if fix.size:
            idx = np.where(sliver[fix], -1, columns)
            idx = np.maximum.accumulate(idx, axis=1)
            idx = np.where(idx < 0, idx[:, -1:], idx)
            inside[fix] = np.take_along_axis(inside[fix], idx, axis=1)

    total_angle = np.einsum("ij,ij->i", gap, inside)
    starts, ends = cyclic_edges(inside)
    n_arcs = row_sums(starts)

    W = max(max_arcs, 1)
    start, end = (np.empty((N, W)), np.empty((N, W))) if out is None else out
    start.fill(np.nan)
    end.fill(np.nan)
    # One arc (the common case): its start and end are the only hits in their rows. An arc that
    # runs through the seam (its end lies before its start) ends one turn on.
    one = n_arcs == 1
    rows = slice(None) if one.all() else np.nonzero(one)[0]
    s_col = first_true(starts[rows])
    e_col = first_true(ends[rows])
    start[rows, 0] = b.reshape(-1)[row_start[rows] + s_col]
    end[rows, 0] = right.reshape(-1)[row_start[rows] + e_col] + TWO_PI * (e_col < s_col)
    many = np.nonzero(n_arcs > 1)[0]
    if many.size:
        start[many], end[many] = _arcs_by_rank(starts[many], ends[many], b[many], right[many],
                                               n_arcs[many], W)

    full = rows_all(inside)
    if full.any():
        n_arcs[full] = 1
        start[full, 0] = b[full, 0]
        end[full, 0] = b[full, 0] + TWO_PI
        total_angle[full] = TWO_PI
    return total_angle, n_arcs, start, end


@functools.lru_cache(maxsize=8)
def _row_offsets(N: int, G: int) -> np.ndarray:
    """(N, G) array whose row ``i`` is ``i * G``: turns per-row column indices into flat ones."""
    offsets = np.repeat(np.arange(N) * G, G).reshape(N, G)
    offsets.flags.writeable = False
    return offsets


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
