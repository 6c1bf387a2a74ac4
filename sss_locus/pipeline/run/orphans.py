"""Nothing left running or lying around after a run is killed, even by SIGKILL.

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
