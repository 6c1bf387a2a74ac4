"""Statistics of a pose-space table: rank correlations with replicate intervals, binned medians.

Works on the tables of :func:`sss_locus.experiments.pose_space.study.sample_pose_space` (any DataFrame with the named
columns). Angles in degrees, lengths in metres.
"""

from __future__ import annotations

import hashlib
from collections import OrderedDict
from collections.abc import Sequence

import numpy as np
import pandas as pd
from scipy.stats import binned_statistic_dd

from sss_locus.experiments.stats.replicates import (N_BATCHES, batch_count, check_confidence, fisher_z_interval,
                                                    rank_correlation, replicate_interval)
from sss_locus.experiments.stats.rowstats import average_ranks, batch_average_ranks

TARGETS = ("locus_length_m", "locus_length_normalized")
"""Raw and range-normalised locus length (``locus_length_m / mean_range_m``)."""

CANDIDATES = (
    "r1_m", "r2_m", "mean_range_m", "baseline_m",
    "elevation_misalignment_deg", "abs_psi1_deg", "abs_psi2_deg",
    "azimuth1_deg", "azimuth2_deg", "abs_elevation1_deg", "abs_elevation2_deg",
    "abs_yaw2_deg", "pitch2_deg", "abs_pitch2_deg",
)
"""Candidate drivers ranked by Spearman rho. ``abs_*`` are magnitudes added by
:func:`with_derived` (signed yaw, elevation and psi are symmetric about 0, so their rank
correlation with length is ~0 by construction and says nothing)."""

_RANK_MEMO_BYTES = 256 * 2 ** 20
"""Bound of the memo of column ranks (:func:`column_ranks`), bytes."""
_rank_memo: OrderedDict[tuple, np.ndarray] = OrderedDict()
_memo_bytes = [0]  # bytes held by _rank_memo
_COPY_ON_WRITE = int(pd.__version__.split(".")[0]) >= 3  # always on from pandas 3


MISALIGNMENT_READINGS = ("magnitude", "signed")
"""Readings of the paper's ``max(psi1, psi2)`` (Sec. IV-B): ``"magnitude"`` (the default,
``max(|psi1|, |psi2|)``: a line through both origins has no sign) or ``"signed"`` (the formula
as printed, ``max(psi1, psi2)`` of the signed elevations)."""


def with_derived(df: pd.DataFrame, misalignment: str = "magnitude") -> pd.DataFrame:
    """A copy of ``df`` with the magnitude columns used in :data:`CANDIDATES`, and with
    ``elevation_misalignment_deg`` recomputed from ``psi1_deg`` and ``psi2_deg`` under the
    reading ``misalignment`` (:data:`MISALIGNMENT_READINGS`; ``"magnitude"`` reproduces the
    kernel's column).

    Parameters
    ----------
    df : pandas.DataFrame
        A pose-space table (:func:`~sss_locus.experiments.pose_space.study.sample_pose_space`).
    misalignment : {"magnitude", "signed"}
        Reading of the paper's ``max(psi1, psi2)``.

    Returns
    -------
    pandas.DataFrame
        A copy of ``df`` with the added and recomputed columns (degrees).
    """
    if misalignment not in MISALIGNMENT_READINGS:
        raise ValueError(f"misalignment must be one of {list(MISALIGNMENT_READINGS)}; got {misalignment!r}")
    out = df.copy(deep=not _COPY_ON_WRITE)  # with copy-on-write a shallow copy is a copy
    for src in ("psi1_deg", "psi2_deg", "elevation1_deg", "elevation2_deg", "yaw2_deg", "pitch2_deg"):
        if src in out:
            out["abs_" + src] = out[src].abs()
    if "psi1_deg" in out and "psi2_deg" in out:
        a, b = out["psi1_deg"].to_numpy(float), out["psi2_deg"].to_numpy(float)
        if misalignment == "magnitude":
            a, b = np.abs(a), np.abs(b)
        out["elevation_misalignment_deg"] = np.maximum(a, b)
    return out


def _require(df: pd.DataFrame, columns: Sequence[str], name: str = "df") -> None:
    missing = [c for c in columns if c not in df.columns]
    if missing:
        raise ValueError(f"{name} lacks columns {missing}; it has {list(df.columns)}")


