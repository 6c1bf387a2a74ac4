"""The statistics taken from one sort of a column give the numbers of one scipy call per batch.

References: :func:`scipy.stats.rankdata` of each replicate batch ``v[j::k]`` (the batch ranks of
the Spearman table) and :func:`scipy.stats.binned_statistic_dd` with ``"median"`` of each batch
(the heatmaps' medians and their batches), compared bit for bit; and the pose-space sampler's
short acceptance test against the plain computation of every candidate.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from sss_locus.experiments.pose_claims import batch_medians, batches, dealt_batch_medians
from sss_locus.experiments.pose_stats import binned_median, binned_profile, column_rank_sets, grouped_binned_medians
from sss_locus.experiments.rowstats import batch_average_ranks

RNG = np.random.default_rng(2024)
COLUMNS = {
    "distinct": RNG.standard_normal(997),
    "ties": RNG.integers(0, 7, 1000).astype(float),
    "signed zeros": RNG.choice([-0.0, 0.0, 1.0, -1.0], 500),
    "integers": RNG.integers(-3, 3, 300),
    "float32": RNG.standard_normal(301).astype(np.float32),
    "extremes": np.tile([np.inf, -np.inf, 0.0, -0.0, 5e-324, -5e-324, 1e308, -1e308, 2.5], 7),
}


def _rankdata_per_batch(v, k):
    return np.concatenate([np.asarray(stats.rankdata(v[j::k]), float) for j in range(k)])


@pytest.mark.parametrize("name", sorted(COLUMNS))
@pytest.mark.parametrize("k", [1, 2, 3, 7, 20])
def test_batch_ranks_are_rankdata_of_each_batch_bit_for_bit(name, k):
    v = COLUMNS[name]
    assert batch_average_ranks(v, k).tobytes() == _rankdata_per_batch(v, k).tobytes()


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
    assert whole.tobytes() == np.asarray(stats.rankdata(v), float).tobytes() == again[1].tobytes()
    assert dealt.tobytes() == _rankdata_per_batch(v, 20).tobytes() == again[0].tobytes()


def _scipy_medians(coords, values, edges):
    if len(values) == 0:
        return np.full(tuple(len(e) - 1 for e in edges), np.nan)
    return stats.binned_statistic_dd(coords, values, "median", bins=list(edges)).statistic


@pytest.mark.parametrize("n_groups", [1, 3, 20])
@pytest.mark.parametrize("dims", [1, 2])
def test_grouped_medians_are_scipy_per_group_bit_for_bit(n_groups, dims):
    n = 5000
    coords = RNG.uniform(-1.2, 10.2, (n, dims))  # some rows outside the edges
    coords[:40] = 10.0  # on the last edge (in the last bin)
    coords[40:60] = 10.0 + 1e-9  # above it by less than scipy's rounding: the last bin too
    coords[60:80] = np.round(coords[60:80])  # on inner edges
    values = np.round(RNG.lognormal(0, 1, n), 1)  # many ties
    values[::97] = 0.0
    values[::89] = -0.0
    edges = [np.linspace(0.0, 10.0, 9), np.array([-1.0, 0.5, 2.0, 7.0, 10.0])][:dims]
    groups = RNG.integers(0, n_groups, n)
    count, med = grouped_binned_medians(coords, values, edges, groups, n_groups)
    for g in range(n_groups):
        sel = groups == g
        ref = _scipy_medians(coords[sel], values[sel], edges)
        assert med[g].tobytes() == ref.tobytes(), g
        hist = stats.binned_statistic_dd(coords[sel], values[sel], "count", bins=list(edges)).statistic
        assert np.array_equal(count[g], hist)


def test_binned_tables_keep_scipy_numbers_with_nan_rows():
    n = 3000
    df = pd.DataFrame({"x": RNG.uniform(0, 1, n), "y": RNG.uniform(0, 1, n), "v": RNG.lognormal(0, 1, n)})
    df.loc[5:9, "x"] = np.nan
    df.loc[20:22, "v"] = np.nan
    xe, ye = np.linspace(0, 1, 6), np.linspace(0, 1, 4)
    ok = df.notna().all(axis=1)
    b = binned_median(df, "x", "y", "v", x_edges=xe, y_edges=ye, min_count=1)
    ref = stats.binned_statistic_dd(df[ok][["x", "y"]].to_numpy(), df[ok]["v"].to_numpy(), "median", bins=[xe, ye])
    assert b["median"].to_numpy().tobytes() == ref.statistic.ravel().tobytes() and b.attrs["n_nan"] == 8
    prof = binned_profile(df, "x", "v", edges=xe, min_count=1)
    ref = stats.binned_statistic(df[ok]["x"], df[ok]["v"], "median", bins=xe).statistic
    assert prof["median"].to_numpy().tobytes() == ref.tobytes()
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
            ref = stats.binned_statistic_dd(xy, part["v"].to_numpy(), "median", bins=edges).statistic
            assert dealt[j].tobytes() == ref.ravel().tobytes(), j


def test_grouped_medians_signed_zero_ties_in_row_order_like_scipy():
    # the middle value is one of three zeros: scipy takes the zeros in row order (+0.0 here);
    # an order of the bits (-0.0 first) would give -0.0
    values = np.array([-1.0, 0.0, -1.0, -0.0, -1.0, 0.0, 1.0])
    coords = np.full((7, 1), 0.5)
    _, med = grouped_binned_medians(coords, values, [np.array([0.0, 1.0])], np.zeros(7, int), 1)
    ref = stats.binned_statistic_dd(coords, values, "median", bins=[np.array([0.0, 1.0])]).statistic
    assert med[0].tobytes() == ref.tobytes() == np.array([0.0]).tobytes()
