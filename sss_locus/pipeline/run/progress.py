"""What ``sss-locus run`` and ``sss-locus book`` show while notebooks run.

* A line when each notebook starts (:func:`start_line`, with the UTC clock time) and when it
  ends (the runner's ``ran <name> [<profile>] in <s> s`` line, or ``failed <name> after <s> s``).
* ``book``: a bar over the notebooks (:class:`NotebookBar`).
* Long studies: a bar over their batches. The experiments layer never prints; its chunked
  studies (:func:`sss_locus.experiments.stats.scale.map_chunks` and the study functions with a
  ``progress=`` argument) call a callback ``progress(done, total)`` after each chunk (on a Dask
  cluster, as each future completes). A notebook's kernel runs in a child process whose output
  belongs to the notebook, so the callback does not write to the terminal: the pipeline's cache
  wrapper (:func:`sss_locus.pipeline.run.cache.cached`) gives every study it computes a
  :func:`batch_reporter`, which appends one line per batch to the run context's
  ``progress_file`` (in the run's staging folder; :mod:`sss_locus.pipeline.run.context`). The runner reads that file while the
  notebook runs (:func:`relay_batches`) and shows the bar. Nothing reaches the executed
  notebook. Cache hits compute nothing and show no bar. With ``book --jobs N`` (N > 1) the
  notebooks run in child processes whose output is collected, so only the notebook lines and
  bar are shown (the context's ``quiet_batches``).

On a terminal (``isatty()``) the bars are tqdm bars on stderr and the lines go to stdout above
them. Anywhere else (a CI log, a pipe, a file) there are no bars and no terminal codes: plain
lines only: a notebook count after each notebook and, for a study still running after
:data:`PLAIN_EVERY_S` seconds, a batch line about that often and one when it ends (short studies,
most of a quick run's, print nothing). Batch bars likewise appear only after
:data:`BAR_DELAY_S` seconds.
"""

from __future__ import annotations

import sys
import threading
import time
import uuid
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from sss_locus.pipeline.run import context

START_PREFIX = "start "
#: Seconds between two reads of the progress file.
POLL_S = 0.5
#: Seconds between two plain batch lines of one study (the first comes this long after its start).
PLAIN_EVERY_S = 10.0
#: Seconds a study runs before its bar appears on a terminal.
BAR_DELAY_S = 1.0


def is_terminal(stream: Any) -> bool:
    """Whether ``stream`` is an interactive terminal (bars) rather than a file or pipe (lines)."""
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):
        return False


def start_line(name: str, profile: str) -> str:
    """``start <name> [<profile>] at HH:MM:SS UTC``."""
    return f"{START_PREFIX}{name} [{profile}] at {time.strftime('%H:%M:%S', time.gmtime())} UTC"


def batch_reporter(label: str) -> Callable[[int, int], None] | None:
    """A ``progress(done, total)`` callback for one study, for a kernel started by the runner:
    it appends ``<call id>\\t<label>\\t<done>\\t<total>`` to the file named by
    the run context's ``progress_file``. ``None`` outside a run (a plain papermill or Python run)."""
    target = context.current().progress_file
    if target is None:
        return None
    call = uuid.uuid4().hex[:12]

    def report(done: int, total: int) -> None:
        with open(target, "a", encoding="utf-8") as fh:
            fh.write(f"{call}\t{label}\t{int(done)}\t{int(total)}\n")

    return report


class _BatchView:
    """Shows the lines of one progress file: a bar per study on a terminal, else plain lines."""

    def __init__(self, name: str, write: Callable[[str], Any], stream: Any, every_s: float) -> None:
        self.name, self.write, self.stream, self.every_s = name, write, stream, every_s
        self.tty = is_terminal(stream)
        self.call: str | None = None
        self.bar = None
        self.last: float | None = None  # when the study began, then when its last line was written
        self.printed = False

    def show(self, call: str, label: str, done: int, total: int) -> None:
        if total < 2:
            return  # one batch: nothing to follow
        if call != self.call:
            self.close()
            self.call, self.last, self.printed = call, time.monotonic(), False
            if self.tty:
                from tqdm import tqdm

                self.bar = tqdm(total=total, desc=f"{self.name}: {label}", unit="batch",
                                file=self.stream, leave=False, dynamic_ncols=True, delay=BAR_DELAY_S)
        if self.bar is not None:
            self.bar.update(done - self.bar.n)
        elif time.monotonic() - self.last >= self.every_s or (done == total and self.printed):
            self.last, self.printed = time.monotonic(), True
            self.write(f"  {self.name}: {label} batch {done}/{total}")

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
        self.bar = None


