"""What a run guarantees, reproduced with real processes and real signals (issue 11).

Each test drives the pipeline the way a user or a parallel build does: a run that fails or is
killed (exception, SIGINT, SIGTERM) must leave the last good results byte for byte and nothing
behind; side runs never touch the build area; ``book --no-run`` names every unusable executed
copy in one message; concurrent runs and cache users neither crash nor corrupt each other; bad
cache entries of any shape are recomputed; bad values and registries are refused up front; a
kernel that dies before its first cell (a port race of parallel starts) is started again.
"""

from __future__ import annotations

import hashlib
import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

pytest.importorskip("papermill")
nbformat = pytest.importorskip("nbformat")

from notebook_support import write_notebook  # noqa: E402
from sss_locus.pipeline.run import cache, outputs  # noqa: E402
from sss_locus.pipeline.run.registry import NotebookEntry, load_registry  # noqa: E402
from sss_locus.pipeline.run.runner import NotebookFailed, run_notebook  # noqa: E402

PARAMETERS = ("n: int = 3   # points [1, 1000]\nfail = False\nsleep_s = 0.0   # seconds to wait [0, 600]\n"
              "marker = ''\ngrandchild_marker = ''\n")
BODY = """\
import os, subprocess, sys, time
import matplotlib.pyplot as plt
import pandas as pd
from sss_locus.pipeline.publish.publish import publish
if grandchild_marker:  # a process of the kernel's own, as a Dask worker would be
    worker = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(600)"])
    open(grandchild_marker, "w").write(str(worker.pid))
if marker:
    open(marker, "w").write(str(os.getpid()))
time.sleep(sleep_s)
if fail:
    raise ValueError(f"n = {n} is not what this cell wants")
frame = pd.DataFrame({"i": range(n), "y": [2.0 * i for i in range(n)]})
fig, ax = plt.subplots()
ax.plot(frame["i"], frame["y"])
publish(fig, "fig-tiny-reliable", frame, caption=f"A line of {n} points.")
"""
DRIVER = """\
import json, sys
from pathlib import Path
from sss_locus.pipeline.run.registry import NotebookEntry
from sss_locus.pipeline.run.runner import run_notebook
source, overrides = sys.argv[1], json.loads(sys.argv[2])
entry = NotebookEntry("tiny", Path(source), "executed/tiny.ipynb", {"book": {}, "quick": {}})
run_notebook(entry, "book", overrides, log=lambda *_: None)
"""


def tiny_notebook(folder: Path, label: str = "fig-tiny-reliable") -> Path:
    return write_notebook(folder / "tiny.ipynb", PARAMETERS, BODY.replace("fig-tiny-reliable", label))


@pytest.fixture
def area(build_area):
    return build_area


@pytest.fixture
def entry(tmp_path):
    return NotebookEntry("tiny", tiny_notebook(tmp_path), "executed/tiny.ipynb", {"book": {}, "quick": {}})


def snapshot(build: Path) -> dict[str, str]:
    """SHA-256 of every result file: the executed copies and the figures."""
    files = [p for sub in ("source/executed", "source/_extra/figures") for p in (build / sub).rglob("*")
             if p.is_file()]
    return {p.relative_to(build).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest() for p in files}


def leftovers(build: Path) -> list[str]:
    """Temporary files, staging folders and kernel connection files left in the build area."""
    found = [p for p in build.rglob("*") if ".tmp-" in p.name or p.name.startswith(".run-")
             or (p.name.startswith("kernel-") and p.suffix == ".json")]
    return sorted(p.relative_to(build).as_posix() for p in found)


def quiet(*_: object) -> None:
    pass


# -- 1. atomic runs ------------------------------------------------------------------------------

def test_failed_rerun_keeps_the_last_good_results(area, entry):
    run_notebook(entry, "book", {"n": 5}, log=quiet)
    good = snapshot(area)
    assert any(name.endswith("fig-tiny-reliable.png") for name in good)
    with pytest.raises(NotebookFailed) as info:
        run_notebook(entry, "book", {"n": 7, "fail": True}, log=quiet)
    assert snapshot(area) == good  # executed copy and figures untouched, byte for byte
    message = str(info.value)
    assert "\n" not in message and "ValueError: n = 7 is not what this cell wants" in message
    assert "raise ValueError" in message  # the failing line of the cell
    assert (area / "failed" / "tiny.ipynb").is_file() and "ValueError" in info.value.traceback
    assert leftovers(area) == []
    assert outputs.problems([entry]) == []  # what is there is still a consistent, good result


