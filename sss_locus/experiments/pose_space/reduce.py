"""The pose-space study reduced where its samples are made: summaries travel, rows do not.

:func:`sample_pose_space` returns the whole table (about 140 bytes a sample, all of which a Dask
cluster sends back to the client). :func:`reduce_pose_space` computes the chapter's main
statistics (Spearman's rho of every candidate driver with each target, with replicate-batch
intervals, and the heatmaps' per-bin counts and medians) without ever bringing rows to the
client:

* the ``n`` rows are cut into ``k`` replicate batches of consecutive rows of equal sizes
  (:func:`batch_rows`; batch ``j`` holds the same rows as
  :func:`sample_pose_space`'s table for the same ``(spec, n, seed)``); rows are i.i.d. draws, so
  these are ``k`` independent replicate studies;
* each batch is one task (:func:`sss_locus.experiments.stats.scale.map_reduce`): it samples its rows,
  ranks them and returns its rho matrix (a few hundred bytes), and keeps, for each heatmap panel,
  its rows' bin numbers and lengths (12 bytes a row) as one part for that panel's reduce task;
* each panel's reduce task joins its parts in batch order and computes the exact per-bin counts
  and medians (:func:`~sss_locus.experiments.pose_space.stats.binned_median`, the same numbers as from
  the whole table); only these travel to the client.

Spearman's rho is the mean of the ``k`` batch rhos (a full-table rank needs every row in one
place), and its interval is the batch-means interval around it
(:func:`~sss_locus.experiments.stats.replicates.replicate_interval`); it differs from the full-table
rho of :func:`~sss_locus.experiments.pose_space.stats.spearman_table` by far less than that interval
(``tests/experiments/stats/test_reduce.py``). Every number is a pure function of ``(spec, n, seed, k)``
combined in batch order, so it is bit-identical in-process and on any number of workers.
"""

from __future__ import annotations

import pickle
from dataclasses import dataclass
from functools import partial

import numpy as np
import pandas as pd

from sss_locus.experiments.pose_space.study import BLOCK_SIZE, PoseSpaceSpec, check_n_seed, evaluate_blocks
from sss_locus.experiments.pose_space.stats import (CANDIDATES, HEATMAP_PANELS, MISALIGNMENT_READINGS, TARGETS, bin_index,
                                                    binned_median, panel_edges, rho_frame, with_derived)
from sss_locus.experiments.stats.replicates import N_BATCHES, batch_count, centred_from, check_confidence, rank_correlation
from sss_locus.experiments.stats.rowstats import average_ranks
from sss_locus.experiments.stats.scale import map_reduce

SIDE2_CHOICES = ("port", "either")


@dataclass(frozen=True)
class PoseReduction:
    """What :func:`reduce_pose_space` returns.

    Attributes
    ----------
    rho : pandas.DataFrame
        The columns of :func:`~sss_locus.experiments.pose_space.stats.spearman_table`; ``rho`` is the
        mean of the batch rhos.
    maps : dict of str to pandas.DataFrame
        Per panel letter, the frame of :func:`~sss_locus.experiments.pose_space.stats.heatmaps`.
    batch_rho : numpy.ndarray
        ``(k, p, q)``: each batch's rho (candidates kept x targets).
    n, n_heatmap : int
        Rows of the study, and of them those in the heatmaps (sensor 2's side ``heatmap_side2``).
    bytes_to_client : int
        Pickled size of everything the client receives (summaries and reduced panels).
    bytes_between_workers : int
        Bytes of the panel parts handed from the batch tasks to the reduce tasks (on a cluster
        they move between workers, never to the client).
    """

    rho: pd.DataFrame
    maps: dict
    batch_rho: np.ndarray
    n: int
    n_heatmap: int
    bytes_to_client: int
    bytes_between_workers: int


