"""Progress of long work (sss_locus.pipeline.run.progress): the studies' batch callback observes
without changing a number, serial and on Dask; `run`/`book` print start and finish lines with
times and no terminal codes when not on a terminal, and bars on a terminal (a pty)."""

from __future__ import annotations

import fcntl
import io
import os
import pty
import re
import select
import struct
import subprocess
import sys
import termios
import time
from pathlib import Path

import pytest

from sss_locus.experiments.stats import scale
from sss_locus.experiments.datamodel.envelopes import OffsetModel, load_envelope
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.pose_space.study import BLOCK_SIZE, PoseSpaceSpec, sample_pose_space
from sss_locus.experiments.survey_passes.study import simulate_passes
from sss_locus.pipeline.run import cache, progress

ANSI = re.compile(r"\x1b\[")
ANGLES = [0.0, 35.0, 90.0]


def _studies(pose_progress=None, survey_progress=None):
    pose = sample_pose_space(PoseSpaceSpec(load_platform("auv")), 3 * BLOCK_SIZE + 11, 5,
                             chunk_size=BLOCK_SIZE, progress=pose_progress)
    survey = simulate_passes(load_platform("boat"), load_envelope("boat"), OffsetModel("independent"),
                             ANGLES, 200, 3, progress=survey_progress)
    return pose, survey


def _assert_same(with_cb, without):
    pose_a, (survey_a, acc_a) = with_cb
    pose_b, (survey_b, acc_b) = without
    for a, b in ((pose_a, pose_b), (survey_a, survey_b), (acc_a, acc_b)):
        assert a.equals(b)  # same values, NaN patterns and dtypes


def test_callback_is_called_once_per_batch_and_changes_no_number(monkeypatch):
    monkeypatch.delenv(scale.SCHEDULER_ENV, raising=False)
    pose_calls, survey_calls = [], []
    with_cb = _studies(lambda *a: pose_calls.append(a), lambda *a: survey_calls.append(a))
    assert pose_calls == [(1, 4), (2, 4), (3, 4), (4, 4)]  # 3 full blocks + 11 rows, one block per chunk
    assert survey_calls == [(1, 3), (2, 3), (3, 3)]  # one chunk per crossing angle
    _assert_same(with_cb, _studies())


def test_callback_follows_the_futures_on_a_dask_cluster(monkeypatch):
    pytest.importorskip("distributed")
    monkeypatch.delenv(scale.SCHEDULER_ENV, raising=False)
    serial = _studies()
    monkeypatch.setenv(scale.SCHEDULER_ENV, "local:1")
    calls = []
    try:
        on_cluster = _studies(lambda *a: calls.append(("pose", *a)), lambda *a: calls.append(("survey", *a)))
    finally:
        scale.close_clients()
    assert calls == [("pose", k, 4) for k in range(1, 5)] + [("survey", k, 3) for k in range(1, 4)]
    _assert_same(on_cluster, serial)


def test_cached_studies_report_to_the_runner_file_and_keep_their_key(tmp_path, monkeypatch, run_context):
    monkeypatch.delenv(scale.SCHEDULER_ENV, raising=False)
    monkeypatch.setenv("SSS_LOCUS_CACHE_DIR", str(tmp_path / "cache"))
    target = tmp_path / "progress.txt"
    run_context(progress_file=target)
    spec = PoseSpaceSpec(load_platform("boat"))
    first = cache.cached(sample_pose_space)(spec, 2 * BLOCK_SIZE, 1, chunk_size=BLOCK_SIZE)
    lines = [line.split("\t") for line in target.read_text().splitlines()]
    assert [(label, done, total) for _, label, done, total in lines] == [
        ("sample_pose_space", "1", "2"), ("sample_pose_space", "2", "2")]
    # an explicit callback is used, and is not part of the key: this is a cache hit (no batches)
    calls = []
    again = cache.cached(sample_pose_space)(spec, 2 * BLOCK_SIZE, 1, chunk_size=BLOCK_SIZE,
                                            progress=lambda *a: calls.append(a))
    assert calls == [] and again.equals(first)
    assert len(target.read_text().splitlines()) == 2
    run_context()
    assert progress.batch_reporter("x") is None  # outside a runner's kernel: no reporting


def _feed(path: Path, rows):
    with open(path, "a") as fh:
        fh.writelines(f"{call}\t{label}\t{done}\t{total}\n" for call, label, done, total in rows)


def test_relay_prints_plain_lines_for_long_studies_when_not_on_a_terminal(tmp_path):
    path, lines, stream = tmp_path / "progress.txt", [], io.StringIO()
    rows = [("a", "study", k, 8) for k in range(1, 9)] + [("b", "single", 1, 1)]
    with progress.relay_batches(path, "nb", lines.append, stream=stream, every_s=0.0):
        _feed(path, rows)
    assert lines == [f"  nb: study batch {k}/8" for k in range(1, 9)]  # one-batch studies: nothing
    with progress.relay_batches(tmp_path / "again.txt", "nb", lines.append, stream=stream):
        _feed(tmp_path / "again.txt", rows)  # over before PLAIN_EVERY_S: not worth a line
    assert len(lines) == 8 and stream.getvalue() == ""


def _openpty():
    """A pty 100 columns wide (a fresh pty has 0 columns, and tqdm draws bars to the width)."""
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 40, 100, 0, 0))
    return master, slave


def _pty_stream():
    master, slave = _openpty()
    return master, os.fdopen(slave, "w", buffering=1)


def _drain(master: int) -> str:
    out = b""
    while select.select([master], [], [], 0.2)[0]:
        try:
            chunk = os.read(master, 65536)
        except OSError:
            break
        if not chunk:
            break
        out += chunk
    return out.decode("utf-8", "replace")