def _pid_gone(pid: int, timeout: float = 20.0) -> bool:
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return True
        time.sleep(0.2)
    return False


def _stopped(pid: int) -> bool:
    """The process ``pid`` has ended (a zombie waiting for its new parent to reap it counts)."""
    psutil = pytest.importorskip("psutil")
    try:
        return psutil.Process(pid).status() == psutil.STATUS_ZOMBIE
    except psutil.NoSuchProcess:
        return True


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT])
def test_interrupted_run_leaves_nothing_and_keeps_the_last_good_results(area, entry, tmp_path, signum):
    run_notebook(entry, "book", {"n": 4}, log=quiet)
    good = snapshot(area)
    marker, worker = tmp_path / "kernel.pid", tmp_path / "worker.pid"
    # Ctrl-C as a terminal delivers it: a command started in the background of a non-interactive
    # shell (`make test &`, nohup) inherits SIGINT *ignored* and Python then keeps ignoring it,
    # which is what the user asked for there; give the driver the default disposition back
    child = subprocess.Popen(
        [sys.executable, "-c", DRIVER, str(entry.source), json.dumps({"sleep_s": 120, "marker": str(marker), "n": 9,
                                                  "grandchild_marker": str(worker)})],
        env=os.environ.copy(), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        end = time.monotonic() + 240
        while not marker.exists() and child.poll() is None and time.monotonic() < end:
            time.sleep(0.2)
        assert marker.exists(), child.communicate(timeout=10)
        time.sleep(0.5)
        child.send_signal(signum)
        _, err = child.communicate(timeout=60)
        # gone when the run has returned, not a moment later (the kernel's own poll of its parent
        # took up to a second, and the kernel's children were never stopped)
        kernel_stopped, worker_stopped = _stopped(int(marker.read_text())), _stopped(int(worker.read_text()))
    finally:
        if child.poll() is None:
            child.kill()
        if worker.exists() and not _stopped(int(worker.read_text())):  # the old code's orphan
            os.kill(int(worker.read_text()), signal.SIGKILL)
    assert child.returncode != 0
    assert "Traceback" in err  # the driver has no CLI around it; the exception reached the top
    assert kernel_stopped, "the kernel outlived the interrupted run"
    assert worker_stopped, "a process the kernel started outlived the interrupted run"
    assert snapshot(area) == good
    assert leftovers(area) == []
    assert not (area / "failed" / "tiny.ipynb").exists()  # nothing that looks like a result


# -- 2. side runs --------------------------------------------------------------------------------

def test_a_rerun_that_no_longer_draws_a_figure_says_it_removed_it(area, tmp_path):
    # a chapter run for platform A, then for B in the same build area, silently removed A's
    # figures (README: "never touches another's figures"); the command now names them
    first = NotebookEntry("tiny", tiny_notebook(tmp_path, "fig-tiny-rov9"), "executed/tiny.ipynb",
                          {"book": {}, "quick": {}})
    lines = []
    run_notebook(first, "book", {"n": 4}, log=lines.append)
    assert not any("removed" in line for line in lines)
    figures = area / "source" / "_extra" / "figures"
    assert (figures / "fig-tiny-rov9.png").is_file()
    second = NotebookEntry("tiny", tiny_notebook(tmp_path, "fig-tiny-boat"), "executed/tiny.ipynb",
                           {"book": {}, "quick": {}})  # the same chapter, now drawing another label
    lines = []
    run_notebook(second, "book", {"n": 4}, log=lines.append)
    removed = [line for line in lines if "removed" in line]
    assert not (figures / "fig-tiny-rov9.png").exists() and (figures / "fig-tiny-boat.png").is_file()
    assert len(removed) == 1 and removed[0].rstrip().endswith(": fig-tiny-rov9"), lines
    lines = []
    run_notebook(second, "book", {"n": 5}, log=lines.append)  # same labels again: nothing removed
    assert not any("removed" in line for line in lines)


def test_side_run_never_writes_into_the_build_area(area, entry, tmp_path):
    run_notebook(entry, "book", log=quiet)
    good = snapshot(area)
    side = tmp_path / "side" / "mine.ipynb"
    run_notebook(entry, "book", {"n": 11}, output=side, log=quiet)
    assert snapshot(area) == good
    manifest = json.loads((side.parent / "figures" / "fig-tiny-reliable.json").read_text())
    assert manifest["parameters"]["n"] == 11 and side.is_file()
    assert outputs.problems([entry]) == []
    with pytest.raises(ValueError, match="inside the build area"):
        run_notebook(entry, "book", output=area / "x.ipynb", log=quiet)


# -- 3. book --no-run ----------------------------------------------------------------------------

def test_book_no_run_names_every_unusable_copy_in_one_message(tmp_path):
    env = {**os.environ, "SSS_LOCUS_BUILD_DIR": str(tmp_path / "empty-build")}
    result = subprocess.run([sys.executable, "-m", "sss_locus.pipeline.cli.command", "book", "--no-run"],
                            env=env, capture_output=True, text=True, timeout=300, stdin=subprocess.DEVNULL)
    assert result.returncode == 2
    assert "jupyter-book" not in result.stdout  # refused before building
    message = result.stderr
    for name in load_registry():
        assert f"{name} (" in message and "missing" in message
    assert message.count("sss-locus book: error") == 1


def test_problems_names_failed_stale_and_mixed_copies(area, tmp_path):
    one = NotebookEntry("one", tiny_notebook(tmp_path), "executed/one.ipynb", {"book": {}, "quick": {"n": 2}})
    (tmp_path / "b").mkdir()
    two = NotebookEntry("two", tiny_notebook(tmp_path / "b", "fig-tiny-two"), "executed/two.ipynb", {"book": {}, "quick": {"n": 2}})
    (tmp_path / "c").mkdir()
    three = NotebookEntry("three", tiny_notebook(tmp_path / "c", "fig-tiny-three"), "executed/three.ipynb",
                          {"book": {}, "quick": {"n": 2}})
    run_notebook(one, "book", log=quiet)
    run_notebook(two, "book", log=quiet)
    run_notebook(three, "book", log=quiet)
    assert outputs.problems([one, two, three]) == []
    # two: another profile; three: its notebook changed; one: its copy says the run failed
    run_notebook(two, "quick", log=quiet)
    three.source.write_text(three.source.read_text().replace("A line of", "A straight line of"))
    nb = json.loads(one.executed_path().read_text())
    nb["metadata"]["papermill"]["exception"] = True
    one.executed_path().write_text(json.dumps(nb))
    found = "\n".join(outputs.problems([one, two, three]))
    assert "one (" in found and "failed" in found
    assert "two: computed with profile 'quick'" in found
    assert "three (" in found and "stale" in found


def test_a_copy_whose_table_is_missing_is_refused(area, tmp_path):
    """A run records its tables with its figures: a table deleted after the run makes the copy
    unusable, like a missing figure (the book would link a table that is not there)."""
    body = BODY + 'from sss_locus.pipeline.publish.publish import publish_table\npublish_table(frame, "tab-tiny-reliable", caption="The points.")\n'
    entry = NotebookEntry("tiny", write_notebook(tmp_path / "tiny.ipynb", PARAMETERS, body), "executed/tiny.ipynb",
                          {"book": {}, "quick": {}})
    run_notebook(entry, "book", log=quiet)
    assert outputs.problems([entry]) == []
    (area / "source" / "_extra" / "figures" / "tab-tiny-reliable.csv").unlink()
    assert "tab-tiny-reliable missing or modified" in "\n".join(outputs.problems([entry]))


# -- 4. concurrency ------------------------------------------------------------------------------

def test_two_runs_of_one_notebook_at_once(area, entry):
    procs = [subprocess.Popen([sys.executable, "-c", DRIVER, str(entry.source), json.dumps({"n": n})],
                              env=os.environ.copy(), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
             for n in (3, 6)]
    results = [(p.wait(timeout=400), p.stderr.read()) for p in procs]
    assert [code for code, _ in results] == [0, 0], results
    assert outputs.problems([entry]) == []  # one run's copy with that same run's figures
    assert leftovers(area) == []


CACHE_USER = """\
import sys, time
import pandas as pd
from pathlib import Path
from sss_locus.pipeline.run.cache import cached_result
def slow():
    time.sleep(1.0)
    return pd.DataFrame({"x": range(1000)})
for _ in range(3):
    frame = cached_result({"test": "concurrent", "round": sys.argv[2]}, slow, cache_dir=Path(sys.argv[1]))
    assert list(frame["x"]) == list(range(1000))
"""


def test_cache_users_at_once_neither_crash_nor_corrupt(tmp_path):
    procs = [subprocess.Popen([sys.executable, "-c", CACHE_USER, str(tmp_path), "1"], stderr=subprocess.PIPE,
                              text=True) for _ in range(4)]
    errors = [(p.wait(timeout=300), p.stderr.read()) for p in procs]
    assert all(code == 0 for code, _ in errors), errors
    assert cache.usage(tmp_path) | {"bytes": 0} == {"entries": 1, "bytes": 0, "reachable": 1,
                                                     "removed": 0, "freed": 0}
    assert [p for p in tmp_path.rglob(".*")] == []


EXPORTER = """\
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import pandas as pd
from pathlib import Path
from sss_locus.pipeline.publish.export import export_figure
fig, ax = plt.subplots()
ax.plot([0, 1], [0, int(sys.argv[2])])
for _ in range(6):
    export_figure(fig, "fig-shared", pd.DataFrame({"a": [1]}), caption="C.", parameters={}, out_dir=Path(sys.argv[1]))
"""


def test_two_writers_of_one_label_never_share_a_temporary_file(tmp_path):
    procs = [subprocess.Popen([sys.executable, "-c", EXPORTER, str(tmp_path), str(k)], stderr=subprocess.PIPE,
                              text=True) for k in (1, 2)]
    errors = [(p.wait(timeout=300), p.stderr.read()) for p in procs]
    assert all(code == 0 for code, _ in errors), errors
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]


# -- 5. cache entries of any shape ---------------------------------------------------------------

def _frame():
    import pandas as pd

    return pd.DataFrame({"v": [1.0, 2.0]})


@pytest.mark.parametrize("damage", ["null", "list", "number", "string", "files-null", "entry-is-file",
                                    "shard-is-file", "parquet-gone", "manifest-is-dir"])
def test_malformed_cache_entry_is_recomputed(tmp_path, damage):
    calls = []

    def compute():
        calls.append(1)
        return _frame()

    cache.cached_result({"t": damage}, compute, cache_dir=tmp_path)
    folder = cache.entry_dir(cache.cache_key({"t": damage}), tmp_path)
    manifest = folder / cache.MANIFEST_NAME
    if damage in ("null", "list", "number", "string", "files-null"):
        manifest.write_text({"null": "null", "list": "[1, 2]", "number": "3", "string": '"x"',
                             "files-null": '{"files": null}'}[damage])
    elif damage == "entry-is-file":
        import shutil

        shutil.rmtree(folder)
        folder.write_text("not a folder")
    elif damage == "shard-is-file":
        import shutil

        shutil.rmtree(folder.parent)
        folder.parent.write_text("not a folder")
    elif damage == "parquet-gone":
        (folder / "data-0.parquet").unlink()
    elif damage == "manifest-is-dir":
        manifest.unlink()
        manifest.mkdir()
    again = cache.cached_result({"t": damage}, compute, cache_dir=tmp_path)
    assert len(calls) == 2 and list(again["v"]) == [1.0, 2.0]
    cache.cached_result({"t": damage}, compute, cache_dir=tmp_path)
    assert len(calls) == 2  # the recomputed entry is used


def test_cache_command_shows_size_and_prunes_unreachable_entries(tmp_path):
    import shutil

    cache.cached_result({"t": "kept"}, _frame, cache_dir=tmp_path)
    real = cache.entry_dir(cache.cache_key({"t": "kept"}), tmp_path)
    orphan = cache.entry_dir("ab" * 32, tmp_path)  # made by other code: its key is never asked again
    orphan.parent.mkdir(parents=True, exist_ok=True)
    shutil.copytree(real, orphan)
    dead = real.parent / f".tmp-{'cd' * 32}-999999999-0123456789ab"  # writer long gone
    dead.mkdir()
    os.utime(dead, (time.time() - 3600,) * 2)
    live = real.parent / f".tmp-{'ef' * 32}-{os.getpid()}-0123456789ab"  # writer (us) still running
    live.mkdir()
    env = {**os.environ, "SSS_LOCUS_CACHE_DIR": str(tmp_path)}
    shown = subprocess.run([sys.executable, "-m", "sss_locus.pipeline.cli.command", "cache"], env=env,
                           capture_output=True, text=True, timeout=120)
    assert shown.returncode == 0 and "2 entries" in shown.stdout and "1 reachable" in shown.stdout
    pruned = subprocess.run([sys.executable, "-m", "sss_locus.pipeline.cli.command", "cache", "--prune"], env=env,
                            capture_output=True, text=True, timeout=120)
    assert pruned.returncode == 0 and "pruned 2" in pruned.stdout, pruned.stdout + pruned.stderr
    assert real.is_dir() and not orphan.exists() and not dead.exists() and live.exists()


# -- 6. validation before work -------------------------------------------------------------------

@pytest.mark.parametrize("args, fragment", [
    (["concept", "-p", "n_per_arc", "100000000"], "parameter 'n_per_arc' = 100000000 is out of range"),
    (["concept", "-p", "platforms", '["ship"]'], "parameter 'platforms[0]' = 'ship' is not allowed"),
    (["concept", "-p", "sonar_platform", "auv"], "parameter 'sonar_platform' is now 'platforms'"),
    (["planning", "-p", "n_per_angle", "[10, 'x']"], "parameter 'n_per_angle[1]' = 'x': must be int"),
    (["pose_space", "-p", "n_samples", "-5"], "parameter 'n_samples' = -5 is out of range: allowed [100, 5000000]"),
])
def test_bad_values_are_refused_in_one_line_before_a_kernel_starts(tmp_path, args, fragment):
    build = tmp_path / "build"
    env = {**os.environ, "SSS_LOCUS_BUILD_DIR": str(build)}
    start = time.monotonic()
    result = subprocess.run([sys.executable, "-m", "sss_locus.pipeline.cli.command", "run", *args], env=env,
                            capture_output=True, text=True, timeout=120, stdin=subprocess.DEVNULL)
    assert result.returncode == 2 and fragment in result.stderr, result.stderr
    assert len(result.stderr.strip().splitlines()) == 1
    assert not build.exists()  # no kernel, no staging folder, nothing
    assert time.monotonic() - start < 60


def test_failing_cell_in_one_line_traceback_only_with_verbose(area, entry, tmp_path):
    script = textwrap.dedent(f"""
        import sys
        from pathlib import Path
        from sss_locus.pipeline.cli import command as cli
        from sss_locus.pipeline.run.registry import NotebookEntry
        cli.get_entry = lambda name: NotebookEntry("tiny", Path({str(entry.source)!r}), "executed/tiny.ipynb",
                                                   {{"book": {{}}, "quick": {{}}}})
        sys.exit(cli.main(["run", "tiny", "-p", "fail", "true", *sys.argv[1:]]))
    """)
    short = subprocess.run([sys.executable, "-c", script], env=os.environ.copy(), capture_output=True, text=True,
                           timeout=300)
    assert short.returncode == 1
    lines = short.stderr.strip().splitlines()
    assert "cell 2" in lines[0] and "ValueError: n = 3 is not what this cell wants" in lines[0]
    assert "Traceback" not in short.stderr and len(lines) == 2  # the line, and the hint for --verbose
    verbose = subprocess.run([sys.executable, "-c", script, "--verbose"], env=os.environ.copy(),
                             capture_output=True, text=True, timeout=300)
    assert verbose.returncode == 1 and "time.sleep(sleep_s)" in verbose.stderr  # the traceback's code


def test_name_patterns_match_the_whole_string(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from sss_locus.pipeline.publish.export import export_figure

    fig, _ = plt.subplots()
    for label in ("fig-ok\n", "fig-ok\nfig-x"):
        with pytest.raises(ValueError, match="label must look like"):
            export_figure(fig, label, _frame(), caption="C.", parameters={}, out_dir=tmp_path)
    with pytest.raises(ValueError, match="data keys"):
        export_figure(fig, "fig-ok", {"arcs\n": _frame()}, caption="C.", parameters={}, out_dir=tmp_path)
    plt.close(fig)


# -- 7. registry ---------------------------------------------------------------------------------

GOOD = '[notebooks.d]\nsource = "nb.ipynb"\nexecuted = "executed/d.ipynb"\nprofiles = {book = {}, quick = {}}\n'


@pytest.mark.parametrize("body, fragment", [
    ("notebooks = 3\n", "notebooks must be a table"),
    ("notebooks = [1, 2]\n", "notebooks must be a table"),
    ("[notebooks]\nd = 5\n", "notebooks.d must be a table"),
    ('[notebooks.d]\nsource = 1\nexecuted = "executed/d.ipynb"\nprofiles = {book = {}, quick = {}}\n',
     "notebooks.d.source must be a non-empty string"),
    ('[notebooks.d]\nsource = "nb.ipynb"\nexecuted = ["x"]\nprofiles = {book = {}, quick = {}}\n',
     "notebooks.d.executed must be a non-empty string"),
    ('[notebooks.d]\nsource = "nb.ipynb"\nexecuted = "executed/d.ipynb"\nprofiles = 3\n',
     "notebooks.d.profiles must be a table"),
    ('[notebooks.d]\nsource = "nb.ipynb"\nexecuted = "executed/d.ipynb"\nprofiles = {book = 1, quick = {}}\n',
     "notebooks.d.profiles.book must be a table"),
    ('[notebooks."D\\n"]\nsource = "nb.ipynb"\nexecuted = "executed/d.ipynb"\nprofiles = {book = {}, quick = {}}\n',
     "notebook names must be"),
    ("stray = 1\n" + GOOD, "unknown top-level key(s) stray"),
    ("[notebooks.d\n", "not valid TOML"),
    (GOOD + GOOD.replace("notebooks.d", "notebooks.e"), "notebooks.e.executed: 'executed/d.ipynb' is already"),
])
def test_malformed_registry_names_the_key(tmp_path, body, fragment):
    nbformat.write(nbformat.v4.new_notebook(), tmp_path / "nb.ipynb")
    registry = tmp_path / "registry.toml"
    registry.write_text(body)
    with pytest.raises(ValueError) as info:
        load_registry(registry, root=tmp_path)
    assert fragment in str(info.value) and str(registry) in str(info.value)


def test_every_temporary_name_is_unique(tmp_path, monkeypatch):
    """Two writers of one label must never share a temporary file: no name is ever reused."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from sss_locus.pipeline.publish.export import export_figure

    used: list[str] = []
    real_replace = os.replace
    monkeypatch.setattr(os, "replace", lambda src, dst: (used.append(str(src)), real_replace(src, dst))[1])
    fig, _ = plt.subplots()
    for _ in range(2):
        export_figure(fig, "fig-same", _frame(), caption="C.", parameters={}, out_dir=tmp_path)
    plt.close(fig)
    assert len(used) >= 2 * 6 and len(set(used)) == len(used)


# -- 6. kernels that never start -------------------------------------------------------------------

def _flaky_child(counter: Path, failures: int) -> str:
    """A papermill child whose first ``failures`` starts die as a kernel lost to a port race."""
    from sss_locus.pipeline.run import runner

    return (f"import pathlib, sys\nc = pathlib.Path({str(counter)!r})\nn = int(c.read_text()) if c.exists() else 0\n"
            f"c.write_text(str(n + 1))\nif n < {failures}:\n"
            "    sys.exit('RuntimeError: Kernel died before replying to kernel_info')\n" + runner._CHILD)


@pytest.mark.parametrize("failures", [1, 2])
def test_a_kernel_that_dies_before_any_cell_is_started_again(area, entry, tmp_path, monkeypatch, failures):
    from sss_locus.pipeline.run import runner

    counter = tmp_path / "starts"
    monkeypatch.setattr(runner, "_CHILD", _flaky_child(counter, failures))
    run_notebook(entry, "book", {"n": 6}, log=quiet)
    assert int(counter.read_text()) == failures + 1
    manifest = json.loads((area / "source" / "_extra" / "figures" / "fig-tiny-reliable.json").read_text())
    assert manifest["parameters"]["n"] == 6 and leftovers(area) == []


def test_kernel_start_retries_are_bounded_and_keep_the_last_good_results(area, entry, tmp_path, monkeypatch):
    from sss_locus.pipeline.run import runner

    run_notebook(entry, "book", {"n": 4}, log=quiet)
    good = snapshot(area)
    counter = tmp_path / "starts"
    monkeypatch.setattr(runner, "_CHILD", _flaky_child(counter, 99))
    with pytest.raises(NotebookFailed, match="did not run: RuntimeError: Kernel died before replying"):
        run_notebook(entry, "book", {"n": 9}, log=quiet)
    assert int(counter.read_text()) == runner.KERNEL_START_ATTEMPTS
    assert snapshot(area) == good and leftovers(area) == []


def test_a_failing_cell_is_never_rerun(area, entry, tmp_path, monkeypatch):
    from sss_locus.pipeline.run import runner

    counter = tmp_path / "starts"
    monkeypatch.setattr(runner, "_CHILD", _flaky_child(counter, 0))
    with pytest.raises(NotebookFailed, match="ValueError"):
        run_notebook(entry, "book", {"fail": True}, log=quiet)
    assert int(counter.read_text()) == 1
