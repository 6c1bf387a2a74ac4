"""Nothing left running or lying around after a run is killed, even by SIGKILL.

* :func:`stop_process_tree` stops the papermill child of an interrupted run (Ctrl-C, SIGTERM,
  SIGHUP, an exception) together with every process below it: the kernel, which jupyter_client
  starts in a session of its own (so a signal to papermill's group never reaches it), and the
  kernel's own children (a Dask ``LocalCluster``'s nannies and workers, a subprocess of a cell).
  The run removes its staging folder only once they have all ended, so nothing writes into it
  afterwards. Before, the kernel outlived the run until it noticed its parent was gone (up to a
  second, longer inside a C call holding the GIL), and its children were never stopped.
* :func:`die_with_parent` (a ``preexec_fn``) asks Linux to send the papermill child SIGTERM when
  the ``sss-locus run`` process that started it dies (``prctl(PR_SET_PDEATHSIG)``); papermill
  then stops, and the kernel, which polls its parent, exits too. A run killed with SIGKILL
  cannot clean up after itself, so nothing else would stop them.
* :func:`remove_stale_staging` deletes the staging folders (``.run-<name>-<pid>-<random>``) whose
  run is gone: each run does it in its staging area before it starts, and ``sss-locus cache
  --prune`` in the build area's.
* :func:`remove_stale_temporaries` deletes the hidden files a commit stages beside the results
  (``.<name>.tmp-<pid>-<random>``, ``.<name>.old-<pid>-<random>``,
  :func:`sss_locus.pipeline.run.atomic.temp_name`) whose writer is gone (a run killed during its
  commit): each run does it in the folders it commits to, and ``sss-locus cache --prune`` in the
  build area's figures and executed copies.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import re
import shutil
import signal
import sys
import time
from pathlib import Path

from sss_locus.pipeline.run.atomic import pid_alive, pid_of_temp

PR_SET_PDEATHSIG = 1  # <linux/prctl.h>
STAGING_PREFIX = ".run-"
#: A commit's staged or backup file (:func:`sss_locus.pipeline.run.atomic.temp_name`).
TEMPORARY = re.compile(r"\..+\.(?:tmp|old)-[0-9]+-[0-9a-f]{12}")


def die_with_parent() -> None:
    """In a child before ``exec``: receive SIGTERM when the parent dies (Linux; else nothing)."""
    if not sys.platform.startswith("linux"):
        return
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6", use_errno=True)
        libc.prctl(PR_SET_PDEATHSIG, signal.SIGTERM, 0, 0, 0)
    except (OSError, AttributeError):
        pass


#: Seconds the processes of an interrupted run get to end after SIGTERM before SIGKILL.
STOP_GRACE_S = 10.0


def _frozen_tree(pid: int) -> list:
    """``pid`` and every process below it, each suspended (SIGSTOP) before its children are
    listed, so none can start another one unseen; ``psutil.Process`` objects (they guard against
    a reused pid). Processes that end meanwhile are left out."""
    import psutil

    found: dict[int, psutil.Process] = {}
    try:
        todo = [psutil.Process(pid)]
    except psutil.NoSuchProcess:
        return []
    while todo:
        proc = todo.pop()
        if proc.pid in found:
            continue
        try:
            proc.suspend()
            found[proc.pid] = proc
            todo.extend(proc.children())
        except psutil.NoSuchProcess:
            continue
    return list(found.values())


def _ended(proc) -> bool:
    """The process has exited (a zombie its new parent has not reaped yet counts)."""
    import psutil

    try:
        return not proc.is_running() or proc.status() == psutil.STATUS_ZOMBIE
    except psutil.NoSuchProcess:
        return True


def _signal_all(procs: list, signum: int) -> None:
    import psutil

    for proc in procs:
        try:
            proc.send_signal(signum)
        except psutil.NoSuchProcess:
            pass


def stop_process_tree(pid: int, grace_s: float = STOP_GRACE_S) -> list[int]:
    """End the process ``pid`` (a run's papermill child) and every process below it.

    The tree is frozen (:func:`_frozen_tree`), sent SIGTERM, resumed (SIGCONT; a stopped
    process acts on SIGTERM only once continued) and given ``grace_s`` seconds to end; what is
    left gets SIGKILL. Returns when every process of the tree has ended (zombies of processes
    that are not ours count as ended: their new parent reaps them). Call it with SIGINT/SIGTERM/
    SIGHUP held back, so the tree is never left suspended.

    Parameters
    ----------
    pid : int
        The root of the tree; a pid that no longer exists is a tree of nothing.
    grace_s : float
        Seconds between SIGTERM and SIGKILL.

    Returns
    -------
    list of int
        The pids that were signalled, the root first if it was alive.
    """
    procs = _frozen_tree(pid)
    try:
        _signal_all(procs, signal.SIGTERM)
    finally:
        _signal_all(procs, signal.SIGCONT)
    for stubborn in (False, True):
        end = time.monotonic() + grace_s
        while time.monotonic() < end and not all(_ended(p) for p in procs):
            time.sleep(0.02)
        left = [p for p in procs if not _ended(p)]
        if not left:
            break
        if not stubborn:
            _signal_all(left, signal.SIGKILL)
    return [p.pid for p in procs]


def staging_pid(folder: Path) -> int | None:
    """The pid of the run that made the staging folder ``.run-<name>-<pid>-<random>``."""
    try:
        return int(folder.name.rsplit("-", 2)[-2])
    except (IndexError, ValueError):
        return None


def remove_stale_staging(folder: Path) -> tuple[int, int]:
    """Delete the staging folders in ``folder`` whose run is no longer alive; return how many and
    their bytes."""
    removed = freed = 0
    if not Path(folder).is_dir():
        return removed, freed
    for staging in Path(folder).glob(STAGING_PREFIX + "*"):
        pid = staging_pid(staging)
        if not staging.is_dir() or pid is None or pid_alive(pid):
            continue
        size = sum(p.stat().st_size for p in staging.rglob("*") if p.is_file() and not p.is_symlink())
        shutil.rmtree(staging, ignore_errors=True)
        if not staging.exists():
            removed, freed = removed + 1, freed + size
    return removed, freed


def remove_stale_temporaries(*folders: Path) -> tuple[int, int]:
    """Delete the hidden temporary and backup files of commits (:data:`TEMPORARY`) in ``folders``
    whose writing process is gone; files of a live process are kept. Returns how many and their
    bytes."""
    removed = freed = 0
    for folder in folders:
        if not Path(folder).is_dir():
            continue
        for path in Path(folder).iterdir():
            if not TEMPORARY.fullmatch(path.name) or pid_alive(pid_of_temp(path)):
                continue
            try:
                size = path.lstat().st_size
                if path.is_dir() and not path.is_symlink():
                    shutil.rmtree(path)
                else:
                    path.unlink()
            except OSError:
                continue
            removed, freed = removed + 1, freed + size
    return removed, freed
