"""A set of file replacements that happens whole or not at all (the commit of a run).

:class:`FileSwap` first *stages* every new file beside its target under a unique hidden name
(:func:`sss_locus.pipeline.run.atomic.temp_name`), after checking that the folder has the space
they need, and keeps a hard link to every old file it will replace or delete. Only when all of
that succeeded does it touch the old files, with renames and unlinks alone (no data written,
so a full disk cannot stop it halfway). Any failure, in staging or in that last step, removes
what it staged and puts every old file back: the previous results stay exactly as they were,
and the error is one line (:class:`CommitFailed`).

Example::

    with FileSwap("figures of concept") as swap:
        swap.check_space(folder, [staged / name for name in names])
        swap.copy(staged / "a.csv", folder / "a.csv")
        swap.unlink(folder / "old.csv")
        swap.move(staged_notebook, executed)
    # applied here, when the block ends without an exception
"""

from __future__ import annotations

import errno
import os
import shutil
from pathlib import Path
from types import TracebackType

from sss_locus.pipeline.run import atomic

#: Bytes kept free beyond what a commit needs (directory entries, the lock file, the log).
SPACE_MARGIN_BYTES = 1 << 20


class CommitFailed(RuntimeError):
    """A commit could not be made; nothing was changed. ``str()`` is one line."""


def describe_os_error(exc: OSError) -> str:
    """One line for an ``OSError``: its reason in words and the file it concerns."""
    reason = exc.strerror or str(exc) or type(exc).__name__
    if exc.errno == errno.ENOSPC:
        reason = "no space left on the device"
    elif exc.errno == errno.EROFS:
        reason = "read-only filesystem"
    elif exc.errno in (errno.EACCES, errno.EPERM):
        reason = "permission denied"
    where = f" ({exc.filename})" if exc.filename else ""
    return f"{reason}{where}"


def free_bytes(folder: Path) -> int:
    """Free bytes on the filesystem of ``folder`` (or of its nearest existing parent)."""
    folder = Path(folder)
    while not folder.exists() and folder != folder.parent:
        folder = folder.parent
    return shutil.disk_usage(folder).free


class FileSwap:
    """Replace, add and delete files as one step (see the module docstring).

    ``what`` names the results in the error message (e.g. ``"the run of concept"``).
    """

    def __init__(self, what: str) -> None:
        self.what = what
        self._staged: list[Path] = []  # temporary files to remove if we fail
        self._steps: list[tuple[str, Path, Path | None]] = []  # ("replace", tmp, target) / ("unlink", path, None)
        self._backups: dict[Path, Path | None] = {}  # target -> hard link of its old contents (None: absent)

    # -- staging: nothing old is touched ---------------------------------------------------------

    def check_space(self, folder: Path, files: list[Path]) -> None:
        """Refuse (before anything is staged) when ``files`` would not fit in ``folder``."""
        need = sum(Path(f).stat().st_size for f in files)
        free = free_bytes(folder)
        if need + SPACE_MARGIN_BYTES > free:
            raise CommitFailed(
                f"could not commit {self.what}: {folder} has {free / 1e6:.1f} MB free, it needs "
                f"{(need + SPACE_MARGIN_BYTES) / 1e6:.1f} MB; the previous results are unchanged")

    def _keep_old(self, target: Path) -> None:
        if target in self._backups:
            return
        if not target.exists():
            self._backups[target] = None
            return
        backup = atomic.temp_name(target, "old")
        self._staged.append(backup)
        try:
            os.link(target, backup)  # a second name for the old contents: no data written
        except OSError as exc:
            if exc.errno == errno.ENOSPC:
                raise
            shutil.copyfile(target, backup)  # a filesystem without hard links
        self._backups[target] = backup

    def copy(self, source: Path, target: Path) -> None:
        """Stage a copy of ``source`` that will replace ``target``."""
        self._stage(source, target, shutil.copyfile)

    def move(self, source: Path, target: Path) -> None:
        """Stage ``source`` (moved, a copy if on another filesystem) to replace ``target``."""
        self._stage(source, target, shutil.move)

    def _stage(self, source: Path, target: Path, put) -> None:
        target = Path(target)
        tmp = atomic.temp_name(target)
        self._staged.append(tmp)
        put(source, tmp)
        self._keep_old(target)
        self._steps.append(("replace", tmp, target))

    def unlink(self, path: Path) -> None:
        """Delete ``path`` (if it exists) when the swap is applied."""
        path = Path(path)
        self._keep_old(path)
        self._steps.append(("unlink", path, None))

    # -- applying: renames and unlinks only ------------------------------------------------------

    def _apply(self) -> None:
        for kind, path, target in self._steps:
            if kind == "replace":
                os.replace(path, target)
            else:
                path.unlink(missing_ok=True)

    def _restore(self) -> None:
        for target, backup in self._backups.items():
            try:
                if backup is None:
                    target.unlink(missing_ok=True)
                else:
                    os.replace(backup, target)
            except OSError:
                pass

    def _clean(self) -> None:
        for tmp in self._staged:
            try:
                tmp.unlink(missing_ok=True)
            except OSError:
                pass

    def __enter__(self) -> FileSwap:
        return self

    def __exit__(self, kind: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> bool:
        try:
            if kind is None:
                try:
                    self._apply()
                except BaseException as error:
                    self._restore()
                    if isinstance(error, OSError):
                        raise self._failed(error) from error
                    raise
            elif isinstance(exc, OSError) and not isinstance(exc, CommitFailed):
                raise self._failed(exc) from exc
        finally:
            self._clean()
        return False

    def _failed(self, error: OSError) -> CommitFailed:
        return CommitFailed(f"could not commit {self.what}: {describe_os_error(error)}; "
                            "the previous results are unchanged")
