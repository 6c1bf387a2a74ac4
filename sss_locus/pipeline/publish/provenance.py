"""Provenance of a run: package version, git commit, lock-file hash, notebook identity.

Used by :mod:`sss_locus.pipeline.publish.export` (figure manifests), :mod:`sss_locus.pipeline.run.cache`
(cache keys) and :mod:`sss_locus.pipeline.run.runner` (up-to-date checks).
Every function returns a string and never raises: outside a git checkout the commit is
``"unknown"``, and so on.
"""

from __future__ import annotations

import functools
import hashlib
from typing import Any
import subprocess
from datetime import datetime, timezone
from pathlib import Path

from sss_locus import paths


def json_default(value: Any) -> Any:
    """``default=`` hook for :func:`json.dumps`: numpy scalars/arrays and paths become JSON."""
    import numpy as np

    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, Path):
        return value.as_posix()
    raise ValueError(
        f"value {value!r} of type {type(value).__name__} is not JSON-like "
        "(use numbers, strings, bools, None, lists, dicts or numpy scalars)"
    )


def package_version() -> str:
    """The package's version, ``sss_locus.__version__``: the one place it is stated (the
    distribution's metadata, CITATION.cff and .zenodo.json are checked to agree with it; an
    editable install's metadata would lag behind a bump until reinstalled)."""
    import sss_locus

    return sss_locus.__version__


def git_commit(repo: Path | None = None) -> str:
    """Commit hash of the checkout, with ``+dirty`` when tracked files are modified; ``"unknown"``
    for an installed package (no checkout: git is not asked, or a virtual environment inside the
    user's own repository would report that repository's commit)."""
    if repo is None and not paths.IN_CHECKOUT:
        return "unknown"
    repo = paths.REPO_ROOT if repo is None else repo
    try:
        commit = subprocess.run(
            ["git", "rev-parse", "HEAD"], cwd=repo, capture_output=True, text=True, timeout=10
        )
        if commit.returncode != 0:
            return "unknown"
        dirty = subprocess.run(
            ["git", "status", "--porcelain", "--untracked-files=no"],
            cwd=repo, capture_output=True, text=True, timeout=10,
        )
        suffix = "+dirty" if dirty.returncode == 0 and dirty.stdout.strip() else ""
        return commit.stdout.strip() + suffix
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def short_commit(commit: str) -> str:
    """First 12 hex digits of a commit as returned by :func:`git_commit`, keeping ``+dirty``."""
    dirty = commit.endswith("+dirty")
    return commit.removesuffix("+dirty")[:12] + ("+dirty" if dirty else "")


def file_sha256(path: Path) -> str:
    """SHA-256 hex digest of a file's bytes (``"missing"`` if it does not exist)."""
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError:
        return "missing"


def lock_sha256() -> str:
    """SHA-256 of ``environment.lock``: identifies the exact software environment."""
    return file_sha256(paths.LOCK_FILE)


def environment_sha256() -> str:
    """What identifies the software environment a run's key holds: in a checkout the SHA-256 of
    ``environment.lock`` (:func:`lock_sha256`); an installed package has no lock, so the SHA-256 of
    the installed distributions' names and versions (an upgraded library makes its runs stale, as
    an edited lock does in a checkout; listed once per process)."""
    if paths.IN_CHECKOUT:
        return lock_sha256()
    return installed_distributions_sha256()


@functools.cache
def installed_distributions_sha256() -> str:
    """SHA-256 of the sorted ``name==version`` of every distribution this Python sees (computed
    once per process; ``installed_distributions_sha256.cache_clear()`` forgets it)."""
    from importlib import metadata

    names = sorted({f"{d.metadata['Name']}=={d.version}" for d in metadata.distributions()})
    return hashlib.sha256("\n".join(names).encode()).hexdigest()


def tree_sha256(*roots: Path, patterns: tuple[str, ...] = ("*",)) -> str:
    """One SHA-256 over the relative names and bytes of every file under ``roots``.

    Files in ``__pycache__`` folders and hidden files are skipped.
    """
    digest = hashlib.sha256()
    for root in roots:
        root = Path(root)
        files = sorted({p for pattern in patterns for p in root.rglob(pattern) if p.is_file()})
        for path in files:
            rel = path.relative_to(root)
            if "__pycache__" in rel.parts or any(part.startswith(".") for part in rel.parts):
                continue
            digest.update(f"{root.name}/{rel.as_posix()}\0".encode())
            digest.update(hashlib.sha256(path.read_bytes()).digest())
    return digest.hexdigest()


def code_sha256() -> str:
    """Fingerprint of the package source and its inputs: ``sss_locus/*.py`` and ``data/``.

    The package version alone does not change when the code is edited in place (editable
    install), so caches and up-to-date checks key on this as well.
    """
    parts = tree_sha256(paths.PACKAGE_DIR, patterns=("*.py",)) + tree_sha256(paths.DATA_DIR)
    return hashlib.sha256(parts.encode()).hexdigest()


def science_sha256() -> str:
    """Fingerprint of what a computed result can depend on: ``sss_locus/geometry/``,
    ``sss_locus/experiments/`` (their ``*.py``) and ``data/``.

    The cache keys on this (:mod:`sss_locus.pipeline.run.cache`), so editing the report or pipeline
    layers never invalidates a simulation.
    """
    pkg = paths.PACKAGE_DIR
    parts = (tree_sha256(pkg / "geometry", patterns=("*.py",))
             + tree_sha256(pkg / "experiments", patterns=("*.py",)) + tree_sha256(paths.DATA_DIR))
    return hashlib.sha256(parts.encode()).hexdigest()


def utc_now() -> str:
    """Current UTC time, ISO 8601 with seconds."""
    return datetime.now(timezone.utc).isoformat(timespec="seconds")
