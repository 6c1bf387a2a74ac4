"""Nothing lost under faults (issue 27, item 1): a full disk or a failing rename during the
commit of a run leaves the previous figures, manifests and executed copy byte for byte, with a
one-line error; a side run on a full disk keeps no truncated notebook and says why it stopped.

A small filesystem is simulated by making the copy step raise ``ENOSPC`` (or by reporting little
free space); everything else is a real run of a throwaway notebook.
"""

from __future__ import annotations

import errno
import os
import shutil
from pathlib import Path

import pytest

pytest.importorskip("papermill")
pytest.importorskip("nbformat")

from test_reliability import leftovers, quiet, snapshot, tiny_notebook  # noqa: E402
from sss_locus import paths  # noqa: E402
from sss_locus.pipeline import cli, faults, outputs, preflight, runner, transaction  # noqa: E402
from sss_locus.pipeline.registry import NotebookEntry  # noqa: E402
from sss_locus.pipeline.runner import NotebookFailed, run_notebook  # noqa: E402


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
    assert len(err.strip().splitlines()) == 1 and "read-only" in err and "Traceback" not in err
