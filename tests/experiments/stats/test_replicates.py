"""Replicate-batch intervals (sss_locus.experiments.stats.replicates) cover known population values.

For each statistic the studies report with a replicate interval, many independent small studies
with a population value known in closed form: the share of 95 % intervals that contain it must
be 93-97 %, and the mean width within 25 % of a percentile bootstrap's (written here with
numpy, 200 resamples, on the first studies). Populations:

- Spearman's rho: a Gaussian copula (normal pair with correlation r, then monotone margins
  ``exp`` and cube), whose rho is ``(6 / pi) asin(r / 2)`` whatever the margins;
- medians and their ratio: log-normal samples, median ``exp(mu)``;
- the water crop's means and ratio of means: pairs with a known mixture (shares and expectations
  in closed form, below).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from sss_locus.experiments.survey_passes.planning import median_ratio
from sss_locus.experiments.pose_space.stats import spearman_table
from sss_locus.experiments.stats.replicates import median_with_interval
from sss_locus.experiments.water.study import crop_effect

N_STUDIES = 1000  # coverage's standard error ~0.7 %: 93-97 % is about +-3 of them
N_BOOT_STUDIES, N_RESAMPLES = 100, 200
PERCENTILES = [2.5, 97.5]


def _check(name, covered, widths, boot_widths):
    coverage = float(np.mean(covered))
    ratio = float(np.mean(widths[:len(boot_widths)]) / np.mean(boot_widths))
    print(f"{name}: coverage {coverage:.3f} over {len(covered)} studies, width / bootstrap width {ratio:.3f}")
    assert 0.93 <= coverage <= 0.97, (name, coverage)
    assert 0.75 <= ratio <= 1.25, (name, ratio)


def _copula(rng, n, r):
    z1 = rng.standard_normal(n)
    z2 = r * z1 + math.sqrt(1 - r * r) * rng.standard_normal(n)
    return pd.DataFrame({"x": np.exp(z1), "y": z2 ** 3})


@pytest.mark.parametrize("r, n", [(0.6, 2000), (-0.9, 1200)])
def test_spearman_interval_covers_the_copula_rho(r, n):
    truth = 6 / math.pi * math.asin(r / 2)
    rng = np.random.default_rng(20261124)
    covered, z_covered, widths, z_widths, boot_widths = [], [], [], [], []
    for study in range(N_STUDIES // 2):
        df = _copula(rng, n, r)
        row = spearman_table(df, ["x"], ["y"]).iloc[0]
        covered.append(row.ci_low <= truth <= row.ci_high)
        widths.append(row.ci_high - row.ci_low)
        z_widths.append(row.ci_high_z - row.ci_low_z)
        z_covered.append(row.ci_low_z <= truth <= row.ci_high_z)
        if study < N_BOOT_STUDIES:  # resample rows, re-rank, correlate (scipy's definition)
            idx = rng.integers(0, n, (N_RESAMPLES, n))
            rx = np.argsort(np.argsort(df["x"].to_numpy()[idx], axis=1), axis=1).astype(float)
            ry = np.argsort(np.argsort(df["y"].to_numpy()[idx], axis=1), axis=1).astype(float)
            rx -= rx.mean(axis=1, keepdims=True)
            ry -= ry.mean(axis=1, keepdims=True)
            rho = (rx * ry).sum(axis=1) / np.sqrt((rx * rx).sum(axis=1) * (ry * ry).sum(axis=1))
            boot_widths.append(np.subtract(*np.percentile(rho, PERCENTILES)[::-1]))
    _check(f"spearman rho={truth:.3f} n={n}", covered, np.array(widths), boot_widths)
    # cross-check: the asymptotic Fisher-z interval has about the same width and coverage
    print(f"  Fisher-z: coverage {np.mean(z_covered):.3f}, replicate width / Fisher-z width "
          f"{np.mean(widths) / np.mean(z_widths):.3f}")
    assert 0.8 <= np.mean(widths) / np.mean(z_widths) <= 1.25


def _boot_median_width(rng, x):
    b = np.median(x[rng.integers(0, x.size, (N_RESAMPLES, x.size))], axis=1)
    return np.subtract(*np.percentile(b, PERCENTILES)[::-1])


@pytest.mark.parametrize("n", [400, 2000])
def test_median_interval_covers_the_lognormal_median(n):
    # n = 400: batches of 20 rows (the quick profiles' size), where a median's batch spread is
    # furthest from its large-sample behaviour
    rng = np.random.default_rng(7 + n)
    covered, widths, boot_widths = [], [], []
    for study in range(N_STUDIES):
        x = rng.lognormal(0.5, 1.0, n)
        med, lo, hi = median_with_interval(x)
        covered.append(lo <= math.exp(0.5) <= hi)
        widths.append(hi - lo)
        if study < N_BOOT_STUDIES:
            boot_widths.append(_boot_median_width(rng, x))
    _check(f"median n={n}", covered, np.array(widths), boot_widths)


def test_median_ratio_interval_covers_the_ratio():
    rng = np.random.default_rng(11)
    covered, widths, boot_widths = [], [], []
    for study in range(N_STUDIES):
        x, y = rng.lognormal(0.3, 1.0, 1000), rng.lognormal(0.0, 0.7, 1500)
        out = median_ratio(x, y)
        covered.append(out["ratio_ci_low"] <= math.exp(0.3) <= out["ratio_ci_high"])
        widths.append(out["ratio_ci_high"] - out["ratio_ci_low"])
        if study < N_BOOT_STUDIES:
            bx = np.median(x[rng.integers(0, x.size, (N_RESAMPLES, x.size))], axis=1)
            by = np.median(y[rng.integers(0, y.size, (N_RESAMPLES, y.size))], axis=1)
            boot_widths.append(np.subtract(*np.percentile(bx / by, PERCENTILES)[::-1]))
    _check("median ratio", covered, np.array(widths), boot_widths)


def _crop_pairs(rng, n):
    """Uncropped length ``a``: 0 with probability 0.2, else Exp(1) (one arc) or 1 + Exp(1) (two
    arcs, probability 0.3 of the non-empty). The crop keeps a locus with probability 0.6, else
    shortens it to ``a U``, U uniform (emptied if U < 0.25: length 0); a shortened two-arc locus
    keeps one arc."""
    a_nonempty = rng.random(n) >= 0.2
    two = a_nonempty & (rng.random(n) < 0.3)
    a = np.where(a_nonempty, rng.exponential(1.0, n) + two, 0.0)
    cut = a_nonempty & (rng.random(n) >= 0.6)
    u = rng.random(n)
    b = np.where(cut, np.where(u < 0.25, 0.0, a * u), a)
    arcs_a = np.where(two, 2, a_nonempty.astype(int))
    arcs_b = np.where(cut, (b > 0).astype(int), arcs_a)
    return (pd.DataFrame({"locus_length_m": a, "n_arcs": arcs_a}),
            pd.DataFrame({"locus_length_m": b, "n_arcs": arcs_b}))


def test_crop_effect_intervals_cover_the_population_values():
    # E[a] = 0.8 (1 + 0.3); E[b] = 0.8 (0.6 * 1.3 + 0.4 * 1.3 * E[U; U >= 0.25]) with
    # E[U; U >= 0.25] = (1 - 0.0625) / 2
    truth = {"length_ratio": 0.6 + 0.4 * 0.46875, "shortened_share": 0.8 * 0.4,
             "emptied_share": 0.4 * 0.25, "multi_arc_share_uncropped": 0.8 * 0.3,
             "multi_arc_share_cropped": 0.8 * 0.3 * 0.6, "extra_arcs_share": 0.8 * 0.3 * 0.4}
    rng = np.random.default_rng(3)
    covered = {k: [] for k in truth}
    widths = {k: [] for k in truth}
    boot_widths = {k: [] for k in truth}
    for study in range(N_STUDIES):
        a, b = _crop_pairs(rng, 1000)
        eff = crop_effect(a, b).set_index("statistic")
        for k, v in truth.items():
            covered[k].append(eff.loc[k, "ci_low"] <= v <= eff.loc[k, "ci_high"])
            widths[k].append(eff.loc[k, "ci_high"] - eff.loc[k, "ci_low"])
        if study < N_BOOT_STUDIES // 2:  # 50 bootstraps: these widths vary little
            idx = rng.integers(0, len(a), (N_RESAMPLES, len(a)))
            la, lb = a["locus_length_m"].to_numpy()[idx], b["locus_length_m"].to_numpy()[idx]
            na, nb = a["n_arcs"].to_numpy()[idx], b["n_arcs"].to_numpy()[idx]
            boot = {"length_ratio": lb.sum(1) / la.sum(1), "shortened_share": (lb < la).mean(1),
                    "emptied_share": ((la > 0) & (lb == 0)).sum(1) / (la > 0).sum(1),
                    "multi_arc_share_uncropped": (na > 1).mean(1), "multi_arc_share_cropped": (nb > 1).mean(1),
                    "extra_arcs_share": ((na > 1) & (nb <= 1)).mean(1)}
            for k in truth:
                boot_widths[k].append(np.subtract(*np.percentile(boot[k], PERCENTILES)[::-1]))
    for k in truth:
        _check(f"crop {k}", covered[k], np.array(widths[k]), boot_widths[k])