def test_bars_on_a_terminal(tmp_path):
    master, stream = _pty_stream()
    try:
        path = tmp_path / "progress.txt"
        bar = progress.NotebookBar(2, stream=stream)
        with progress.relay_batches(path, "nb", stream=stream):
            _feed(path, [("a", "study", k, 4) for k in range(1, 4)])
            time.sleep(progress.BAR_DELAY_S + 2 * progress.POLL_S)  # a bar appears after BAR_DELAY_S
            _feed(path, [("a", "study", 4, 4)])
        bar.finished("nb", True)
        bar.close()
        shown = _drain(master)
    finally:
        stream.close()
        os.close(master)
    assert re.search(r"notebooks: +50%\|", shown) and "1/2" in shown  # tqdm's bar over notebooks
    assert re.search(r"nb: study: +\d+%\|", shown)  # and over the study's batches


# -- real runs: a tiny notebook whose study has 3 batches ---------------------------------------------

STUDY = """\
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.pose_space.study import BLOCK_SIZE, PoseSpaceSpec, sample_pose_space
from sss_locus.pipeline.run.cache import cached
table = cached(sample_pose_space)(PoseSpaceSpec(load_platform("boat")), 3 * BLOCK_SIZE, seed, chunk_size=BLOCK_SIZE)
print(len(table))
if fail:
    raise RuntimeError("asked to fail")
"""


def _entries(folder: Path, names, failing=()):
    pytest.importorskip("papermill")
    from notebook_support import write_notebook
    from sss_locus.pipeline.run.registry import NotebookEntry

    source = write_notebook(folder / "study.ipynb", "seed = 1  # [0, 100]\nfail = False\n", STUDY)
    return [NotebookEntry(n, source, f"executed/{n}.ipynb", {"quick": {"seed": i, "fail": n in failing}})
            for i, n in enumerate(names)]


def test_book_run_prints_start_and_finish_lines_without_terminal_codes(build_area, tmp_path, capsys, monkeypatch):
    from sss_locus.pipeline.run.runner import run_many

    monkeypatch.setattr(progress, "PLAIN_EVERY_S", 0.0)  # a line per batch, however fast the study

    with pytest.raises(RuntimeError, match=r"1 notebook\(s\) failed:\nstudy_b: "):
        run_many(_entries(tmp_path, ["study_a", "study_b"], failing={"study_b"}), "quick")
    out, err = capsys.readouterr()
    lines = out.splitlines()
    for name, end in (("study_a", r"ran study_a \[quick\] in \d+\.\d s -> "),
                      ("study_b", r"failed study_b after \d+\.\d s \(its error is listed at the end\)")):
        start = [i for i, line in enumerate(lines) if re.fullmatch(
            rf"start {name} \[quick\] at \d\d:\d\d:\d\d UTC", line)]
        ran = [i for i, line in enumerate(lines) if re.match(end, line)]
        batches = [i for i, line in enumerate(lines) if line.startswith(f"  {name}: sample_pose_space batch ")]
        assert len(start) == 1 and len(ran) == 1 and start[0] < batches[0] <= batches[-1] < ran[0]
        assert lines[batches[-1]].endswith("batch 3/3")
    assert [line.split(",")[0] for line in lines if "notebooks done" in line] == [
        "  1/2 notebooks done", "  2/2 notebooks done"]
    assert not ANSI.search(out + err) and "\r" not in out + err


def test_run_on_a_terminal_shows_bars(build_area, tmp_path):
    """A book of one notebook run by a child process whose stdout and stderr are a pty."""
    code = ("import sys; sys.path[:0] = ['tests/pipeline/run', 'tests']; from test_progress import _entries; from pathlib import Path; "
            "from sss_locus.pipeline.run import progress; progress.BAR_DELAY_S = 0; "
            "from sss_locus.pipeline.run.runner import run_many; "
            "run_many(_entries(Path(sys.argv[1]), ['study_t']), 'quick')")
    master, slave = _openpty()
    child = subprocess.Popen([sys.executable, "-c", code, str(tmp_path)], stdout=slave, stderr=slave,
                             stdin=subprocess.DEVNULL, cwd=Path(__file__).parents[3])
    os.close(slave)
    shown = b""
    while True:
        try:
            chunk = os.read(master, 65536)
        except OSError:  # the child closed the terminal
            break
        if not chunk:
            break
        shown += chunk
    os.close(master)
    assert child.wait() == 0, shown.decode(errors="replace")
    text = shown.decode("utf-8", "replace")
    assert re.search(r"notebooks: +100%\|", text) and re.search(r"start study_t \[quick\]", text)
    assert "study_t: sample_pose_space" in text  # the batch bar (it is removed when the study ends)


def test_lines_written_from_many_threads_at_once_stay_whole(monkeypatch):
    """``book --jobs`` logs each notebook's start from its worker thread while the main thread
    logs results: every line must come out whole. The stream here yields to other threads inside
    each write, as a busy pipe does, so text and newline written apart would be split."""
    import threading

    from sss_locus.pipeline.run.progress import NotebookBar

    class YieldingStream(io.StringIO):
        def write(self, text):
            time.sleep(0.0005)
            return super().write(text)

    out = YieldingStream()
    monkeypatch.setattr(sys, "stdout", out)
    bar = NotebookBar(total=0, stream=io.StringIO())
    barrier = threading.Barrier(4)

    def writer(k: int) -> None:
        barrier.wait()
        for i in range(50):
            bar.write(f"line {k} {i} end")

    threads = [threading.Thread(target=writer, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    lines = out.getvalue().splitlines()
    assert len(lines) == 4 * 50
    assert all(re.fullmatch(r"line \d \d+ end", line) for line in lines)
