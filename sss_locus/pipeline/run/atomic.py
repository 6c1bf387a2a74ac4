"""Building blocks of safe runs: file locks, unique temporary names, atomic replacement and
signals turned into exceptions.

* :func:`file_lock` takes an advisory lock (``fcntl.flock``) on a lock file; the kernel releases
  it when the process dies, so a killed run never leaves a stale lock behind.
* :func:`temp_name` gives a name no other process or thread can pick (pid + random), so two
  writers of one file never share a temporary file.
* :func:`write_atomic` / :func:`copy_atomic` write to such a name and ``os.replace`` it: a reader
  sees the old file or the new one, never a partial one.
* :func:`signals_as_exceptions` turns SIGTERM (and SIGHUP) into :class:`Interrupted` (a
  ``KeyboardInterrupt``, like Ctrl-C), so ``finally`` blocks clean up after a kill as after an
  error.
* :func:`pid_alive` tells whether a temporary folder's writer is still running.
"""

from __future__ import annotations

import fcntl
import os
import shutil
import signal
import threading
import uuid
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path


class Interrupted(KeyboardInterrupt):
    """The process received SIGTERM or SIGHUP (handled like Ctrl-C)."""


def temp_name(path: Path, tag: str = "tmp") -> Path:
    """A sibling of ``path`` that is hidden and unique to this process and call."""
    path = Path(path)
    return path.with_name(f".{path.name}.{tag}-{os.getpid()}-{uuid.uuid4().hex[:12]}")


def pid_of_temp(path: Path) -> int | None:
    """The writer's pid encoded by :func:`temp_name` in ``path``'s name (None if not one)."""
    try:
        return int(Path(path).name.rsplit("-", 2)[-2])
    except (IndexError, ValueError):
        return None


def pid_alive(pid: int | None) -> bool:
    """True when a process with this pid exists (so its temporary files may be in use)."""
    if pid is None or pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def write_atomic(path: Path, data: str | bytes) -> None:
    """Write ``data`` to ``path`` through a unique temporary file and ``os.replace``."""
    path = Path(path)
    tmp = temp_name(path)
    try:
        if isinstance(data, str):
            tmp.write_text(data, encoding="utf-8")
        else:
            tmp.write_bytes(data)
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)


def copy_atomic(source: Path, target: Path) -> None:
    """Copy ``source`` to ``target`` so that ``target`` is never seen half-written."""
    target = Path(target)
    tmp = temp_name(target)
    try:
        shutil.copyfile(source, tmp)
        os.replace(tmp, target)
    finally:
        tmp.unlink(missing_ok=True)


@contextmanager
def file_lock(lock_file: Path, shared: bool = False) -> Iterator[None]:
    """Hold an advisory lock on ``lock_file`` (created if needed) for the ``with`` block.

    Exclusive by default; ``shared=True`` lets several holders in at once but none while an
    exclusive holder is in. Blocks until the lock is free.
    """
    lock_file = Path(lock_file)
    lock_file.parent.mkdir(parents=True, exist_ok=True)
    fd = os.open(lock_file, os.O_RDWR | os.O_CREAT, 0o644)
    try:
        fcntl.flock(fd, fcntl.LOCK_SH if shared else fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)  # closing releases the lock


def _raise_interrupted(signum: int, _frame: object) -> None:
    raise Interrupted(f"received {signal.Signals(signum).name}")


@contextmanager
def signals_as_exceptions() -> Iterator[None]:
    """Raise :class:`Interrupted` on SIGTERM/SIGHUP inside the block (main thread only)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    saved = {sig: signal.signal(sig, _raise_interrupted) for sig in (signal.SIGTERM, signal.SIGHUP)}
    try:
        yield
    finally:
        for sig, handler in saved.items():
            signal.signal(sig, handler)
