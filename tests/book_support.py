"""The quick book the book tests share, built once per test run in a background process
(imported like ``reference_locus``).

``conftest.py`` starts the build as soon as collection shows a test that uses the ``quick_book``
fixture, and moves those tests to the end of the run: the book's notebooks and Sphinx build
overlap the other tests. Under pytest-xdist (``make test`` runs ``-n auto``) every worker
collects the same tests, so the build is shared through files in the run's common temporary
folder: the first worker to take the lock starts it, every worker's ``quick_book`` fixture waits
for its exit status file, and the controller (the process that outlives the workers) kills it if
the run ends first. A failing build fails the book tests exactly as a synchronous build would,
with its own output in the message.
"""

from __future__ import annotations

import fcntl
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

from sss_locus import paths

TIMEOUT_S = 900  # a hang guard, not a speed test: a loaded 2-core machine needs ~8 min for the quick book
DEFAULT_INDEX = paths.REPO_ROOT / "_build" / "html" / "index.html"
POLL_S = 0.5

# The build's shell wrapper: its exit status goes to `rc` (written, then renamed, so a reader
# never sees half a number) when the book ends, however it ends.
_WRAPPER = '"$@" > "$LOG" 2> "$ERR"; echo $? > "$RC.tmp" && mv "$RC.tmp" "$RC"'


def _mtime(path: Path) -> int | None:
    return path.stat().st_mtime_ns if path.exists() else None


def shared_root(basetemp: Path) -> Path:
    """The temporary folder every process of this run sees: an xdist worker's ``basetemp`` is a
    sub-folder (``gw0``, ``gw1``, ...) of the controller's."""
    return basetemp.parent if os.environ.get("PYTEST_XDIST_WORKER") else basetemp


class QuickBook:
    """``sss-locus book --profile quick`` into its own build area under ``root/quick-book``, shared
    by every process of one test run through the files of that folder."""

    def __init__(self, root: Path):
        self.dir = root / "quick-book"
        self.area = self.dir / "build"
        self.log, self.errlog = self.dir / "stdout", self.dir / "stderr"
        self.rc, self.pid, self.meta = self.dir / "rc", self.dir / "pid", self.dir / "started"
        self.lock = root / "quick-book.lock"
        # its own result cache, so the build computes everything as on a fresh clone
        self.env = {**os.environ, paths.BUILD_DIR_ENV: str(self.area),
                    paths.CACHE_DIR_ENV: str(self.dir / "cache")}
        self._result: dict | None = None

    def start(self) -> None:
        """Start the build unless a process of this run already has (safe to call from each)."""
        self.lock.parent.mkdir(parents=True, exist_ok=True)
        with open(self.lock, "a") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            if self.meta.exists():
                return
            self.dir.mkdir(parents=True, exist_ok=True)
            env = {**self.env, "LOG": str(self.log), "ERR": str(self.errlog), "RC": str(self.rc)}
            process = subprocess.Popen(
                ["bash", "-c", _WRAPPER, "quick-book",
                 sys.executable, "-m", "sss_locus.pipeline.cli.command", "book", "--profile", "quick"],
                env=env, stdin=subprocess.DEVNULL, start_new_session=True)
            self.pid.write_text(str(process.pid))
            self.meta.write_text(f"{time.time()} {_mtime(DEFAULT_INDEX)}")

    def _started(self) -> tuple[float, str]:
        started, index_before = self.meta.read_text().split()
        return float(started), index_before

    def result(self) -> dict:
        """Wait for the build (at most :data:`TIMEOUT_S` from its start); return ``{"area",
        "html", "stdout", "env"}`` (``env``: the build's environment, its cache included). Raises
        ``RuntimeError`` with the build's output if it failed, hung or touched the default build
        area."""
        if self._result is None:
            if not self.meta.exists():
                raise RuntimeError("the quick book was never started (conftest.py starts it at collection)")
            started, index_before = self._started()
            while not self.rc.exists():
                if time.time() - started > TIMEOUT_S:
                    self.stop()
                    raise RuntimeError(f"the quick book hung for {TIMEOUT_S} s:\n{self.output()}")
                time.sleep(POLL_S)
            if self.rc.read_text().strip() != "0":
                raise RuntimeError(f"sss-locus book --profile quick failed (exit status "
                                   f"{self.rc.read_text().strip()}):\n{self.output()}")
            if str(_mtime(DEFAULT_INDEX)) != index_before:
                raise RuntimeError("the test build touched the default build area")
            self._result = {"area": self.area, "html": self.area / "html", "stdout": self.log.read_text(),
                            "env": self.env}
        return self._result

    def output(self) -> str:
        """The ends of the build's stdout and stderr, for a failure message."""
        return "\n".join(p.read_text(errors="replace")[-6000:] for p in (self.log, self.errlog) if p.exists())

    def stop(self) -> None:
        """Kill the build's process group if it is still running (a run that ends early)."""
        if self.pid.exists() and not self.rc.exists():
            try:
                os.killpg(int(self.pid.read_text()), signal.SIGKILL)
            except ProcessLookupError:
                pass
