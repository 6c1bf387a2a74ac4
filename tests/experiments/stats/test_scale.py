"""Scale-out: chunked Monte Carlo studies give bit-identical results serial and on a Dask
cluster of worker processes; the default path never imports Dask; the kernel's lengths-only
mode and the vectorised NaN quantile agree with their references."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pandas as pd
import pytest

from reference_locus import EDGETECH, feature_seeded_configs
from sss_locus import Aperture, two_view_locus
from sss_locus.experiments.stats import scale
from sss_locus.experiments.datamodel.envelopes import OffsetModel, load_envelope
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.stats.rowstats import nanquantile_rows
from sss_locus.experiments.pose_space.study import BLOCK_SIZE, PoseSpaceSpec, sample_pose_space
from sss_locus.experiments.survey_passes.study import simulate_passes


def _studies(monkeypatch, setting):
    """The pose-space table (4 chunks) and a survey simulation (3 angles) under a setting."""
    if setting is None:
        monkeypatch.delenv(scale.SCHEDULER_ENV, raising=False)
    else:
        monkeypatch.setenv(scale.SCHEDULER_ENV, setting)
    spec = PoseSpaceSpec(load_platform("auv"))
    pose = sample_pose_space(spec, 3 * BLOCK_SIZE + 123, 7, chunk_size=BLOCK_SIZE)
    pf = load_platform("boat")
    survey = simulate_passes(pf, load_envelope("boat"), OffsetModel("independent"), [0.0, 35.0, 90.0], 300, 3)
    return pose, survey


def _assert_bit_identical(a: pd.DataFrame, b: pd.DataFrame):
    assert list(a.columns) == list(b.columns) and len(a) == len(b)
    for col in a.columns:
        x, y = a[col].to_numpy(), b[col].to_numpy()
        if x.dtype.kind == "f":
            assert x.tobytes() == y.tobytes(), col  # bit for bit, NaN patterns included
        else:
            assert np.array_equal(x, y), col


def test_two_worker_process_cluster_is_bit_identical_to_serial(monkeypatch):
    distributed = pytest.importorskip("distributed")
    serial_pose, (serial_survey, serial_acc) = _studies(monkeypatch, None)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster:
        with distributed.Client(cluster) as client:
            with distributed.get_task_stream(client) as stream:
                pose, (survey, acc) = _studies(monkeypatch, cluster.scheduler_address)
            workers = {task["worker"] for task in stream.data}
            pids = set(client.run(lambda: __import__("os").getpid()).values())
        scale.close_clients()
    assert len(pids) == 2 and len(workers) == 2  # two processes did the work
    assert len(stream.data) >= 4 + 3
    _assert_bit_identical(serial_pose, pose)
    _assert_bit_identical(serial_survey, survey)
    _assert_bit_identical(serial_acc, acc)


def test_chunking_does_not_change_the_table():
    spec = PoseSpaceSpec(load_platform("boat"))
    one = sample_pose_space(spec, 2 * BLOCK_SIZE + 5, 4, chunk_size=10 * BLOCK_SIZE)
    many = sample_pose_space(spec, 2 * BLOCK_SIZE + 5, 4, chunk_size=1)
    _assert_bit_identical(one, many)


def test_default_runs_in_process_without_importing_dask():
    code = ("import os, sys; os.environ.pop('SSS_LOCUS_SCHEDULER', None)\n"
            "from sss_locus.experiments.datamodel.platforms import load_platform\n"
            "from sss_locus.experiments.pose_space.study import PoseSpaceSpec, sample_pose_space\n"
            "sample_pose_space(PoseSpaceSpec(load_platform('auv')), 5000, 1, chunk_size=4096)\n"
            "print(sorted(m for m in sys.modules if m.split('.')[0] in ('dask', 'distributed')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


@pytest.mark.parametrize("value", ["local:0", "local:x", "local:-2"])
def test_bad_local_worker_count_is_rejected(value):
    with pytest.raises(ValueError, match="SSS_LOCUS_SCHEDULER=local:N"):
        scale.parse_scheduler(value)


def test_scheduler_settings_are_parsed():
    assert scale.parse_scheduler("") is None and scale.parse_scheduler(None) is None
    assert scale.parse_scheduler("local:3") == ("local", 3)
    assert scale.parse_scheduler("tcp://10.0.0.1:8786") == ("address", "tcp://10.0.0.1:8786")


def test_lengths_only_kernel_matches_the_full_result():
    ap = Aperture(*EDGETECH[:3])
    R, t, r1, r2 = (feature_seeded_configs(np.random.default_rng(5), 10_000, EDGETECH, EDGETECH)[k] for k in ("R", "t", "r1", "r2"))
    full = two_view_locus(R, t, r1, r2, ap, ap)
    lean = two_view_locus(R, t, r1, r2, ap, ap, outputs="lengths")
    for name in ("length", "n_arcs", "status", "radius", "C", "exists", "in_range"):
        assert np.array_equal(getattr(full, name), getattr(lean, name)), name
    assert lean.arc_start is None and lean.basis1 is None and lean.center is None
    assert full.length.sum() > 0


def _kernel_rows(n):
    """Feature-seeded rows plus every degenerate kind, with two random half-spaces per row."""
    rng = np.random.default_rng(11)
    c = feature_seeded_configs(rng, n, EDGETECH, EDGETECH)
    R, t, r1, r2 = (np.array(c[k]) for k in ("R", "t", "r1", "r2"))
    b = np.linalg.norm(t, axis=-1)
    t[0:50] = 0.0  # coincident origins
    r2[50:100] = r1[50:100] + b[50:100]  # tangent spheres
    r2[100:150] = r1[100:150] + 2 * b[100:150] + 1.0  # no intersection
    r1[150:200] = 1e3  # out of the 150 m range
    normals = rng.standard_normal((n, 2, 3))
    normals[200:250, 0] = 0.0  # zero normal: vacuous or empty by the offset's sign
    offsets = rng.uniform(-60.0, 60.0, (n, 2))
    return R, t, r1, r2, dict(half_space_normals=normals, half_space_offsets=offsets)


@pytest.mark.parametrize("outputs", ["all", "lengths"])
def test_one_large_call_equals_small_calls_bit_for_bit(outputs):
    """The kernel streams a batch through cache-sized chunks: a row's result must not depend on
    the batch it came in (reference: the same rows in calls of 1, 7 and 1000 rows)."""
    ap = Aperture(*EDGETECH[:3])
    R, t, r1, r2, half = _kernel_rows(9_001)  # more than two internal chunks, not a multiple
    big = two_view_locus(R, t, r1, r2, ap, ap, outputs=outputs, **half)
    names = ["length", "n_arcs", "status", "radius", "C", "exists", "in_range"]
    names += ["arc_start", "arc_end", "center", "normal", "basis1", "basis2", "u"] if outputs == "all" else []
    for size in (1, 7, 1000):
        rows = np.arange(9_001) if size == 1000 else np.arange(0, 9_001, 97)  # size 1, 7: a sample
        for start in range(0, len(rows), size):
            i = rows[start:start + size]
            part = two_view_locus(R[i], t[i], r1[i], r2[i], ap, ap, outputs=outputs,
                                  **{k: v[i] for k, v in half.items()})
            for name in names:
                np.testing.assert_array_equal(getattr(part, name), getattr(big, name)[i], err_msg=name)
    statuses = set(np.unique(big.status))
    assert len(statuses) >= 4 and (big.n_arcs > 0).sum() > 1000  # every kind is exercised


def test_lengths_only_with_half_spaces_matches_the_full_result():
    ap = Aperture(*EDGETECH[:3])
    R, t, r1, r2, half = _kernel_rows(5_000)
    full = two_view_locus(R, t, r1, r2, ap, ap, **half)
    lean = two_view_locus(R, t, r1, r2, ap, ap, outputs="lengths", **half)
    for name in ("length", "n_arcs", "status", "radius", "C", "exists", "in_range"):
        assert np.array_equal(getattr(full, name), getattr(lean, name)), name


def test_kernel_outputs_argument_is_checked():
    ap = Aperture(*EDGETECH[:3])
    with pytest.raises(ValueError, match="outputs must be 'all' or 'lengths'"):
        two_view_locus(np.eye(3), [0.0, 0.0, -1.0], 50.0, 50.0, ap, ap, outputs="arcs")


def test_one_big_kernel_call_equals_chunked_calls():
    ap = Aperture(*EDGETECH[:3])
    R, t, r1, r2 = (feature_seeded_configs(np.random.default_rng(6), 9000, EDGETECH, EDGETECH)[k] for k in ("R", "t", "r1", "r2"))
    big = two_view_locus(R, t, r1, r2, ap, ap)
    parts = [two_view_locus(R[i:i + 1000], t[i:i + 1000], r1[i:i + 1000], r2[i:i + 1000], ap, ap)
             for i in range(0, 9000, 1000)]
    for name in ("length", "arc_start", "basis2"):
        assert np.concatenate([getattr(p, name) for p in parts]).tobytes() == getattr(big, name).tobytes()


def test_vectorised_nan_quantile_equals_numpy_nanquantile():
    rng = np.random.default_rng(3)
    for shape in [(300, 64), (100, 7), (40, 1500), (20, 1), (10, 2)]:
        x = rng.standard_normal(shape) * np.exp(rng.standard_normal(shape))
        x[rng.random(shape) < 0.3] = np.nan
        x[0], x[1] = np.nan, 1.0
        for q in (0.95, 0.5, 0.05, 0.0, 1.0):
            ok = ~np.isnan(x).all(axis=1)
            ref = np.full(shape[0], np.nan)
            ref[ok] = np.nanquantile(x[ok], q, axis=1)
            assert np.array_equal(nanquantile_rows(x, q), ref, equal_nan=True), (shape, q)


def _worker_environ(dask_client, names):
    return list(dask_client.run(lambda: {k: __import__("os").environ.get(k) for k in names}).values())


def test_both_local_cluster_paths_give_workers_the_documented_memory_trim(monkeypatch):
    """``sss-locus run --workers 2`` and ``SSS_LOCUS_SCHEDULER=local:2`` start their workers
    with MALLOC_TRIM_THRESHOLD_ = 256 MiB (book/cluster.md, README), not Dask's 65536, and the
    launcher leaves this process's environment as it was (Dask's nannies write their spawn
    variables into it)."""
    distributed = pytest.importorskip("distributed")
    import argparse

    from sss_locus.pipeline.run import scaleout

    monkeypatch.delenv("MALLOC_TRIM_THRESHOLD_", raising=False)  # another test's cluster may leak it
    monkeypatch.delenv("OMP_NUM_THREADS", raising=False)
    monkeypatch.delenv(scale.SCHEDULER_ENV, raising=False)
    names = ("MALLOC_TRIM_THRESHOLD_", "OMP_NUM_THREADS")
    before = dict(__import__("os").environ)
    args = argparse.Namespace(workers=2, scheduler=None)
    with scaleout.scheduler_environment(args):
        address = scale.scheduler_setting()  # the run context's, which the kernels get
        with distributed.Client(address) as dask_client:
            via_cli = _worker_environ(dask_client, names)
    try:
        via_env = _worker_environ(scale.client("local:2"), names)
    finally:
        scale.close_clients()
    expected = {"MALLOC_TRIM_THRESHOLD_": str(256 * 2**20), "OMP_NUM_THREADS": "1"}
    assert via_cli == [expected, expected] and via_env == [expected, expected]
    assert dict(__import__("os").environ) == before


def test_a_local_cluster_does_not_warn_when_port_8787_is_taken(recwarn):
    """Dask's default HTTP port 8787 taken (by another cluster, a notebook's, a test's): the
    local cluster starts on a free port without warning "Port 8787 is already in use"."""
    pytest.importorskip("distributed")
    import socket

    taken = socket.socket()
    try:
        taken.bind(("", 8787))
        taken.listen()
    except OSError:
        pass  # taken already: the case this test is about
    try:
        cluster = scale.start_local_cluster(1)
        cluster.close()
    finally:
        taken.close()
    assert not [w for w in recwarn if "already in use" in str(w.message)]
