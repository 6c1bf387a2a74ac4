"""Nothing lost under faults (issue 27, item 1): a full disk or a failing rename during the
commit of a run leaves the previous figures, manifests and executed copy byte for byte, with a
one-line error; a side run on a full disk keeps no truncated notebook and says why it stopped.

A small filesystem is simulated by making the copy step raise ``ENOSPC`` (or by reporting little
free space); everything else is a real run of a throwaway notebook.
"""

from __future__ import annotations

import argparse
import errno
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytest.importorskip("papermill")
pytest.importorskip("nbformat")

from test_reliability import DRIVER, _pid_gone, leftovers, quiet, snapshot, tiny_notebook  # noqa: E402
from sss_locus import paths  # noqa: E402
from sss_locus.pipeline.run import cache, faults, orphans, outputs, preflight, runner, transaction
from sss_locus.pipeline.cli import command as cli  # noqa: E402
from sss_locus.pipeline.run.registry import NotebookEntry  # noqa: E402
from sss_locus.pipeline.run.runner import NotebookFailed, run_notebook  # noqa: E402


@pytest.fixture
def entry(tmp_path):
    return NotebookEntry("tiny", tiny_notebook(tmp_path), "executed/tiny.ipynb", {"book": {}, "quick": {}})


def _fail_on_call(monkeypatch, module, name, number, error, only=lambda *a: True):
    """Make ``module.name`` raise ``error`` on its ``number``-th call that ``only`` accepts."""
    real = getattr(module, name)
    calls = []

    def wrapped(*args, **kwargs):
        if only(*args):
            calls.append(args)
            if len(calls) == number:
                raise error
        return real(*args, **kwargs)

    monkeypatch.setattr(module, name, wrapped)
    return calls


def _into(folder: Path):
    return lambda _source, target, *rest: Path(target).parent == folder


@pytest.mark.parametrize("number", [1, 3])
def test_full_disk_during_the_commit_keeps_the_last_good_figure_set(build_area, entry, monkeypatch, number):
    run_notebook(entry, "book", {"n": 5}, log=quiet)
    good = snapshot(build_area)
    figures = build_area / "source" / "_extra" / "figures"
    calls = _fail_on_call(monkeypatch, shutil, "copyfile", number,
                          OSError(errno.ENOSPC, "No space left on device"), only=_into(figures))
    with pytest.raises(transaction.CommitFailed) as info:
        run_notebook(entry, "book", {"n": 7}, log=quiet)
    assert len(calls) == number
    message = str(info.value)
    assert "\n" not in message and "no space left" in message and "unchanged" in message
    assert snapshot(build_area) == good  # the CSVs, images and manifest of the last good run
    assert leftovers(build_area) == [] and not [p for p in figures.iterdir() if p.name.startswith(".")]
    assert outputs.problems([entry]) == []  # `book --no-run` still accepts it


def test_a_failing_rename_in_the_last_step_puts_every_old_file_back(build_area, entry, monkeypatch):
    run_notebook(entry, "book", {"n": 5}, log=quiet)
    good = snapshot(build_area)
    figures = build_area / "source" / "_extra" / "figures"
    _fail_on_call(monkeypatch, os, "replace", 3, OSError(errno.EIO, "Input/output error"),
                  only=lambda source, target: Path(target).parent == figures)
    with pytest.raises(transaction.CommitFailed, match="Input/output error"):
        run_notebook(entry, "book", {"n": 8}, log=quiet)
    assert snapshot(build_area) == good
    assert outputs.problems([entry]) == []


def test_too_little_space_is_refused_before_anything_is_staged(build_area, entry, monkeypatch):
    run_notebook(entry, "book", {"n": 5}, log=quiet)
    good = snapshot(build_area)
    monkeypatch.setattr(transaction, "free_bytes", lambda folder: 2000)
    with pytest.raises(transaction.CommitFailed, match=r"MB free, it needs .* MB; the previous results are unchanged"):
        run_notebook(entry, "book", {"n": 6}, log=quiet)
    assert snapshot(build_area) == good


