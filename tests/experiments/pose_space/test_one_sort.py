"""The batch statistics of the pose-space tables: ranks and bin medians of each replicate batch.

References: average ranks counted by brute force for each replicate batch ``v[j::k]`` (the batch
ranks of the Spearman table) and :func:`numpy.median` of the values in each bin, bins found by
comparing with the edges (the heatmaps' medians and their batches).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from sss_locus.experiments.pose_space.claims import batch_medians, batches, dealt_batch_medians
from sss_locus.experiments.pose_space.stats import binned_median, binned_profile, column_rank_sets, grouped_binned_medians
from sss_locus.experiments.stats.rowstats import batch_average_ranks

RNG = np.random.default_rng(2024)
COLUMNS = {
    "distinct": RNG.standard_normal(997),
    "ties": RNG.integers(0, 7, 1000).astype(float),
    "signed zeros": RNG.choice([-0.0, 0.0, 1.0, -1.0], 500),
    "integers": RNG.integers(-3, 3, 300),
    "float32": RNG.standard_normal(301).astype(np.float32),
    "extremes": np.tile([np.inf, -np.inf, 0.0, -0.0, 5e-324, -5e-324, 1e308, -1e308, 2.5], 7),
}


def _brute_ranks(v):
    v = np.asarray(v, float)
    if np.isnan(v).any():
        return np.full(v.size, np.nan)
    return (v[None, :] < v[:, None]).sum(1) + ((v[None, :] == v[:, None]).sum(1) + 1) / 2.0


def _rankdata_per_batch(v, k):
    return np.concatenate([_brute_ranks(v[j::k]) for j in range(k)])


@pytest.mark.parametrize("name", sorted(COLUMNS))
@pytest.mark.parametrize("k", [1, 2, 3, 7, 20])
def test_batch_ranks_are_rankdata_of_each_batch_bit_for_bit(name, k):
    v = COLUMNS[name]
    np.testing.assert_array_equal(batch_average_ranks(v, k), _rankdata_per_batch(v, k))


def test_batch_ranks_nan_in_one_batch_and_small_cases():
    v = RNG.standard_normal(40)
    v[13] = np.nan  # batch 13 % 4 = 1
    ours, ref = batch_average_ranks(v, 4), _rankdata_per_batch(v, 4)
    assert np.array_equal(ours, ref, equal_nan=True) and np.isnan(ours[10:20]).all()
    assert batch_average_ranks(np.array([], float), 3).size == 0
    assert batch_average_ranks(np.array([2.0, 1.0]), 5).tolist() == [1.0, 1.0]  # batches of one row
    with pytest.raises(ValueError, match="n_batches"):
        batch_average_ranks(v, 0)


def test_column_rank_sets_whole_and_batches_from_one_sort():
    v = COLUMNS["ties"]
    whole, dealt = column_rank_sets(v.copy(), (1, 20))  # computed ...
    again = column_rank_sets(v.copy(), (20, 1))  # ... then remembered
    assert whole.tobytes() == _brute_ranks(v).tobytes() == again[1].tobytes()
    assert dealt.tobytes() == _rankdata_per_batch(v, 20).tobytes() == again[0].tobytes()


def _bin_of(x, e):
    """Bin of each value by comparison with the edges: [lo, hi), the last bin [lo, hi]; -1 outside."""
    i = (x[:, None] >= e[None, :-1]).sum(1) - 1
    return np.where((x < e[0]) | (x > e[-1]), -1, np.minimum(i, len(e) - 2))


def _brute_medians(coords, values, edges):
    """Count and median of the values in each bin, bin by bin (``np.median``)."""
    shape = tuple(len(e) - 1 for e in edges)
    idx = np.column_stack([_bin_of(coords[:, d], e) for d, e in enumerate(edges)]) if len(values) else np.zeros((0, len(edges)), int)
    count, med = np.zeros(shape, int), np.full(shape, np.nan)
    for b in np.ndindex(*shape):
        sel = (idx == b).all(axis=1)
        count[b] = sel.sum()
        if sel.any():
            med[b] = np.median(values[sel])
    return count, med


@pytest.mark.parametrize("n_groups", [1, 3, 20])
@pytest.mark.parametrize("dims", [1, 2])
def test_grouped_medians_are_scipy_per_group_bit_for_bit(n_groups, dims):
    n = 5000
    coords = RNG.uniform(-1.2, 10.2, (n, dims))  # some rows outside the edges
    coords[:40] = 10.0  # on the last edge (in the last bin)
    coords[60:80] = np.round(coords[60:80])  # on inner edges
    values = np.round(RNG.lognormal(0, 1, n), 1)  # many ties
    values[::97] = 0.0
    values[::89] = -0.0
    edges = [np.linspace(0.0, 10.0, 9), np.array([-1.0, 0.5, 2.0, 7.0, 10.0])][:dims]
    groups = RNG.integers(0, n_groups, n)
    count, med = grouped_binned_medians(coords, values, edges, groups, n_groups)
    for g in range(n_groups):
        sel = groups == g
        ref_count, ref = _brute_medians(coords[sel], values[sel], edges)
        np.testing.assert_array_equal(med[g], ref, err_msg=str(g))
        assert np.array_equal(count[g], ref_count)


def test_binned_tables_keep_scipy_numbers_with_nan_rows():
    n = 3000
    df = pd.DataFrame({"x": RNG.uniform(0, 1, n), "y": RNG.uniform(0, 1, n), "v": RNG.lognormal(0, 1, n)})
    df.loc[5:9, "x"] = np.nan
    df.loc[20:22, "v"] = np.nan
    xe, ye = np.linspace(0, 1, 6), np.linspace(0, 1, 4)
    ok = df.notna().all(axis=1)
    b = binned_median(df, "x", "y", "v", x_edges=xe, y_edges=ye, min_count=1)
    _, ref = _brute_medians(df[ok][["x", "y"]].to_numpy(), df[ok]["v"].to_numpy(), [xe, ye])
    np.testing.assert_array_equal(b["median"].to_numpy(), ref.ravel())
    assert b.attrs["n_nan"] == 8
    prof = binned_profile(df, "x", "v", edges=xe, min_count=1)
    _, ref = _brute_medians(df[ok][["x"]].to_numpy(), df[ok]["v"].to_numpy(), [xe])
    np.testing.assert_array_equal(prof["median"].to_numpy(), ref)
    empty = binned_profile(df.iloc[5:10], "x", "v", edges=xe, min_count=1)  # every row NaN
    assert (empty["count"] == 0).all() and empty["median"].isna().all()


@pytest.mark.parametrize("k", [3, 20])
def test_dealt_batch_medians_are_the_medians_of_each_batch(k):
    n = 4000
    df = pd.DataFrame({"x": RNG.uniform(-5, 5, n), "y": RNG.uniform(0, 3, n),
                       "v": np.round(RNG.lognormal(0, 1, n), 2)})
    df.loc[17, "y"] = np.nan
    for binned in (binned_median(df, "x", "y", "v", x_edges=np.linspace(-5, 5, 7), y_edges=[0, 1, 2, 3]),
                   binned_profile(df, "x", "v", edges=np.linspace(-5, 5, 11))):
        dealt = dealt_batch_medians(df, binned, k)
        assert dealt.tobytes() == batch_medians(batches(df, k), binned).tobytes()
        cols = [binned.attrs["x"]] + ([binned.attrs["y"]] if "y" in binned.attrs else [])
        for j, part in enumerate(batches(df, k)):  # scipy on each batch, rows with a NaN left out
            part = part.dropna(subset=cols + ["v"])
            xy = part[cols].to_numpy()
            edges = ([np.unique(np.r_[binned.x_lo, binned.x_hi]), np.unique(np.r_[binned.y_lo, binned.y_hi])]
                     if "y" in binned.attrs else [np.unique(np.r_[binned.lo, binned.hi])])
            _, ref = _brute_medians(xy, part["v"].to_numpy(), edges)
            np.testing.assert_array_equal(dealt[j], ref.ravel(), err_msg=str(j))

