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


def _wrap(angle: np.ndarray) -> np.ndarray:
    """Map angles to [-pi, pi)."""
    return np.mod(angle + np.pi, TWO_PI) - np.pi


def halfspace_arcs(A: np.ndarray, B: np.ndarray, D: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Arc of the circle angle where ``A cos(alpha) + B sin(alpha) + D >= 0``.

    Parameters
    ----------
    A, B, D : ndarray, same shape

    Returns
    -------
    lo, width : ndarray
        The condition holds for ``alpha`` with ``mod(alpha - lo, 2 pi) <= width``. ``width`` is
        ``4 pi`` where it holds on the whole circle and ``-1`` where it holds nowhere, so the same
        membership test works in every case without branches.
    """
    M = np.hypot(A, B)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(M > 0.0, -D / M, np.where(D >= 0.0, -np.inf, np.inf))
    delta = np.arccos(np.clip(ratio, -1.0, 1.0))
    lo = np.arctan2(B, A) - delta
    width = np.where(ratio <= -1.0, 2.0 * TWO_PI, np.where(ratio > 1.0, -1.0, 2.0 * delta))
    return lo, width


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
    lo, width = halfspace_arcs(A, B, D)
    b = np.sort(np.concatenate([_wrap(lo), _wrap(lo + np.clip(width, 0.0, TWO_PI))], axis=1), axis=1)
    G = 2 * K
    right = np.concatenate([b[:, 1:], b[:, :1] + TWO_PI], axis=1)
    gap = right - b
    mid = b + 0.5 * gap

    inside = np.ones((N, G), dtype=bool)
    for indices, mode in groups:
        if mode not in ("all", "any"):
            raise ValueError(f"groups mode must be 'all' or 'any'; got {mode!r}")
        acc = np.full((N, G), mode == "all")
        for k in indices:
            member = np.mod(mid - lo[:, k : k + 1], TWO_PI) <= width[:, k : k + 1]
            acc = (acc & member) if mode == "all" else (acc | member)
        inside &= acc

    # Rounding slivers inherit the membership of the previous real gap (cyclically).
    idx = np.where(gap >= GAP_EPS_RAD, np.arange(G), -1)
    idx = np.maximum.accumulate(idx, axis=1)
    idx = np.where(idx < 0, idx[:, -1:], idx)
    inside = np.take_along_axis(inside, idx, axis=1)

    total_angle = np.sum(np.where(inside, gap, 0.0), axis=1)
    starts = inside & ~np.roll(inside, 1, axis=1)
    ends = inside & ~np.roll(inside, -1, axis=1)
    n_arcs = starts.sum(axis=1)

    cols = np.arange(G)
    W = max(max_arcs, 1)
    start_pos = np.sort(np.where(starts, cols, G), axis=1)[:, :W]
    end_pos = np.sort(np.where(ends, cols, G), axis=1)[:, :W]
    # An arc that runs through the seam (end position before its start position) pairs the
    # last start with the first end, one turn later.
    wrapped = (n_arcs > 0) & (end_pos[:, 0] < start_pos[:, 0])
    k = np.arange(W)
    n_safe = np.maximum(n_arcs, 1)[:, None]
    rot = np.where(wrapped[:, None], (k + 1) % n_safe, k)
    rot = np.where(k < n_safe, rot, k)
    end_pos = np.take_along_axis(end_pos, rot, axis=1)

    valid = k[None, :] < n_arcs[:, None]
    sp = np.where(valid, start_pos, 0)
    ep = np.where(valid, end_pos, 0)
    start = np.where(valid, np.take_along_axis(b, sp, axis=1), np.nan)
    end = np.take_along_axis(right, ep, axis=1)
    end = np.where(wrapped[:, None] & (k == n_safe - 1), end + TWO_PI, end)
    end = np.where(valid, end, np.nan)

    full = inside.all(axis=1)
    n_arcs = np.where(full, 1, n_arcs)
    start[full, 0] = b[full, 0]
    end[full, 0] = b[full, 0] + TWO_PI
    total_angle = np.where(full, TWO_PI, total_angle)
    return total_angle, n_arcs, start, end
