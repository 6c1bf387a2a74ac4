"""The pose-space study reduced on the workers (experiments/pose_reduce.py): its heatmaps are the
whole table's, its rhos the batches' Spearman rhos (scipy on the table's rows), it is
bit-identical in-process and on local clusters of 1, 2 and 3 worker processes, and it sends the
client at least 50 times fewer bytes than the table."""

from __future__ import annotations

import pickle
import time

import numpy as np
import pytest
from scipy.stats import spearmanr
from test_scale import _assert_bit_identical  # bit for bit, NaN patterns included

from sss_locus.experiments import scale
from sss_locus.experiments.platforms import load_platform
from sss_locus.experiments.pose_reduce import batch_rows, reduce_pose_space
from sss_locus.experiments.pose_space import PoseSpaceSpec, sample_pose_space
from sss_locus.experiments.pose_stats import CANDIDATES, TARGETS, heatmaps, spearman_table, with_derived


@pytest.mark.parametrize("key", ["auv", "boat"])
def test_reduction_equals_the_statistics_of_the_whole_table(key, monkeypatch):
    monkeypatch.delenv(scale.SCHEDULER_ENV, raising=False)
    spec, n, seed, k = PoseSpaceSpec(load_platform(key)), 40_003, 5, 20
    red = reduce_pose_space(spec, n, seed, n_batches=k, n_bins=16, min_count=30)
    raw = sample_pose_space(spec, n, seed)
    table = with_derived(raw)
    port = table[table["side2"] == "port"]
    ref = heatmaps(port, spec.platform, n_bins=16, min_count=30)
    for letter in ref:  # exact per-bin counts and medians, bit for bit
        _assert_bit_identical(red.maps[letter], ref[letter])
    assert red.n == n and red.n_heatmap == len(port)
    # each batch's rho is scipy's Spearman rho of that batch's rows of the table
    rows = red.rho.set_index(["target", "quantity"])
    kept = [c for c in CANDIDATES if c not in red.rho.attrs["dropped"]]  # batch_rho's axis 1
    for i, c in list(enumerate(kept))[::4]:
        for t_pos, target in enumerate(TARGETS):
            expect = [spearmanr(table[c].to_numpy()[a:b], table[target].to_numpy()[a:b])[0]
                      for a, b in batch_rows(n, k)]
            np.testing.assert_allclose(red.batch_rho[:, i, t_pos], expect, rtol=0, atol=1e-12)
            assert abs(rows.loc[(target, c), "rho"] - red.batch_rho[:, i, t_pos].mean()) < 1e-15
    # the mean of the batch rhos is within a tenth of its interval of the full-table rho
    full = spearman_table(table).set_index(["target", "quantity"])
    half = (rows["ci_high"] - rows["ci_low"]) / 2
    assert ((rows["rho"] - full.loc[rows.index, "rho"]).abs() < 0.1 * half).all()
    assert set(red.rho.attrs["dropped"]) == set(full.attrs["dropped"])
    # the client receives at least 50x fewer bytes than the table would bring
    assert len(pickle.dumps(raw)) >= 50 * red.bytes_to_client


def test_bit_identical_in_process_and_on_1_2_3_workers(monkeypatch):
    distributed = pytest.importorskip("distributed")
    spec = PoseSpaceSpec(load_platform("auv"))

    def run():
        return reduce_pose_space(spec, 9_001, 2, n_batches=5, n_bins=6, min_count=5)

    monkeypatch.delenv(scale.SCHEDULER_ENV, raising=False)
    here = run()
    with distributed.LocalCluster(n_workers=3, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        monkeypatch.setenv(scale.SCHEDULER_ENV, cluster.scheduler_address)
        try:
            for workers in (3, 2, 1):  # one cluster, shrunk: no worker started twice
                cluster.scale(workers)
                dask_client = scale.client(cluster.scheduler_address)
                deadline = time.monotonic() + 60
                while len(dask_client.scheduler_info()["workers"]) != workers and time.monotonic() < deadline:
                    time.sleep(0.1)
                assert len(dask_client.scheduler_info()["workers"]) == workers
                there = run()
                _assert_bit_identical(there.rho, here.rho)
                assert there.batch_rho.tobytes() == here.batch_rho.tobytes()
                for letter in here.maps:
                    _assert_bit_identical(there.maps[letter], here.maps[letter])
                assert (there.n, there.n_heatmap) == (here.n, here.n_heatmap)
        finally:
            scale.close_clients()


@pytest.mark.parametrize("kwargs, message", [
    (dict(heatmap_side2="starboard"), "heatmap_side2 must be one of"),
    (dict(misalignment="max"), "misalignment must be one of"),
    (dict(n_batches=2), "n_batches must be an integer >= 3"),
    (dict(n_bins=1), "n_bins must be an integer in"),
    (dict(min_count=0), "min_count must be an integer >= 1"),
    (dict(candidates=["depth_m"]), "unknown columns"),
])
def test_bad_arguments_are_refused_before_any_sampling(kwargs, message):
    with pytest.raises(ValueError, match=message):
        reduce_pose_space(PoseSpaceSpec(load_platform("boat")), 1000, 1, **kwargs)