def spearman_table(df: pd.DataFrame, candidates: Sequence[str] = CANDIDATES,
                   targets: Sequence[str] = TARGETS, *, n_batches: int = N_BATCHES,
                   confidence_level: float = 0.95, drop_constant: bool = True) -> pd.DataFrame:
    """Spearman rho of each candidate with each target, with replicate-batch intervals.

    The point estimate is Spearman's rho of the whole table (Pearson correlation of average
    ranks, :func:`~sss_locus.experiments.stats.replicates.rank_correlation`; the numbers of
    :func:`scipy.stats.spearmanr` to rounding). The interval comes from ``n_batches``
    independent replicates: the rows, i.i.d. draws, are dealt into batches (row ``i`` to batch
    ``i mod k``, :mod:`~sss_locus.experiments.stats.replicates`), each batch is ranked on its own and its rho computed, and
    :func:`~sss_locus.experiments.stats.replicates.replicate_interval` turns their spread into an
    interval at ``confidence_level`` (coverage measured in ``tests/experiments/stats/test_replicates.py``),
    clipped to [-1, 1].
    ``ci_low_z``/``ci_high_z`` are the asymptotic Fisher-z interval
    (:func:`~sss_locus.experiments.stats.replicates.fisher_z_interval`), the cross-check. Ranks of
    whole columns and of batches are remembered between calls (:func:`column_ranks`). A
    constant column (e.g. the boat's pitch, always 0) has no rank correlation: with
    ``drop_constant`` it is left out (listed in ``out.attrs["dropped"]``), otherwise it raises
    ``ValueError``.

    Parameters
    ----------
    df : pandas.DataFrame
        The table, with the columns named in ``candidates`` and ``targets``.
    candidates, targets : sequence of str
        Columns correlated (default :data:`CANDIDATES`, :data:`TARGETS`).
    n_batches : int
        Replicate batches, ``>= 2``.
    confidence_level : float
        Level of the intervals, in (0, 1).
    drop_constant : bool
        Leave constant candidates out instead of raising.

    Returns
    -------
    pandas.DataFrame
        One row per (target, quantity): ``target, quantity, rho, ci_low, ci_high, n,
        ci_low_z, ci_high_z``, sorted by target then decreasing ``|rho|``;
        ``attrs["n_batches"]`` the number of replicates used, ``min(n_batches, n // 3)`` (a
        batch has at least three rows). A batch in which a column is constant has no rho, and
        the intervals of that column are NaN.
    """
    _require(df, list(candidates) + list(targets))
    check_confidence(confidence_level)
    n = len(df)
    k = batch_count(n // 3, n_batches)  # checks n_batches; batches of >= 3 rows, n >= 9

    constant = [c for c in list(candidates) + list(targets) if _is_constant(df[c])]
    if constant and (not drop_constant or set(constant) & set(targets)):
        raise ValueError(f"columns {constant} are constant: their rank correlation is undefined")
    candidates = [c for c in candidates if c not in constant]
    # whole columns, and each batch ranked on its own (the batches one after another)
    ranks = {c: column_rank_sets(df[c].to_numpy(), (1, k)) for c in [*candidates, *targets]}
    starts = np.concatenate([[0], np.cumsum([len(range(j, n, k)) for j in range(k)])])
    spans = list(zip(starts[:-1].tolist(), starts[1:].tolist()))
    X, Xb = (_centred_stack([ranks[c][i] for c in candidates], s) for i, s in ((0, [(0, n)]), (1, spans)))
    Y, Yb = (_centred_stack([ranks[c][i] for c in targets], s) for i, s in ((0, [(0, n)]), (1, spans)))
    rho = rank_correlation(X, Y)
    with np.errstate(invalid="ignore", divide="ignore"):  # a batch with a constant column: NaN
        batches = np.stack([rank_correlation(Xb[a:b], Yb[a:b]) for a, b in spans])
    return rho_frame(rho, batches, n, candidates, targets, confidence_level, dropped=constant)


def _centred_stack(columns: list[np.ndarray], spans: list[tuple[int, int]]) -> np.ndarray:
    """``centred_from`` of the rows ``a:b`` of each span of ``column_stack(columns)``, in one
    array (each element the same operations: one pass over the columns instead of three over
    the stacked matrix)."""
    rows = np.empty((len(columns), len(columns[0])))  # column by column, then one transposing copy
    for i, r in enumerate(columns):
        for a, b in spans:
            np.divide(np.subtract(r[a:b], (b - a + 1) / 2.0, out=rows[i, a:b]), b - a, out=rows[i, a:b])
    return np.ascontiguousarray(rows.T)


def rho_frame(rho: np.ndarray, batches: np.ndarray, n: int, candidates: Sequence[str],
              targets: Sequence[str], confidence_level: float = 0.95, dropped=()) -> pd.DataFrame:
    """The table of :func:`spearman_table` from a point estimate ``rho`` ``(p, q)`` (candidates x
    targets), the ``k`` replicate batches' rhos ``(k, p, q)`` and the number of rows ``n``.

    Parameters
    ----------
    rho : numpy.ndarray, shape (p, q)
        Spearman rho of the whole table, candidates x targets.
    batches : numpy.ndarray, shape (k, p, q)
        Rho of each replicate batch.
    n : int
        Rows of the table.
    candidates, targets : sequence of str
        Names of the ``p`` candidates and ``q`` targets.
    confidence_level : float
        Level of the intervals, in (0, 1).
    dropped : sequence of str
        Constant columns left out (``attrs["dropped"]``).

    Returns
    -------
    pandas.DataFrame
        As :func:`spearman_table`.
    """
    lo, hi = replicate_interval(rho, batches, confidence_level, bounds=(-1.0, 1.0))
    zlo, zhi = fisher_z_interval(rho, n, confidence_level)
    rows = [dict(target=tg, quantity=c, rho=rho[i, j], ci_low=lo[i, j], ci_high=hi[i, j], n=n,
                 ci_low_z=zlo[i, j], ci_high_z=zhi[i, j])
            for j, tg in enumerate(targets) for i, c in enumerate(candidates)]
    out = pd.DataFrame(rows)
    out["abs_rho"] = out["rho"].abs()
    out = out.sort_values(["target", "abs_rho"], ascending=[True, False]).drop(columns="abs_rho")
    out = out.reset_index(drop=True)
    out.attrs["dropped"] = list(dropped)
    out.attrs["n_batches"] = len(batches)
    return out


def column_ranks(values: np.ndarray, n_batches: int = 1) -> np.ndarray:
    """:func:`~sss_locus.experiments.stats.rowstats.average_ranks` of one column, remembered by its
    content; with ``n_batches = k > 1``, the ranks of each batch ``values[j::k]`` within the
    batch, concatenated in batch order
    (:func:`~sss_locus.experiments.stats.rowstats.batch_average_ranks`).

    A chapter ranks the same columns of a table more than once (the readings of the
    misalignment share all other columns); ranking costs a sort, recognising a column one
    SHA-256 of its bytes. Numeric columns without NaN are remembered (least recently used
    first out, at most :data:`_RANK_MEMO_BYTES`), as twice their ranks in ``uint32`` (exact:
    ranks are half-integers up to ``n``); the ranks returned are the same numbers either way.

    Parameters
    ----------
    values : numpy.ndarray, shape (n,)
        One column of a table.
    n_batches : int
        Number of replicate batches ``k >= 1`` (1: the whole column).

    Returns
    -------
    numpy.ndarray, shape (n,), float64
        The average ranks (half-integers), batches one after another.
    """
    return column_rank_sets(values, (int(n_batches),))[0]


def column_rank_sets(values: np.ndarray, batch_counts: Sequence[int]) -> list[np.ndarray]:
    """:func:`column_ranks` of ``values`` for each ``k`` in ``batch_counts`` (1: the whole
    column).

    Parameters
    ----------
    values : numpy.ndarray, shape (n,)
        One column of a table.
    batch_counts : sequence of int
        Numbers of replicate batches ``k``, each ``>= 1``.

    Returns
    -------
    list of numpy.ndarray, each shape (n,)
        Per ``k``, the ranks of each batch ``values[j::k]`` within it, batches in order
        (:func:`~sss_locus.experiments.stats.rowstats.batch_average_ranks`).
    """
    v = np.ascontiguousarray(values)

    def rank(k: int) -> np.ndarray:
        return average_ranks(v) if k == 1 else batch_average_ranks(v, k)

    if v.ndim != 1 or v.dtype.kind not in "fiub" or not 0 < 2 * v.size < 2 ** 32:
        return [rank(int(k)) for k in batch_counts]
    digest = hashlib.sha256(v.view(np.uint8)).digest()
    out = []
    for k in map(int, batch_counts):
        key = (v.dtype.str, v.size, k, digest)
        if key in _rank_memo:
            _rank_memo.move_to_end(key)
            out.append(_rank_memo[key] * 0.5)
            continue
        ranks = rank(k)
        out.append(ranks)
        if np.isnan(ranks).any():
            continue
        _rank_memo[key] = (2.0 * ranks).astype(np.uint32)
        _memo_bytes[0] += _rank_memo[key].nbytes
        while _memo_bytes[0] > _RANK_MEMO_BYTES:
            _memo_bytes[0] -= _rank_memo.popitem(last=False)[1].nbytes
    return out


def _is_constant(column: pd.Series) -> bool:
    """Fewer than two distinct non-NaN values (``nunique() < 2``, without hashing the column)."""
    v = column.to_numpy(float)
    v = v[~np.isnan(v)]
    return v.size == 0 or bool(v.min() == v.max())


def _edges(name: str, edges) -> np.ndarray:
    e = np.asarray(edges, float)
    if e.ndim != 1 or len(e) < 2 or not np.all(np.diff(e) > 0):
        raise ValueError(f"{name} must be a strictly increasing 1-D array of >= 2 edges")
    return e


def _binned(df: pd.DataFrame, columns: Sequence[str], edges: Sequence[np.ndarray], value: str,
            min_count: int) -> tuple[np.ndarray, np.ndarray, int]:
    """Counts and medians of ``value`` per bin of ``columns`` (one axis per column), and the
    number of rows left out for a NaN (:func:`grouped_binned` with one group)."""
    if int(min_count) < 1:
        raise ValueError(f"min_count must be >= 1; got {min_count}")
    count, med, n_nan = grouped_binned(df, columns, edges, value)
    return count[0], med[0], n_nan


def grouped_binned(df: pd.DataFrame, columns: Sequence[str], edges: Sequence[np.ndarray], value: str,
                   groups=None, n_groups: int = 1) -> tuple[np.ndarray, np.ndarray, int]:
    """:func:`grouped_binned_medians` of the rows of ``df`` without those with a NaN
    coordinate or value, and their number.

    Parameters
    ----------
    df : pandas.DataFrame
        Table holding ``columns`` and ``value``.
    columns : sequence of str
        Columns binned, one axis each.
    edges : sequence of numpy.ndarray
        Increasing bin edges of each column.
    value : str
        Column whose medians are taken.
    groups : array_like of int, shape (len(df),), optional
        Group ``0 .. n_groups - 1`` of each row; ``None``: all in group 0.
    n_groups : int
        Number of groups.

    Returns
    -------
    count, median : numpy.ndarray, shape (n_groups, *bins)
        As :func:`grouped_binned_medians`.
    n_nan : int
        Rows left out for a NaN.
    """
    coords = np.column_stack([df[c].to_numpy(float) for c in columns])
    v = df[value].to_numpy(float)
    ok = ~(np.isnan(coords).any(axis=1) | np.isnan(v))
    groups = np.zeros(len(v), np.intp) if groups is None else np.asarray(groups)
    count, med = grouped_binned_medians(coords[ok], v[ok], edges, groups[ok], n_groups)
    return count, med, int((~ok).sum())


def grouped_binned_medians(coords: np.ndarray, values: np.ndarray, edges: Sequence[np.ndarray],
                           groups: np.ndarray, n_groups: int) -> tuple[np.ndarray, np.ndarray]:
    """Per group, the count and the median of ``values`` in each bin of ``coords``: one
    :func:`scipy.stats.binned_statistic_dd` (statistic ``"median"``) per group.

    Parameters
    ----------
    coords : numpy.ndarray, shape (n, d)
        Coordinates of the rows (no NaN).
    values : numpy.ndarray, shape (n,)
        Values of the rows (no NaN).
    edges : sequence of d numpy.ndarray
        Increasing bin edges of each coordinate (scipy's bins: half-open, the last closed).
    groups : numpy.ndarray of int, shape (n,)
        Group ``0 .. n_groups - 1`` of each row.
    n_groups : int
        Number of groups.

    Returns
    -------
    count : numpy.ndarray of int, shape (n_groups, *bins)
        Rows per bin (``bins`` one less than each axis' edges).
    median : numpy.ndarray of float, shape (n_groups, *bins)
        Median per bin; NaN in empty bins.
    """
    bins = tuple(len(e) - 1 for e in edges)
    count = np.zeros((int(n_groups),) + bins, np.intp)
    med = np.full((int(n_groups),) + bins, np.nan)
    groups = np.asarray(groups)
    for g in range(int(n_groups)):
        sel = groups == g
        if sel.any():  # scipy needs a sample to bin: an empty group keeps every bin empty
            res = binned_statistic_dd(coords[sel], values[sel], "median", bins=list(edges))
            med[g] = res.statistic
            inner = tuple(slice(1, -1) for _ in edges)  # scipy's bin numbers count the outlier bins
            count[g] = np.bincount(res.binnumber, minlength=int(np.prod([b + 2 for b in bins]))
                                   ).reshape(tuple(b + 2 for b in bins))[inner]
    return count, med


def binned_median(df: pd.DataFrame, x: str, y: str, value: str = "locus_length_m", *,
                  x_edges, y_edges, min_count: int = 30) -> pd.DataFrame:
    """Median of ``value`` per 2-D bin of ``(x, y)``, with counts and a sparse-bin mask.

    Bins are those of :func:`scipy.stats.binned_statistic_dd`: half-open ``[lo, hi)``
    except the last, which includes its upper edge (and, by scipy's rounding, a value above it by
    less than a millionth of the narrowest bin); rows outside the edges are ignored. A row with a
    NaN coordinate or value lies in no bin (neither counted nor in a median); their number is
    ``attrs["n_nan"]``. Every bin appears (empty ones with ``count`` 0 and NaN median).

    Parameters
    ----------
    df : pandas.DataFrame
        Table holding ``x``, ``y`` and ``value``.
    x, y : str
        Columns binned.
    value : str
        Column whose median is taken.
    x_edges, y_edges : array_like
        Strictly increasing bin edges, at least two each.
    min_count : int
        Rows a bin needs to be shown, ``>= 1``.

    Returns
    -------
    pandas.DataFrame
        ``x_lo, x_hi, y_lo, y_hi, x_mid, y_mid, count, median, masked``, one row per bin with
        ``y`` varying fastest; ``masked`` is true where ``count < min_count`` (such medians are
        not shown).
    """
    _require(df, [x, y, value])
    xe, ye = _edges("x_edges", x_edges), _edges("y_edges", y_edges)
    count, med, n_nan = _binned(df, [x, y], [xe, ye], value, min_count)
    gx, gy = np.divmod(np.arange(count.size), len(ye) - 1)
    out = pd.DataFrame({
        "x_lo": xe[gx], "x_hi": xe[gx + 1], "y_lo": ye[gy], "y_hi": ye[gy + 1],
        "x_mid": 0.5 * (xe[gx] + xe[gx + 1]), "y_mid": 0.5 * (ye[gy] + ye[gy + 1]),
        "count": count.ravel(), "median": med.ravel(),
    })
    out["masked"] = out["count"] < int(min_count)
    out.attrs.update(x=x, y=y, value=value, min_count=int(min_count), n_nan=n_nan)
    return out


def bin_index(v: np.ndarray, edges: np.ndarray) -> np.ndarray:
    """Bin of each value for increasing ``edges``: half-open ``[lo, hi)``, the last bin closed; -1 outside.

    Parameters
    ----------
    v : numpy.ndarray
        Values.
    edges : numpy.ndarray, shape (m + 1,)
        Increasing bin edges.

    Returns
    -------
    numpy.ndarray of int, shape of ``v``
        Bin ``0 .. m - 1`` of each value, -1 outside the edges.
    """
    i = np.searchsorted(edges, v, side="right") - 1
    i = np.where(v == edges[-1], len(edges) - 2, i)
    return np.where((v < edges[0]) | (v > edges[-1]), -1, i)


def median_grid(binned: pd.DataFrame) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(x_edges, y_edges, Z)`` for ``pcolormesh`` from :func:`binned_median`; masked bins NaN.
    ``Z`` has shape ``(n_y, n_x)``.

    Parameters
    ----------
    binned : pandas.DataFrame
        A :func:`binned_median` table.

    Returns
    -------
    x_edges : numpy.ndarray, shape (n_x + 1,)
    y_edges : numpy.ndarray, shape (n_y + 1,)
    Z : numpy.ndarray, shape (n_y, n_x)
        Medians, NaN in masked bins.
    """
    xe = np.unique(np.concatenate([binned["x_lo"], binned["x_hi"]]))
    ye = np.unique(np.concatenate([binned["y_lo"], binned["y_hi"]]))
    z = np.where(binned["masked"], np.nan, binned["median"]).reshape(len(xe) - 1, len(ye) - 1)
    return xe, ye, z.T


def binned_profile(df: pd.DataFrame, x: str, value: str = "locus_length_m", *, edges,
                   min_count: int = 30) -> pd.DataFrame:
    """1-D version of :func:`binned_median`: ``lo, hi, mid, count, median, masked``; the same
    bins and NaN rule.

    Parameters
    ----------
    df : pandas.DataFrame
        Table holding ``x`` and ``value``.
    x : str
        Column binned.
    value : str
        Column whose median is taken.
    edges : array_like
        Strictly increasing bin edges, at least two.
    min_count : int
        Rows a bin needs to be shown, ``>= 1``.

    Returns
    -------
    pandas.DataFrame
        One row per bin; ``attrs`` as :func:`binned_median` (``x``, ``value``, ``min_count``,
        ``n_nan``).
    """
    _require(df, [x, value])
    e = _edges("edges", edges)
    count, med, n_nan = _binned(df, [x], [e], value, min_count)
    out = pd.DataFrame({"lo": e[:-1], "hi": e[1:], "mid": 0.5 * (e[:-1] + e[1:]),
                        "count": count, "median": med})
    out["masked"] = out["count"] < int(min_count)
    out.attrs.update(x=x, value=value, min_count=int(min_count), n_nan=n_nan)
    return out


# --------------------------------------------------------------------------------------------
# The paper's Fig. 4 panels and the numbers its claims are checked against
# --------------------------------------------------------------------------------------------
HEATMAP_PANELS = (
    ("a", "r1_m", "r2_m"),
    ("b", "azimuth1_deg", "azimuth2_deg"),
    ("c", "elevation1_deg", "elevation2_deg"),
    ("d", "yaw2_deg", "pitch2_deg"),
    ("e", "yaw2_deg", "azimuth2_deg"),
)
"""Fig. 4 panels: (panel, x column, y column)."""


def panel_edges(column: str, platform, n_bins: int) -> np.ndarray:
    """Bin edges spanning the sampled range of ``column`` for ``platform`` (its aperture and
    attitude limits). A column held at 0 (the boat's pitch) gets a single bin [-0.5, 0.5].

    Parameters
    ----------
    column : str
        A heatmap column (``r1_m``, ``azimuth1_deg``, ``yaw2_deg`` ...).
    platform : Platform
        The platform sampled.
    n_bins : int
        Number of bins.

    Returns
    -------
    numpy.ndarray
        ``n_bins + 1`` equal-width edges (metres or degrees, as the column), or the two edges of
        the single bin.
    """
    sonar = platform.sonar
    limits = {
        "r1_m": (sonar.min_range_m, sonar.max_range_m), "r2_m": (sonar.min_range_m, sonar.max_range_m),
        "azimuth1_deg": (-sonar.azimuth_deg / 2, sonar.azimuth_deg / 2),
        "azimuth2_deg": (-sonar.azimuth_deg / 2, sonar.azimuth_deg / 2),
        "elevation1_deg": (-sonar.elevation_deg / 2, sonar.elevation_deg / 2),
        "elevation2_deg": (-sonar.elevation_deg / 2, sonar.elevation_deg / 2),
        "yaw2_deg": (-180.0, 180.0), "pitch2_deg": (-platform.pitch_max_deg, platform.pitch_max_deg),
    }
    if column not in limits:
        raise ValueError(f"column must be one of {sorted(limits)}; got {column!r}")
    lo, hi = limits[column]
    if hi <= lo:
        return np.array([lo - 0.5, hi + 0.5])
    return np.linspace(lo, hi, int(n_bins) + 1)


def heatmaps(df: pd.DataFrame, platform, *, n_bins: int = 24, min_count: int = 30,
             value: str = "locus_length_m") -> dict[str, pd.DataFrame]:
    """:func:`binned_median` for every panel of :data:`HEATMAP_PANELS`, keyed by panel letter.

    Parameters
    ----------
    df : pandas.DataFrame
        The pose-space table (feature on the side the chapter maps).
    platform : Platform
        The platform sampled (for :func:`panel_edges`).
    n_bins : int
        Bins per axis.
    min_count : int
        Rows a bin needs to be shown.
    value : str
        Column whose median is taken.

    Returns
    -------
    dict of str to pandas.DataFrame
        Per panel letter of :data:`HEATMAP_PANELS`, its :func:`binned_median` table.
    """
    return {p: binned_median(df, x, y, value, x_edges=panel_edges(x, platform, n_bins),
                             y_edges=panel_edges(y, platform, n_bins), min_count=min_count)
            for p, x, y in HEATMAP_PANELS}
