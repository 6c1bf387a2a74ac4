"""Studies reduced on the workers (experiments/pose_space/reduce.py, survey_reduce.py): the pose-space
heatmaps are the whole table's, its rhos the batches' Spearman rhos (scipy on the table's rows),
the crossing-angle curve is crossing_angle_curve's; both are bit-identical in-process and on local
clusters of 1, 2 and 3 worker processes and send the client at least 50 times fewer bytes than
the table."""

from __future__ import annotations

import pickle
import time

import numpy as np
import pytest
from scipy.stats import spearmanr
from test_scale import _assert_bit_identical  # bit for bit, NaN patterns included

from sss_locus.experiments.stats import scale
from sss_locus.experiments.datamodel.envelopes import OffsetModel, load_envelope
from sss_locus.experiments.survey_passes.planning import crossing_angle_curve
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.pose_space.reduce import batch_rows, reduce_pose_space
from sss_locus.experiments.pose_space.study import PoseSpaceSpec, sample_pose_space
from sss_locus.experiments.pose_space.stats import CANDIDATES, TARGETS, heatmaps, spearman_table, with_derived
from sss_locus.experiments.survey_passes.study import simulate_passes
from sss_locus.experiments.survey_passes.reduce import reduce_crossing_angle_curve

ANGLES = [0.0, 35.0, 90.0]


def _survey(n=600):
    pf = load_platform("boat")
    return reduce_crossing_angle_curve(pf, load_envelope("boat"), OffsetModel("independent"), ANGLES, n, 3)


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

    survey = _survey(300)

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
                _assert_bit_identical(_survey(300)[0], survey[0])
        finally:
            scale.close_clients()


def test_survey_curve_reduced_equals_the_curve_of_the_whole_table(monkeypatch):
    monkeypatch.delenv(scale.SCHEDULER_ENV, raising=False)
    pf, env, model = load_platform("boat"), load_envelope("boat"), OffsetModel("independent")
    curve, sent = _survey(600)
    ref = crossing_angle_curve(pf, env, model, crossing_angles_deg=ANGLES, n_per_angle=600, seed=3,
                               n_resamples=10)
    _assert_bit_identical(curve, ref.curve)
    samples, _ = simulate_passes(pf, env, model, ANGLES, 600, 3)
    assert len(pickle.dumps(samples)) >= 50 * sent


@pytest.mark.parametrize("kwargs, message", [
    (dict(crossing_angles_deg=[10.0, 10.0]), "must be distinct"),
    (dict(crossing_angles_deg=[200.0]), "crossing_angles_deg must be"),
    (dict(n_per_angle=0), "n_per_angle must be"),
    (dict(n_batches=1), "n_batches must be"),
])
def test_bad_survey_arguments_are_refused(kwargs, message):
    args = dict(crossing_angles_deg=ANGLES, n_per_angle=100, seed=1) | kwargs
    with pytest.raises(ValueError, match=message):
        reduce_crossing_angle_curve(load_platform("boat"), load_envelope("boat"), OffsetModel("independent"), **args)


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
