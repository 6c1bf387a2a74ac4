"""Analysis statistics against independent references (scipy, brute force, closed forms)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from sss_locus.experiments.stats.significant import agree_sig, round_sig
from sss_locus.experiments.pose_space.stats import (
    binned_median,
    binned_profile,
    median_grid,
    spearman_table,
    with_derived,
)
from sss_locus.report.common.text import fmt_sig


def _frame(n, r, seed=0, ties=False):
    rng = np.random.default_rng(seed)
    x = rng.normal(size=n)
    y = r * x + math.sqrt(1 - r * r) * rng.normal(size=n)
    if ties:
        x = np.round(x, 1)
    return pd.DataFrame({"x": x, "y": y, "z": rng.normal(size=n)})


def test_point_estimate_is_scipy_spearman():
    df = _frame(1500, 0.6, ties=True)
    tab = spearman_table(df, ["x", "z"], ["y"])
    for q in ("x", "z"):
        ref = stats.spearmanr(df[q], df["y"]).statistic
        assert tab.set_index("quantity").loc[q, "rho"] == pytest.approx(ref, abs=1e-12)


def test_matches_gaussian_closed_form():
    # bivariate normal: rho_s = (6 / pi) asin(r / 2)
    df = _frame(100_000, 0.5, seed=3)
    tab = spearman_table(df, ["x"], ["y"]).iloc[0]
    expect = 6 / math.pi * math.asin(0.25)
    assert tab["ci_low"] - 0.005 < expect < tab["ci_high"] + 0.005
    assert tab["rho"] == pytest.approx(expect, abs=0.01)


@pytest.mark.parametrize("n, n_batches", [(1000, 20), (1013, 25), (90, 50)])
def test_interval_is_the_t_interval_of_batch_spearmanr(n, n_batches):
    # reference: scipy.stats.spearmanr of each batch (rows j, j + k, ...), scipy.stats.t, and
    # scipy's Fisher-z arithmetic written out (Bonett-Wright standard error)
    df = _frame(n, 0.4, seed=5, ties=n > 100)
    tab = spearman_table(df, ["x", "z"], ["y"], n_batches=n_batches, confidence_level=0.9)
    k = min(n // 3, n_batches)
    assert tab.attrs["n_batches"] == k
    for row in tab.itertuples():
        x, y = df[row.quantity].to_numpy(), df["y"].to_numpy()
        full = stats.spearmanr(x, y).statistic
        batches = [stats.spearmanr(x[j::k], y[j::k]).statistic for j in range(k)]
        half = stats.t.ppf(0.95, k - 1) * np.std(batches, ddof=1) / math.sqrt(k)
        assert row.rho == pytest.approx(full, abs=1e-12)
        assert (row.ci_low, row.ci_high) == pytest.approx((full - half, full + half), abs=1e-12)
        se = math.sqrt((1 + full ** 2 / 2) / (n - 3))
        z = stats.norm.ppf(0.95)
        assert (row.ci_low_z, row.ci_high_z) == pytest.approx(
            (math.tanh(math.atanh(full) - z * se), math.tanh(math.atanh(full) + z * se)), abs=1e-12)


def test_sorted_by_magnitude_and_errors():
    df = _frame(500, -0.8)
    tab = spearman_table(df, ["z", "x"], ["y"])
    assert list(tab["quantity"]) == ["x", "z"] and tab["rho"].iloc[0] < -0.7
    with pytest.raises(ValueError, match="lacks columns"):
        spearman_table(df, ["nope"], ["y"])
    df["c"] = 1.0
    with pytest.raises(ValueError, match="constant"):
        spearman_table(df, ["c"], ["y"], drop_constant=False)
    kept = spearman_table(df, ["c", "x"], ["y"])
    assert list(kept["quantity"]) == ["x"] and kept.attrs["dropped"] == ["c"]
    with pytest.raises(ValueError, match="constant"):
        spearman_table(df, ["x"], ["c"])


def _brute_bins(v: pd.Series, edges) -> list[pd.Series]:
    """Membership of each bin by the stated rule, one comparison at a time: [lo, hi), the last
    bin [lo, hi]; NaN in no bin."""
    return [(v >= lo) & ((v <= hi) if hi == edges[-1] else (v < hi)) for lo, hi in zip(edges[:-1], edges[1:])]


def test_binned_median_brute_force():
    rng = np.random.default_rng(9)
    df = pd.DataFrame({"a": rng.uniform(-1, 1, 3000), "b": rng.uniform(0, 10, 3000),
                       "v": rng.exponential(size=3000)})
    df.loc[0, "a"] = 1.0  # the last edge is inclusive
    df.loc[1, "a"] = 1.5  # outside: ignored
    df.loc[2:9, "a"] = 0.0  # on an interior edge: in the bin above it
    df.loc[10, "a"], df.loc[11, "b"], df.loc[12, "v"] = np.nan, np.nan, np.nan  # in no bin
    xe, ye = np.linspace(-1, 1, 5), np.linspace(0, 10, 4)
    out = binned_median(df, "a", "b", "v", x_edges=xe, y_edges=ye, min_count=200)
    assert len(out) == 12 and out["count"].sum() == 2996 and out.attrs["n_nan"] == 3
    keep = df.v.notna()
    for _, row in out.iterrows():
        sel = (_brute_bins(df.a, xe)[int(np.searchsorted(xe, row.x_lo))]
               & _brute_bins(df.b, ye)[int(np.searchsorted(ye, row.y_lo))] & keep)
        assert row["count"] == sel.sum()
        assert row["median"] == pytest.approx(np.median(df.v[sel]))
        assert row["masked"] == (sel.sum() < 200)
    x, y, z = median_grid(out)
    assert z.shape == (3, 4) and np.allclose(x, xe) and np.allclose(y, ye)
    assert np.isnan(z).sum() == out["masked"].sum()
    prof = binned_profile(df, "a", "v", edges=xe, min_count=1)
    for i, sel in enumerate(_brute_bins(df.a, xe)):
        assert prof["count"][i] == (sel & keep).sum()
        assert prof["median"][i] == pytest.approx(np.median(df.v[sel & keep]))
    assert prof["count"][2] >= 8  # the eight rows on the edge 0.0 are in [0, 0.5)
    empty = binned_profile(df.iloc[:0], "a", "v", edges=xe)
    assert (empty["count"] == 0).all() and empty["median"].isna().all()
    with pytest.raises(ValueError, match="x_edges"):
        binned_median(df, "a", "b", "v", x_edges=[1, 0], y_edges=ye)
    with pytest.raises(ValueError, match="min_count"):
        binned_profile(df, "a", "v", edges=xe, min_count=0)


def test_significant_figures():
    assert np.allclose(round_sig([0.012345, 123.4, -0.0999]), [0.012, 120.0, -0.1])
    assert agree_sig(0.4449, 0.4401) and not agree_sig(0.445, 0.455)
    assert fmt_sig(0.012345) == "0.012" and fmt_sig(123.4) == "120" and fmt_sig(2.0) == "2.0"


def test_with_derived_adds_magnitudes():
    df = pd.DataFrame({"yaw2_deg": [-170.0, 20.0], "psi1_deg": [-3.0, 4.0]})
    out = with_derived(df)
    assert list(out["abs_yaw2_deg"]) == [170.0, 20.0] and list(out["abs_psi1_deg"]) == [3.0, 4.0]
    out.loc[0, "yaw2_deg"] = 5.0  # a copy: changing it leaves the table given
    out["psi1_deg"] *= 2
    assert list(df["yaw2_deg"]) == [-170.0, 20.0] and list(df["psi1_deg"]) == [-3.0, 4.0]


def test_plain_label():
    from sss_locus.report.common.text import plain_label

    assert plain_label("abs_psi2_deg") == "|ψ₂|" and plain_label("azimuth1_deg") == "azimuth θ₁"
    assert plain_label("unknown_q") == "unknown_q"