def batch_rows(n: int, k: int) -> list[tuple[int, int]]:
    """``(start, stop)`` rows of each of the ``k`` batches of ``n`` rows: consecutive, of sizes
    differing by at most one. Equal sizes matter: the mean of the batch rhos weighs every batch
    alike, so unequal batches (e.g. whole sampler blocks, 1 or 2 of them) would make it a
    differently weighted, noisier estimate than the full table's (by ~0.3 of the interval's
    half-width, measured). A block that two batches share is drawn by both (at most ``k - 1``
    extra blocks of :data:`~sss_locus.experiments.pose_space.study.BLOCK_SIZE` rows).

    Parameters
    ----------
    n : int
        Rows of the study.
    k : int
        Number of batches.

    Returns
    -------
    list of (int, int)
        ``k`` half-open row ranges covering ``0 .. n - 1`` in order.
    """
    return [(j * n // k, (j + 1) * n // k) for j in range(k)]


def batch_table(spec: PoseSpaceSpec, seed: int, n: int, start: int, stop: int) -> pd.DataFrame:
    """Rows ``start .. stop - 1`` of ``sample_pose_space(spec, n, seed)``, made on their own.

    Parameters
    ----------
    spec : PoseSpaceSpec
        The study.
    seed : int
        Seed of the stream.
    n : int
        Rows of the whole study.
    start, stop : int
        Rows wanted, ``start .. stop - 1``.

    Returns
    -------
    pandas.DataFrame
        Those rows, index from 0.
    """
    first, last = start // BLOCK_SIZE, -(-stop // BLOCK_SIZE)
    rows = evaluate_blocks(spec, seed, first, last, n)
    return rows.iloc[start - first * BLOCK_SIZE:stop - first * BLOCK_SIZE].reset_index(drop=True)


def _batch(spec, seed, n, start, stop, candidates, targets, misalignment, side2, edges):
    """One batch task: ``(summary, parts)`` (see :func:`scale.map_reduce`)."""
    table = with_derived(batch_table(spec, seed, n, start, stop), misalignment=misalignment)
    ranks = {c: average_ranks(table[c].to_numpy(float)) for c in (*candidates, *targets)}
    constant = {c: bool(r.min() == r.max()) for c, r in ranks.items()}
    with np.errstate(invalid="ignore", divide="ignore"):  # a constant column: NaN
        rho = rank_correlation(centred_from(np.column_stack([ranks[c] for c in candidates])),
                               centred_from(np.column_stack([ranks[c] for c in targets])))
    shown = table if side2 == "either" else table[table["side2"] == side2]
    value = shown["locus_length_m"].to_numpy(float)
    parts = []
    for (_, x, y), (xe, ye) in zip(HEATMAP_PANELS, edges):
        ix, iy = bin_index(shown[x].to_numpy(float), xe), bin_index(shown[y].to_numpy(float), ye)
        ok = (ix >= 0) & (iy >= 0)
        parts.append((ix[ok].astype(np.int16), iy[ok].astype(np.int16), value[ok]))
    summary = dict(rho=rho, constant=constant, n=len(table), n_heatmap=len(shown),
                   part_bytes=sum(a.nbytes for p in parts for a in p))
    return summary, parts


def _panel(g, parts, edges, min_count):
    """Reduce task of panel ``g``: exact per-bin counts and medians of its parts, in batch order.

    Each row enters at its bin's centre, so :func:`binned_median` puts it in the bin the batch
    task found, and the medians are those of the whole table's rows in that bin."""
    (_, x, y), (xe, ye) = HEATMAP_PANELS[g], edges[g]
    ix, iy, v = (np.concatenate([p[i] for p in parts]) for i in range(3))
    mid = lambda e, i: 0.5 * (e[:-1] + e[1:])[i]
    frame = pd.DataFrame({x: mid(xe, ix), y: mid(ye, iy), "locus_length_m": v})
    return binned_median(frame, x, y, x_edges=xe, y_edges=ye, min_count=min_count)


def reduce_pose_space(spec: PoseSpaceSpec, n_samples: int, seed: int, *, n_batches: int = N_BATCHES,
                      n_bins: int = 24, min_count: int = 30, heatmap_side2: str = "port",
                      misalignment: str = "magnitude", candidates=CANDIDATES, targets=TARGETS,
                      confidence_level: float = 0.95, progress=None) -> PoseReduction:
    """Spearman's rho table and heatmaps of the pose-space study, reduced on the workers.

    Parameters
    ----------
    spec, n_samples, seed
        As for :func:`~sss_locus.experiments.pose_space.study.sample_pose_space` (the same rows).
    n_batches : int
        Replicate batches ``k`` (>= 3; at most ``n_samples // 3``), one task each.
    n_bins, min_count
        Heatmap bins per axis and the count below which a bin is masked
        (:func:`~sss_locus.experiments.pose_space.stats.heatmaps`).
    heatmap_side2 : {"port", "either"}
        Rows in the heatmaps: sensor 2 on the port side (the chapter's default) or all.
    misalignment : {"magnitude", "signed"}
        Reading of the elevation misalignment (:func:`~sss_locus.experiments.pose_space.stats.with_derived`).
    candidates, targets, confidence_level
        As for :func:`~sss_locus.experiments.pose_space.stats.spearman_table`.
    progress : callable or None
        ``progress(done, total)`` after each batch; no effect on the result.

    Returns
    -------
    PoseReduction
        Bit-identical in-process and on a Dask cluster of any size (module docstring).
    """
    n, seed = check_n_seed(n_samples, seed)
    k = batch_count(n // 3, n_batches)
    if heatmap_side2 not in SIDE2_CHOICES:
        raise ValueError(f"heatmap_side2 must be one of {list(SIDE2_CHOICES)}; got {heatmap_side2!r}")
    if misalignment not in MISALIGNMENT_READINGS:
        raise ValueError(f"misalignment must be one of {list(MISALIGNMENT_READINGS)}; got {misalignment!r}")
    if isinstance(min_count, bool) or not isinstance(min_count, (int, np.integer)) or min_count < 1:
        raise ValueError(f"min_count must be an integer >= 1; got {min_count!r}")
    if isinstance(n_bins, bool) or not isinstance(n_bins, (int, np.integer)) or not 2 <= n_bins <= 2 ** 15 - 1:
        raise ValueError(f"n_bins must be an integer in [2, 32767]; got {n_bins!r}")
    confidence_level = check_confidence(confidence_level)
    candidates, targets = list(candidates), list(targets)
    unknown = sorted(set(candidates + targets) - set(CANDIDATES) - set(TARGETS))
    if unknown:
        raise ValueError(f"unknown columns {unknown}; candidates and targets are among {list(CANDIDATES + TARGETS)}")
    edges = [(panel_edges(x, spec.platform, n_bins), panel_edges(y, spec.platform, n_bins))
             for _, x, y in HEATMAP_PANELS]
    tasks = [(spec, seed, n, a, b, candidates, targets, misalignment, heatmap_side2, edges)
             for a, b in batch_rows(n, k)]
    summaries, panels = map_reduce(_batch, tasks, partial(_panel, edges=edges, min_count=int(min_count)),
                                   len(HEATMAP_PANELS), progress)
    constant = [c for c in candidates + targets if all(s["constant"][c] for s in summaries)]
    if set(constant) & set(targets):
        raise ValueError(f"columns {constant} are constant: their rank correlation is undefined")
    keep = [i for i, c in enumerate(candidates) if c not in constant]
    batches = np.stack([s["rho"][keep] for s in summaries])
    rho = rho_frame(batches.mean(axis=0), batches, n, [candidates[i] for i in keep], targets,
                    confidence_level, dropped=constant)
    maps = {letter: frame for (letter, _, _), frame in zip(HEATMAP_PANELS, panels)}
    return PoseReduction(rho=rho, maps=maps, batch_rho=batches, n=n,
                         n_heatmap=sum(s["n_heatmap"] for s in summaries),
                         bytes_to_client=len(pickle.dumps((summaries, panels))),
                         bytes_between_workers=sum(s["part_bytes"] for s in summaries))
