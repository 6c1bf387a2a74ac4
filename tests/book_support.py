"""The quick book the book tests share, built in a background process (imported like
``reference_locus``).

``conftest.py`` starts the build when the session's first test starts, if any collected test uses
the ``quick_book`` fixture, and moves those tests to the end of the run: the book's notebooks and
Sphinx build overlap the other tests, on two cores about three minutes of a ten-minute suite. The
fixture then waits for the same process, so a failing build fails the book tests exactly as a
synchronous build would, with its own output in the message.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

from sss_locus import paths

TIMEOUT_S = 900  # a hang guard, not a speed test: a loaded 2-core machine needs ~8 min for the quick book
DEFAULT_INDEX = paths.REPO_ROOT / "_build" / "html" / "index.html"


def _mtime(path: Path) -> int | None:
    return path.stat().st_mtime_ns if path.exists() else None


class QuickBook:
    """``sss-locus book --profile quick`` into its own build ``area``, running from construction."""

    def __init__(self, area: Path):
        self.area = area
        self.log = area.parent / f"{area.name}.stdout"
        self.errlog = area.parent / f"{area.name}.stderr"
        self.default_index_before = _mtime(DEFAULT_INDEX)
        self.started = time.monotonic()
        # its own result cache, so the build computes everything as on a fresh clone
        self.env = {**os.environ, paths.BUILD_DIR_ENV: str(area), paths.CACHE_DIR_ENV: str(area.parent / "cache")}
        with open(self.log, "w") as out, open(self.errlog, "w") as err:
            self.process = subprocess.Popen(
                [sys.executable, "-m", "sss_locus.pipeline.cli", "book", "--profile", "quick"],
                env=self.env, stdout=out, stderr=err, stdin=subprocess.DEVNULL, text=True)
        self._result: dict | None = None

    def result(self) -> dict:
        """Wait for the build (at most :data:`TIMEOUT_S` from its start); return ``{"area",
        "html", "stdout", "env"}`` (``env``: the build's environment, its cache included). Raises ``RuntimeError`` with the build's output if it failed, hung or
        touched the default build area."""
        if self._result is None:
            try:
                self.process.wait(timeout=max(1.0, TIMEOUT_S - (time.monotonic() - self.started)))
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
                raise RuntimeError(f"the quick book hung for {TIMEOUT_S} s:\n{self.output()}") from None
            if self.process.returncode != 0:
                raise RuntimeError(f"sss-locus book --profile quick failed:\n{self.output()}")
            if _mtime(DEFAULT_INDEX) != self.default_index_before:
                raise RuntimeError("the test build touched the default build area")
            self._result = {"area": self.area, "html": self.area / "html", "stdout": self.log.read_text(),
                            "env": self.env}
        return self._result

    def output(self) -> str:
        """The ends of the build's stdout and stderr, for a failure message."""
        return (self.log.read_text(errors="replace")[-6000:] + "\n"
                + self.errlog.read_text(errors="replace")[-6000:])

    def stop(self) -> None:
        """Kill the build if it is still running (a session that ends early)."""
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()
