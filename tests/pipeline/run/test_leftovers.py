"""Hidden staging files of commits killed midway (issue 38, item 7) are cleaned by the next run
and by ``sss-locus cache --prune``; those of a live process are kept. A read-only figures folder
is refused before the run, not found at its commit."""

from __future__ import annotations

import errno
import subprocess
import sys
import uuid

import pytest

pytest.importorskip("papermill")

from test_reliability import quiet, tiny_notebook  # noqa: E402
from sss_locus import paths  # noqa: E402
from sss_locus.pipeline.run import atomic, cache, preflight, runner
from sss_locus.pipeline.cli import command as cli  # noqa: E402
from sss_locus.pipeline.run.registry import NotebookEntry  # noqa: E402
from sss_locus.pipeline.run.runner import run_notebook  # noqa: E402


@pytest.fixture
def entry(tmp_path):
    return NotebookEntry("tiny", tiny_notebook(tmp_path), "executed/tiny.ipynb", {"book": {}, "quick": {}})


def _dead_pid() -> int:
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid


def _plant(folder, pid):
    """Files named as a killed commit leaves them (atomic.temp_name with the writer's pid)."""
    folder.mkdir(parents=True, exist_ok=True)
    planted = [folder / f".fig-x.png.{tag}-{pid}-{uuid.uuid4().hex[:12]}" for tag in ("tmp", "old")]
    for path in planted:
        path.write_bytes(b"x" * 100)
    return planted


def test_the_pattern_is_atomics_temp_name(tmp_path):
    from sss_locus.pipeline.run.orphans import TEMPORARY

    for tag in ("tmp", "old"):
        assert TEMPORARY.fullmatch(atomic.temp_name(tmp_path / "fig-a.png", tag).name)
    assert not TEMPORARY.fullmatch("fig-a.png") and not TEMPORARY.fullmatch(".run-x-1-abc")


def test_prune_removes_the_files_of_dead_writers_only(build_area):
    dead = _plant(paths.figures_dir(), _dead_pid()) + _plant(paths.executed_dir(), _dead_pid())
    live = _plant(paths.figures_dir(), atomic.os.getpid())
    report = cache.prune()
    assert not any(p.exists() for p in dead) and all(p.exists() for p in live)
    assert report["removed"] >= len(dead) and report["freed"] >= 100 * len(dead)


def test_the_next_run_removes_them(build_area, entry):
    dead = _plant(paths.figures_dir(), _dead_pid())
    run_notebook(entry, "book", {"n": 4}, log=quiet)
    assert not any(p.exists() for p in dead)
    assert [p.name for p in paths.figures_dir().iterdir() if p.name.startswith(".")] == []


def test_a_read_only_figures_folder_is_refused_before_the_kernel(build_area, monkeypatch, capsys):
    figures = paths.figures_dir()
    figures.mkdir(parents=True)
    real = preflight.tempfile.mkstemp

    def read_only_figures(*args, dir=None, **kwargs):
        if dir is not None and str(dir) == str(figures):
            raise OSError(errno.EROFS, "Read-only file system")
        return real(*args, dir=dir, **kwargs)

    monkeypatch.setattr(preflight.tempfile, "mkstemp", read_only_figures)
    started = []
    monkeypatch.setattr(runner, "_execute", lambda *a: started.append(a))
    assert cli.main(["run", "concept"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "figures folder" in err and "not writable" in err and not started


@pytest.mark.parametrize("make, fragment", [
    (lambda tmp: (tmp / "afile").write_text("x") and tmp / "afile" / "sub", "is a file, not a folder"),
    (lambda tmp: "/proc/nope", "not writable"),
])
def test_a_bad_cache_folder_is_named_in_one_line(tmp_path, monkeypatch, capsys, make, fragment):
    monkeypatch.setenv("SSS_LOCUS_CACHE_DIR", str(make(tmp_path)))
    assert cli.main(["answer", "-p", "platform", "auv"]) == 2
    assert cli.main(["cache", "--prune"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and all("result cache (SSS_LOCUS_CACHE_DIR)" in e and fragment in e for e in err), err
    assert all("Errno" not in e for e in err)