def test_the_command_reports_a_full_disk_in_one_line(build_area, entry, monkeypatch, capsys):
    run_notebook(entry, "book", {"n": 5}, log=quiet)
    good = snapshot(build_area)
    monkeypatch.setattr(cli, "get_entry", lambda name: entry)
    figures = build_area / "source" / "_extra" / "figures"
    _fail_on_call(monkeypatch, shutil, "copyfile", 2, OSError(errno.ENOSPC, "No space left on device"),
                  only=_into(figures))
    assert cli.main(["run", "tiny", "-p", "n", "9"]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "no space left" in err and "Traceback" not in err
    assert snapshot(build_area) == good


def test_side_run_on_a_full_disk_keeps_no_truncated_notebook(build_area, entry, tmp_path, monkeypatch):
    """The papermill child stops with ENOSPC: its output notebook is cut off mid-JSON and its log
    mid-line. The run says "no space left" and deletes the cut notebook instead of keeping it."""
    side = tmp_path / "side" / "mine.ipynb"

    def full_disk(args, log_file):
        staged = Path(runner.json.loads(args.read_text())["output_path"])
        staged.write_text('{"cells": [{"cell_type": "code", "sou', encoding="utf-8")
        log_file.write_text("Traceback (most recent call last):\n  File \"/x/papermill/iorw.py\", li",
                            encoding="utf-8")
        return 1

    monkeypatch.setattr(runner, "_papermill_child", full_disk)
    monkeypatch.setattr(faults, "free_bytes", lambda folder: 0)
    with pytest.raises(NotebookFailed) as info:
        run_notebook(entry, "book", output=side, log=quiet)
    message = str(info.value)
    assert "no space left" in message and "\n" not in message and "li" != message[-2:]
    assert info.value.kept is None
    assert not side.with_name("mine.failed.ipynb").exists() and not side.exists()
    assert not [p for p in side.parent.iterdir() if p.name.startswith(".run-")]


def test_a_stopped_papermill_is_reported_by_its_error_line_not_a_cut_line(tmp_path):
    log = "Traceback (most recent call last):\n  File \"x.py\", line 3\nRuntimeError: kernel gone\n  done\n"
    assert faults.papermill_failure(log, tmp_path) == "RuntimeError: kernel gone"


# -- items 2, 3 and 7: output paths checked before the run --------------------------------------

def test_second_side_run_into_one_folder_is_refused_before_it_runs(build_area, entry, tmp_path):
    first = tmp_path / "side" / "a.ipynb"
    run_notebook(entry, "book", {"n": 4}, output=first, log=quiet)
    figures = first.parent / "figures"
    before = {p.name: p.read_bytes() for p in figures.iterdir()}
    with pytest.raises(preflight.OutputError) as info:
        run_notebook(entry, "book", {"n": 6}, output=first.with_name("b.ipynb"), log=quiet)
    assert "a.ipynb" in str(info.value) and "\n" not in str(info.value)
    assert {p.name: p.read_bytes() for p in figures.iterdir()} == before  # a's figures untouched
    assert not first.with_name("b.ipynb").exists()


@pytest.mark.parametrize("where, fragment", [
    (lambda tmp: tmp, "is a directory"),
    (lambda tmp: paths.NOTEBOOKS_DIR / "concept.ipynb", "the notebooks' sources"),
    (lambda tmp: paths.NOTEBOOKS_DIR / "new.ipynb", "the notebooks' sources"),
    (lambda tmp: tmp / "x.txt", "ending in .ipynb"),
])
def test_bad_side_outputs_are_refused_before_a_kernel_starts(build_area, tmp_path, monkeypatch, capsys,
                                                             where, fragment):
    source = paths.NOTEBOOKS_DIR / "concept.ipynb"
    committed = source.read_bytes()
    started = []
    monkeypatch.setattr(runner, "_execute", lambda *a: started.append(a))
    assert cli.main(["run", "concept", "--output", str(where(tmp_path))]) == 2
    err = capsys.readouterr().err
    assert fragment in err and len(err.strip().splitlines()) == 1 and not started
    assert source.read_bytes() == committed and not (paths.NOTEBOOKS_DIR / "figures").exists()


def test_read_only_folders_are_refused_in_one_line(build_area, tmp_path, monkeypatch, capsys):
    def read_only(*args, **kwargs):
        raise OSError(errno.EROFS, "Read-only file system")

    monkeypatch.setattr(preflight.tempfile, "mkstemp", read_only)
    started = []
    monkeypatch.setattr(runner, "_execute", lambda *a: started.append(a))
    assert cli.main(["run", "concept", "--output", str(tmp_path / "side" / "c.ipynb")]) == 2
    assert cli.main(["run", "concept"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and all("not writable" in line and "Read-only" in line for line in err)
    assert not started


def test_book_no_run_on_a_read_only_build_area_says_so_in_one_line(build_area, monkeypatch, capsys):
    def read_only(*args, **kwargs):
        raise OSError(errno.EROFS, "Read-only file system", str(build_area / ".lock"))

    monkeypatch.setattr(os, "open", read_only)
    assert cli.main(["book", "--no-run"]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "read-only filesystem" in err and "Traceback" not in err


# -- item 8: resources -------------------------------------------------------------------------

def _start_driver(entry, marker, env, overrides):
    return subprocess.Popen(
        [sys.executable, "-c", DRIVER, str(entry.source), json.dumps({"marker": str(marker), **overrides})],
        env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))


def _wait_for(marker, child, timeout=240):
    end = time.monotonic() + timeout
    while not marker.exists() and child.poll() is None and time.monotonic() < end:
        time.sleep(0.2)
    assert marker.exists(), child.communicate(timeout=10)
    time.sleep(0.5)


def _papermill_children(pid: int) -> list[int]:
    """Pids of papermill processes started by ``pid`` (from /proc)."""
    found = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
            cmdline = (stat.parent / "cmdline").read_bytes()
        except OSError:
            continue
        if int(fields[1]) == pid and b"papermill" in cmdline:
            found.append(int(stat.parent.name))
    return found


def test_a_run_killed_with_sigkill_leaves_nothing_running_and_the_next_run_cleans_up(build_area, entry, tmp_path):
    marker = tmp_path / "kernel.pid"
    scratch = tmp_path / "scratch"
    scratch.mkdir()
    env = {**os.environ, "TMPDIR": str(scratch)}
    child = _start_driver(entry, marker, env, {"sleep_s": 120, "n": 9})
    try:
        _wait_for(marker, child)
        papermill = _papermill_children(child.pid)
        assert papermill, "the run's papermill child was not found"
        child.kill()  # SIGKILL: no finally block runs
        child.communicate(timeout=60)
    finally:
        if child.poll() is None:
            child.kill()
    assert _pid_gone(int(marker.read_text())), "the kernel outlived the SIGKILLed run"
    assert all(_pid_gone(pid) for pid in papermill), "papermill outlived the SIGKILLed run"
    assert [p for p in (build_area / "tmp").iterdir() if p.name.startswith(".run-")]  # its staging folder
    assert not list(scratch.glob("*.json"))  # the connection file was in the staging folder
    run_notebook(entry, "book", {"n": 3}, log=quiet)  # the next run removes the dead run's folder
    assert leftovers(build_area) == []


def test_cache_prune_removes_the_staging_folder_of_a_killed_run(build_area):
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    stale = build_area / "tmp" / f".run-tiny-{dead.pid}-0123456789ab"
    (stale / "runtime").mkdir(parents=True)
    (stale / "tiny.ipynb").write_text("{}")
    alive = build_area / "tmp" / f".run-tiny-{os.getpid()}-0123456789ab"
    alive.mkdir()
    report = cache.prune()
    assert not stale.exists() and alive.exists() and report["removed"] >= 1


def test_a_connection_file_never_lands_in_the_system_temporary_folder(build_area, entry, tmp_path):
    scratch = tmp_path / "scratch"
    scratch.mkdir()
    marker = tmp_path / "kernel.pid"
    child = _start_driver(entry, marker, {**os.environ, "TMPDIR": str(scratch)}, {"sleep_s": 120})
    try:
        _wait_for(marker, child)
        child.send_signal(signal.SIGINT)  # Ctrl-C
        child.communicate(timeout=60)
    finally:
        if child.poll() is None:
            child.kill()
    assert not list(scratch.glob("*.json")) and leftovers(build_area) == []


def test_workers_are_capped_at_the_machines_cores(monkeypatch, capsys):
    from sss_locus.pipeline.run import scaleout

    started = []

    class FakeCluster:  # records the worker count instead of starting processes
        def __init__(self, n_workers, **kwargs):
            started.append(n_workers)
            self.scheduler_address = "tcp://127.0.0.1:1"

        def close(self):
            pass

    monkeypatch.setattr("dask.distributed.LocalCluster", FakeCluster)
    cores = len(os.sched_getaffinity(0))
    with scaleout.scheduler_environment(argparse.Namespace(workers=100_000, scheduler=None)):
        pass
    assert started == [cores]
    err = capsys.readouterr().err
    assert f"--workers 100000 capped at {cores}" in err and len(err.strip().splitlines()) == 1


def test_book_jobs_children_die_with_a_killed_book(build_area, entry, monkeypatch):
    """``book --jobs N`` starts one ``sss-locus run`` child per notebook: each is asked to get
    SIGTERM when the book process dies, even by SIGKILL (the same ``preexec_fn`` whose effect the
    SIGKILL test above checks end to end for a run's papermill child)."""
    started = []

    class FakeChild:  # records how the child would be started instead of starting it
        returncode = 0

        def __init__(self, cmd, **kwargs):
            started.append((cmd, kwargs))

        def communicate(self):
            return "", ""

        def poll(self):
            return 0

    monkeypatch.setattr(runner.subprocess, "Popen", FakeChild)
    other = NotebookEntry("tiny2", entry.source, "executed/tiny2.ipynb", {"book": {}, "quick": {}})
    runner.run_many([entry, other], "quick", jobs=2, log=quiet)
    assert sorted(cmd[cmd.index("run") + 1] for cmd, _ in started) == ["tiny", "tiny2"]
    assert all(kwargs.get("preexec_fn") is orphans.die_with_parent for _, kwargs in started)
