"""Checks of a run's output paths, made before any kernel starts (each refused in one line).

A side run's ``--output`` (:func:`check_side_output`) must:

* name a notebook file (``.ipynb``), not an existing directory;
* lie outside every build area: the reproduction's (``_build/``, or ``$SSS_LOCUS_BUILD_DIR``
  without ``--name``) with all its named areas ``_build/NAME``, whatever ``--name`` is given
  (:func:`build_roots`), and its ``figures/`` folder too (a link there is followed); outside the
  result cache, outside ``notebooks/`` and not over a file git tracks (the committed notebooks,
  data and book pages are sources, never outputs);
* lie in a folder this process can write (the nearest existing folder is probed);
* not take the folder of another side run of the same notebook: the figures of a side run go
  into ``figures/`` beside its notebook, one set per notebook, so a second ``--output`` in the
  same folder would replace the first run's figures under its notebook. Rerunning into the same
  ``--output`` replaces both together and is allowed.

:func:`check_writable` probes a folder the run will write (the build area of a book run).
"""

from __future__ import annotations

import json
import os
import subprocess
import tempfile
from pathlib import Path
from typing import Any

from sss_locus import paths
from sss_locus.pipeline.publish import export

#: A side run's notebook that starts like this is the record of a failed run, not a result.
FAILED_SUFFIX = ".failed.ipynb"


class OutputError(ValueError):
    """An output path a run must not write (one line)."""


def _nearest_existing(folder: Path) -> Path:
    while not folder.exists() and folder != folder.parent:
        folder = folder.parent
    return folder


def check_writable(folder: Path, what: str) -> None:
    """Refuse when ``folder`` (or, if it does not exist yet, its nearest existing parent) cannot
    be written: a read-only filesystem or a folder without write permission."""
    base = _nearest_existing(Path(folder))
    if not base.is_dir():
        raise OutputError(f"{what} {folder}: {base} is a file, not a folder")
    try:
        fd, probe = tempfile.mkstemp(prefix=".sss-locus-probe-", dir=base)
    except OSError as exc:
        raise OutputError(f"{what} {folder} is not writable ({exc.strerror or exc}: {base})") from None
    os.close(fd)
    os.unlink(probe)


def build_roots() -> list[Path]:
    """Folders no side run may write into: the reproduction's build area (which holds every named
    area, ``_build/NAME``) as this process sees it, and the repository's default ``_build/``."""
    current = paths.build_dir().resolve()
    reproduction = current.parent if paths.build_name() else current
    return list(dict.fromkeys([reproduction, (paths.REPO_ROOT / "_build").resolve()]))


def _within(path: Path, folder: Path) -> bool:
    return path == folder or folder in path.parents


def _check_outside_builds(path: Path) -> None:
    figures = (path.parent / paths.FIGURES_SUBDIR).resolve()  # follows a link named figures/
    for root in build_roots():
        for written, what in ((path, "is"), (figures, "would put its figures")):
            if _within(written, root):
                raise OutputError(
                    f"--output {path} {what} inside the build area {root}{' (' + str(written) + ')' if written != path else ''}, "
                    "which holds the reproduction and every named area (--name): a side run must write "
                    "elsewhere (run without --output to update a book)")
    cache = paths.cache_dir().resolve()
    if _within(path, cache) or _within(figures, cache):
        raise OutputError(f"--output {path} is inside the result cache {cache}: write side runs elsewhere")


def _tracked(path: Path) -> bool:
    """Whether git tracks ``path`` in the project's repository (False without git or checkout)."""
    if not paths.IN_CHECKOUT:
        return False
    try:
        relative = path.relative_to(paths.REPO_ROOT)
    except ValueError:
        return False
    try:
        result = subprocess.run(["git", "-C", str(paths.REPO_ROOT), "ls-files", "--error-unmatch", "--",
                                 relative.as_posix()], capture_output=True, timeout=30)
    except (OSError, subprocess.TimeoutExpired):
        return False
    return result.returncode == 0


def _run_key_of(notebook: Path) -> str | None:
    try:
        meta = json.loads(notebook.read_text(encoding="utf-8")).get("metadata", {})
    except (OSError, ValueError, AttributeError):
        return None
    record = meta.get("sss_locus") if isinstance(meta, dict) else None
    return record.get("run_key") if isinstance(record, dict) else None


def side_folder_owner(output: Path, entry: Any) -> Path | None:
    """Another side notebook in ``output``'s folder whose run made figures of ``entry`` that
    are still in ``figures/`` there (a run into ``output`` would replace them), or None."""
    figures = output.parent / paths.FIGURES_SUBDIR
    if not figures.is_dir():
        return None
    keys = {m.get("run_key") for m in export.load_manifests(figures) if m.get("notebook") == entry.source_relative}
    if not keys:
        return None
    for other in sorted(output.parent.glob("*.ipynb")):
        if other.resolve() != output and not other.name.endswith(FAILED_SUFFIX) and _run_key_of(other) in keys:
            return other
    return None


def check_side_output(output: str | Path, entry: Any) -> Path:
    """The resolved ``--output`` path of a side run of ``entry``, or :class:`OutputError` (see the
    module docstring)."""
    path = Path(output).expanduser().resolve()
    if path.is_dir():
        raise OutputError(f"--output {path} is a directory: name the notebook to write, e.g. "
                          f"{path / (entry.name + '.ipynb')}")
    if path.suffix != ".ipynb":
        raise OutputError(f"--output {path}: name a notebook file ending in .ipynb")
    _check_outside_builds(path)
    if paths.NOTEBOOKS_DIR.resolve() in path.parents:
        raise OutputError(f"--output {path} is inside {paths.NOTEBOOKS_DIR}, the notebooks' sources: "
                          "write side runs elsewhere")
    if path.exists() and _tracked(path):
        raise OutputError(f"--output {path} is a file of the repository (tracked by git): write side "
                          "runs elsewhere")
    check_writable(path.parent, "--output folder")
    owner = side_folder_owner(path, entry)
    if owner is not None:
        raise OutputError(f"--output {path}: {path.parent / paths.FIGURES_SUBDIR} holds the figures of "
                          f"the side run {owner.name} of {entry.name}, which this run would replace; "
                          f"use another folder (or --output {owner} to rerun that one)")
    return path