@contextmanager
def relay_batches(path: Path, name: str, write: Callable[[str], Any] = print,
                  stream: Any = None, every_s: float | None = None) -> Iterator[None]:
    """While the body runs, show the batch progress a kernel appends to ``path`` (see
    :func:`batch_reporter`) for notebook ``name``: tqdm bars on ``stream`` (default stderr) if
    it is a terminal, else lines through ``write`` (one per ``every_s`` seconds of a study, default :data:`PLAIN_EVERY_S`, and
    its last batch if any was shown). Nothing when the run context says ``quiet_batches`` (a child
    run of ``book --jobs N``)."""
    if context.current().quiet_batches:
        yield
        return
    view = _BatchView(name, write, sys.stderr if stream is None else stream,
                      PLAIN_EVERY_S if every_s is None else every_s)
    stop = threading.Event()
    offset = [0]

    def read() -> None:
        try:
            with open(path, "rb") as fh:
                fh.seek(offset[0])
                data = fh.read()
        except OSError:
            return
        end = data.rfind(b"\n") + 1  # whole lines only; a partial line is read next time
        offset[0] += end
        for line in data[:end].decode("utf-8", "replace").splitlines():
            parts = line.split("\t")
            if len(parts) == 4 and parts[2].isdigit() and parts[3].isdigit():
                view.show(parts[0], parts[1], int(parts[2]), int(parts[3]))

    def poll() -> None:
        while not stop.wait(POLL_S):
            read()

    thread = threading.Thread(target=poll, name=f"progress-{name}", daemon=True)
    thread.start()
    try:
        yield
    finally:
        stop.set()
        thread.join()
        read()
        view.close()


class NotebookBar:
    """Progress over ``total`` notebooks: a tqdm bar on ``stream`` (default stderr) when it is
    a terminal, else a plain ``k/total notebooks done`` line after each; the bar closes after the
    last. :meth:`write` prints a line (stdout) without breaking the bar."""

    def __init__(self, total: int, stream: Any = None) -> None:
        self.total, self.done, self.start = total, 0, time.perf_counter()
        self._lock = threading.Lock()
        self.stream = sys.stderr if stream is None else stream
        self.bar = None
        if total and is_terminal(self.stream):
            from tqdm import tqdm

            self.bar = tqdm(total=total, desc="notebooks", unit="notebook", file=self.stream,
                            dynamic_ncols=True)

    def write(self, line: str) -> None:
        """One whole line, also from several threads at once (``book --jobs`` logs each start from
        its worker thread): ``print`` writes the text and its newline separately, so two
        threads' lines could run into one."""
        with self._lock:
            if self.bar is not None:
                self.bar.write(line, file=sys.stdout)
            else:
                sys.stdout.write(line + "\n")
                sys.stdout.flush()

    @contextmanager
    def timed(self, name: str) -> Iterator[None]:
        """Count the notebook run in the body: finished, or failed (with its time) if it raises."""
        start = time.perf_counter()
        try:
            yield
        except Exception:
            self.finished(name, False, time.perf_counter() - start)
            raise
        self.finished(name, True)

    def finished(self, name: str, ok: bool, seconds: float | None = None) -> None:
        """Count one notebook; a failure gets its own line (its error is reported at the end)."""
        self.done += 1
        if not ok:
            took = f" after {seconds:.1f} s" if seconds is not None else ""
            self.write(f"failed {name}{took} (its error is listed at the end)")
        if self.bar is not None:
            self.bar.update(1)
            if self.done >= self.total:
                self.close()
        else:
            self.write(f"  {self.done}/{self.total} notebooks done, "
                       f"{time.perf_counter() - self.start:.0f} s elapsed")

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
        self.bar = None
